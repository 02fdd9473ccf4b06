//! Stage 2 on concave pairs across mesh resolution, old path against new in one run: the
//! pencil resting in the bowl (the fixture's two-contact pose, every component pair) and a ball
//! of radius 8 in a spherical cavity of radius 20 at gap 0.02 mm, tilted 0.3 rad (the report's
//! scene), at chordal tolerances 0.2, 0.05 and 0.01 mm, for
//! - `proxy`: [`ConcavePath::ProxyRegions`], the paper's proxy-mesh regions;
//! - `cones-warm`: [`ConcavePath::NormalCones`] repeating the pose with one scratch (the
//!   traversal front of the previous query is carried, as between the frames of a simulation);
//! - `cones-cold`: the same with the scratch's warm starts and fronts forgotten before every
//!   query (a pose never seen).

use criterion::Criterion;
use geom_param::{
    DPose3, DQuat, DVec3, MeshOptions, ObjectDescription, ObjectModel, Profile, SegmentSpec,
};
use mesh_narrowphase::{
    ComponentRef, ConcavePath, ContactBand, MeshNarrowphase, MeshNarrowphaseOptions, MeshOutput,
    MeshPhase, MeshScratch, PreparedObject,
};
use std::hint::black_box;
use std::time::Duration;

fn options(tolerance: f64) -> MeshOptions {
    MeshOptions {
        chordal_tolerance: tolerance,
    }
}

fn paper_object(name: &str, tolerance: f64) -> ObjectModel {
    let path = format!(
        "{}/../../fixtures/objects/{name}.json",
        env!("CARGO_MANIFEST_DIR")
    );
    let text = std::fs::read_to_string(&path).expect("fixture exists");
    ObjectDescription::from_json(&text)
        .expect("valid fixture")
        .build(&options(tolerance))
        .expect("valid tolerance")
}

fn profile_object(specs: &[SegmentSpec], tolerance: f64) -> ObjectModel {
    let profile = Profile::new(specs).expect("profile");
    ObjectModel::from_profile("bench", profile, &options(tolerance)).expect("model")
}

/// The report's sphere_in_bowl(r 8, R 20, gap 0.02, tilt 0.3): the ball is A, the bowl (a block
/// with a spherical cavity of radius 20 about the origin, opening upwards) is B at the
/// identity; returns both and B's pose in A's frame.
fn sphere_in_bowl(tolerance: f64) -> (ObjectModel, ObjectModel, DPose3) {
    let (r, big, gap, tilt) = (8.0, 20.0, 0.02, 0.3_f64);
    let (w, t) = (1.5 * big, 0.3 * big);
    let ball = profile_object(
        &[SegmentSpec::Arc {
            center: [0.0, 0.0],
            from: [0.0, -r],
            to: [0.0, r],
            ccw: true,
        }],
        tolerance,
    );
    let line = |from: [f64; 2], to: [f64; 2]| SegmentSpec::Line { from, to };
    let bowl = profile_object(
        &[
            line([0.0, -big - t], [w, -big - t]),
            line([w, -big - t], [w, 0.0]),
            line([w, 0.0], [big, 0.0]),
            SegmentSpec::Arc {
                center: [0.0, 0.0],
                from: [big, 0.0],
                to: [0.0, -big],
                ccw: false,
            },
        ],
        tolerance,
    );
    let direction = DVec3::new(tilt.sin(), 0.0, -tilt.cos());
    let pose_a = DPose3 {
        rotation: DQuat::IDENTITY,
        translation: direction * (big - r - gap),
    };
    (ball, bowl, pose_a.inverse())
}

/// The fixture pencil-bowl-two-contacts: the bowl (A) at the identity, the pencil (B) resting
/// in it (pose copied from fixtures/scenes/pencil-bowl-two-contacts.json).
fn pencil_in_bowl(tolerance: f64) -> (ObjectModel, ObjectModel, DPose3) {
    let pose = DPose3 {
        rotation: DQuat::from_xyzw(0.0, 0.8977059759571835, 0.0, 0.44059503030647196),
        translation: DVec3::new(-130.3998473869082, 0.0, 114.60598684057987),
    };
    (
        paper_object("bowl", tolerance),
        paper_object("pencil", tolerance),
        pose,
    )
}

/// A scene at a chordal tolerance: objects A and B and B's pose in A's frame.
type SceneBuilder = fn(f64) -> (ObjectModel, ObjectModel, DPose3);

/// Stage 2 over every component pair of `a` and `b`; the number of seeds.
fn stage2(
    phase: &MeshNarrowphase,
    (a, pa): (&ObjectModel, &PreparedObject),
    (b, pb): (&ObjectModel, &PreparedObject),
    pose_ab: &DPose3,
    scratch: &mut MeshScratch,
    out: &mut MeshOutput,
) -> usize {
    let band = ContactBand {
        margin: 1.0,
        delta1: -0.001,
        delta2: 0.1,
    };
    let mut seeds = 0;
    for ca in &a.components {
        for cb in &b.components {
            phase.query(
                ComponentRef {
                    object: a,
                    prepared: pa,
                    component: ca.id,
                },
                ComponentRef {
                    object: b,
                    prepared: pb,
                    component: cb.id,
                },
                pose_ab,
                &band,
                scratch,
                out,
            );
            seeds += out.seeds.len();
        }
    }
    seeds
}

fn bench(c: &mut Criterion) {
    let scenes: [(&str, SceneBuilder); 2] = [
        ("pencil_in_bowl", pencil_in_bowl),
        ("sphere_in_bowl", sphere_in_bowl),
    ];
    for (name, build) in scenes {
        let mut group = c.benchmark_group(format!("stage2/{name}"));
        group
            .warm_up_time(Duration::from_millis(300))
            .measurement_time(Duration::from_millis(1500))
            .sample_size(20);
        for tolerance in [0.2, 0.05, 0.01] {
            let (a, b, pose_ab) = build(tolerance);
            for (label, path, cold) in [
                ("proxy", ConcavePath::ProxyRegions, false),
                ("cones-warm", ConcavePath::NormalCones, false),
                ("cones-cold", ConcavePath::NormalCones, true),
            ] {
                let phase = MeshNarrowphase {
                    options: MeshNarrowphaseOptions {
                        concave_path: path,
                        ..MeshNarrowphaseOptions::default()
                    },
                };
                let (pa, pb) = (phase.prepare(&a), phase.prepare(&b));
                let mut scratch = MeshScratch::default();
                let mut out = MeshOutput::default();
                let go = |scratch: &mut MeshScratch, out: &mut MeshOutput| {
                    if cold {
                        scratch.forget_warm_starts();
                    }
                    stage2(&phase, (&a, &pa), (&b, &pb), &pose_ab, scratch, out)
                };
                // Untimed: builds the lazily prepared proxies and patch trees.
                let seeds = go(&mut scratch, &mut out);
                let triangles: usize = a.meshes.iter().chain(&b.meshes).map(|m| m.len()).sum();
                println!(
                    "{name} chordal {tolerance} {label}: {triangles} triangles, {seeds} seeds"
                );
                group.bench_function(format!("chordal{tolerance}/{label}"), |bench| {
                    bench.iter(|| black_box(go(&mut scratch, &mut out)));
                });
            }
        }
        group.finish();
    }
}

// What `criterion_group!` / `criterion_main!` expand to, written out so that no undocumented
// public function is generated.
fn main() {
    let mut c = Criterion::default().configure_from_args();
    bench(&mut c);
    c.final_summary();
}
