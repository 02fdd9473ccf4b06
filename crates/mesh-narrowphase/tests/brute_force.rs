//! Against brute force over all triangle pairs, on random poses: the proxy path finds every
//! colliding triangle pair; the normal-cone path reports only true ones, never calls
//! intersecting meshes separated, and seeds the meshes' closest pair whenever it is within the
//! band; and refused inputs.

mod common;

use common::*;
use geom_param::{ComponentId, DPose3, DQuat, DVec3, ObjectModel};
use mesh_narrowphase::triangles::triangle_intersection::triangles_intersect;
use mesh_narrowphase::{ConcavePath, ContactBand, MeshInputError, MeshScratch, MeshVerdict};
use parry3d_f64::query::{ClosestPoints, closest_points};
use parry3d_f64::shape::Triangle;

fn band() -> ContactBand {
    ContactBand {
        margin: 1.0,
        delta1: -0.05,
        delta2: 0.3,
    }
}

/// All intersecting pairs by testing every triangle of `a` against every triangle of `b`
/// (B's positions moved by `pose`).
fn brute_force(
    positions_a: &[DVec3],
    triangles_a: &[[u32; 3]],
    positions_b: &[DVec3],
    triangles_b: &[[u32; 3]],
    pose: &DPose3,
) -> Vec<(u32, u32)> {
    let moved: Vec<DVec3> = positions_b.iter().map(|p| *pose * *p).collect();
    let mut out = Vec::new();
    for (i, ta) in triangles_a.iter().enumerate() {
        let t1 = ta.map(|k| positions_a[k as usize]);
        for (j, tb) in triangles_b.iter().enumerate() {
            let t2 = tb.map(|k| moved[k as usize]);
            if triangles_intersect(&t1, &t2) {
                out.push((i as u32, j as u32));
            }
        }
    }
    out
}

/// A random rotation, and a translation that puts a random vertex of B within `reach` of a
/// random vertex of A (so that the meshes often meet).
fn random_pose(rng: &mut Rng, a: &[DVec3], b: &[DVec3], reach: f64) -> DPose3 {
    let rotation = rng.rotation();
    let pa = a[(rng.next_u64() % a.len() as u64) as usize];
    let pb = b[(rng.next_u64() % b.len() as u64) as usize];
    let offset = rng.rotation() * DVec3::new(rng.range(0.0, reach), 0.0, 0.0);
    pose(rotation, pa - rotation * pb + offset)
}

