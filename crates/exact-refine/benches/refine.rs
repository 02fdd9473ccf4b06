//! Time per refinement for each feature pair kind, next to the paper's Table 2 (Newton method:
//! point-curve 0.17, curve-curve 0.32, curve-surface 0.62, surface-surface 0.95 ms). Seeds are
//! 0.05-0.2 rad from the answer, as a mesh phase gives them; the Newton steps per solve are
//! printed once per case.

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

fn point(s: &Solid, location: FeatureLocation) -> SeedPoint {
    SeedPoint {
        component: ComponentId(0),
        local_point: s.point_at(&location),
        location,
    }
}

struct Case {
    name: &'static str,
    a: Solid,
    b: Solid,
    pose: DPose3,
    seed: Seed,
}

fn cases() -> Vec<Case> {
    let mut out = Vec::new();
    // point-curve: cone apex against a cylinder's top rim.
    let (a, b) = (cylinder(5.0, 10.0), cone(2.0, 4.0));
    let out_dir = DVec3::new(0.6f64.cos(), 0.0, 0.6f64.sin());
    let apex = DVec3::new(5.0, 0.0, 10.0) + out_dir * 0.1;
    let rotation = DQuat::from_rotation_arc(DVec3::Z, -out_dir);
    let seed = Seed {
        a: point(
            &a,
            FeatureLocation::Edge {
                id: EdgeId(1),
                t: 0.15,
            },
        ),
        b: point(&b, FeatureLocation::Vertex { id: VertexId(1) }),
    };
    out.push(Case {
        name: "point-curve",
        pose: DPose3 {
            rotation,
            translation: apex - rotation * DVec3::new(0.0, 0.0, 4.0),
        },
        seed,
        a,
        b,
    });
    // curve-curve: two rims in perpendicular planes.
    let (a, b) = (cylinder(5.0, 10.0), cylinder(2.0, 6.0));
    let seed = Seed {
        a: point(
            &a,
            FeatureLocation::Edge {
                id: EdgeId(1),
                t: 0.15,
            },
        ),
        b: point(
            &b,
            FeatureLocation::Edge {
                id: EdgeId(1),
                t: PI - 0.2,
            },
        ),
    };
    out.push(Case {
        name: "curve-curve",
        pose: DPose3 {
            rotation: DQuat::from_rotation_x(FRAC_PI_2),
            translation: DVec3::new(8.0, 6.0, 10.0),
        },
        seed,
        a,
        b,
    });
    // curve-surface: a sphere against a cylinder's bottom rim.
    let (a, b) = (sphere(4.0), cylinder(5.0, 10.0));
    let dir = DVec3::new(0.7f64.cos(), 0.0, -(0.7f64.sin()));
    let center_local = DVec3::new(5.0, 0.0, 0.0) + dir * 4.1;
    let seed = Seed {
        a: point(
            &a,
            FeatureLocation::Face {
                id: FaceId(0),
                u: PI + 0.1,
                v: 0.7,
            },
        ),
        b: point(
            &b,
            FeatureLocation::Face {
                id: FaceId(1),
                u: 0.1,
                v: 0.03,
            },
        ),
    };
    out.push(Case {
        name: "curve-surface",
        pose: DPose3 {
            rotation: DQuat::IDENTITY,
            translation: -center_local,
        },
        seed,
        a,
        b,
    });
    // surface-surface: a sphere against a torus.
    let (a, b) = (torus(20.0, 5.0), sphere(3.0));
    let (phi, theta) = (1.0f64, 0.4f64);
    let out_dir = DVec3::new(
        theta.cos() * phi.cos(),
        theta.cos() * phi.sin(),
        theta.sin(),
    );
    let center = DVec3::new(20.0 * phi.cos(), 20.0 * phi.sin(), 0.0) + out_dir * 8.1;
    let seed = Seed {
        a: point(
            &a,
            FeatureLocation::Face {
                id: FaceId(0),
                u: phi + 0.05,
                v: (theta + FRAC_PI_2) / PI + 0.02,
            },
        ),
        b: point(
            &b,
            FeatureLocation::Face {
                id: FaceId(0),
                u: 0.0,
                v: 0.2,
            },
        ),
    };
    out.push(Case {
        name: "surface-surface",
        pose: DPose3 {
            rotation: DQuat::IDENTITY,
            translation: center,
        },
        seed,
        a,
        b,
    });
    // surface-surface, penetrating by 0.5 mm.
    let (a, b) = (torus(20.0, 5.0), sphere(3.0));
    let center = DVec3::new(20.0 * phi.cos(), 20.0 * phi.sin(), 0.0) + out_dir * 7.5;
    let seed = Seed {
        a: point(
            &a,
            FeatureLocation::Face {
                id: FaceId(0),
                u: phi + 0.05,
                v: (theta + FRAC_PI_2) / PI + 0.02,
            },
        ),
        b: point(
            &b,
            FeatureLocation::Face {
                id: FaceId(0),
                u: 0.0,
                v: 0.2,
            },
        ),
    };
    out.push(Case {
        name: "surface-surface penetrating",
        pose: DPose3 {
            rotation: DQuat::IDENTITY,
            translation: center,
        },
        seed,
        a,
        b,
    });
    out
}

fn bench(c: &mut Criterion) {
    let refiner = NewtonRefiner::default();
    let mut group = c.benchmark_group("refine");
    for case in cases() {
        let result = refiner.refine(&case.a, &case.b, &case.pose, &case.seed, &mut ());
        println!(
            "{}: {:?}, {} Newton steps, distance {:.6}",
            case.name, result.diagnostics.status, result.diagnostics.iterations, result.distance
        );
        group.bench_function(case.name, |bench| {
            bench.iter(|| {
                refiner.refine(
                    &case.a,
                    &case.b,
                    &case.pose,
                    std::hint::black_box(&case.seed),
                    &mut (),
                )
            })
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
