//! Closed-form answers for every feature pair kind: sphere-sphere (separated and penetrating),
//! sphere-torus, crossed cylinders, point-torus, point-curve, curve-curve (separated, and two
//! crossing rims penetrating) and curve-surface.

mod support;

use geom_param::{DQuat, DVec3, FeatureId, Seed};
use std::f64::consts::{FRAC_PI_2, PI, TAU};
use support::*;

#[test]
fn sphere_sphere_separated_and_penetrating() {
    let mut rng = Rng(1);
    let (ra, rb) = (10.0, 4.0);
    let (a, b) = (sphere(ra), sphere(rb));
    for k in 0..200 {
        let dir = rng.unit_vector();
        let gap = [5.0, 1e-3, 1e-6, 0.0, -1e-6, -0.5, -3.0][k % 7];
        let rotation = rng.rotation();
        let center = dir * (ra + rb + gap);
        let pose_ab = pose(rotation, center);
        // Seeds: the true points moved by up to ~0.2 rad, and pulled off the surface.
        let (ua, va) = sphere_params(dir);
        let (ub, vb) = sphere_params(rotation.inverse() * -dir);
        let sa = face(
            0,
            ua + rng.range(-0.2, 0.2),
            (va + rng.range(-0.05, 0.05)).clamp(0.01, 0.99),
        );
        let sb = face(
            0,
            ub + rng.range(-0.2, 0.2),
            (vb + rng.range(-0.05, 0.05)).clamp(0.01, 0.99),
        );
        let seed = Seed {
            a: seed_point(&a, sa, rng.unit_vector() * 0.01),
            b: seed_point(&b, sb, DVec3::ZERO),
        };
        let c = refine(&a, &b, &pose_ab, &seed);
        let what = format!("case {k}, gap {gap}");
        assert_converged(&c, &what);
        let (de, pe) = assert_answer(&c, gap, dir * ra, center - dir * rb, &what);
        if k < 7 {
            let d = &c.diagnostics;
            println!(
                "gap {gap:e}: distance error {de:.1e} (est {:.1e}), point error {pe:.1e} (est {:.1e}), {} iterations",
                d.error_estimate, d.point_error_estimate, d.iterations
            );
        }
        // The gap's curvature: a point of A at arc s from the contact is |a − c_b| − rb from B,
        // with |a − c_b|² = ra² + D² − 2 ra D cos(s / ra), D = ra + rb + gap, so
        // κ = D / (ra (D − ra)) (1/ra + 1/rb at touch); measured with both points sliding it
        // differs by O(gap x curvature) relative.
        if gap.abs() <= 1e-3 {
            let centres = ra + rb + gap;
            let kappa = centres / (ra * (centres - ra));
            assert!(
                (c.diagnostics.gap_curvature - kappa).abs() <= 1e-3 * kappa,
                "{what}: gap curvature {:e} vs {kappa:e}",
                c.diagnostics.gap_curvature
            );
        }
        // The normal turns with the points: by point error x curvature (1 / 10 mm).
        let tol = 1e-12 + c.diagnostics.point_error_estimate / ra;
        assert!(
            c.normal.distance(dir) < tol,
            "{what}: normal {:?} vs {dir:?}",
            c.normal
        );
    }
}

#[test]
fn sphere_torus() {
    let mut rng = Rng(2);
    let (rc, ta, rs) = (20.0, 5.0, 3.0);
    let (a, b) = (torus(rc, ta), sphere(rs));
    for k in 0..100 {
        // Sphere centre outside the tube, on the outer side (face 0 of the torus).
        let phi = rng.range(0.0, std::f64::consts::TAU);
        let theta = rng.range(-1.2, 1.2); // angle about the core circle, outer half
        let gap = rng.range(1e-6, 4.0);
        let core = DVec3::new(rc * phi.cos(), rc * phi.sin(), 0.0);
        let out = DVec3::new(
            theta.cos() * phi.cos(),
            theta.cos() * phi.sin(),
            theta.sin(),
        );
        let center = core + out * (ta + rs + gap);
        let v = (theta + FRAC_PI_2) / PI;
        let seed = Seed {
            a: seed_point(&a, face(0, phi + 0.1, (v + 0.05).min(0.99)), DVec3::ZERO),
            b: seed_point(&b, face(0, 0.5, 0.5), DVec3::ZERO),
        };
        let c = refine(&a, &b, &pose(DQuat::IDENTITY, center), &seed);
        let what = format!("case {k}");
        assert_converged(&c, &what);
        assert_answer(&c, gap, core + out * ta, center - out * rs, &what);
    }
}

