//! Intersecting mesh triangles (exact predicates) and what both triangle paths report from
//! them: the intersecting pairs, one witness point per connected region, and one seed per
//! region for Stage 3 to confirm the penetration on the exact surfaces.

use crate::mesh_phase::{MeshOutput, MeshStats};
use crate::query_side::Side;
use crate::triangles::collision_regions::{
    IntersectionSegment, RegionScratch, group_regions, region_centres,
};
#[cfg(doc)]
use crate::triangles::plane_filter::{clearly_apart, planes_apart};
use crate::triangles::triangle_intersection::{TriangleContact, intersect_triangles};
use geom_param::{DPose3, Seed};
use glam::DVec3;

/// Buffers of the triangle tests and of the regions they group into, kept across queries
/// (both concave paths use them).
#[derive(Debug, Default)]
pub(crate) struct TriangleBuffers {
    /// Candidate triangle pairs (A's, B's) of a tree traversal or of leaf pairs.
    pub(crate) candidates: Vec<(u32, u32)>,
    /// The intersection segments of the pairs that intersect.
    pub(crate) segments: Vec<IntersectionSegment>,
    /// The region of each segment.
    pub(crate) region_of: Vec<u32>,
    /// The grouping's own buffers.
    pub(crate) regions: RegionScratch,
    /// Each region's centre p_ci (A's frame).
    pub(crate) centres: Vec<DVec3>,
    /// Each region's radius and the two ends of its loop (A's frame).
    pub(crate) extremes: Vec<(f64, [DVec3; 2])>,
}

impl TriangleBuffers {
    /// The exact test of every pair in `candidates` (A's and B's triangles of the two sides'
    /// meshes, B posed by `pose_ab`) not dropped by `apart` (a floating-point filter that never
    /// drops a pair that meets), and what both triangle paths report of the pairs that
    /// intersect ([`report_mesh_intersections`]). Returns whether any did.
    pub(crate) fn report_intersecting(
        &mut self,
        (side_a, side_b): (&Side<'_>, &Side<'_>),
        pose_ab: &DPose3,
        apart: ApartFilter,
        out: &mut MeshOutput,
    ) -> bool {
        let (ma, mb) = (side_a.mesh, side_b.mesh);
        intersect_candidates(
            (&ma.positions, &ma.triangles),
            (&mb.positions, &mb.triangles),
            pose_ab,
            (&self.candidates, apart),
            &mut self.segments,
            &mut out.stats,
        );
        report_mesh_intersections(
            side_a,
            side_b,
            pose_ab,
            &self.segments,
            &mut self.regions,
            &mut self.region_of,
            out,
        );
        !out.penetrating_pairs.is_empty()
    }
}

/// A floating-point filter in front of the exact triangle test: true only for two triangles the
/// exact test would find disjoint ([`clearly_apart`], [`planes_apart`], [`none_apart`]).
pub(crate) type ApartFilter = fn(&[DVec3; 3], &[DVec3; 3]) -> bool;

/// The filter that drops no pair, for candidates whose triangles have already been tested by
/// separating axes (the normal-cone path's leaf pairs,
/// [`crate::cones::cone_traversal::StopPair::meshes_may_meet`]): every pair goes to the exact
/// test.
pub(crate) fn none_apart(_: &[DVec3; 3], _: &[DVec3; 3]) -> bool {
    false
}

/// Runs the exact triangle test on every candidate pair (B's triangles moved into A's frame)
/// that the filter `apart` leaves, and collects the intersection segments; a coplanar overlap
/// contributes its polygon's edges.
pub(crate) fn intersect_candidates(
    (positions_a, triangles_a): (&[DVec3], &[[u32; 3]]),
    (positions_b, triangles_b): (&[DVec3], &[[u32; 3]]),
    pose_ab: &DPose3,
    (candidates, apart): (&[(u32, u32)], ApartFilter),
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
        // The floating-point filter, then the exact test itself: the candidates the filter
        // leaves mostly meet (a boolean exact test first, the same decision, only doubled their
        // cost).
        if apart(&t1, &t2) {
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

/// The corners of triangle `t`, if its indices resolve.
pub(crate) fn corners(positions: &[DVec3], triangles: &[[u32; 3]], t: u32) -> Option<[DVec3; 3]> {
    let tri = triangles.get(t as usize)?;
    Some([
        *positions.get(tri[0] as usize)?,
        *positions.get(tri[1] as usize)?,
        *positions.get(tri[2] as usize)?,
    ])
}

/// Reports intersecting mesh triangles (`segments`, from [`intersect_candidates`] on the two
/// meshes): every intersecting pair into `out.penetrating_pairs`, one centre per connected
/// region into `out.penetration_centres`, one seed per region (the centre projected onto both
/// meshes) into `out.seeds`, and the region count into the stats. Nothing when `segments` is
/// empty.
pub(crate) fn report_mesh_intersections(
    side_a: &Side<'_>,
    side_b: &Side<'_>,
    pose_ab: &DPose3,
    segments: &[IntersectionSegment],
    regions_scratch: &mut RegionScratch,
    region_of: &mut Vec<u32>,
    out: &mut MeshOutput,
) {
    if segments.is_empty() {
        return;
    }
    out.penetrating_pairs
        .extend(segments.iter().map(|s| (s.a_triangle, s.b_triangle)));
    out.penetrating_pairs.dedup();
    let regions = group_regions(segments, regions_scratch, region_of);
    region_centres(
        segments,
        region_of,
        regions,
        regions_scratch,
        &mut out.penetration_centres,
    );
    out.stats.regions += regions;
    push_region_seeds(
        side_a,
        side_b,
        pose_ab,
        (&out.penetration_centres, segments),
        &mut out.seeds,
    );
}

/// One seed per region centre (A's frame): the centre projected onto both meshes. The
/// intersection segments' ends lie on both meshes, so the nearest of them bounds both
/// searches (plus a rounding allowance): nodes beyond it are never opened.
pub(crate) fn push_region_seeds(
    side_a: &Side<'_>,
    side_b: &Side<'_>,
    pose_ab: &DPose3,
    (centres, segments): (&[DVec3], &[IntersectionSegment]),
    seeds: &mut Vec<Seed>,
) {
    let inverse = pose_ab.inverse();
    for &centre in centres {
        let nearest_end = segments
            .iter()
            .flat_map(|s| [s.start, s.end])
            .map(|p| p.distance(centre))
            .fold(f64::INFINITY, f64::min);
        let bound = if nearest_end.is_finite() {
            nearest_end * (1.0 + 1e-9) + 1e-9 * (side_a.size + side_b.size)
        } else {
            f64::MAX
        };
        let a = side_a.seed_side.seed_point(centre, bound);
        let b = side_b.seed_side.seed_point(inverse * centre, bound);
        if let (Some(a), Some(b)) = (a, b) {
            seeds.push(Seed { a, b });
        }
    }
}
