//! Time per refinement for each feature pair kind, next to the paper's Table 2 (Newton method:
//! point-curve 0.17, curve-curve 0.32, curve-surface 0.62, surface-surface 0.95 ms).
//!
//! Two groups of the same scenes: `refine-stage2-seed` starts where a mesh phase leaves it (seed
//! points 0.05 mm along the surface from the answer, and 0.05 mm off it, the chordal error), and
//! `refine-far-seed` starts 0.1-0.2 rad off (the sphere of the surface-surface cases on its far
//! side, across a pole). The Newton steps per solve are printed once per case.

// `criterion_group!` expands to an undocumented public function.
#![allow(missing_docs)]

use criterion::{Criterion, criterion_group, criterion_main};
use exact_refine::{NewtonRefiner, Refiner};
use geom_param::{
    ComponentId, DPose3, DQuat, DVec3, EdgeId, FaceId, FeatureLocation, MeshOptions, ObjectModel,
    Profile, Seed, SeedPoint, SegmentSpec, Solid, VertexId,
};
use std::f64::consts::{FRAC_PI_2, PI};

fn solid(specs: &[SegmentSpec]) -> Solid {
    let profile = Profile::new(specs).expect("profile");
    let tolerance = 0.05 * profile.scale();
    ObjectModel::from_profile(
        "bench",
        profile,
        &MeshOptions {
            chordal_tolerance: tolerance,
        },
    )
    .expect("model")
    .solid
}

fn sphere(r: f64) -> Solid {
    solid(&[SegmentSpec::Arc {
        center: [0.0, 0.0],
        from: [0.0, -r],
        to: [0.0, r],
        ccw: true,
    }])
}

fn cylinder(r: f64, h: f64) -> Solid {
    solid(&[
        SegmentSpec::Line {
            from: [0.0, 0.0],
            to: [r, 0.0],
        },
        SegmentSpec::Line {
            from: [r, 0.0],
            to: [r, h],
        },
        SegmentSpec::Line {
            from: [r, h],
            to: [0.0, h],
        },
    ])
}

fn cone(r: f64, h: f64) -> Solid {
    solid(&[
        SegmentSpec::Line {
            from: [0.0, 0.0],
            to: [r, 0.0],
        },
        SegmentSpec::Line {
            from: [r, 0.0],
            to: [0.0, h],
        },
    ])
}

fn torus(rc: f64, a: f64) -> Solid {
    solid(&[
        SegmentSpec::Arc {
            center: [rc, 0.0],
            from: [rc, -a],
            to: [rc, a],
            ccw: true,
        },
        SegmentSpec::Arc {
            center: [rc, 0.0],
            from: [rc, a],
            to: [rc, -a],
            ccw: true,
        },
    ])
}

/// A seed point at `location` as a mesh phase gives it: off the exact surface by `offset` (a
/// chordal error).
fn point(s: &Solid, location: FeatureLocation, offset: DVec3) -> SeedPoint {
    SeedPoint {
        component: ComponentId(0),
        local_point: s.point_at(&location) + offset,
        location,
    }
}

/// 0.05 mm, the chordal error of a Stage 2 seed point.
const CHORD: DVec3 = DVec3::new(0.03, -0.03, 0.028_3);

/// A Stage 2 seed's parameter error (rad) on a circle of `radius` (mm): 0.05 mm along it (at
/// most a degree for the radii here).
fn slip(radius: f64) -> f64 {
    0.05 / radius
}

/// One scene with a seed as Stage 2 gives it (`near`) and a far one.
struct Case {
    name: &'static str,
    a: Solid,
    b: Solid,
    pose: DPose3,
    near: Seed,
    far: Seed,
}

