//! The paper's vase (Fig. 6): two vases side by side, and a ball in a vase's concave neck, against
//! truth from dense sampling of the exact profile.

mod common;

use common::*;
use geom_param::{ComponentKind, DQuat, DVec2, DVec3};
use mesh_narrowphase::{ConcavePath, ContactBand, MeshScratch, MeshVerdict};

const TOL: f64 = 0.02;

fn band() -> ContactBand {
    ContactBand {
        margin: 0.5,
        delta1: -0.05,
        delta2: 0.3,
    }
}

fn bezier(p: [[f64; 2]; 4], s: f64) -> DVec2 {
    let t = 1.0 - s;
    let p = p.map(DVec2::from);
    p[0] * (t * t * t) + p[1] * (3.0 * t * t * s) + p[2] * (3.0 * t * s * s) + p[3] * (s * s * s)
}

/// The vase's profile (from fixtures/objects/vase.json), densely sampled: points and unit
/// outward normals in the (r, z) half-plane.
fn vase_profile_samples() -> Vec<(DVec2, DVec2)> {
    let body = [[26.0, 0.0], [38.0, 15.0], [40.0, 45.0], [18.0, 70.0]];
    let neck = [[18.0, 70.0], [13.6, 75.0], [10.0, 85.0], [11.0, 95.0]];
    let n = 20_000;
    let mut out = Vec::new();
    for curve in [body, neck] {
        for i in 0..=n {
            let s = i as f64 / n as f64;
            let h = 1e-6;
            let t = (bezier(curve, (s + h).min(1.0)) - bezier(curve, (s - h).max(0.0))).normalize();
            // Counter-clockwise around the material: outward is the right-hand side.
            out.push((bezier(curve, s), DVec2::new(t.y, -t.x)));
        }
    }
    out
}

fn check_contact_point(got: DVec3, exact: DVec3, normal: DVec3, rho: f64, what: &str) {
    let e = got - exact;
    let along = e.dot(normal).abs();
    let across = (e - normal * e.dot(normal)).length();
    println!("{what}: normal error {along:.2e}, tangential error {across:.2e}");
    assert!(
        along <= TOL,
        "{what}: {got} is {along} from {exact} along the normal"
    );
    // See tests/concave_regions.rs: the mesh cannot place a contact more precisely than the
    // band where the exact gap is within 2 TOL of its minimum.
    let bound = (4.0 * rho * TOL).sqrt();
    assert!(
        across <= bound,
        "{what}: {got} is {across} > {bound} from {exact} across the normal"
    );
}

#[test]
fn two_vases_side_by_side_touch_once_at_their_bulges() {
    let vase = Prepared::new(paper_object("vase", TOL));
    let samples = vase_profile_samples();
    let (bulge, _) = samples
        .iter()
        .copied()
        .max_by(|a, b| a.0.x.total_cmp(&b.0.x))
        .expect("samples");
    let gap = 0.1;
    let pose = pose(DQuat::IDENTITY, DVec3::new(2.0 * bulge.x + gap, 0.0, 0.0));
    let mut scratch = MeshScratch::default();
    let mut seeds = Vec::new();
    for ca in vase.object.components.iter().map(|c| c.id) {
        for cb in vase.object.components.iter().map(|c| c.id) {
            let (verdict, out) = query(&vase, ca, &vase, cb, &pose, &band(), &mut scratch);
            match verdict {
                MeshVerdict::Seeds => seeds.extend(out.seeds.iter().map(|s| (ca, cb, *s))),
                MeshVerdict::Separated => {}
                other => panic!("{ca:?} vs {cb:?}: {other:?}"),
            }
        }
    }
    assert_eq!(seeds.len(), 1, "{seeds:?}");
    let (ca, cb, seed) = seeds[0];
    assert_eq!(ca, cb);
    assert_eq!(vase.object.component(ca).kind, ComponentKind::Convex);
    // The bulge is a maximum of r(z): the relative radius of curvature is half the meridian
    // radius there (two equal bodies), or half the bulge radius around the axis; the bulge's
    // meridian radius of curvature is below 60 mm (dense sampling of the Bezier's turn).
    let rho = 0.5 * 60.0_f64.max(bulge.x);
    check_contact_point(
        seed.a.local_point,
        DVec3::new(bulge.x, 0.0, bulge.y),
        DVec3::X,
        rho,
        "A",
    );
    check_contact_point(
        seed.b.local_point,
        DVec3::new(-bulge.x, 0.0, bulge.y),
        DVec3::X,
        rho,
        "B",
    );
}

