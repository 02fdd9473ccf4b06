//! The same answer after a rigid motion of the whole scene, and with the two objects swapped.

mod support;

use geom_param::{DPose3, DVec3, Seed};
use support::*;

/// A sphere-torus scene with the answer computed in world coordinates.
struct World {
    point_a: DVec3,
    point_b: DVec3,
    distance: f64,
    normal: DVec3,
    error: f64,
}

fn solve_in_world(pose_a: DPose3, pose_b: DPose3, seed: &Seed, swapped: bool) -> World {
    let (a, b) = (torus(20.0, 5.0), sphere(3.0));
    if swapped {
        let pose_ba = pose_b.inverse() * pose_a;
        let c = refine(
            &b,
            &a,
            &pose_ba,
            &Seed {
                a: seed.b,
                b: seed.a,
            },
        );
        assert_converged_at(&c, 30.0 + pose_ba.translation.length(), "swapped");
        World {
            point_a: pose_b * c.point_b,
            point_b: pose_b * c.point_a,
            distance: c.distance,
            normal: -(pose_b.rotation * c.normal),
            error: c.diagnostics.point_error_estimate,
        }
    } else {
        let pose_ab = pose_a.inverse() * pose_b;
        let c = refine(&a, &b, &pose_ab, seed);
        assert_converged_at(&c, 30.0 + pose_ab.translation.length(), "direct");
        World {
            point_a: pose_a * c.point_a,
            point_b: pose_a * c.point_b,
            distance: c.distance,
            normal: pose_a.rotation * c.normal,
            error: c.diagnostics.point_error_estimate,
        }
    }
}

#[test]
fn rigid_motion_and_swap_leave_the_answer_unchanged() {
    let mut rng = Rng(7);
    let torus_a = torus(20.0, 5.0);
    let sphere_b = sphere(3.0);
    for k in 0..100 {
        let gap = [2.0, 1e-4, -0.5][k % 3];
        let phi = rng.range(0.0, std::f64::consts::TAU);
        let theta = rng.range(-1.2, 1.2);
        let core = DVec3::new(20.0 * phi.cos(), 20.0 * phi.sin(), 0.0);
        let out = DVec3::new(
            theta.cos() * phi.cos(),
            theta.cos() * phi.sin(),
            theta.sin(),
        );
        let center = core + out * (5.0 + 3.0 + gap);
        let seed = Seed {
            a: seed_point(&torus_a, face(0, phi + 0.05, 0.5), DVec3::ZERO),
            b: seed_point(&sphere_b, face(0, 1.0, 0.5), DVec3::ZERO),
        };
        let base_b = pose(rng.rotation(), center);
        let reference = solve_in_world(DPose3::IDENTITY, base_b, &seed, false);
        let motion = pose(rng.rotation(), rng.unit_vector() * rng.range(0.0, 1000.0));
        for (what, world) in [
            (
                "moved",
                solve_in_world(motion, motion * base_b, &seed, false),
            ),
            (
                "swapped",
                solve_in_world(DPose3::IDENTITY, base_b, &seed, true),
            ),
            (
                "moved and swapped",
                solve_in_world(motion, motion * base_b, &seed, true),
            ),
        ] {
            let back = |p: DVec3| {
                if what == "swapped" {
                    p
                } else {
                    motion.inverse() * p
                }
            };
            let rounding = 64.0 * f64::EPSILON * (1000.0 + 30.0);
            let tol = reference.error.max(world.error) + rounding;
            assert!(
                back(world.point_a).distance(reference.point_a) <= tol,
                "case {k} {what}: point_a off by {} (tol {tol}), distances {} {}",
                back(world.point_a).distance(reference.point_a),
                world.distance,
                reference.distance
            );
            assert!(
                back(world.point_b).distance(reference.point_b) <= tol,
                "case {k} {what}: point_b"
            );
            assert!(
                (world.distance - reference.distance).abs() <= rounding,
                "case {k} {what}: distance"
            );
            let normal = if what == "swapped" {
                world.normal
            } else {
                motion.rotation.inverse() * world.normal
            };
            // The normal turns with the points by point error x curvature (at most 1 / 3 mm).
            let normal_tol = 1e-12 + (reference.error + world.error) / 3.0;
            assert!(
                normal.distance(reference.normal) <= normal_tol,
                "case {k} {what}: normal"
            );
        }
    }
}
