//! Planted answers: a point and outward normal chosen on a face of a paper object (lines, arcs
//! and Beziers revolved), a second object placed so that its own chosen point touches along that
//! normal at a chosen gap (negative: penetrating), then that gap and those points must be found
//! from perturbed seeds.

mod support;

use geom_param::{DQuat, DVec3, FaceId, MeshOptions, ObjectDescription, ObjectModel, Seed, Solid};
use support::*;

fn fixture(name: &str) -> ObjectModel {
    let path = format!(
        "{}/../../fixtures/objects/{name}.json",
        env!("CARGO_MANIFEST_DIR")
    );
    let text = std::fs::read_to_string(&path).expect("fixture");
    ObjectDescription::from_json(&text)
        .expect("parse")
        .build(&MeshOptions {
            chordal_tolerance: 0.05,
        })
        .expect("build")
}

/// A random interior point of a random face of `solid` whose smallest principal curvature is
/// above `min_curvature`: (face, u, v, point, normal).
fn pick(solid: &Solid, rng: &mut Rng, min_curvature: f64) -> (u32, f64, f64, DVec3, DVec3) {
    loop {
        let f = (rng.next_u64() % solid.faces.len() as u64) as u32;
        let surface = &solid.face(FaceId(f)).surface;
        let (u, v) = (rng.range(0.0, std::f64::consts::TAU), rng.range(0.1, 0.9));
        let (Some(n), Some(k)) = (surface.normal(u, v), surface.principal_curvatures(u, v)) else {
            continue;
        };
        if k.min > min_curvature {
            return (f, u, v, surface.eval(u, v).point, n);
        }
    }
}

/// Plants `b` against `a` and checks the answer; returns how many cases ran.
fn plant(a: &Solid, b: &Solid, b_min_curvature: f64, seed_value: u64, cases: usize) {
    let mut rng = Rng(seed_value);
    for k in 0..cases {
        // A's point must curve less towards B than B curves away: κ_a,min > -κ_b,min / 2.
        let (fa, ua, va, pa, na) = pick(a, &mut rng, -0.5 * b_min_curvature);
        let (fb, ub, vb, pb_local, nb_local) = pick(b, &mut rng, 0.0);
        let gap = [1.0, 1e-3, 1e-8, -1e-3, -0.2][k % 5];
        // Turn B so its normal opposes A's, spin it randomly about that line, and place it.
        let align = DQuat::from_rotation_arc(nb_local, -na);
        let rotation = DQuat::from_axis_angle(na, rng.range(0.0, std::f64::consts::TAU)) * align;
        let pb = pa + na * gap;
        let pose_ab = pose(rotation, pb - rotation * pb_local);
        let seed = Seed {
            a: seed_point(
                a,
                face(fa, ua + rng.range(-0.02, 0.02), va + rng.range(-0.02, 0.02)),
                DVec3::ZERO,
            ),
            b: seed_point(
                b,
                face(fb, ub + rng.range(-0.02, 0.02), vb + rng.range(-0.02, 0.02)),
                DVec3::ZERO,
            ),
        };
        let c = refine(a, b, &pose_ab, &seed);
        let what =
            format!("case {k}: A face {fa} ({ua}, {va}), B face {fb} ({ub}, {vb}), gap {gap}");
        assert_converged(&c, &what);
        assert_answer(&c, gap, pa, pb, &what);
    }
}

#[test]
fn small_sphere_planted_on_every_paper_object() {
    let b = sphere(1.0);
    for (i, name) in ["paperweight", "goblet", "bowl", "pencil", "jar", "vase"]
        .into_iter()
        .enumerate()
    {
        let a = fixture(name);
        plant(&a.solid, &b, 1.0, 10 + i as u64, 60);
    }
}

#[test]
fn torus_planted_on_paper_objects() {
    // Outer half of a torus (core 6, tube 2): smallest principal curvature 1 / (6 + 2) on it.
    let b = torus(6.0, 2.0);
    for (i, name) in ["paperweight", "vase", "jar"].into_iter().enumerate() {
        let a = fixture(name);
        plant(&a.solid, &b, 1.0 / 8.0, 20 + i as u64, 40);
    }
}
