//! Convex pairs: GJK with the hill-climbing support map against parry's own `ConvexPolyhedron`
//! answer, seeds against closed forms, caps, and proxies left untouched.

mod common;

use common::*;
use geom_param::{ComponentKind, ConvexHull, DQuat, DVec3};
use mesh_narrowphase::convex::convex_pair::{GjkScratch, HullProximity, WarmStart, hull_proximity};
use mesh_narrowphase::convex::hill_climb_support::HillClimbSupport;
use mesh_narrowphase::{ContactBand, MeshScratch, MeshVerdict};
use parry3d_f64::query;
use parry3d_f64::shape::{ConvexPolyhedron, SupportMap};

fn hulls(names: &[&str], tolerance: f64) -> Vec<(String, ConvexHull)> {
    let mut out = Vec::new();
    for name in names {
        let object = paper_object(name, tolerance);
        for (i, hull) in object.hulls.iter().enumerate() {
            if let Some(h) = hull {
                out.push((format!("{name}#{i}"), h.clone()));
            }
        }
    }
    out
}

#[test]
fn hill_climbing_support_matches_brute_force_scan() {
    let mut rng = Rng(7);
    for (name, hull) in hulls(&["goblet", "vase", "pencil"], 0.05) {
        let support = HillClimbSupport::new(&hull, 0);
        for _ in 0..200 {
            let dir = rng.rotation() * DVec3::X;
            let got = support.local_support_point(dir).dot(dir);
            let best = hull
                .points
                .iter()
                .map(|p| p.dot(dir))
                .fold(f64::MIN, f64::max);
            assert!(
                got >= best - 1e-12 * best.abs().max(1.0),
                "{name}: {got} < {best}"
            );
        }
    }
}

/// A random pose of B (a random rotation, its origin up to 130 mm from A's in a random
/// direction) and the distance of the two hulls there by parry's `ConvexPolyhedron`.
fn random_pose_and_parry_distance(
    rng: &mut Rng,
    ha: &ConvexHull,
    hb: &ConvexHull,
) -> (geom_param::DPose3, f64) {
    let pa = ConvexPolyhedron::from_convex_hull(&ha.points).expect("hull");
    let pb = ConvexPolyhedron::from_convex_hull(&hb.points).expect("hull");
    let pose = pose(
        rng.rotation(),
        rng.rotation() * DVec3::new(rng.range(0.0, 130.0), 0.0, 0.0),
    );
    let truth = query::distance(&pose_identity(), &pa, &pose, &pb)
        .expect("supported")
        .distance;
    (pose, truth)
}

#[test]
fn gjk_with_hill_climbing_agrees_with_parry_convex_polyhedron() {
    let all = hulls(&["paperweight", "goblet", "vase", "pencil", "jar"], 0.05);
    let mut rng = Rng(42);
    let mut scratch = GjkScratch::default();
    let mut checked = [0usize; 3];
    for k in 0..400 {
        let (na, ha) = &all[k % all.len()];
        let (nb, hb) = &all[(k * 7 + 3) % all.len()];
        let (pose, truth) = random_pose_and_parry_distance(&mut rng, ha, hb);
        let max_distance = 20.0;
        let size = 200.0;
        let mut warm = WarmStart::default();
        let (got, _) = hull_proximity(
            ha,
            hb,
            &pose,
            max_distance,
            1e-7 * size,
            &mut warm,
            &mut scratch,
        );
        match got {
            HullProximity::Close { p1, p2 } => {
                let d = p1.distance(p2);
                assert!(
                    (d - truth).abs() <= 1e-6 * size,
                    "{na} vs {nb}: {d} vs parry {truth}"
                );
                checked[0] += 1;
            }
            HullProximity::Overlapping => {
                assert!(
                    truth <= 1e-6 * size,
                    "{na} vs {nb}: overlap but parry says {truth}"
                );
                checked[1] += 1;
            }
            HullProximity::Separated => {
                assert!(
                    truth > max_distance,
                    "{na} vs {nb}: separated but parry says {truth}"
                );
                checked[2] += 1;
            }
            HullProximity::NotConverged => panic!("{na} vs {nb}: not converged"),
        }
        // Warm-started from its own answer, the same query gives the same distance.
        let (again, _) = hull_proximity(
            ha,
            hb,
            &pose,
            max_distance,
            1e-7 * size,
            &mut warm,
            &mut scratch,
        );
        if let (HullProximity::Close { p1, p2 }, HullProximity::Close { p1: q1, p2: q2 }) =
            (got, again)
        {
            assert!((p1.distance(p2) - q1.distance(q2)).abs() <= 1e-6 * size);
        } else {
            assert_eq!(std::mem::discriminant(&got), std::mem::discriminant(&again));
        }
    }
    println!("close / overlapping / separated: {checked:?}");
    assert!(
        checked.iter().all(|&n| n >= 20),
        "too few cases of some kind: {checked:?}"
    );
}

