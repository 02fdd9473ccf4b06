//! The nearest point of an object's meshes to a point, and the faces whose meshes come near it:
//! [`MeshPhase::nearest_boundary_point`] and [`MeshPhase::faces_near`] of
//! [`crate::MeshNarrowphase`], the queries Stage 3's witness check needs.
//!
//! [`MeshPhase::nearest_boundary_point`]: crate::MeshPhase::nearest_boundary_point
//! [`MeshPhase::faces_near`]: crate::MeshPhase::faces_near

use crate::mesh_phase::MeshBoundaryPoint;
use crate::prepared_object::PreparedObject;
use geom_param::{ComponentId, FeatureLocation, ObjectModel};
use glam::DVec3;

/// The point of `object`'s component meshes nearest to `local_point` (object frame, mm), when
/// one lies within `reach` + the error bound: each component's triangle tree answers in turn,
/// bounded by that and then by the best distance so far. The error bound is the largest
/// chordal error of the components (each mesh is within its chordal error of its surface in
/// the Hausdorff sense). When no mesh point is that near, the answer has distance +∞ (see
/// [`MeshBoundaryPoint`]). `None` for a non-finite point, prepared data of another object, or
/// an object without triangles.
///
/// Why the reach: a penetration witness's check asks only whether a boundary comes nearer
/// than the depth, and a search bounded by it skips the subtrees farther off (unbounded, the
/// check was a sixth of a pencil-through-bowl query).
///
/// Kept out of line: it runs only for penetrating pairs, and must not change how the hot
/// query code around it is compiled.
#[inline(never)]
#[must_use]
pub fn nearest_boundary_point(
    object: &ObjectModel,
    prepared: &PreparedObject,
    local_point: DVec3,
    reach: f64,
) -> Option<MeshBoundaryPoint> {
    if !local_point.is_finite()
        || prepared.components.len() != object.meshes.len()
        || object.meshes.iter().all(|m| m.triangles.is_empty())
    {
        return None;
    }
    let error_bound = object
        .meshes
        .iter()
        .map(|m| m.chordal_error)
        .fold(0.0, f64::max);
    let mut best: Option<MeshBoundaryPoint> = None;
    // (A NaN reach seeks everything, as +∞ does: `min` drops the NaN.)
    let sought = (reach + error_bound).min(f64::MAX);
    for (i, (component, mesh)) in prepared.components.iter().zip(&object.meshes).enumerate() {
        let reach = best.map_or(sought, |b| b.distance);
        let found = component
            .bvh
            .nearest(&mesh.positions, &mesh.triangles, local_point, reach);
        if let Some(n) = found.filter(|n| n.distance < reach) {
            best = Some(MeshBoundaryPoint {
                point: n.point,
                distance: n.distance,
                component: Some(ComponentId(u32::try_from(i).ok()?)),
                error_bound,
            });
        }
    }
    Some(best.unwrap_or(MeshBoundaryPoint {
        point: local_point,
        distance: f64::INFINITY,
        component: None,
        error_bound,
    }))
}

/// Every face whose mesh comes within `radius` (mm) of `local_point` (object frame), each once,
/// at the exact parameters of the nearest point of its triangles ([`MeshPhase::faces_near`]).
/// Empty for a non-finite point or prepared data of another object.
///
/// Kept out of line like [`nearest_boundary_point`].
///
/// [`MeshPhase::faces_near`]: crate::MeshPhase::faces_near
#[inline(never)]
#[must_use]
pub fn faces_near(
    object: &ObjectModel,
    prepared: &PreparedObject,
    local_point: DVec3,
    radius: f64,
) -> Vec<FeatureLocation> {
    let mut nearest: Vec<(f64, FeatureLocation)> = Vec::new();
    if prepared.components.len() != object.meshes.len() {
        return Vec::new();
    }
    for (component, mesh) in prepared.components.iter().zip(&object.meshes) {
        component.bvh.within(
            &mesh.positions,
            &mesh.triangles,
            local_point,
            radius,
            |n| {
                let triangle = n.triangle as usize;
                let (Some(&face), true) = (
                    mesh.triangle_faces.get(triangle),
                    triangle < mesh.triangle_params.len(),
                ) else {
                    return;
                };
                let location = mesh.locate(triangle, n.barycentric);
                let same_face = |l: &FeatureLocation| {
                    matches!(l, FeatureLocation::Face { id, .. } if *id == face)
                };
                match nearest.iter_mut().find(|(_, l)| same_face(l)) {
                    Some(best) if n.distance < best.0 => *best = (n.distance, location),
                    Some(_) => {}
                    None => nearest.push((n.distance, location)),
                }
            },
        );
    }
    nearest.into_iter().map(|(_, l)| l).collect()
}