fn cases() -> Vec<Case> {
    let mut out = Vec::new();
    // point-curve: cone apex against a cylinder's top rim (answer at t = 0 on the rim).
    let (a, b) = (cylinder(5.0, 10.0), cone(2.0, 4.0));
    let out_dir = DVec3::new(0.6f64.cos(), 0.0, 0.6f64.sin());
    let apex = DVec3::new(5.0, 0.0, 10.0) + out_dir * 0.1;
    let rotation = DQuat::from_rotation_arc(DVec3::Z, -out_dir);
    let rim = |t| FeatureLocation::Edge { id: EdgeId(1), t };
    let tip = FeatureLocation::Vertex { id: VertexId(1) };
    out.push(Case {
        name: "point-curve",
        pose: DPose3 {
            rotation,
            translation: apex - rotation * DVec3::new(0.0, 0.0, 4.0),
        },
        near: Seed {
            a: point(&a, rim(slip(5.0)), CHORD),
            b: point(&b, tip, CHORD),
        },
        far: Seed {
            a: point(&a, rim(0.15), DVec3::ZERO),
            b: point(&b, tip, DVec3::ZERO),
        },
        a,
        b,
    });
    // curve-curve: two rims in perpendicular planes (answer at t = 0 on A, t = π on B).
    let (a, b) = (cylinder(5.0, 10.0), cylinder(2.0, 6.0));
    out.push(Case {
        name: "curve-curve",
        pose: DPose3 {
            rotation: DQuat::from_rotation_x(FRAC_PI_2),
            translation: DVec3::new(8.0, 6.0, 10.0),
        },
        near: Seed {
            a: point(&a, rim(slip(5.0)), CHORD),
            b: point(&b, rim(PI - slip(2.0)), CHORD),
        },
        far: Seed {
            a: point(&a, rim(0.15), DVec3::ZERO),
            b: point(&b, rim(PI - 0.2), DVec3::ZERO),
        },
        a,
        b,
    });
    // curve-surface: a sphere against a cylinder's bottom rim (answer at the sphere's (π, v0),
    // the rim's t = 0); the far seed starts on the cylinder's side face.
    let (a, b) = (sphere(4.0), cylinder(5.0, 10.0));
    let dir = DVec3::new(0.7f64.cos(), 0.0, -(0.7f64.sin()));
    let center_local = DVec3::new(5.0, 0.0, 0.0) + dir * 4.1;
    let v0 = (0.7 + FRAC_PI_2) / PI;
    let face = |id, u, v| FeatureLocation::Face {
        id: FaceId(id),
        u,
        v,
    };
    out.push(Case {
        name: "curve-surface",
        pose: DPose3 {
            rotation: DQuat::IDENTITY,
            translation: -center_local,
        },
        near: Seed {
            a: point(
                &a,
                face(0, PI + slip(4.0 * 0.7f64.cos()), v0 + slip(4.0) / PI),
                CHORD,
            ),
            b: point(
                &b,
                FeatureLocation::Edge {
                    id: EdgeId(0),
                    t: slip(5.0),
                },
                CHORD,
            ),
        },
        far: Seed {
            a: point(&a, face(0, PI + 0.1, 0.7), DVec3::ZERO),
            b: point(&b, face(1, 0.1, 0.03), DVec3::ZERO),
        },
        a,
        b,
    });
    // surface-surface: a sphere against a torus, separated by 0.1 and penetrating by 0.5 (answer
    // at the torus's (φ, (θ + π/2)/π), the sphere's (φ + π, (π/2 − θ)/π)).
    let (phi, theta) = (1.0f64, 0.4f64);
    let out_dir = DVec3::new(
        theta.cos() * phi.cos(),
        theta.cos() * phi.sin(),
        theta.sin(),
    );
    let (va, vb) = ((theta + FRAC_PI_2) / PI, (FRAC_PI_2 - theta) / PI);
    for (name, offset) in [
        ("surface-surface", 8.1),
        ("surface-surface penetrating", 7.5),
    ] {
        let (a, b) = (torus(20.0, 5.0), sphere(3.0));
        let center = DVec3::new(20.0 * phi.cos(), 20.0 * phi.sin(), 0.0) + out_dir * offset;
        out.push(Case {
            name,
            pose: DPose3 {
                rotation: DQuat::IDENTITY,
                translation: center,
            },
            near: Seed {
                a: point(
                    &a,
                    face(0, phi + slip(20.0 + 5.0 * theta.cos()), va + slip(5.0) / PI),
                    CHORD,
                ),
                b: point(
                    &b,
                    face(0, phi + PI - slip(3.0 * theta.cos()), vb + slip(3.0) / PI),
                    CHORD,
                ),
            },
            far: Seed {
                a: point(&a, face(0, phi + 0.05, va + 0.02), DVec3::ZERO),
                b: point(&b, face(0, 0.0, 0.2), DVec3::ZERO),
            },
            a,
            b,
        });
    }
    out
}

fn bench(c: &mut Criterion) {
    let refiner = NewtonRefiner::default();
    let cases = cases();
    for (group_name, near) in [("refine-stage2-seed", true), ("refine-far-seed", false)] {
        let mut group = c.benchmark_group(group_name);
        for case in &cases {
            let seed = if near { &case.near } else { &case.far };
            let result = refiner.refine(&case.a, &case.b, &case.pose, seed, &mut ());
            println!(
                "{group_name}/{}: {:?}, {} Newton steps, distance {:.6}",
                case.name,
                result.diagnostics.status,
                result.diagnostics.iterations,
                result.distance
            );
            group.bench_function(case.name, |bench| {
                bench.iter(|| {
                    refiner.refine(
                        &case.a,
                        &case.b,
                        &case.pose,
                        std::hint::black_box(seed),
                        &mut (),
                    )
                })
            });
        }
        group.finish();
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
