//! The mesh-only baseline that most users would pick instead of the exact pipeline: mesh each
//! object once into one welded, watertight, outward triangle mesh of about a requested triangle
//! count, and ask parry for contact manifolds between the two meshes.
//!
//! ```text
//! BaselineMesh::new(&solid, 20_000)            (once per object: uniform (u, v) tessellation)
//! MeshOnlyBaseline::contacts(a, pose_a, b, pose_b, prediction) -> Vec<BaselineContact>
//! ```
//! Its contacts are only as good as the meshes: a distance is off by up to the sum of the two
//! meshes' chordal errors ([`BaselineMesh::chordal_error`]), and a penetration shallower than
//! that may not show at all. Units: millimetres; points and normals of contacts are in the
//! world frame.

mod baseline;
mod contact;
mod error;
mod mesh;
mod tessellation;

pub use baseline::MeshOnlyBaseline;
pub use contact::{BaselineContact, nearest_to};
pub use error::BaselineError;
pub use mesh::BaselineMesh;
