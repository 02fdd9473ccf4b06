//! The mesh half of a component's dual representation.

use crate::topology::feature::{FaceId, FeatureLocation};
use glam::DVec3;

/// A triangle mesh of one surface component whose every vertex lies on the exact surface and
/// knows its exact feature, and whose every triangle knows its face and the face parameters of its
/// corners. All positions are in the object frame (mm).
///
/// The mesh is within [`ComponentMesh::chordal_error`] of the exact surface in the Hausdorff
/// sense: every exact point S(u, v) is within that distance of the point with the same barycentric
/// coordinates in the triangle whose corner parameters span (u, v), and vice versa.
#[derive(Clone, Debug, Default)]
pub struct ComponentMesh {
    /// Vertex positions.
    pub positions: Vec<DVec3>,
    /// Unit outward normal per vertex: the exact surface normal, averaged over the faces that
    /// meet at the vertex where it lies on an edge or apex.
    pub normals: Vec<DVec3>,
    /// The exact feature and parameters of each vertex.
    pub vertex_locations: Vec<FeatureLocation>,
    /// Triangles as vertex indices, counter-clockwise seen from outside.
    pub triangles: Vec<[u32; 3]>,
    /// The face each triangle approximates.
    pub triangle_faces: Vec<FaceId>,
    /// The (u, v) of each triangle's corners on its face. Periodic parameters are unwrapped so
    /// that they vary continuously across the triangle (u may exceed the domain's end).
    pub triangle_params: Vec<[[f64; 2]; 3]>,
    /// Measured largest distance between the mesh and the exact surface (mm).
    pub chordal_error: f64,
}

impl ComponentMesh {
    /// The face location of the point with `barycentric` coordinates in triangle `triangle`,
    /// interpolated from the corners' parameters (periodic parameters are already unwrapped per
    /// triangle, so the interpolation is continuous across the seam).
    ///
    /// # Panics
    /// If `triangle` is out of range.
    #[must_use]
    pub fn locate(&self, triangle: usize, barycentric: [f64; 3]) -> FeatureLocation {
        let p = self.triangle_params[triangle];
        let [a, b, c] = barycentric;
        FeatureLocation::Face {
            id: self.triangle_faces[triangle],
            u: a * p[0][0] + b * p[1][0] + c * p[2][0],
            v: a * p[0][1] + b * p[1][1] + c * p[2][1],
        }
    }

    /// The three corner positions of a triangle.
    ///
    /// # Panics
    /// If `triangle` is out of range.
    #[must_use]
    pub fn triangle(&self, triangle: usize) -> [DVec3; 3] {
        self.triangles[triangle].map(|i| self.positions[i as usize])
    }

    /// Number of triangles.
    #[must_use]
    pub fn len(&self) -> usize {
        self.triangles.len()
    }

    /// True when there are no triangles.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.triangles.is_empty()
    }
}