#[test]
fn meridian_radius_of_the_bulge_is_below_60_mm() {
    // Backs the bound used above: radius of curvature = ds / dθ along the sampled profile.
    let samples = vase_profile_samples();
    let i = samples
        .iter()
        .enumerate()
        .max_by(|a, b| a.1.0.x.total_cmp(&b.1.0.x))
        .map(|(i, _)| i)
        .expect("samples");
    let (p0, n0) = samples[i - 50];
    let (p1, n1) = samples[i + 50];
    let radius = p0.distance(p1) / n0.angle_to(n1).abs();
    assert!(radius < 60.0, "{radius}");
}

#[test]
fn ball_in_the_concave_neck_gives_one_region() {
    let vase = Prepared::new(paper_object("vase", TOL));
    let ball = Prepared::new(sphere(3.0, TOL));
    let neck: Vec<_> = components_of(&vase.object, ComponentKind::Concave);
    assert_eq!(neck.len(), 1);
    let samples = vase_profile_samples();
    // A point on the neck's waist and its outward normal; the ball (r = 3, well inside the
    // neck's concave meridian radius) sits on it, gap above.
    let neck_start = samples.len() / 2 + 1;
    let (p, n) = samples[neck_start + (samples.len() / 2) * 45 / 100];
    let (r, gap) = (3.0, 0.1);
    let centre = p + n * (r + gap);
    // Truth by dense sampling: the closest profile point to the ball's centre.
    let (q, _) = samples
        .iter()
        .copied()
        .min_by(|a, b| a.0.distance(centre).total_cmp(&b.0.distance(centre)))
        .expect("samples");
    assert!(
        (q.distance(centre) - (r + gap)).abs() < 1e-4,
        "the ball touches elsewhere first"
    );
    let pose = pose(DQuat::IDENTITY, DVec3::new(centre.x, 0.0, centre.y));
    let ball_c = ball.object.components[0].id;
    for path in PATHS {
        let mut scratch = MeshScratch::default();
        let (verdict, out) = query_path(
            path,
            (&vase, neck[0]),
            (&ball, ball_c),
            &pose,
            &band(),
            &mut scratch,
        );
        assert_eq!(verdict, MeshVerdict::Seeds);
        assert_eq!(out.stats.regions, 1);
        // Only the proxy path builds proxies.
        assert_eq!(out.stats.proxy_built, path == ConcavePath::ProxyRegions);
        let seed = out.seeds[0];
        let normal = DVec3::new(n.x, 0.0, n.y);
        // Relative radius: the ball's 3 mm against the neck (concave, so larger): at most 3 mm.
        check_contact_point(
            seed.a.local_point,
            DVec3::new(q.x, 0.0, q.y),
            normal,
            3.0,
            "neck",
        );
        check_contact_point(seed.b.local_point, -normal * r, normal, 3.0, "ball");
        // The same pair the other way round gives the same seed, mirrored.
        let (verdict, swapped) = query_path(
            path,
            (&ball, ball_c),
            (&vase, neck[0]),
            &pose.inverse(),
            &band(),
            &mut scratch,
        );
        assert_eq!(verdict, MeshVerdict::Seeds);
        assert_eq!(swapped.seeds.len(), 1);
        assert!(swapped.seeds[0].a.local_point.distance(seed.b.local_point) <= TOL);
        assert!(swapped.seeds[0].b.local_point.distance(seed.a.local_point) <= TOL);
    }
}