#[test]
fn crossed_cylinders_side_to_side() {
    let mut rng = Rng(3);
    let (r1, r2) = (5.0, 2.0);
    let (a, b) = (cylinder(r1, 40.0), cylinder(r2, 40.0));
    for k in 0..100 {
        let angle = rng.range(0.3, PI - 0.3); // crossing angle between the axes
        let gap = [2.0, 1e-4, 1e-7, -0.3][k % 4];
        // B's axis: direction (sin(angle), 0, cos(angle))... rotated about x by 90° then about z.
        let rotation = DQuat::from_rotation_y(angle) * DQuat::IDENTITY;
        let axis_b = rotation * DVec3::Z;
        let normal = DVec3::Z.cross(axis_b).normalize(); // common perpendicular
        let phi = rng.range(0.0, std::f64::consts::TAU);
        let spin = DQuat::from_rotation_z(phi);
        let (normal, axis_b) = (spin * normal, spin * axis_b);
        let rotation = spin * rotation;
        // Foot on A's axis at z = 20, on B's axis at its middle (local z = 20).
        let foot_a = DVec3::new(0.0, 0.0, 20.0);
        let foot_b = foot_a + normal * (r1 + r2 + gap);
        let translation = foot_b - axis_b * 20.0;
        let pose_ab = pose(rotation, translation);
        let local_n = rotation.inverse() * -normal;
        let ub = local_n.y.atan2(local_n.x);
        let ua = normal.y.atan2(normal.x);
        let seed = Seed {
            a: seed_point(&a, face(1, ua + 0.3, 0.4), DVec3::ZERO),
            b: seed_point(&b, face(1, ub - 0.3, 0.6), DVec3::ZERO),
        };
        let c = refine(&a, &b, &pose_ab, &seed);
        let what = format!("case {k}, gap {gap}, angle {angle}");
        assert_converged(&c, &what);
        assert_answer(&c, gap, foot_a + normal * r1, foot_b - normal * r2, &what);
        // The gap's curvature: the smallest eigenvalue of the sum of the two rank-one curvature
        // tensors 1/r1 and 1/r2 across their axes, which cross at `angle`.
        if gap.abs() <= 1e-4 {
            let (k1, k2) = (1.0 / r1, 1.0 / r2);
            let s = k1 + k2;
            let kappa = 0.5 * (s - (s * s - 4.0 * k1 * k2 * angle.sin().powi(2)).sqrt());
            assert!(
                (c.diagnostics.gap_curvature - kappa).abs() <= 1e-3 * kappa,
                "{what}: gap curvature {:e} vs {kappa:e}",
                c.diagnostics.gap_curvature
            );
        }
    }
}

#[test]
fn point_torus_cone_apex() {
    let mut rng = Rng(4);
    let (rc, ta) = (20.0, 5.0);
    let a = torus(rc, ta);
    let b = cone(3.0, 6.0);
    for k in 0..100 {
        let phi = rng.range(0.0, std::f64::consts::TAU);
        let theta = rng.range(-1.3, 1.3);
        let gap = rng.range(1e-6, 3.0);
        let core = DVec3::new(rc * phi.cos(), rc * phi.sin(), 0.0);
        let out = DVec3::new(
            theta.cos() * phi.cos(),
            theta.cos() * phi.sin(),
            theta.sin(),
        );
        let apex = core + out * (ta + gap);
        // The cone's axis points from the apex away from the torus: rotate local +z onto -out.
        let rotation = DQuat::from_rotation_arc(DVec3::Z, -out);
        let pose_ab = pose(rotation, apex - rotation * DVec3::new(0.0, 0.0, 6.0));
        let v = (theta + FRAC_PI_2) / PI;
        let seed = Seed {
            a: seed_point(&a, face(0, phi - 0.1, (v - 0.05).max(0.01)), DVec3::ZERO),
            b: seed_point(&b, vertex(1), DVec3::ZERO),
        };
        let c = refine(&a, &b, &pose_ab, &seed);
        let what = format!("case {k}");
        assert_converged(&c, &what);
        assert_eq!(
            c.location_b.feature(),
            FeatureId::Vertex(geom_param::VertexId(1)),
            "{what}"
        );
        assert_answer(&c, gap, core + out * ta, apex, &what);
    }
}