fn pose_identity() -> geom_param::DPose3 {
    pose(DQuat::IDENTITY, DVec3::ZERO)
}

#[test]
fn two_spheres_give_one_seed_at_the_closed_form_points_and_no_proxy() {
    let tol = 0.02;
    let a = Prepared::new(sphere(10.0, tol));
    let b = Prepared::new(sphere(6.0, tol));
    let (ca, cb) = (a.object.components[0].id, b.object.components[0].id);
    let band = ContactBand {
        margin: 0.5,
        delta1: -0.05,
        delta2: 0.3,
    };
    let mut scratch = MeshScratch::default();
    let mut rng = Rng(3);
    for _ in 0..20 {
        let dir = rng.rotation() * DVec3::Z;
        let gap = rng.range(0.0, 0.25);
        let pose_ab = pose(rng.rotation(), dir * (16.0 + gap));
        let (verdict, out) = query(&a, ca, &b, cb, &pose_ab, &band, &mut scratch);
        assert_eq!(verdict, MeshVerdict::Seeds);
        assert_eq!(out.seeds.len(), 1);
        assert!(!out.stats.proxy_built && !out.stats.convex_fallback);
        let seed = out.seeds[0];
        // Mesh points within the chordal error of the surface, and no further than the facet
        // size from the exact closest points: the facets near the contact are within
        // sqrt(2 r e) of them for a sphere of radius r meshed to error e.
        let on_a = dir * 10.0;
        let on_b = pose_ab.inverse() * (dir * (10.0 + gap));
        assert!(
            seed.a.local_point.distance(on_a) <= (2.0 * 10.0 * tol).sqrt(),
            "{seed:?}"
        );
        assert!(
            seed.b.local_point.distance(on_b) <= (2.0 * 6.0 * tol).sqrt(),
            "{seed:?}"
        );
        let d = seed.a.local_point.distance(pose_ab * seed.b.local_point);
        assert!(
            (d - gap).abs() <= 2.0 * tol,
            "mesh distance {d} vs gap {gap}"
        );
        // Far apart: separated.
        let far = pose(pose_ab.rotation, dir * (16.0 + 0.3 + 2.0 * tol + 0.01));
        let (verdict, _) = query(&a, ca, &b, cb, &far, &band, &mut scratch);
        assert_eq!(verdict, MeshVerdict::Separated);
    }
    assert_eq!(
        a.prepared.components[0].proxies.len(),
        0,
        "a convex pair built a proxy"
    );
    assert_eq!(
        b.prepared.components[0].proxies.len(),
        0,
        "a convex pair built a proxy"
    );
}

#[test]
fn a_closest_point_on_a_hull_cap_sends_the_pair_to_the_general_path() {
    // The socket's outer (convex) component is the outer sphere and the flat rim annulus at
    // z = 40; its hull is closed by a cap over the opening. A ball hovering over the centre of the
    // opening is closest to the cap's centre (0, 0, 40), which is no point of the surface and
    // says nothing about where the surface is nearest. The general path answers: the nearest
    // points of the component are on the inner rim circle (r = 30, z = 40), sqrt(30² + 10.2²)
    // - 10 = 21.7 mm from the ball, far outside the band, so no seed.
    let socket = Prepared::new(socket(30.0, 35.0, 40.0, 0.05));
    let ball = Prepared::new(sphere(10.0, 0.05));
    let outer = components_of(&socket.object, ComponentKind::Convex)[0];
    let band = ContactBand {
        margin: 0.5,
        delta1: -0.05,
        delta2: 0.3,
    };
    let mut scratch = MeshScratch::default();
    let over_the_opening = pose(DQuat::IDENTITY, DVec3::new(0.0, 0.0, 50.2));
    let ball_id = ball.object.components[0].id;
    let (verdict, out) = query(
        &socket,
        outer,
        &ball,
        ball_id,
        &over_the_opening,
        &band,
        &mut scratch,
    );
    assert!(out.stats.convex_fallback, "{:?}", out.stats);
    assert_eq!(verdict, MeshVerdict::Separated, "{:?}", out.seeds);
    // Over the rim annulus (r = 32.5), 0.2 mm above it: GJK's closest point is on the surface,
    // and the seed is the annulus point under the ball.
    let over_the_rim = pose(DQuat::IDENTITY, DVec3::new(32.5, 0.0, 50.2));
    let (verdict, out) = query(
        &socket,
        outer,
        &ball,
        ball_id,
        &over_the_rim,
        &band,
        &mut scratch,
    );
    assert!(!out.stats.convex_fallback, "{:?}", out.stats);
    assert_eq!(verdict, MeshVerdict::Seeds);
    let p = out.seeds[0].a.local_point;
    assert!(p.distance(DVec3::new(32.5, 0.0, 40.0)) <= 0.05, "{p}");
    let exact = socket.object.solid.point_at(&out.seeds[0].a.location);
    assert!(exact.distance(p) <= 0.05, "{exact} against {p}");
}

