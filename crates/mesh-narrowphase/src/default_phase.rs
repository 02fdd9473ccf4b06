//! [`MeshNarrowphase`]: the default [`MeshPhase`], GJK for convex pairs and proxy-mesh collision
//! regions for the rest.

use crate::cones::cone_path::{ConeScratch, cone_path};
use crate::convex::convex_pair::{GjkScratch, HullProximity, WarmStart, hull_proximity};
use crate::mesh_phase::{
    ComponentRef, ContactBand, MeshBoundaryPoint, MeshInputError, MeshOutput, MeshPhase,
    MeshVerdict,
};
use crate::nearest_boundary::{faces_near, nearest_boundary_point};
use crate::pair_key::PairKey;
use crate::prepared_object::PreparedObject;
use crate::proxy::proxy_path::triangle_path;
use crate::query_side::Side;
use crate::triangles::mesh_intersections::TriangleBuffers;
use geom_param::{ComponentKind, DPose3, FeatureLocation, ObjectModel, Seed};
use glam::DVec3;
use std::collections::HashMap;

/// Tuning of [`MeshNarrowphase`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeshNarrowphaseOptions {
    /// Hull distances at or below this fraction of the pair's size (sum of the two components'
    /// largest coordinates plus the distance between their frames) count as touching and go to
    /// the triangle path. Parry's GJK reports touching within about 4e-8 of that size, so the
    /// default is 1e-7.
    pub touching_relative: f64,
    /// How pairs with a concave component (and convex pairs whose hulls overlap) are answered.
    pub concave_path: ConcavePath,
}

impl Default for MeshNarrowphaseOptions {
    fn default() -> Self {
        Self {
            touching_relative: 1e-7,
            concave_path: ConcavePath::default(),
        }
    }
}

/// The two triangle paths of [`MeshNarrowphase`] (see [`MeshPhase`] for both contracts).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ConcavePath {
    /// The default: a simultaneous traversal of the two components' patch trees
    /// ([`crate::cones::patch_tree`], [`crate::cones::cone_traversal`]) that drops node pairs by
    /// distance and normal cones, stops at pairs certified to hold one minimum at most (one seed
    /// each, from second-order models of the exact faces) and tests triangles only where no
    /// certificate holds (apexes, concave creases, flat or conforming contacts, and intersecting
    /// meshes). Its cost follows the geometry of the contacts, not the number of triangles.
    #[default]
    NormalCones,
    /// The paper's proxy meshes: every colliding triangle pair of the mesh-mesh and the
    /// proxy-mesh passes, grouped into connected regions (the `proxy_path` module). Kept for
    /// comparison; its cost grows with the number of triangles near the contacts.
    ProxyRegions,
}

/// The default [`MeshPhase`] (see the trait for the contract).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct MeshNarrowphase {
    /// Tuning.
    pub options: MeshNarrowphaseOptions,
}

/// Caller-owned scratch of [`MeshNarrowphase`]: GJK warm starts per component pair and the
/// buffers of the triangle path. After the first queries of a scene it stops allocating.
#[derive(Debug, Default)]
pub struct MeshScratch {
    warm: HashMap<PairKey, WarmStart>,
    gjk: GjkScratch,
    triangles: TriangleBuffers,
    cone: ConeScratch,
}

impl MeshScratch {
    /// Forgets all warm starts (e.g. after a teleport); buffers are kept.
    pub fn forget_warm_starts(&mut self) {
        self.warm.clear();
        self.cone.fronts.clear();
    }
}

impl MeshPhase for MeshNarrowphase {
    type Prepared = PreparedObject;
    type Scratch = MeshScratch;

    fn prepare(&self, object: &ObjectModel) -> PreparedObject {
        PreparedObject::new(object)
    }

    /// Each component's triangle tree answers in turn ([`nearest_boundary_point`]).
    fn nearest_boundary_point(
        &self,
        object: &ObjectModel,
        prepared: &PreparedObject,
        local_point: DVec3,
        reach: f64,
    ) -> Option<MeshBoundaryPoint> {
        nearest_boundary_point(object, prepared, local_point, reach)
    }

