//! [`MeshNarrowphase`]: the default [`MeshPhase`], GJK for convex pairs and proxy-mesh collision
//! regions for the rest.

use crate::collision_regions::{
    IntersectionSegment, RegionScratch, group_regions, region_centres, region_extremes,
};
use crate::convex_pair::{GjkScratch, HullProximity, WarmStart, hull_proximity};
use crate::mesh_phase::{
    ComponentRef, ContactBand, MeshInputError, MeshOutput, MeshPhase, MeshStats, MeshVerdict,
    RegionProbes,
};
use crate::plane_filter::clearly_apart;
use crate::prepared_object::{PreparedComponent, PreparedObject};
use crate::seeds::MeshSide;
use crate::triangle_intersection::{TriangleContact, intersect_triangles, triangles_intersect};
use geom_param::{ComponentKind, ComponentMesh, ConvexHull, DPose3, ObjectModel, Seed};
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
}

impl Default for MeshNarrowphaseOptions {
    fn default() -> Self {
        Self {
            touching_relative: 1e-7,
        }
    }
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
    candidates: Vec<(u32, u32)>,
    segments: Vec<IntersectionSegment>,
    region_of: Vec<u32>,
    regions: RegionScratch,
    centres: Vec<DVec3>,
    extremes: Vec<(f64, [DVec3; 2])>,
}

impl MeshScratch {
    /// Forgets all warm starts (e.g. after a teleport); buffers are kept.
    pub fn forget_warm_starts(&mut self) {
        self.warm.clear();
    }
}

/// A component pair, by object address and component index (warm starts are per ordered pair).
type PairKey = (usize, u32, usize, u32);

/// One side of a query, resolved.
struct Side<'a> {
    mesh: &'a ComponentMesh,
    prepared: &'a PreparedComponent,
    hull: Option<&'a ConvexHull>,
    kind: ComponentKind,
    seed_side: MeshSide<'a>,
    size: f64,
}

impl<'a> Side<'a> {
    fn resolve(c: &ComponentRef<'a, PreparedObject>) -> Result<Self, MeshInputError> {
        let object = c.object;
        let i = c.component.0 as usize;
        if c.prepared.components.len() != object.meshes.len() {
            return Err(MeshInputError::PreparedMismatch);
        }
        let (Some(mesh), Some(prepared), Some(component)) = (
            object.meshes.get(i),
            c.prepared.components.get(i),
            object.components.get(i),
        ) else {
            return Err(MeshInputError::NoSuchComponent {
                component: c.component,
                count: object.components.len(),
            });
        };
        Ok(Self {
            mesh,
            prepared,
            hull: object.hulls.get(i).and_then(Option::as_ref),
            kind: component.kind,
            seed_side: MeshSide {
                component: c.component,
                mesh,
                bvh: &prepared.bvh,
            },
            size: prepared.size,
        })
    }

    fn chordal_error(&self) -> f64 {
        let e = self.mesh.chordal_error;
        if e.is_finite() { e.max(0.0) } else { 0.0 }
    }
}

impl MeshPhase for MeshNarrowphase {
    type Prepared = PreparedObject;
    type Scratch = MeshScratch;

    fn prepare(&self, object: &ObjectModel) -> PreparedObject {
        PreparedObject::new(object)
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

        if let (ComponentKind::Convex, ComponentKind::Convex, Some(hull_a), Some(hull_b)) =
            (side_a.kind, side_b.kind, side_a.hull, side_b.hull)
        {
            let key = (
                std::ptr::from_ref(a.object) as usize,
                a.component.0,
                std::ptr::from_ref(b.object) as usize,
                b.component.0,
            );
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
                    let g = &scratch.gjk;
                    let inverse = pose_ab.inverse();
                    let on_b = g.on_b.map(|p| inverse * p);
                    let seed_a =
                        side_a
                            .seed_side
                            .seed_point_on_hull(p1, &g.on_a[..g.len], on_mesh(&side_a));
                    let seed_b = side_b.seed_side.seed_point_on_hull(
                        inverse * p2,
                        &on_b[..g.len],
                        on_mesh(&side_b),
                    );
                    if let (Some(a), Some(b)) = (seed_a, seed_b) {
                        out.seeds.push(Seed { a, b });
                        return MeshVerdict::Seeds;
                    }
                }
                HullProximity::Overlapping | HullProximity::NotConverged => {}
            }
            out.stats.convex_fallback = true;
        }
        triangle_path(&side_a, &side_b, pose_ab, band.delta2, errors, scratch, out)
    }
}