/// Two flat caps nearly parallel (a cylinder of radius 20 stacked on another, tilted by
/// 0.01-0.03 rad, 0.05 mm apart): GJK's slow case, where each query builds its simplex over
/// many iterations. The same query again starts from the last simplex, kept in its warm start:
/// the same distance as parry's `ConvexPolyhedron` (to 1e-9 mm) in fewer support evaluations,
/// and after a small motion (0.01 mm, 1e-3 rad) still parry's distance.
#[test]
fn a_warm_simplex_answers_nearly_parallel_caps_again_in_fewer_evaluations() {
    let model = cylinder(20.0, 10.0, 0.05);
    let hull = model
        .hulls
        .iter()
        .flatten()
        .max_by_key(|h| h.points.len())
        .expect("a convex component");
    let polyhedron = ConvexPolyhedron::from_convex_hull(&hull.points).expect("hull");
    let truth = |pose: &geom_param::DPose3| {
        query::distance(&pose_identity(), &polyhedron, pose, &polyhedron)
            .expect("supported")
            .distance
    };
    let lowest_after = |rotation: DQuat| {
        hull.points
            .iter()
            .map(|p| (rotation * *p).z)
            .fold(f64::INFINITY, f64::min)
    };
    let top = hull.points.iter().map(|p| p.z).fold(f64::MIN, f64::max);
    let mut scratch = GjkScratch::default();
    let mut rng = Rng(11);
    for _ in 0..10 {
        let rotation = DQuat::from_rotation_z(rng.range(-0.5, 0.5))
            * DQuat::from_rotation_x(rng.range(0.01, 0.03))
            * DQuat::from_rotation_y(rng.range(-0.01, 0.01));
        let lift = top - lowest_after(rotation) + 0.05;
        let shift = DVec3::new(rng.range(-5.0, 5.0), rng.range(-5.0, 5.0), lift);
        let at = pose(rotation, shift);
        let distance = |got: HullProximity| match got {
            HullProximity::Close { p1, p2 } => p1.distance(p2),
            other => panic!("{other:?}"),
        };
        let mut warm = WarmStart::default();
        let (cold, cold_evaluations) =
            hull_proximity(hull, hull, &at, 1.0, 1e-9, &mut warm, &mut scratch);
        let expected = truth(&at);
        assert!(
            (distance(cold) - expected).abs() <= 1e-9,
            "{cold:?} vs {expected}"
        );
        let (again, warm_evaluations) =
            hull_proximity(hull, hull, &at, 1.0, 1e-9, &mut warm, &mut scratch);
        assert!(
            (distance(again) - expected).abs() <= 1e-9,
            "{again:?} vs {expected}"
        );
        assert!(
            warm_evaluations < cold_evaluations,
            "warm {warm_evaluations} vs cold {cold_evaluations}"
        );
        let moved = pose(
            DQuat::from_rotation_y(1e-3) * rotation,
            shift + DVec3::new(0.01, 0.0, 0.01),
        );
        let (after, _) = hull_proximity(hull, hull, &moved, 1.0, 1e-9, &mut warm, &mut scratch);
        let expected = truth(&moved);
        assert!(
            (distance(after) - expected).abs() <= 1e-9,
            "{after:?} vs {expected}"
        );
    }
}

/// A warm start left by other hulls (a scratch whose pair key came back for other objects)
/// only starts GJK elsewhere: its simplex holds vertex indices, read from the hulls at hand, so
/// every restored point is a point of their Minkowski difference. One warm start carried
/// across 200 queries of different hull pairs gives parry's distance every time.
#[test]
fn a_warm_start_left_by_other_hulls_gives_the_same_distances() {
    let all = hulls(&["paperweight", "goblet", "vase", "pencil", "jar"], 0.05);
    let mut rng = Rng(17);
    let mut scratch = GjkScratch::default();
    let mut warm = WarmStart::default();
    let mut close = 0;
    for k in 0..200 {
        let (na, ha) = &all[(k * 3) % all.len()];
        let (nb, hb) = &all[(k * 5 + 1) % all.len()];
        let (pose, truth) = random_pose_and_parry_distance(&mut rng, ha, hb);
        let size = 200.0;
        let (got, _) = hull_proximity(ha, hb, &pose, 20.0, 1e-7 * size, &mut warm, &mut scratch);
        match got {
            HullProximity::Close { p1, p2 } => {
                close += 1;
                let d = p1.distance(p2);
                assert!(
                    (d - truth).abs() <= 1e-6 * size,
                    "{na} vs {nb}: {d} vs {truth}"
                );
            }
            HullProximity::Overlapping => assert!(truth <= 1e-6 * size, "{na} vs {nb}: {truth}"),
            HullProximity::Separated => assert!(truth > 20.0, "{na} vs {nb}: {truth}"),
            HullProximity::NotConverged => panic!("{na} vs {nb}: not converged"),
        }
    }
    assert!(close >= 10, "too few close pairs: {close}");
}
