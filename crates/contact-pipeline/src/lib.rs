//! The contact pipeline: Stage 1 (broad phase), Stage 2 (mesh phase) and Stage 3 (exact
//! refinement) composed through their traits, with the query options and the report.
//!
//! ```text
//! ContactPipeline<B: BroadPhase, M: MeshPhase, R: Refiner>
//!   prepare(ObjectModel) -> PreparedObject   (once per object)
//!   query(a, pose_a, b, pose_b, &mut scratch) -> PairReport { state, contacts, stats }
//! ```
//! The defaults are [`bvh_hybrid::HybridBvh`], [`mesh_narrowphase::MeshNarrowphase`] and
//! [`exact_refine::NewtonRefiner`]; naming another type for one parameter swaps that stage only.

mod coherence;
mod merge;
mod options;
mod pipeline;
mod report;

pub use coherence::{CoherenceOptions, ContactId, FrameKind, ISOLATED_POINT_ERROR, PairCache};
pub use options::{ContactOptions, OptionsError, QueryDepth};
pub use pipeline::{ContactPipeline, PreparedObject, QueryError, QueryScratch};
pub use report::{Contact, PairReport, PairState, StageStats};
