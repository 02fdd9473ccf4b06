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
//!
//! Across frames and objects:
//! ```text
//! query_coherent(a, pose_a, b, pose_b, &options, &mut PairCache, &mut scratch, &mut report)
//!   -> FrameKind::{Warm, Full}; PairCache::contact_ids()      (coherence: one cache per pair)
//! World::new(pipeline, options); insert(Arc<PreparedObject>, pose, groups) -> ObjectKey;
//!   set_pose / remove; step() (or step_parallel()) -> WorldStats; pairs()   (many objects)
//! ```
//!
//! # Cargo features
//! - `parallel` (default): [`World::step_parallel`] answers a world's pairs on rayon's thread pool, with
//!   the same answers in the same order as [`World::step`] for any number of threads.

pub mod coherence;
mod merge;
mod options;
mod pipeline;
mod report;
pub mod world;

pub use coherence::{
    CoherenceOptions, ContactId, FrameKind, ISOLATED_POINT_ERROR, PairCache, WARM_MAX_ITERATIONS,
    WARM_POINT_TRAVEL,
};
pub use options::{ContactOptions, OptionsError, QueryDepth};
pub use pipeline::{ContactPipeline, PreparedObject, QueryError, QueryScratch};
pub use report::{Contact, PairReport, PairState, StageStats};
pub use world::{Groups, ObjectKey, PairFilter, World, WorldError, WorldPair, WorldStats};