#[test]
fn point_curve_apex_against_rim() {
    // A cylinder's top rim (edge 1) against a cone apex beyond the corner: the closest point of
    // the rim circle to p is the circle point in p's direction.
    let mut rng = Rng(5);
    let (r, h) = (5.0, 10.0);
    let a = cylinder(r, h);
    let b = cone(2.0, 4.0);
    for k in 0..50 {
        let phi = rng.range(0.0, std::f64::consts::TAU);
        let beta = rng.range(0.2, 1.3); // direction in the corner's normal cone
        let gap = rng.range(1e-5, 2.0);
        let radial = DVec3::new(phi.cos(), phi.sin(), 0.0);
        let corner = radial * r + DVec3::Z * h;
        let out = radial * beta.cos() + DVec3::Z * beta.sin();
        let apex = corner + out * gap;
        let rotation = DQuat::from_rotation_arc(DVec3::Z, -out);
        let pose_ab = pose(rotation, apex - rotation * DVec3::new(0.0, 0.0, 4.0));
        let seed = Seed {
            a: seed_point(&a, face(2, phi + 0.2, 0.05), DVec3::ZERO),
            b: seed_point(&b, vertex(1), DVec3::ZERO),
        };
        let c = refine(&a, &b, &pose_ab, &seed);
        let what = format!("case {k}");
        assert_converged(&c, &what);
        assert_eq!(
            c.location_a.feature(),
            FeatureId::Edge(geom_param::EdgeId(1)),
            "{what}: {c:?}"
        );
        assert_answer(&c, gap, corner, apex, &what);
    }
}

#[test]
fn curve_curve_rim_against_rim() {
    // A's top rim (radius r at z = h) against B's top rim turned into A's xz-plane, centre
    // (r + cc, 0, h), radius r2 < cc: the closest pair is (r, 0, h) and (r + cc - r2, 0, h).
    let (r, h, r2, h2) = (5.0, 10.0, 2.0, 6.0);
    let (a, b) = (cylinder(r, h), cylinder(r2, h2));
    for (k, cc) in [2.5, 3.0, 2.0 + 1e-6, 7.0].into_iter().enumerate() {
        let rotation = DQuat::from_rotation_x(FRAC_PI_2);
        let pose_ab = pose(rotation, DVec3::new(r + cc, h2, h));
        let seed = Seed {
            a: seed_point(&a, edge(1, 0.15), DVec3::ZERO),
            b: seed_point(&b, edge(1, PI - 0.2), DVec3::ZERO),
        };
        let c = refine(&a, &b, &pose_ab, &seed);
        let what = format!("case {k}");
        assert_converged(&c, &what);
        assert_eq!(
            c.location_a.feature(),
            FeatureId::Edge(geom_param::EdgeId(1)),
            "{what}: {c:?}"
        );
        assert_eq!(
            c.location_b.feature(),
            FeatureId::Edge(geom_param::EdgeId(1)),
            "{what}: {c:?}"
        );
        assert_answer(
            &c,
            cc - r2,
            DVec3::new(r, 0.0, h),
            DVec3::new(r + cc - r2, 0.0, h),
            &what,
        );
    }
}

