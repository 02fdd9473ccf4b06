//! The mesh half of the dual representation: component meshes and their convex hulls.

pub(crate) mod component_mesh;
pub(crate) mod convex_hull;
pub(crate) mod revolved_mesher;
