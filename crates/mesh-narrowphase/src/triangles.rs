//! Mesh triangles as both concave paths use them: triangle trees, closest points, exact
//! intersection tests with their floating-point filter, vertex rings, and the grouping of
//! intersecting triangle pairs into connected regions.

pub mod collision_regions;
pub(crate) mod mesh_intersections;
pub mod plane_filter;
pub mod triangle_bvh;
pub mod triangle_distance;
pub mod triangle_intersection;
pub mod triangle_rings;
