//! Stage 2: mesh phase — exact narrow-phase tests between the triangles of the meshes of two solids.

pub mod triangle_intersection;
