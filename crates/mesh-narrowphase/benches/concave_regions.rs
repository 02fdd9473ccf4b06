//! Concave region finding: proxy-mesh collision regions and seeds for (1) a ball resting in a
//! spherical bowl across mesh resolutions, and (2) a rod across a torus whose ring radius grows
//! while the contact stays the same, so the mesh grows but the triangles near the contact do not.

use criterion::Criterion;
use geom_param::{
    ComponentId, DPose3, DQuat, DVec3, MeshOptions, ObjectModel, Profile, SegmentSpec,
};
use mesh_narrowphase::{
    ComponentRef, ContactBand, MeshNarrowphase, MeshOutput, MeshPhase, MeshScratch, MeshVerdict,
};
use std::hint::black_box;

fn model(specs: &[SegmentSpec], tolerance: f64) -> ObjectModel {
    let profile = Profile::new(specs).expect("profile");
    ObjectModel::from_profile(
        "bench",
        profile,
        &MeshOptions {
            chordal_tolerance: tolerance,
        },
    )
    .expect("model")
}

fn sphere(r: f64, tolerance: f64) -> ObjectModel {
    model(
        &[SegmentSpec::Arc {
            center: [0.0, 0.0],
            from: [0.0, -r],
            to: [0.0, r],
            ccw: true,
        }],
        tolerance,
    )
}

fn socket(tolerance: f64) -> ObjectModel {
    model(
        &[
            SegmentSpec::Arc {
                center: [0.0, 40.0],
                from: [0.0, 5.0],
                to: [35.0, 40.0],
                ccw: true,
            },
            SegmentSpec::Line {
                from: [35.0, 40.0],
                to: [30.0, 40.0],
            },
            SegmentSpec::Arc {
                center: [0.0, 40.0],
                from: [30.0, 40.0],
                to: [0.0, 10.0],
                ccw: false,
            },
        ],
        tolerance,
    )
}

fn torus(rc: f64, a: f64, tolerance: f64) -> ObjectModel {
    model(
        &[
            SegmentSpec::Arc {
                center: [rc, 0.0],
                from: [rc + a, 0.0],
                to: [rc - a, 0.0],
                ccw: true,
            },
            SegmentSpec::Arc {
                center: [rc, 0.0],
                from: [rc - a, 0.0],
                to: [rc + a, 0.0],
                ccw: true,
            },
        ],
        tolerance,
    )
}

fn cylinder(r: f64, h: f64, tolerance: f64) -> ObjectModel {
    model(
        &[
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
        ],
        tolerance,
    )
}

fn run(
    c: &mut Criterion,
    label: String,
    (a, ca): (&ObjectModel, ComponentId),
    (b, cb): (&ObjectModel, ComponentId),
    pose: DPose3,
) {
    let phase = MeshNarrowphase::default();
    let (pa, pb) = (phase.prepare(a), phase.prepare(b));
    let band = ContactBand {
        margin: 0.5,
        delta1: -0.05,
        delta2: 0.3,
    };
    let mut scratch = MeshScratch::default();
    let mut out = MeshOutput::default();
    let mut go = |out: &mut MeshOutput| {
        phase.query(
            ComponentRef {
                object: a,
                prepared: &pa,
                component: ca,
            },
            ComponentRef {
                object: b,
                prepared: &pb,
                component: cb,
            },
            &pose,
            &band,
            &mut scratch,
            out,
        )
    };
    assert_eq!(go(&mut out), MeshVerdict::Seeds);
    println!(
        "{label}: {} + {} triangles, {} triangle pairs tested, {} regions",
        a.mesh(ca).len(),
        b.mesh(cb).len(),
        out.stats.triangle_pairs_tested,
        out.stats.regions
    );
    c.bench_function(&label, |bench| bench.iter(|| black_box(go(&mut out))));
}

fn bench(c: &mut Criterion) {
    for tolerance in [0.1, 0.03, 0.01, 0.003] {
        let (bowl, ball) = (socket(tolerance), sphere(10.0, tolerance));
        let inner = bowl
            .components
            .iter()
            .find(|c| c.faces.len() == 1 && c.id.0 > 0)
            .map_or(ComponentId(1), |c| c.id);
        let pose = DPose3 {
            rotation: DQuat::IDENTITY,
            translation: DVec3::new(0.0, 0.0, 20.1),
        };
        run(
            c,
            format!("concave/ball_in_bowl/tol{tolerance}"),
            (&bowl, inner),
            (&ball, ComponentId(0)),
            pose,
        );
    }
    for rc in [20.0, 40.0, 80.0, 160.0] {
        let (ring, rod) = (torus(rc, 5.0, 0.02), cylinder(4.0, 2.0 * rc + 40.0, 0.02));
        let pose = DPose3 {
            rotation: DQuat::from_rotation_y(std::f64::consts::FRAC_PI_2),
            translation: DVec3::new(-(rc + 20.0), 0.0, 5.0 + 0.1 + 4.0),
        };
        run(
            c,
            format!("concave/rod_across_torus/rc{rc}"),
            (&ring, ComponentId(0)),
            (&rod, ComponentId(0)),
            pose,
        );
    }
}

// What `criterion_group!` / `criterion_main!` expand to, written out so that no undocumented
// public function is generated.
fn main() {
    let mut c = Criterion::default().configure_from_args();
    bench(&mut c);
    c.final_summary();
}