#[test]
fn crossing_rims_penetrating_edge_against_edge() {
    // A's top rim (radius r at z = h) and B's top rim cross, B's rim point P_b = P_a − δ n
    // inside A: n lies strictly inside A's normal cone at P_a (between the side's radial
    // normal and the top's +z, at angle β from the radial), −n strictly inside B's (angle β2
    // from B's radial), and B's rim tangent is normal to n and turned by γ from A's. Both
    // tangents are normal to d = δ n, so (P_a, P_b) is a critical pair of the two rims; the
    // translation along n that separates them is δ: the witness is edge against edge, at
    // distance −δ, with no face involved (the closest boundary point of B to P_a is on one
    // of B's faces, never on its rim).
    let mut rng = Rng(7);
    let (r, h, r2, h2) = (5.0, 10.0, 2.0, 6.0);
    let (a, b) = (cylinder(r, h), cylinder(r2, h2));
    for k in 0..60 {
        let depth = [1e-3, 0.05, 2e-6][k % 3];
        let phi = rng.range(0.0, std::f64::consts::TAU);
        let beta = rng.range(0.3, FRAC_PI_2 - 0.3);
        let beta2 = rng.range(0.3, FRAC_PI_2 - 0.3);
        let gamma = rng.range(0.5, PI - 0.5);
        let radial = DVec3::new(phi.cos(), phi.sin(), 0.0);
        let tangent_a = DVec3::new(-phi.sin(), phi.cos(), 0.0);
        let n = radial * beta.cos() + DVec3::Z * beta.sin();
        let pa = radial * r + DVec3::Z * h;
        let pb = pa - n * depth;
        // B's frame at its rim point (r2, 0, h2): local x its radial, y its tangent, z its axis.
        let tangent_b = tangent_a * gamma.cos() + n.cross(tangent_a) * gamma.sin();
        let k_dir = tangent_b.cross(n);
        let radial_b = -n * beta2.cos() - k_dir * beta2.sin();
        let axis_b = radial_b.cross(tangent_b);
        let q1 = DQuat::from_rotation_arc(DVec3::Z, axis_b);
        let rotation = DQuat::from_rotation_arc(q1 * DVec3::X, radial_b) * q1;
        assert!(
            (rotation * DVec3::Y).distance(tangent_b) < 1e-12,
            "frame {k}"
        );
        let pose_ab = pose(rotation, pb - rotation * DVec3::new(r2, 0.0, h2));
        // Seeds on the rims a little off the witness, or on their faces next to it.
        let offset = rng.range(-0.05, 0.05);
        let seed = if k % 2 == 0 {
            Seed {
                a: seed_point(&a, edge(1, phi + offset), DVec3::ZERO),
                b: seed_point(&b, edge(1, TAU - offset), DVec3::ZERO),
            }
        } else {
            Seed {
                a: seed_point(&a, face(1, phi + offset, 0.999), DVec3::ZERO),
                b: seed_point(&b, face(2, offset, 0.001), DVec3::ZERO),
            }
        };
        let c = refine(&a, &b, &pose_ab, &seed);
        let what = format!("case {k}, depth {depth}, beta {beta}, beta2 {beta2}, gamma {gamma}");
        assert_converged(&c, &what);
        for location in [c.location_a, c.location_b] {
            assert_eq!(
                location.feature(),
                FeatureId::Edge(geom_param::EdgeId(1)),
                "{what}: {c:?}"
            );
        }
        assert_answer(&c, -depth, pa, pb, &what);
    }
}

#[test]
fn curve_surface_sphere_against_rim() {
    // Sphere A against cylinder B's bottom rim, the sphere centre beyond B's corner.
    let mut rng = Rng(6);
    let rs = 4.0;
    let (r, h) = (5.0, 10.0);
    let (a, b) = (sphere(rs), cylinder(r, h));
    for k in 0..50 {
        let phi = rng.range(0.0, std::f64::consts::TAU);
        let beta = rng.range(0.2, 1.3);
        let gap = rng.range(1e-5, 2.0);
        let radial = DVec3::new(phi.cos(), phi.sin(), 0.0);
        let corner = radial * r; // bottom rim point, local to B
        let out = radial * beta.cos() - DVec3::Z * beta.sin();
        let center_local = corner + out * (gap + rs);
        let rotation = rng.rotation();
        // Sphere at A's origin: B's pose puts its centre_local at the origin.
        let pose_ab = pose(rotation, -(rotation * center_local));
        let seed = Seed {
            a: seed_point(&a, face(0, 0.3, 0.5), DVec3::ZERO),
            b: seed_point(&b, face(1, phi - 0.2, 0.02), DVec3::ZERO),
        };
        let c = refine(&a, &b, &pose_ab, &seed);
        let what = format!("case {k}");
        assert_converged(&c, &what);
        assert_eq!(
            c.location_b.feature(),
            FeatureId::Edge(geom_param::EdgeId(0)),
            "{what}: {c:?}"
        );
        let dir = rotation * -out;
        assert_answer(&c, gap, dir * rs, dir * (rs + gap), &what);
    }
}