    /// Each component's triangle tree lists its triangles within reach ([`faces_near`]).
    fn faces_near(
        &self,
        object: &ObjectModel,
        prepared: &PreparedObject,
        local_point: DVec3,
        radius: f64,
    ) -> Vec<FeatureLocation> {
        faces_near(object, prepared, local_point, radius)
    }

    fn query(
        &self,
        a: ComponentRef<'_, PreparedObject>,
        b: ComponentRef<'_, PreparedObject>,
        pose_ab: &DPose3,
        band: &ContactBand,
        scratch: &mut MeshScratch,
        out: &mut MeshOutput,
    ) -> MeshVerdict {
        out.clear();
        let sides = band
            .validate()
            .and_then(|()| check_pose(pose_ab))
            .and_then(|()| Ok((Side::resolve(&a)?, Side::resolve(&b)?)));
        let (side_a, side_b) = match sides {
            Ok(s) => s,
            Err(e) => return MeshVerdict::InvalidInput(e),
        };
        let errors = side_a.chordal_error() + side_b.chordal_error();

        let key = (
            std::ptr::from_ref(a.object) as usize,
            a.component.0,
            std::ptr::from_ref(b.object) as usize,
            b.component.0,
        );
        if let (ComponentKind::Convex, ComponentKind::Convex, Some(hull_a), Some(hull_b)) =
            (side_a.kind, side_b.kind, side_a.hull, side_b.hull)
        {
            let warm = scratch.warm.entry(key).or_default();
            let size = side_a.size + side_b.size + pose_ab.translation.length();
            let (proximity, evaluations) = hull_proximity(
                hull_a,
                hull_b,
                pose_ab,
                band.delta2 + errors,
                self.options.touching_relative * size,
                warm,
                &mut scratch.gjk,
            );
            out.stats.gjk_iterations = evaluations;
            match proximity {
                HullProximity::Separated => return MeshVerdict::Separated,
                HullProximity::Close { p1, p2 } => {
                    // A hull point off the surface lies on a facet that caps or bridges the
                    // component (`ComponentKind::Convex`), and says nothing about where its
                    // surface is nearest: the general path answers. (Snapped to the nearest
                    // hull vertex instead, an L-bracket's far corner seeded a minimum at
                    // 0.266 mm and the one at 0.035 mm beside the bridge was missed.)
                    let seed_a = side_a.seed_side.seed_point(p1, on_mesh(&side_a));
                    let seed_b = side_b
                        .seed_side
                        .seed_point(pose_ab.inverse() * p2, on_mesh(&side_b));
                    if let (Some(a), Some(b)) = (seed_a, seed_b) {
                        out.seeds.push(Seed { a, b });
                        return MeshVerdict::Seeds;
                    }
                }
                HullProximity::Overlapping | HullProximity::NotConverged => {}
            }
            out.stats.convex_fallback = true;
        }
        match self.options.concave_path {
            ConcavePath::NormalCones => cone_path(
                (&side_a, &side_b),
                key,
                pose_ab,
                band.delta2,
                errors,
                (&mut scratch.cone, &mut scratch.triangles),
                out,
            ),
            ConcavePath::ProxyRegions => triangle_path(
                &side_a,
                &side_b,
                pose_ab,
                band.delta2,
                errors,
                &mut scratch.triangles,
                out,
            ),
        }
    }
}

/// Within this distance (mm) a GJK point counts as lying on the mesh: the mesh's chordal error
/// (a hull facet that re-triangulates the surface differs from the mesh by less), or a rounding
/// allowance on exactly flat meshes.
fn on_mesh(side: &Side<'_>) -> f64 {
    side.chordal_error().max(1e-9 * side.size)
}

fn check_pose(pose: &DPose3) -> Result<(), MeshInputError> {
    let q = pose.rotation;
    let ok = q.is_finite() && pose.translation.is_finite() && (q.length() - 1.0).abs() <= 1e-6;
    if ok {
        Ok(())
    } else {
        Err(MeshInputError::BadPose)
    }
}
