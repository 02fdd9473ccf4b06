//! The nearest point of an object's meshes to a point: [`MeshPhase::nearest_boundary_point`]
//! of [`crate::MeshNarrowphase`], the query Stage 3's witness check needs.
//!
//! [`MeshPhase::nearest_boundary_point`]: crate::MeshPhase::nearest_boundary_point

use crate::mesh_phase::MeshBoundaryPoint;
use crate::prepared_object::PreparedObject;
use geom_param::{ComponentId, ObjectModel};
use glam::DVec3;

/// The point of `object`'s component meshes nearest to `local_point` (object frame, mm): each
/// component's triangle tree answers in turn, bounded by the best distance so far. The error
/// bound is the largest chordal error of the components (each mesh is within its chordal error
/// of its surface in the Hausdorff sense). `None` for a non-finite point, prepared data of
/// another object, or an object without triangles.
///
/// Kept out of line: it runs only for penetrating pairs, and must not change how the hot
/// query code around it is compiled.
#[inline(never)]
#[must_use]
pub fn nearest_boundary_point(
    object: &ObjectModel,
    prepared: &PreparedObject,
    local_point: DVec3,
) -> Option<MeshBoundaryPoint> {
    if !local_point.is_finite() || prepared.components.len() != object.meshes.len() {
        return None;
    }
    let error_bound = object
        .meshes
        .iter()
        .map(|m| m.chordal_error)
        .fold(0.0, f64::max);
    let mut best: Option<MeshBoundaryPoint> = None;
    for (i, (component, mesh)) in prepared.components.iter().zip(&object.meshes).enumerate() {
        let reach = best.map_or(f64::MAX, |b| b.distance);
        let found = component
            .bvh
            .nearest(&mesh.positions, &mesh.triangles, local_point, reach);
        if let Some(n) = found.filter(|n| n.distance < reach) {
            best = Some(MeshBoundaryPoint {
                point: n.point,
                distance: n.distance,
                component: ComponentId(u32::try_from(i).ok()?),
                error_bound,
            });
        }
    }
    best
}