fn check_pairs(
    a: &Prepared,
    ca: ComponentId,
    b: &Prepared,
    cb: ComponentId,
    seed: u64,
    reach: f64,
) {
    let mut rng = Rng(seed);
    let mut scratch = MeshScratch::default();
    let (ma, mb): (&ObjectModel, &ObjectModel) = (&a.object, &b.object);
    let (mesh_a, mesh_b) = (ma.mesh(ca), mb.mesh(cb));
    let mut penetrating = 0;
    let mut proxy_hits = 0;
    for _ in 0..8 {
        let pose = random_pose(&mut rng, &mesh_a.positions, &mesh_b.positions, reach);
        // Mesh against mesh, through the query.
        let truth = brute_force(
            &mesh_a.positions,
            &mesh_a.triangles,
            &mesh_b.positions,
            &mesh_b.triangles,
            &pose,
        );
        let (verdict, out) = query_path(
            ConcavePath::ProxyRegions,
            (a, ca),
            (b, cb),
            &pose,
            &band(),
            &mut scratch,
        );
        if truth.is_empty() {
            assert_ne!(verdict, MeshVerdict::Penetrating);
        } else {
            assert_eq!(verdict, MeshVerdict::Penetrating);
            let mut got = out.penetrating_pairs.clone();
            got.sort_unstable();
            got.dedup();
            assert_eq!(got, truth);
            penetrating += 1;
        }
        // The normal-cone path stops at certified patch pairs without testing their
        // triangles, so it reports a subset, and intersecting meshes are never "separated".
        let (verdict, out) = query_path(
            ConcavePath::NormalCones,
            (a, ca),
            (b, cb),
            &pose,
            &band(),
            &mut scratch,
        );
        for pair in &out.penetrating_pairs {
            assert!(
                truth.binary_search(pair).is_ok(),
                "{pair:?} does not intersect"
            );
        }
        if !truth.is_empty() {
            assert_ne!(verdict, MeshVerdict::Separated);
        }
        // Each side's proxy against the other's mesh, through the public tree API.
        let offset = 0.7;
        let (tree_a, tree_b) = (
            &a.prepared.components[ca.0 as usize].bvh,
            &b.prepared.components[cb.0 as usize].bvh,
        );
        let (proxy_a, _) = a.prepared.components[ca.0 as usize]
            .proxies
            .get_or_build(mesh_a, offset);
        let (proxy_b, _) = b.prepared.components[cb.0 as usize]
            .proxies
            .get_or_build(mesh_b, offset);
        let mut any = false;
        for (positions_a, positions_b, tree_a, tree_b) in [
            (&proxy_a.positions, &mesh_b.positions, &proxy_a.bvh, tree_b),
            (&mesh_a.positions, &proxy_b.positions, tree_a, &proxy_b.bvh),
        ] {
            let truth = brute_force(
                positions_a,
                &mesh_a.triangles,
                positions_b,
                &mesh_b.triangles,
                &pose,
            );
            let mut candidates = Vec::new();
            tree_a.overlapping_pairs(tree_b, &pose, (0.0, 0.0), &mut candidates);
            let moved: Vec<DVec3> = positions_b.iter().map(|p| pose * *p).collect();
            let mut got: Vec<(u32, u32)> = candidates
                .into_iter()
                .filter(|&(i, j)| {
                    let t1 = mesh_a.triangles[i as usize].map(|k| positions_a[k as usize]);
                    let t2 = mesh_b.triangles[j as usize].map(|k| moved[k as usize]);
                    triangles_intersect(&t1, &t2)
                })
                .collect();
            got.sort_unstable();
            assert_eq!(got, truth);
            any |= !truth.is_empty();
        }
        proxy_hits += usize::from(any);
    }
    println!("penetrating poses {penetrating}, proxy-hit poses {proxy_hits}");
    assert!(
        penetrating >= 3 && proxy_hits >= 3,
        "too few colliding poses to be a test"
    );
}

#[test]
fn torus_and_cylinder_pairs_match_brute_force() {
    let ring = Prepared::new(torus(20.0, 5.0, 0.1));
    let rod = Prepared::new(cylinder(4.0, 50.0, 0.1));
    let (cr, cc) = (ring.object.components[0].id, rod.object.components[0].id);
    check_pairs(&ring, cr, &rod, cc, 11, 3.0);
}

#[test]
fn vase_pairs_match_brute_force() {
    let vase = Prepared::new(paper_object("vase", 0.2));
    let bowl = Prepared::new(paper_object("bowl", 0.2));
    for (ca, cb) in [(1, 0), (0, 1), (2, 1)] {
        let (ca, cb) = (ComponentId(ca), ComponentId(cb));
        check_pairs(&vase, ca, &bowl, cb, 5 + u64::from(ca.0), 3.0);
    }
}

