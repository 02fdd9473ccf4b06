//! Seeds: the hand-over from the mesh phase (Stage 2) to exact refinement (Stage 3).

use crate::topology::feature::{ComponentId, FeatureLocation};
use glam::DVec3;

/// One side of a seed: an approximate closest point and the exact feature it corresponds to.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SeedPoint {
    /// The component the point belongs to.
    pub component: ComponentId,
    /// The approximate point, in its own object's frame (mm). It lies on the component's mesh,
    /// so it is off the exact surface by up to the mesh's chordal error.
    pub local_point: DVec3,
    /// The exact feature and parameters the point corresponds to (interpolated from the mesh
    /// vertices' exact correspondences).
    pub location: FeatureLocation,
}

/// A starting pair for exact refinement: approximately closest points on objects A and B.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Seed {
    /// On object A.
    pub a: SeedPoint,
    /// On object B.
    pub b: SeedPoint,
}
