//! The scene's triangles in the world frame: every component mesh of every object, posed.

use crate::run::PreparedScene;
use glam::DVec3;

/// One mesh triangle in the world frame (mm).
#[derive(Clone, Copy, Debug)]
pub(crate) struct WorldTriangle {
    /// Corners, counter-clockwise seen from outside the object.
    pub corners: [DVec3; 3],
    /// Unit outward normal (zero for a degenerate triangle).
    pub normal: DVec3,
    /// Index of its object in the scene.
    pub object: usize,
}

impl WorldTriangle {
    /// Mean of the corners.
    pub fn centroid(&self) -> DVec3 {
        (self.corners[0] + self.corners[1] + self.corners[2]) / 3.0
    }
}

/// Every triangle of every component mesh of every object, moved by the object's pose.
pub(crate) fn world_triangles(scene: &PreparedScene) -> Vec<WorldTriangle> {
    let mut out = Vec::new();
    for (object, (prepared, placed)) in scene.objects.iter().zip(&scene.scene.objects).enumerate() {
        let pose = &placed.pose;
        for component in &prepared.model.components {
            let mesh = prepared.model.mesh(component.id);
            out.extend(mesh.triangles.iter().map(|t| {
                let corners = t.map(|i| *pose * mesh.positions[i as usize]);
                let normal = (corners[1] - corners[0])
                    .cross(corners[2] - corners[0])
                    .normalize_or_zero();
                WorldTriangle {
                    corners,
                    normal,
                    object,
                }
            }));
        }
    }
    out
}

/// The smallest axis-aligned box (mm) holding every corner, as (min, max); `None` without
/// triangles.
pub(crate) fn bounds(triangles: &[WorldTriangle]) -> Option<(DVec3, DVec3)> {
    let mut corners = triangles.iter().flat_map(|t| t.corners);
    let first = corners.next()?;
    Some(corners.fold((first, first), |(lo, hi), p| (lo.min(p), hi.max(p))))
}