#[test]
fn unusable_inputs_are_refused() {
    let a = Prepared::new(sphere(10.0, 0.1));
    let c = a.object.components[0].id;
    let mut scratch = MeshScratch::default();
    let ok = pose(DQuat::IDENTITY, DVec3::new(20.1, 0.0, 0.0));
    let nan = pose(DQuat::IDENTITY, DVec3::new(f64::NAN, 0.0, 0.0));
    let (verdict, out) = query(&a, c, &a, c, &nan, &band(), &mut scratch);
    assert_eq!(verdict, MeshVerdict::InvalidInput(MeshInputError::BadPose));
    assert!(out.seeds.is_empty());
    let scaled = pose(DQuat::from_xyzw(0.0, 0.0, 0.0, 2.0), DVec3::X * 30.0);
    let (verdict, _) = query(&a, c, &a, c, &scaled, &band(), &mut scratch);
    assert_eq!(verdict, MeshVerdict::InvalidInput(MeshInputError::BadPose));
    let bad = ContactBand {
        margin: 0.1,
        delta1: 0.0,
        delta2: 0.3,
    };
    let (verdict, _) = query(&a, c, &a, c, &ok, &bad, &mut scratch);
    assert_eq!(
        verdict,
        MeshVerdict::InvalidInput(MeshInputError::BadBand { band: bad })
    );
    let (verdict, _) = query(&a, ComponentId(7), &a, c, &ok, &band(), &mut scratch);
    assert_eq!(
        verdict,
        MeshVerdict::InvalidInput(MeshInputError::NoSuchComponent {
            component: ComponentId(7),
            count: 1
        })
    );
    let (verdict, _) = query(&a, c, &a, c, &ok, &band(), &mut scratch);
    assert_eq!(verdict, MeshVerdict::Seeds);
}

#[test]
fn plane_filter_never_contradicts_the_exact_test() {
    use mesh_narrowphase::triangles::plane_filter::clearly_apart;
    let mut rng = Rng(99);
    let mut apart = 0;
    for k in 0..200_000 {
        // Triangles around a shared random point, scaled from 1e-3 to 1e3, many of them touching
        // or nearly touching (a corner of one on or just off the other's plane).
        let scale = 10f64.powf(rng.range(-3.0, 3.0));
        let centre = DVec3::new(
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
        ) * 100.0;
        let mut corner = || centre + rng.rotation() * DVec3::X * scale * rng.unit();
        let t1 = [corner(), corner(), corner()];
        let mut t2 = [corner(), corner(), corner()];
        if k % 2 == 0 {
            // Put a corner of t2 (almost) on t1's plane.
            let n = (t1[1] - t1[0]).cross(t1[2] - t1[0]).normalize_or_zero();
            let d = n.dot(t2[0] - t1[0]);
            t2[0] -= n * d * (1.0 - 1e-13 * f64::from(k % 7));
        }
        if clearly_apart(&t1, &t2) {
            apart += 1;
            assert!(
                !triangles_intersect(&t1, &t2),
                "filter says apart: {t1:?} {t2:?}"
            );
        }
    }
    assert!(apart > 10_000, "the filter never fired: {apart}");
}

/// How two meshes lie, by brute force.
enum Closest {
    /// Some triangles intersect.
    Intersecting,
    /// No pair is within the reach.
    Far,
    /// The closest pair: distance and points (A's frame).
    Pair(f64, DVec3, DVec3),
}

/// The closest pair of points between the two meshes (B's positions moved by `pose`), by brute
/// force: every triangle pair whose boxes are within `reach`, measured by parry's GJK (code this
/// crate does not share).
fn brute_closest(
    (positions_a, triangles_a): (&[DVec3], &[[u32; 3]]),
    (positions_b, triangles_b): (&[DVec3], &[[u32; 3]]),
    pose: &DPose3,
    reach: f64,
) -> Closest {
    let moved: Vec<DVec3> = positions_b.iter().map(|p| *pose * *p).collect();
    let boxes = |positions: &[DVec3], triangles: &[[u32; 3]]| -> Vec<(DVec3, DVec3, [DVec3; 3])> {
        triangles
            .iter()
            .map(|t| {
                let c = t.map(|k| positions[k as usize]);
                (c[0].min(c[1]).min(c[2]), c[0].max(c[1]).max(c[2]), c)
            })
            .collect()
    };
    let (ba, bb) = (boxes(positions_a, triangles_a), boxes(&moved, triangles_b));
    let mut best: Option<(f64, DVec3, DVec3)> = None;
    for (lo_a, hi_a, ta) in &ba {
        for (lo_b, hi_b, tb) in &bb {
            let gap = (*lo_b - *hi_a).max(*lo_a - *hi_b).max(DVec3::ZERO).length();
            if gap > reach {
                continue;
            }
            if triangles_intersect(ta, tb) {
                return Closest::Intersecting;
            }
            let identity = DPose3::IDENTITY;
            let (t1, t2) = (
                Triangle::new(ta[0], ta[1], ta[2]),
                Triangle::new(tb[0], tb[1], tb[2]),
            );
            if let Ok(ClosestPoints::WithinMargin(p, q)) =
                closest_points(&identity, &t1, &identity, &t2, reach)
            {
                let d = p.distance(q);
                if best.is_none_or(|b| d < b.0) {
                    best = Some((d, p, q));
                }
            }
        }
    }
    best.map_or(Closest::Far, |(d, p, q)| Closest::Pair(d, p, q))
}

