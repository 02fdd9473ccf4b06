//! The mesh half of the dual representation: component meshes and their convex hulls.

pub(crate) mod component_mesh;
pub(crate) mod convex_hull;
pub(crate) mod edge_sampling;
pub(crate) mod face_boundary;
pub(crate) mod face_metric;
pub(crate) mod face_triangulation;
pub(crate) mod plane_map;
pub(crate) mod revolved_mesher;
pub(crate) mod solid_mesher;
pub(crate) mod surface_extent;
pub(crate) mod vertex_table;
