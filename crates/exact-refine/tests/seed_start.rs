//! Where a solve starts: at the seed's feature locations, whose parameters Stage 2 interpolates
//! from the mesh vertices' exact correspondences. The seed's points place the start only when a
//! location has no finite parameters (they are then projected onto the feature).

mod support;

use geom_param::{DQuat, DVec3, Seed};
use support::*;

/// Two spheres apart by 0.2 mm, seeded up to 0.3 rad from the closest points: the answer is the
/// closed form's, and the same to the last bit whether the seed's points are the locations' own
/// or lie 100 mm off in a random direction (they are not used).
#[test]
fn the_start_is_the_seed_location_whatever_its_point() {
    let mut rng = Rng(21);
    let (ra, rb, gap) = (10.0, 4.0, 0.2);
    let (a, b) = (sphere(ra), sphere(rb));
    for k in 0..50 {
        let dir = rng.unit_vector();
        let rotation = rng.rotation();
        let centre = dir * (ra + rb + gap);
        let pose_ab = pose(rotation, centre);
        let (ua, va) = sphere_params(dir);
        let (ub, vb) = sphere_params(rotation.inverse() * -dir);
        let la = face(
            0,
            ua + rng.range(-0.3, 0.3),
            (va + rng.range(-0.05, 0.05)).clamp(0.01, 0.99),
        );
        let lb = face(
            0,
            ub + rng.range(-0.3, 0.3),
            (vb + rng.range(-0.05, 0.05)).clamp(0.01, 0.99),
        );
        let own = Seed {
            a: seed_point(&a, la, DVec3::ZERO),
            b: seed_point(&b, lb, DVec3::ZERO),
        };
        let far = Seed {
            a: seed_point(&a, la, rng.unit_vector() * 100.0),
            b: seed_point(&b, lb, rng.unit_vector() * 100.0),
        };
        let what = format!("case {k}");
        let c = refine(&a, &b, &pose_ab, &own);
        assert_converged(&c, &what);
        assert_answer(&c, gap, dir * ra, centre - dir * rb, &what);
        let moved = refine(&a, &b, &pose_ab, &far);
        assert_eq!(
            (moved.point_a, moved.point_b, moved.distance),
            (c.point_a, c.point_b, c.distance),
            "{what}: the seed's points moved the answer"
        );
    }
}

/// A seed whose parameters are not finite is placed by projecting its point: the solve finds
/// the closest points of a torus and a ball beside its outer equator at +x, where the torus's
/// mid-domain start (its outer equator at u = pi) lies on the far side.
#[test]
fn a_location_without_parameters_is_placed_by_its_point() {
    let (rc, r) = (10.0, 2.0);
    let torus_solid = torus(rc, r);
    let ball = sphere(1.0);
    // The ball's centre 1.5 mm outside the torus's outer equator at u = 0 (+x): the closest
    // torus point is (rc + r, 0, 0), the ball's (rc + r + 0.5, 0, 0).
    let centre = DVec3::new(rc + r + 1.5, 0.0, 0.0);
    let pose_ab = pose(DQuat::IDENTITY, centre);
    let truth_a = DVec3::new(rc + r, 0.0, 0.0);
    let truth_b = DVec3::new(rc + r + 0.5, 0.0, 0.0);
    let nan = face(0, f64::NAN, f64::NAN);
    let seed = Seed {
        a: geom_param::SeedPoint {
            component: geom_param::ComponentId(0),
            local_point: truth_a + DVec3::new(0.01, 0.02, 0.0),
            location: nan,
        },
        b: geom_param::SeedPoint {
            component: geom_param::ComponentId(0),
            local_point: DVec3::new(-1.0, 0.01, 0.0),
            location: nan,
        },
    };
    let c = refine(&torus_solid, &ball, &pose_ab, &seed);
    assert_converged(&c, "NaN parameters");
    assert_answer(&c, 0.5, truth_a, truth_b, "NaN parameters");
}