/// All of an object's component meshes as one triangle soup.
fn whole_mesh(object: &ObjectModel) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    for m in &object.meshes {
        let base = positions.len() as u32;
        positions.extend_from_slice(&m.positions);
        triangles.extend(m.triangles.iter().map(|t| t.map(|k| k + base)));
    }
    (positions, triangles)
}

/// On poses built to put the two objects' closest mesh pair at a gap in
/// [0, delta2 - e_A - e_B] (B moved along the pair's direction, then measured again), the
/// normal-cone path, asked about every component pair, seeds that pair: some seed has both
/// points within `tolerance` (mm) of it. At that gap the exact surfaces are within delta2 of
/// each other (each mesh lies within its chordal error of its surface), and the closest mesh
/// pair lies next to the exact solids' closest pair, a critical pair of their distance, which a
/// lost contact would leave unseeded. (A mesh pair within delta2 alone proves nothing: the
/// exact surfaces may be up to e_A + e_B farther apart, and the path decides on them; and the
/// check is on whole objects because a component pair's own closest pair may sit on the
/// component's boundary without being critical for the solids.)
fn check_minima(a: &Prepared, b: &Prepared, seed: u64, tolerance: f64) {
    let mut rng = Rng(seed);
    let mut scratch = MeshScratch::default();
    let (mesh_a, mesh_b) = (whole_mesh(&a.object), whole_mesh(&b.object));
    let (mesh_a, mesh_b) = (
        (&mesh_a.0[..], &mesh_a.1[..]),
        (&mesh_b.0[..], &mesh_b.1[..]),
    );
    let band = ContactBand {
        margin: 1.0,
        delta1: -0.05,
        delta2: 1.0,
    };
    let error = |o: &ObjectModel| o.meshes.iter().map(|m| m.chordal_error).fold(0.0, f64::max);
    let sure = band.delta2 - error(&a.object) - error(&b.object);
    assert!(sure > 0.2, "meshes too coarse for the band");
    let mut checked = 0;
    for _ in 0..24 {
        let mut pose = random_pose(&mut rng, mesh_a.0, mesh_b.0, 3.0);
        // B backs off along a random direction while the meshes intersect, and comes back
        // along it while they are far apart, in steps of 1 mm.
        let away = rng.rotation() * DVec3::X;
        let mut start = None;
        for _ in 0..60 {
            match brute_closest(mesh_a, mesh_b, &pose, 2.0) {
                Closest::Intersecting => pose.translation += away,
                Closest::Far => pose.translation -= away * 0.5,
                Closest::Pair(_, p, q) => {
                    start = Some((p, q));
                    break;
                }
            }
        }
        let Some((p, q)) = start else {
            continue;
        };
        let gap = rng.range(0.0, sure);
        pose.translation += (q - p).normalize_or_zero() * (gap - p.distance(q));
        let Closest::Pair(d, p, q) = brute_closest(mesh_a, mesh_b, &pose, sure) else {
            continue;
        };
        let mut seeds = Vec::new();
        for ca in &a.object.components {
            for cb in &b.object.components {
                let (_, out) = query_path(
                    ConcavePath::NormalCones,
                    (a, ca.id),
                    (b, cb.id),
                    &pose,
                    &band,
                    &mut scratch,
                );
                seeds.extend(out.seeds);
            }
        }
        let seeded = seeds.iter().any(|s| {
            s.a.local_point.distance(p) <= tolerance
                && (pose * s.b.local_point).distance(q) <= tolerance
        });
        assert!(
            seeded,
            "no seed within {tolerance} of the closest pair {p} / {q} at {d} (pose {pose:?}): \
             {seeds:?}"
        );
        checked += 1;
    }
    println!("{checked} poses with the closest pair in the band");
    assert!(checked >= 6, "too few poses in the band to be a test");
}

