//! Two tessellated spheres against the closed form: separated, touching and penetrating, at
//! random orientations.

mod common;

use common::{Lcg, max_circumradius, pose, sphere, sphere_deviation};
use geom_param::DVec3;
use mesh_baseline::{BaselineContact, BaselineMesh, MeshOnlyBaseline, nearest_to};

const RA: f64 = 10.0;
const RB: f64 = 7.0;

struct Pair {
    a: BaselineMesh,
    b: BaselineMesh,
    /// Exact deviations of the two meshes from their spheres (mm), computed by the test.
    error: f64,
    /// Largest triangle circumradius over both meshes (mm).
    rho: f64,
}

fn pair(target: usize) -> Pair {
    let a = BaselineMesh::new(&sphere(RA).solid, target).expect("meshes");
    let b = BaselineMesh::new(&sphere(RB).solid, target).expect("meshes");
    let error = sphere_deviation(a.vertices(), a.indices(), RA)
        + sphere_deviation(b.vertices(), b.indices(), RB);
    let rho = max_circumradius(a.vertices(), a.indices())
        .max(max_circumradius(b.vertices(), b.indices()));
    Pair { a, b, error, rho }
}

/// The contact with the smallest distance.
fn deepest(contacts: &[BaselineContact]) -> Option<&BaselineContact> {
    contacts
        .iter()
        .min_by(|x, y| x.distance.total_cmp(&y.distance))
}

const TARGETS: [usize; 3] = [1_000, 5_000, 20_000];
const ORIENTATIONS: usize = 8;

/// Sphere A at a random pose, sphere B at a random rotation with its centre at distance
/// RA + RB + gap along a random direction d: the exact contact has distance `gap`, normal d.
struct Placement {
    pose_a: geom_param::DPose3,
    pose_b: geom_param::DPose3,
    d: DVec3,
}

fn place(rng: &mut Lcg, gap: f64) -> Placement {
    let d = rng.direction();
    let centre = DVec3::new(rng.next(), rng.next(), rng.next()) * 100.0 - 50.0;
    let pose_a = pose(rng.rotation(), centre);
    let pose_b = pose(rng.rotation(), centre + (RA + RB + gap) * d);
    Placement { pose_a, pose_b, d }
}

/// Separated and touching spheres: with a prediction above the gap plus both chordal errors,
/// parry finds the meshes' distance, which lies in [gap, gap + e_a + e_b] for inscribed convex
/// meshes; the normal agrees with the centre line to within both meshes' facet tilt, and
/// point_b = point_a + distance · normal.
#[test]
fn separated_and_touching_spheres_match_the_closed_form() {
    let mut rng = Lcg(11);
    for target in TARGETS {
        let p = pair(target);
        let measured = p.a.chordal_error() + p.b.chordal_error();
        let tilt = (p.rho / (RA - p.error)).asin() + (p.rho / (RB - p.error)).asin();
        for gap in [0.05, 0.0] {
            for _ in 0..ORIENTATIONS {
                let s = place(&mut rng, gap);
                let prediction = gap + measured + 0.01;
                let contacts = MeshOnlyBaseline::new()
                    .contacts(&p.a, &s.pose_a, &p.b, &s.pose_b, prediction)
                    .expect("valid query");
                let c = deepest(&contacts).expect("a contact within the prediction");
                let error = c.distance - gap;
                assert!(
                    error >= -1e-9 && error <= measured + 1e-9,
                    "target {target} gap {gap}: distance {} (chordal errors {measured})",
                    c.distance
                );
                assert!((c.normal.length() - 1.0).abs() < 1e-9);
                let angle = c.normal.angle_between(s.d);
                assert!(
                    angle <= tilt,
                    "target {target} gap {gap}: normal off by {angle} > {tilt}"
                );
                for c in &contacts {
                    assert!(c.distance <= prediction);
                    let residual = c.point_b - (c.point_a + c.distance * c.normal);
                    assert!(residual.length() <= 1e-9 * RA, "residual {residual}");
                }
            }
        }
    }
}

/// A penetration of 1 µm is far below the chordal errors: the inscribed meshes do not
/// overlap (they stay up to e_a + e_b - 0.001 mm apart), so at prediction 0 the baseline
/// reports nothing. This is the meshes' error, not parry's: with a prediction above the
/// chordal errors parry reports the meshes' positive distance.
#[test]
fn a_penetration_below_the_chordal_error_is_missed() {
    let mut rng = Lcg(12);
    let gap = -0.001;
    for target in TARGETS {
        let p = pair(target);
        assert!(p.error > -gap, "the meshes are too fine for this test");
        for _ in 0..ORIENTATIONS {
            let s = place(&mut rng, gap);
            let mut baseline = MeshOnlyBaseline::new();
            let at_zero = baseline
                .contacts_cold(&p.a, &s.pose_a, &p.b, &s.pose_b, 0.0)
                .expect("valid query");
            let wider = baseline
                .contacts_cold(&p.a, &s.pose_a, &p.b, &s.pose_b, p.error + 0.01)
                .expect("valid query");
            let c = deepest(&wider).expect("a contact within the prediction");
            assert!(
                at_zero.is_empty(),
                "target {target}: {} contacts",
                at_zero.len()
            );
            assert!(
                c.distance > 0.0 && c.distance <= gap + p.error + 1e-9,
                "target {target}: distance {}",
                c.distance
            );
        }
    }
}