/// The proxy offset (mm) for a contact band's `delta2` and the two components' chordal errors
/// `errors` = e_A + e_B, for a proxy of a component of size `size` (mm):
/// `max(delta2, 0) + errors + 1e-9 · size`.
///
/// Why it suffices: two exact points within `delta2` have mesh points within
/// `delta2 + e_A + e_B` (each mesh is within its chordal error of its surface), so the other
/// mesh comes at least that close to this one and, unless the meshes intersect (step 1 of the
/// triangle path), reaches a proxy that stands that far off (see [`crate::proxy_mesh::ProxyMesh`]
/// for the shell's thickness). A negative `delta2` counts as 0, so that the proxy stays outside
/// the mesh (a contact band below zero is a penetration band, which the mesh-mesh step and
/// Stage 3 handle); the term `1e-9 · size`, far above the rounding of coordinates of magnitude
/// `size` (about 1e-16 · size) yet far below any chordal tolerance a model accepts
/// ([`geom_param::MIN_RELATIVE_TOLERANCE`] = 2e-5 of the object's size),
/// keeps the offset positive on exactly flat meshes (e = 0) with `delta2 <= 0`, and makes a
/// pair exactly at the band's edge still meet the proxy despite the rounding of the offset
/// vertices. The value depends only on the band, the pair's errors and the proxy side's size,
/// so repeated queries of a pair hit the same cached proxy.
fn proxy_offset(delta2: f64, errors: f64, size: f64) -> f64 {
    delta2.max(0.0) + errors + 1e-9 * size
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

/// Mesh-mesh intersection (penetration), else proxy-mesh collision regions (seeds).
fn triangle_path(
    side_a: &Side<'_>,
    side_b: &Side<'_>,
    pose_ab: &DPose3,
    delta2: f64,
    errors: f64,
    scratch: &mut MeshScratch,
    out: &mut MeshOutput,
) -> MeshVerdict {
    let (ma, mb) = (side_a.mesh, side_b.mesh);
    let (bvh_a, bvh_b) = (&side_a.prepared.bvh, &side_b.prepared.bvh);

    // 1. The meshes themselves.
    scratch.candidates.clear();
    bvh_a.overlapping_pairs(bvh_b, pose_ab, (0.0, 0.0), &mut scratch.candidates);
    intersect_candidates(
        (&ma.positions, &ma.triangles),
        (&mb.positions, &mb.triangles),
        pose_ab,
        &scratch.candidates,
        &mut scratch.segments,
        &mut out.stats,
    );
    if !scratch.segments.is_empty() {
        out.penetrating_pairs.extend(
            scratch
                .segments
                .iter()
                .map(|s| (s.a_triangle, s.b_triangle)),
        );
        out.penetrating_pairs.dedup();
        let regions = group_regions(
            &scratch.segments,
            &mut scratch.regions,
            &mut scratch.region_of,
        );
        region_centres(
            &scratch.segments,
            &scratch.region_of,
            regions,
            &mut scratch.regions,
            &mut out.penetration_centres,
        );
        out.stats.regions = regions;
        // One seed per region, for the caller to confirm the penetration on the exact surfaces.
        push_region_seeds(
            side_a,
            side_b,
            pose_ab,
            &out.penetration_centres,
            &mut out.seeds,
        );
        // Go on to the proxy pass: other contacts of the pair still need their seeds when
        // Stage 3 finds the overlap to be within the chordal errors.
    }
    let meshes_intersect = !out.penetrating_pairs.is_empty();

    // 2. The proxy of one side against the other's mesh: the concave side, A when both or
    // neither are.
    let proxy_on_a =
        !(side_a.kind == ComponentKind::Convex && side_b.kind == ComponentKind::Concave);
    let proxy_side = if proxy_on_a { side_a } else { side_b };
    let offset = proxy_offset(delta2, errors, proxy_side.size);
    let (proxy, built) = proxy_side
        .prepared
        .proxies
        .get_or_build(proxy_side.mesh, offset);
    out.stats.proxy_built = built;
    scratch.candidates.clear();
    let (positions_a, positions_b) = if proxy_on_a {
        proxy
            .bvh
            .overlapping_pairs(bvh_b, pose_ab, (0.0, 0.0), &mut scratch.candidates);
        (&proxy.positions[..], &mb.positions[..])
    } else {
        bvh_a.overlapping_pairs(&proxy.bvh, pose_ab, (0.0, 0.0), &mut scratch.candidates);
        (&ma.positions[..], &proxy.positions[..])
    };
    intersect_candidates(
        (positions_a, &ma.triangles),
        (positions_b, &mb.triangles),
        pose_ab,
        &scratch.candidates,
        &mut scratch.segments,
        &mut out.stats,
    );
    if scratch.segments.is_empty() {
        return if meshes_intersect {
            MeshVerdict::Penetrating
        } else {
            MeshVerdict::Separated
        };
    }
    let regions = group_regions(
        &scratch.segments,
        &mut scratch.regions,
        &mut scratch.region_of,
    );
    out.stats.regions += regions;
    scratch.centres.clear();
    region_centres(
        &scratch.segments,
        &scratch.region_of,
        regions,
        &mut scratch.regions,
        &mut scratch.centres,
    );
    scratch.extremes.clear();
    region_extremes(
        &scratch.segments,
        &scratch.region_of,
        &scratch.centres,
        &mut scratch.regions,
        &mut scratch.extremes,
    );
    push_contact_region_seeds(
        side_a,
        side_b,
        pose_ab,
        &scratch.centres,
        &scratch.extremes,
        out,
    );
    if meshes_intersect {
        MeshVerdict::Penetrating
    } else if out.seeds.is_empty() {
        MeshVerdict::Separated
    } else {
        MeshVerdict::Seeds
    }
}

/// One seed per region centre (A's frame): the centre projected onto both meshes.
fn push_region_seeds(
    side_a: &Side<'_>,
    side_b: &Side<'_>,
    pose_ab: &DPose3,
    centres: &[DVec3],
    seeds: &mut Vec<Seed>,
) {
    let inverse = pose_ab.inverse();
    for &centre in centres {
        let a = side_a.seed_side.seed_point(centre, f64::MAX);
        let b = side_b.seed_side.seed_point(inverse * centre, f64::MAX);
        if let (Some(a), Some(b)) = (a, b) {
            seeds.push(Seed { a, b });
        }
    }
}

/// One seed per contact region centre (A's frame), as [`push_region_seeds`], each with its
/// [`RegionProbes`]: the region's radius and seeds at the two ends of its loop (`extremes`,
/// from [`region_extremes`]). A region whose centre or ends find no mesh point gets no probes.
fn push_contact_region_seeds(
    side_a: &Side<'_>,
    side_b: &Side<'_>,
    pose_ab: &DPose3,
    centres: &[DVec3],
    extremes: &[(f64, [DVec3; 2])],
    out: &mut MeshOutput,
) {
    let inverse = pose_ab.inverse();
    let seed = |p: DVec3| {
        let a = side_a.seed_side.seed_point(p, f64::MAX)?;
        let b = side_b.seed_side.seed_point(inverse * p, f64::MAX)?;
        Some(Seed { a, b })
    };
    for (&centre, &(radius, ends)) in centres.iter().zip(extremes) {
        let Some(centre_seed) = seed(centre) else {
            continue;
        };
        out.seeds.push(centre_seed);
        if let (Some(e1), Some(e2)) = (seed(ends[0]), seed(ends[1])) {
            out.probes.push(RegionProbes {
                centre_seed: out.seeds.len() - 1,
                centre,
                radius,
                ends: [e1, e2],
            });
        }
    }
}

/// Runs the exact triangle test on every candidate pair (B's triangles moved into A's frame)
/// and collects the intersection segments; a coplanar overlap contributes its polygon's edges.
fn intersect_candidates(
    (positions_a, triangles_a): (&[DVec3], &[[u32; 3]]),
    (positions_b, triangles_b): (&[DVec3], &[[u32; 3]]),
    pose_ab: &DPose3,
    candidates: &[(u32, u32)],
    segments: &mut Vec<IntersectionSegment>,
    stats: &mut MeshStats,
) {
    segments.clear();
    for &(ta, tb) in candidates {
        let (Some(t1), Some(t2)) = (
            corners(positions_a, triangles_a, ta),
            corners(positions_b, triangles_b, tb),
        ) else {
            continue;
        };
        let t2 = t2.map(|p| *pose_ab * p);
        stats.triangle_pairs_tested = stats.triangle_pairs_tested.saturating_add(1);
        // A floating-point plane filter, then the boolean exact test (same decision as the full
        // one without computing points): cheaper for the many candidates that do not meet.
        if clearly_apart(&t1, &t2) || !triangles_intersect(&t1, &t2) {
            continue;
        }
        let segment = |start, end| IntersectionSegment {
            a_triangle: ta,
            b_triangle: tb,
            start,
            end,
        };
        match intersect_triangles(&t1, &t2) {
            TriangleContact::Disjoint => {}
            TriangleContact::Segment { a, b } => segments.push(segment(a, b)),
            TriangleContact::Coplanar { points } => {
                let n = points.len();
                segments.extend((0..n).map(|i| segment(points[i], points[(i + 1) % n])));
            }
        }
    }
}

fn corners(positions: &[DVec3], triangles: &[[u32; 3]], t: u32) -> Option<[DVec3; 3]> {
    let tri = triangles.get(t as usize)?;
    Some([
        *positions.get(tri[0] as usize)?,
        *positions.get(tri[1] as usize)?,
        *positions.get(tri[2] as usize)?,
    ])
}