#[test]
fn the_closest_pair_of_torus_and_cylinder_is_seeded() {
    let ring = Prepared::new(torus(20.0, 5.0, 0.1));
    let rod = Prepared::new(cylinder(4.0, 50.0, 0.1));
    check_minima(&ring, &rod, 21, 2.0);
}

#[test]
fn the_closest_pair_of_vase_and_bowl_is_seeded() {
    let vase = Prepared::new(paper_object("vase", 0.2));
    let bowl = Prepared::new(paper_object("bowl", 0.2));
    check_minima(&vase, &bowl, 31, 3.0);
    check_minima(&bowl, &vase, 32, 3.0);
}

#[test]
fn the_closest_pair_of_pencil_and_bowl_is_seeded() {
    let pencil = Prepared::new(paper_object("pencil", 0.2));
    let bowl = Prepared::new(paper_object("bowl", 0.2));
    check_minima(&bowl, &pencil, 41, 3.0);
}

/// The closest points of a segment and a triangle against an independent minimisation: the
/// distance from the segment's point at s to the (convex) triangle is a convex function of s,
/// minimised by ternary search over [0, 1] with `closest_on_triangle` for each point. The
/// distance returned is that minimum (within 1e-9), and its points lie on the segment and the
/// triangle at that distance.
#[test]
fn segment_triangle_closest_points_match_a_convex_search() {
    use mesh_narrowphase::triangles::triangle_distance::{
        closest_between_segment_and_triangle, closest_on_triangle,
    };
    let mut rng = Rng(2121);
    let point = |rng: &mut Rng| {
        DVec3::new(
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
        )
    };
    for case in 0..500 {
        let t = [point(&mut rng), point(&mut rng), point(&mut rng)];
        // Segments beside the triangle, some crossing its plane outside it.
        let shift = DVec3::new(0.0, 0.0, rng.range(0.05, 1.5));
        let (p, q) = (point(&mut rng) + shift, point(&mut rng) + shift);
        let (s, on, distance) = closest_between_segment_and_triangle(p, q, &t);
        let near = p + (q - p) * s;
        assert!((0.0..=1.0).contains(&s), "case {case}: s {s}");
        let b = on.barycentric;
        let from_b = t[0] * b[0] + t[1] * b[1] + t[2] * b[2];
        assert!(from_b.distance(on.point) <= 1e-12, "case {case}: {on:?}");
        assert!(
            (near.distance(on.point) - distance).abs() <= 1e-12,
            "case {case}"
        );
        let gap = |s: f64| {
            let x = p + (q - p) * s;
            x.distance(closest_on_triangle(x, &t).point)
        };
        let (mut lo, mut hi) = (0.0_f64, 1.0_f64);
        for _ in 0..200 {
            let (m1, m2) = (lo + (hi - lo) / 3.0, hi - (hi - lo) / 3.0);
            if gap(m1) <= gap(m2) {
                hi = m2;
            } else {
                lo = m1;
            }
        }
        let truth = gap(0.5 * (lo + hi));
        if truth > 1e-6 {
            // Apart (a segment piercing the triangle is outside the function's contract).
            assert!(
                (distance - truth).abs() <= 1e-9,
                "case {case}: {distance} vs {truth}"
            );
        }
    }
}