/// A penetration of 0.5 mm, deeper than the chordal errors, so the meshes overlap by at least
/// 0.5 - e_a - e_b. parry reports contacts with negative distance, but its depth is that of
/// overlapping triangle pairs, not of the solids: observed, it reports 11 % to 66 % of the
/// meshes' least overlap, less the finer the mesh (a triangle pair's depth is bounded by the
/// triangles' size), with normals tilted by 5 to 17 degrees. Recorded here as observed
/// behaviour of the baseline (it underestimates), not as a requirement.
#[test]
fn a_deep_penetration_is_found_but_its_depth_is_underestimated() {
    let mut rng = Lcg(13);
    let gap = -0.5;
    for target in TARGETS {
        let p = pair(target);
        for _ in 0..ORIENTATIONS {
            let s = place(&mut rng, gap);
            let contacts = MeshOnlyBaseline::new()
                .contacts(&p.a, &s.pose_a, &p.b, &s.pose_b, 0.0)
                .expect("valid query");
            let c = deepest(&contacts).expect("penetration is reported");
            let overlap = -gap - p.error;
            println!(
                "target {target}: depth {:.4} = {:.2} x least mesh overlap, normal off {:.3} rad",
                -c.distance,
                -c.distance / overlap,
                c.normal.angle_between(s.d)
            );
            assert!(
                c.distance < 0.0 && -c.distance < overlap,
                "target {target}: depth {} vs mesh overlap >= {overlap}",
                -c.distance
            );
        }
    }
}

/// Warm queries at the same pose return what a cold query returns.
#[test]
fn warm_and_cold_agree_at_a_fixed_pose() {
    let mut rng = Lcg(14);
    let p = pair(5_000);
    let key = |c: &BaselineContact| {
        [c.point_a.x, c.point_a.y, c.point_a.z, c.distance].map(|x| (x * 1e9).round() as i64)
    };
    for gap in [0.02, -0.3] {
        let s = place(&mut rng, gap);
        let mut warm = MeshOnlyBaseline::new();
        let mut cold = MeshOnlyBaseline::new();
        let prediction = 0.1;
        let mut first = cold
            .contacts_cold(&p.a, &s.pose_a, &p.b, &s.pose_b, prediction)
            .expect("valid query");
        for _ in 0..3 {
            let mut again = warm
                .contacts(&p.a, &s.pose_a, &p.b, &s.pose_b, prediction)
                .expect("valid query");
            first.sort_by_key(key);
            again.sort_by_key(key);
            assert_eq!(
                first.iter().map(key).collect::<Vec<_>>(),
                again.iter().map(key).collect::<Vec<_>>()
            );
        }
    }
}

#[test]
fn nearest_to_picks_the_closest_midpoint() {
    let contact = |x: f64| BaselineContact {
        point_a: DVec3::new(x, 0.0, 0.0),
        point_b: DVec3::new(x, 0.0, 2.0),
        distance: 2.0,
        normal: DVec3::Z,
    };
    let contacts = [contact(0.0), contact(5.0), contact(-3.0)];
    // Midpoints (0, 0, 1), (5, 0, 1), (-3, 0, 1); the point (-2, 0, 1) is 1 from the third.
    assert_eq!(
        nearest_to(&contacts, DVec3::new(-2.0, 0.0, 1.0)),
        Some((2, 1.0))
    );
    assert_eq!(nearest_to(&[], DVec3::ZERO), None);
}

#[test]
fn bad_poses_and_predictions_are_refused() {
    let p = pair(1_000);
    let good = pose(geom_param::DQuat::IDENTITY, DVec3::ZERO);
    let far = pose(geom_param::DQuat::IDENTITY, DVec3::X * 100.0);
    let scaled = pose(
        geom_param::DQuat::from_xyzw(0.0, 0.0, 0.0, 2.0),
        DVec3::ZERO,
    );
    let nan = pose(geom_param::DQuat::IDENTITY, DVec3::new(f64::NAN, 0.0, 0.0));
    let mut b = MeshOnlyBaseline::new();
    assert!(b.contacts(&p.a, &scaled, &p.b, &far, 0.1).is_err());
    assert!(b.contacts(&p.a, &good, &p.b, &nan, 0.1).is_err());
    for prediction in [-1.0, f64::NAN, f64::INFINITY] {
        assert!(b.contacts(&p.a, &good, &p.b, &far, prediction).is_err());
    }
    assert_eq!(b.contacts(&p.a, &good, &p.b, &far, 0.1), Ok(vec![]));
}
