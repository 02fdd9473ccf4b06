//! The proxy-mesh triangle path (the paper's Stage 2 for concave pairs, kept selectable as
//! [`crate::ConcavePath::ProxyRegions`]): mesh-mesh intersection, then the proxy of one side
//! against the other's mesh, grouped into connected collision regions whose centres become
//! seeds.

use crate::mesh_phase::{MeshOutput, MeshVerdict, RegionProbes};
use crate::query_side::Side;
use crate::triangles::collision_regions::{group_regions, region_centres, region_extremes};
use crate::triangles::mesh_intersections::{TriangleBuffers, intersect_candidates};
use crate::triangles::plane_filter::clearly_apart;
use geom_param::{ComponentKind, DPose3, Seed};
use glam::DVec3;

/// The proxy offset (mm) for a contact band's `delta2` and the two components' chordal errors
/// `errors` = e_A + e_B, for a proxy of a component of size `size` (mm):
/// `max(delta2, 0) + errors + 1e-9 · size`.
///
/// Why it suffices: two exact points within `delta2` have mesh points within `delta2 + e_A + e_B`
/// (each mesh is within its chordal error of its surface), so the other mesh comes at least that
/// close to this one and, unless the meshes intersect (step 1 of the triangle path), reaches a
/// proxy that stands that far off (see [`crate::proxy::proxy_mesh::ProxyMesh`] for the shell's
/// thickness). A negative `delta2` counts as 0, so that the proxy stays outside the mesh (a contact
/// band below zero is a penetration band, which the mesh-mesh step and Stage 3 handle); the term
/// `1e-9 · size`, far above the rounding of coordinates of magnitude `size` (about 1e-16 · size)
/// yet far below any chordal tolerance a model accepts ([`geom_param::MIN_RELATIVE_TOLERANCE`] =
/// 2e-5 of the object's size), keeps the offset positive on exactly flat meshes (e = 0) with
/// `delta2 <= 0`, and makes a pair exactly at the band's edge still meet the proxy despite the
/// rounding of the offset vertices. The value depends only on the band, the pair's errors and the
/// proxy side's size, so repeated queries of a pair hit the same cached proxy.
fn proxy_offset(delta2: f64, errors: f64, size: f64) -> f64 {
    delta2.max(0.0) + errors + 1e-9 * size
}

/// Mesh-mesh intersection (penetration), else proxy-mesh collision regions (seeds).
pub(crate) fn triangle_path(
    side_a: &Side<'_>,
    side_b: &Side<'_>,
    pose_ab: &DPose3,
    delta2: f64,
    errors: f64,
    scratch: &mut TriangleBuffers,
    out: &mut MeshOutput,
) -> MeshVerdict {
    let (ma, mb) = (side_a.mesh, side_b.mesh);
    let (bvh_a, bvh_b) = (&side_a.prepared.bvh, &side_b.prepared.bvh);

    // 1. The meshes themselves.
    scratch.candidates.clear();
    bvh_a.overlapping_pairs(bvh_b, pose_ab, (0.0, 0.0), &mut scratch.candidates);
    // One seed per region, for the caller to confirm the penetration on the exact surfaces.
    // Then go on to the proxy pass: other contacts of the pair still need their seeds when
    // Stage 3 finds the overlap to be within the chordal errors.
    let meshes_intersect =
        scratch.report_intersecting((side_a, side_b), pose_ab, clearly_apart, out);

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
        (&scratch.candidates, clearly_apart),
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

/// One seed per contact region centre (A's frame), as
/// [`push_region_seeds`](crate::triangles::mesh_intersections::push_region_seeds), each with its
/// [`RegionProbes`]: the region's radius and seeds at the two ends of its loop (`extremes`, from
/// [`region_extremes`]). A region whose centre or ends find no mesh point gets no probes.
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