/// Curve-surface through a trimmed face: from a seed on a tube's top cap (a plane trimmed by
/// two circles) 1.2 mm inside the outer rim, under a sphere beyond the rim, the solve leaves
/// the cap across its trim onto the rim and ends at the closed-form pair (the rim's point
/// against the sphere's, along the line from the sphere's centre).
#[test]
fn curve_surface_sphere_against_a_trimmed_cap_rim() {
    let mut rng = Rng(7);
    let rs = 3.0;
    let (outer, inner, length) = (10.0, 8.0, 20.0);
    let a = sphere(rs);
    let b = geom_param::tube(outer, inner, length).expect("tube");
    for k in 0..40 {
        let phi = rng.range(0.0, TAU);
        let beta = rng.range(0.2, 1.3);
        let gap = rng.range(1e-4, 0.5);
        let radial = DVec3::new(phi.cos(), phi.sin(), 0.0);
        let corner = radial * outer + DVec3::Z * length; // top outer rim point, local to B
        let out = radial * beta.cos() + DVec3::Z * beta.sin();
        let center_local = corner + out * (gap + rs);
        let rotation = rng.rotation();
        let pose_ab = pose(rotation, -(rotation * center_local));
        let on_cap = DVec3::new((phi + 0.1).cos(), (phi + 0.1).sin(), 0.0) * (outer - 1.2);
        // The sphere's seed faces the cap's, as Stage 2's closest mesh points would.
        let (u, v) = sphere_params((pose_ab * (on_cap + DVec3::Z * length)).normalize());
        let seed = Seed {
            a: seed_point(&a, face(0, u, v), DVec3::ZERO),
            b: seed_point(&b, face(3, on_cap.x, on_cap.y), DVec3::ZERO),
        };
        let c = refine(&a, &b, &pose_ab, &seed);
        let what = format!("case {k}");
        assert_converged(&c, &what);
        assert_eq!(
            c.location_b.feature(),
            FeatureId::Edge(geom_param::EdgeId(1)),
            "{what}: {c:?}"
        );
        let dir = rotation * -out;
        assert_answer(&c, gap, dir * rs, dir * (rs + gap), &what);
    }
}

/// Surface-surface at a near touch in a flat valley: a sphere of radius 20 mm 1e-10 mm above a
/// cylinder's top disk (relative curvature 0.05 /mm), seeded 0.01-1 mm along the disk from the
/// closest points. f = ½|d|² has a gradient of |d| x 0.05 x offset, under its rounding floor
/// (16 ε x the coordinates) while the distance is still well above its minimum: stopping
/// there left it up to 1.3e-9 mm high in these 40 cases; the Newton steps on the distance
/// that follow (`touch_polish`) end within 5.3e-12 mm.
#[test]
fn surface_surface_near_touch_in_a_flat_valley() {
    let mut rng = Rng(8);
    let (r, h, rs, gap) = (30.0, 10.0, 20.0, 1e-10);
    let (a, b) = (cylinder(r, h), sphere(rs));
    // B's local +y (longitude pi/2 on the equator) turned to -z: the sphere's nearest point.
    let rotation = DQuat::from_rotation_x(-FRAC_PI_2);
    for k in 0..40 {
        let (phi, rho) = (rng.range(0.0, TAU), rng.range(2.0, 20.0));
        let foot = DVec3::new(rho * phi.cos(), rho * phi.sin(), h);
        let pose_ab = pose(rotation, foot + DVec3::Z * (gap + rs));
        let offset = rng.range(0.01, 1.0);
        let turn = rng.range(0.0, TAU);
        let start = foot + offset * DVec3::new(turn.cos(), turn.sin(), 0.0);
        // The top disk (face 2) runs from the rim (v = 0) to the axis (v = 1).
        let on_disk = face(
            2,
            start.y.atan2(start.x),
            1.0 - start.truncate().length() / r,
        );
        assert!(
            a.point_at(&on_disk).distance(start) < 1e-9,
            "the disk's parameters"
        );
        let seed = Seed {
            a: seed_point(&a, on_disk, DVec3::ZERO),
            b: seed_point(&b, face(0, FRAC_PI_2 + 0.3 * offset / rs, 0.5), DVec3::ZERO),
        };
        let c = refine(&a, &b, &pose_ab, &seed);
        let what = format!("case {k}, offset {offset:.3} mm");
        assert_converged(&c, &what);
        assert!(
            (c.distance - gap).abs() <= 1e-10,
            "{what}: distance {:e} against {gap:e}: {c:?}",
            c.distance
        );
        assert!(c.point_a.distance(foot) <= 1e-3, "{what}: {c:?}");
    }
}
