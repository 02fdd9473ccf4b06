//! Exact contacts inside parry and rapier.
//!
//! - [`ExactShape`]: a prepared exact solid (an `Arc<PreparedObject>` with its pipeline) as a
//!   parry `Shape` (`ShapeType::Custom`): bounding volumes that hold the exact surface, mass
//!   properties from the closed mesh (divergence theorem, error stated), point and ray queries
//!   on that mesh, a CCD thickness measured on it.
//! - [`ExactDispatcher`]: parry's `QueryDispatcher` (intersection test, distance, contact,
//!   closest points) and `PersistentQueryDispatcher` (contact manifolds: one per local
//!   minimum, exact feature ids, the coherence cache kept in the manifold workspace) answered
//!   by the contact pipeline for every pair with an exact shape, parry's `Ball` and `Cuboid`
//!   included as exact spheres and boxes, in either argument order; every other pair goes to
//!   parry's default dispatcher. What the pipeline cannot answer exactly is `Unsupported`, or
//!   on request a stated mesh approximation ([`BeyondReach`]): never a wrong answer.
//!
//! ```text
//! let pipeline = Arc::new(ContactPipeline::new(options)?);          // mm
//! let shape = ExactShape::from_model(Arc::clone(&pipeline), model)?; // SharedShape::new(shape)
//! let dispatcher = ExactDispatcher::new(DispatcherOptions::default());
//! NarrowPhase::with_query_dispatcher(dispatcher)                      // rapier
//! ```
//!
//! Units: parry's length unit is the pipeline's millimetre.

mod closed_mesh;
mod counters;
mod dispatcher;
mod error;
mod exact_shape;
mod feature_ids;
mod manifolds;
mod primitives;

pub use closed_mesh::ClosedMesh;
pub use counters::{DispatchCounters, DispatchCounts, DispatchPath};
pub use dispatcher::{BeyondReach, DispatcherOptions, ExactDispatcher};
pub use error::ShapeError;
pub use exact_shape::ExactShape;
pub use feature_ids::packed_feature;
pub use primitives::{BALL_AXIS, exact_ball, exact_cuboid};
