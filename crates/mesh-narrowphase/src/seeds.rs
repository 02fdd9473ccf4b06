//! Turning approximate closest points into seed points: the mesh point, the exact feature and
//! its parameters.

use crate::triangles::triangle_bvh::TriangleBvh;
use geom_param::{ComponentId, ComponentMesh, SeedPoint};
use glam::DVec3;

/// One component's mesh and tree, in its own object's frame.
#[derive(Clone, Copy, Debug)]
pub struct MeshSide<'a> {
    /// The component.
    pub component: ComponentId,
    /// Its mesh.
    pub mesh: &'a ComponentMesh,
    /// Its triangle tree.
    pub bvh: &'a TriangleBvh,
}

impl MeshSide<'_> {
    /// The seed point for `point` (own frame): the nearest mesh point within `max_distance`, with
    /// the exact location interpolated from its triangle's corner parameters
    /// ([`ComponentMesh::locate`]; periodic u is unwrapped per triangle, and poles use the
    /// triangle's own parameters). `None` when no mesh point is that close.
    #[must_use]
    pub fn seed_point(&self, point: DVec3, max_distance: f64) -> Option<SeedPoint> {
        let near = self.bvh.nearest(
            &self.mesh.positions,
            &self.mesh.triangles,
            point,
            max_distance,
        )?;
        let t = near.triangle as usize;
        (t < self.mesh.triangle_params.len() && t < self.mesh.triangle_faces.len()).then(|| {
            SeedPoint {
                component: self.component,
                local_point: near.point,
                location: self.mesh.locate(t, near.barycentric),
            }
        })
    }
}
