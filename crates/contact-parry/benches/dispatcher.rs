//! Contact manifolds of two paper scenes (pencil-bowl and vase-vase, two contacts each) through
//! parry's `PersistentQueryDispatcher`, in one run:
//! - `exact_warm`: the exact dispatcher with the pair's workspace kept (coherent frames) while
//!   B moves along a small smooth motion (0.2 µm and 0.3 µrad per frame), so most frames are
//!   warm (Stage 3 from the tracked minima) and one in 65 is a full query;
//! - `exact_cold`: the same poses, a fresh workspace each call (a full pipeline query);
//! - `parry_trimesh_warm` / `parry_trimesh_cold`: parry's default dispatcher on the same
//!   objects' closed meshes (the welded component meshes at 0.05 mm, as `TriMesh`es), with and
//!   without its workspace.
//!
//! `cargo bench -p contact-parry --bench dispatcher`; the ratios are in the final summary line
//! of each scene (mean of the sampled iterations, measured again outside criterion).

#[path = "../tests/support/fixtures.rs"]
mod fixtures;

use contact_parry::{DispatcherOptions, ExactDispatcher, ExactShape};
use criterion::{Criterion, criterion_main};
use parry3d_f64::math::{Pose, Vector};
use parry3d_f64::query::{ContactManifold, DefaultQueryDispatcher, PersistentQueryDispatcher};
use parry3d_f64::shape::Shape;
use std::hint::black_box;
use std::time::Instant;

type Manifolds = Vec<ContactManifold<(), ()>>;

/// B's pose in A's frame at frame `k` of the small motion, cycling over 256 frames.
fn pose_at(base: &Pose, k: usize) -> Pose {
    let t = (k % 256) as f64;
    Pose::from_parts(
        Vector::new(2e-4 * t, -1e-4 * t, 0.0),
        glam::DQuat::from_rotation_z(3e-7 * t),
    ) * *base
}

/// Mean time (µs) of `frames` calls of `f` on consecutive frames.
fn mean_us(frames: usize, mut f: impl FnMut(usize)) -> f64 {
    let start = Instant::now();
    for k in 0..frames {
        f(k);
    }
    start.elapsed().as_secs_f64() * 1e6 / frames as f64
}

fn manifolds_of(
    dispatcher: &impl PersistentQueryDispatcher<(), ()>,
    a: &dyn Shape,
    b: &dyn Shape,
    pos12: &Pose,
    out: &mut Manifolds,
    workspace: &mut Option<parry3d_f64::query::ContactManifoldsWorkspace>,
) -> usize {
    dispatcher
        .contact_manifolds(pos12, a, b, 0.1, out, workspace)
        .expect("supported");
    out.iter().map(|m| m.points.len()).sum()
}

fn bench(c: &mut Criterion) {
    for name in ["pencil-bowl-two-contacts", "vase-vase-two-contacts"] {
        let scene = fixtures::scene(name);
        let base = scene.pose_a.inverse() * scene.pose_b;
        let (a, b): (&ExactShape, &ExactShape) = (&scene.a, &scene.b);
        let (ma, mb) = (&a.closed_mesh().trimesh, &b.closed_mesh().trimesh);
        let exact = ExactDispatcher::new(DispatcherOptions::default());
        let parry = DefaultQueryDispatcher;
        let mut group = c.benchmark_group(format!("dispatcher/{name}"));
        let mut out = Manifolds::new();

        let mut workspace = None;
        let mut k = 0;
        group.bench_function("exact_warm", |bench| {
            bench.iter(|| {
                k += 1;
                black_box(manifolds_of(
                    &exact,
                    a,
                    b,
                    &pose_at(&base, k),
                    &mut out,
                    &mut workspace,
                ))
            })
        });
        let mut k = 0;
        group.bench_function("exact_cold", |bench| {
            bench.iter(|| {
                k += 1;
                black_box(manifolds_of(
                    &exact,
                    a,
                    b,
                    &pose_at(&base, k),
                    &mut out,
                    &mut None,
                ))
            })
        });
        let mut workspace = None;
        let mut k = 0;
        group.bench_function("parry_trimesh_warm", |bench| {
            bench.iter(|| {
                k += 1;
                black_box(manifolds_of(
                    &parry,
                    ma,
                    mb,
                    &pose_at(&base, k),
                    &mut out,
                    &mut workspace,
                ))
            })
        });
        let mut k = 0;
        group.bench_function("parry_trimesh_cold", |bench| {
            bench.iter(|| {
                k += 1;
                black_box(manifolds_of(
                    &parry,
                    ma,
                    mb,
                    &pose_at(&base, k),
                    &mut out,
                    &mut None,
                ))
            })
        });
        group.finish();

        // The same four, timed side by side over one 256-frame cycle, for the ratios.
        let frames = 256;
        let mut ws = None;
        let warm = mean_us(frames, |k| {
            manifolds_of(&exact, a, b, &pose_at(&base, k), &mut out, &mut ws);
        });
        let exact_points = manifolds_of(&exact, a, b, &base, &mut out, &mut None);
        let cold = mean_us(frames, |k| {
            manifolds_of(&exact, a, b, &pose_at(&base, k), &mut out, &mut None);
        });
        let mut ws = None;
        let parry_warm = mean_us(frames, |k| {
            manifolds_of(&parry, ma, mb, &pose_at(&base, k), &mut out, &mut ws);
        });
        let parry_points = manifolds_of(&parry, ma, mb, &base, &mut out, &mut None);
        let parry_cold = mean_us(frames, |k| {
            manifolds_of(&parry, ma, mb, &pose_at(&base, k), &mut out, &mut None);
        });
        let counts = exact.counters().snapshot();
        println!(
            "{name}: exact warm {warm:.1} µs, cold {cold:.1} µs ({exact_points} points); parry trimesh warm {parry_warm:.1} µs, cold {parry_cold:.1} µs ({parry_points} points, {} + {} triangles); cold/warm {:.1}, parry warm / exact warm {:.2}, parry cold / exact cold {:.2}; dispatcher frames {counts:?}",
            ma.indices().len(),
            mb.indices().len(),
            cold / warm,
            parry_warm / warm,
            parry_cold / cold,
        );
    }
}

/// Small samples: the machine is shared; the side-by-side summary gives the ratios.
fn config() -> Criterion {
    Criterion::default()
        .sample_size(20)
        .warm_up_time(std::time::Duration::from_millis(500))
        .measurement_time(std::time::Duration::from_secs(2))
}

fn benches() {
    let mut c = config().configure_from_args();
    bench(&mut c);
}
criterion_main!(benches);