/// The closest points of two disjoint triangles against the least of the six edge-against-
/// triangle distances (one of the two closest points lies on an edge of its triangle; the
/// segment-triangle distance is checked against a convex search above), on random pairs:
/// general positions, nearly parallel triangles facing each other (close surfaces, where many
/// cases tie), a corner over the other's interior, and slivers. The distance returned is that
/// minimum, and its points lie on the triangles (by their barycentric coordinates) at that
/// distance. The triangles' boxes' gap ([`boxes_gap`]) never exceeds it.
///
/// [`boxes_gap`]: mesh_narrowphase::triangles::triangle_distance::boxes_gap
#[test]
fn triangle_closest_points_match_the_edge_triangle_minimum() {
    use mesh_narrowphase::triangles::triangle_distance::{
        boxes_gap, closest_between_segment_and_triangle, closest_between_triangles, separating_gap,
    };
    let mut rng = Rng(4242);
    let point = |rng: &mut Rng, scale: f64| {
        DVec3::new(
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0) * scale,
        )
    };
    let mut checked = 0;
    // Pairs whose boxes' gap is at least half their distance (so that the bound is tested
    // where it is near tight, not only where it is 0).
    let mut tight_boxes = 0;
    for case in 0..3000 {
        // Flat triangles (z squeezed) one above the other for cases 1 and 2 of 3.
        let flat = if case % 3 == 0 { 1.0 } else { 1e-3 };
        let t1 = [(); 3].map(|_| point(&mut rng, flat));
        let lift = DVec3::new(0.0, 0.0, rng.range(0.01, 1.0));
        let mut t2 = [(); 3].map(|_| point(&mut rng, flat) + lift);
        if case % 7 == 0 {
            // A sliver: the third corner almost on the first side.
            t2[2] = t2[0] + (t2[1] - t2[0]) * 0.3 + DVec3::splat(1e-9);
        }
        if separating_gap(&t1, &t2) <= 1e-6 {
            continue;
        }
        checked += 1;
        let pair = closest_between_triangles(&t1, &t2);
        let mut truth = f64::INFINITY;
        for (s, t) in [(&t1, &t2), (&t2, &t1)] {
            for (i, j) in [(0, 1), (1, 2), (2, 0)] {
                truth = truth.min(closest_between_segment_and_triangle(s[i], s[j], t).2);
            }
        }
        assert!(
            (pair.distance - truth).abs() <= 1e-12 * (1.0 + truth),
            "case {case}: {} vs {truth}",
            pair.distance
        );
        // The boxes' gap is a lower bound on the distance.
        let boxes = boxes_gap(&t1, &t2);
        assert!(
            boxes <= truth * (1.0 + 1e-12),
            "case {case}: boxes {boxes} vs {truth}"
        );
        tight_boxes += usize::from(boxes >= 0.5 * truth);
        for (p, t) in [(&pair.a, &t1), (&pair.b, &t2)] {
            let b = p.barycentric;
            assert!(
                b.iter().all(|&x| (-1e-12..=1.0 + 1e-12).contains(&x))
                    && (b[0] + b[1] + b[2] - 1.0).abs() <= 1e-12,
                "case {case}: {b:?}"
            );
            let from_b = t[0] * b[0] + t[1] * b[1] + t[2] * b[2];
            assert!(from_b.distance(p.point) <= 1e-12, "case {case}: {p:?}");
        }
        assert!(
            (pair.a.point.distance(pair.b.point) - pair.distance).abs() <= 1e-15,
            "case {case}"
        );
    }
    assert!(checked > 2000, "{checked} disjoint pairs");
    assert!(
        tight_boxes > 500,
        "{tight_boxes} pairs with near-tight boxes"
    );
}
