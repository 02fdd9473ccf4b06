//! Per-frame cost of coherent queries against cold ones in the same run, on the paper's four
//! two-contact scenes (fixtures/) at small motion, along four trajectories about the first
//! contact (point c, normal n, a tangent u): **rolling**, B turned back and forth about n × u
//! through c (amplitude 2e-3 rad, 2.5e-5 rad per frame), lifted 2 µm so both contacts stay in
//! the band; **sliding**, moved back and forth along u (amplitude 0.05 mm), lifted 2 µm;
//! **approaching**, lowered along n from 0.15 mm to 2 µm above the scene's pose; **leaving**,
//! the reverse (as `cargo xtask coherence`, which tabulates them). `warm` is [`ContactPipeline::query_coherent`] along the trajectory (a full query
//! every `max_warm_frames` = 64 frames, so the time is the amortised one), `warm-only` the same
//! with the chain never broken by the frame count (the certificate alone decides), `cold`
//! [`ContactPipeline::query_into`] with a persistent scratch along the same trajectory. The
//! target (issue 16) is at most 3 µs per contact per frame: divide by the scene's 2 contacts.

// `criterion_group!` expands to an undocumented public function.
#![allow(missing_docs)]

use contact_pipeline::{
    CoherenceOptions, ContactPipeline, FrameKind, PairCache, PairReport, PreparedObject,
    QueryScratch,
};
use criterion::{Criterion, criterion_group, criterion_main};
use fixture_scene::{FixtureScene, load_scene};
use geom_param::{DPose3, DQuat, DVec3};
use std::hint::black_box;
use std::time::Duration;

const SCENES: [&str; 4] = [
    "pencil-paperweight-two-contacts",
    "paperweight-goblet-two-contacts",
    "pencil-bowl-two-contacts",
    "vase-vase-two-contacts",
];

/// Frames of one back-and-forth roll.
const FRAMES: usize = 320;

#[path = "../tests/support/fixture_scene.rs"]
mod fixture_scene;

/// How B moves (see the module documentation).
#[derive(Clone, Copy)]
enum Motion {
    Rolling,
    Sliding,
    Approaching,
    Leaving,
}

impl Motion {
    const ALL: [(Self, &'static str); 4] = [
        (Self::Rolling, "rolling"),
        (Self::Sliding, "sliding"),
        (Self::Approaching, "approaching"),
        (Self::Leaving, "leaving"),
    ];

    /// B's pose at frame `k` from its scene pose `pose_b`, the first contact at `c` with
    /// normal `n`.
    fn pose(self, k: usize, c: DVec3, n: DVec3, pose_b: DPose3) -> DPose3 {
        let phase = (std::f64::consts::TAU * k as f64 / FRAMES as f64).sin();
        let lowered = |from: f64, to: f64| {
            let lift = from + (to - from) * k as f64 / (FRAMES - 1) as f64;
            DPose3::from_parts(n * lift, DQuat::IDENTITY) * pose_b
        };
        match self {
            Self::Rolling => {
                let axis = n.cross(n.any_orthonormal_vector()).normalize();
                let r = DQuat::from_axis_angle(axis, 2e-3 * phase);
                DPose3::from_parts(c - r * c + n * 0.002, r) * pose_b
            }
            Self::Sliding => {
                let u = n.any_orthonormal_vector();
                DPose3::from_parts(u * (0.05 * phase) + n * 0.002, DQuat::IDENTITY) * pose_b
            }
            Self::Approaching => lowered(0.15, 0.002),
            Self::Leaving => lowered(0.002, 0.15),
        }
    }
}

/// A fixture scene and B's trajectory.
struct Scene {
    pipeline: ContactPipeline,
    a: PreparedObject,
    b: PreparedObject,
    pose_a: DPose3,
    trajectory: Vec<DPose3>,
}

fn load(name: &str, motion: Motion) -> Scene {
    let FixtureScene {
        pipeline,
        a,
        b,
        pose_a,
        pose_b,
    } = load_scene(name);
    let start = pipeline
        .query(&a, &pose_a, &b, &pose_b, &mut QueryScratch::default())
        .expect("query");
    assert_eq!(start.contacts.len(), 2, "{name}: two contacts");
    let (c, n) = (start.contacts[0].point_a, start.contacts[0].normal);
    let trajectory = (0..FRAMES).map(|k| motion.pose(k, c, n, pose_b)).collect();
    Scene {
        pipeline,
        a,
        b,
        pose_a,
        trajectory,
    }
}

/// Ten passes over the trajectory: time per frame, warm frames and their time, full frames'
/// time, refinements and Stage 3 time per warm frame, printed beside the timings.
fn census(scene: &Scene, name: &str) {
    let options = CoherenceOptions::default();
    let (mut cache, mut scratch, mut report) = (
        PairCache::new(),
        QueryScratch::default(),
        PairReport::default(),
    );
    let (mut warm, mut refined, mut refine_us, mut contacts) = (0, 0, 0.0, 0);
    let (mut warm_us, mut full_us) = (0.0, 0.0);
    let passes = 10;
    let all = std::time::Instant::now();
    for pose in scene.trajectory.iter().cycle().take(passes * FRAMES) {
        let start = std::time::Instant::now();
        let kind = scene
            .pipeline
            .query_coherent(
                &scene.a,
                &scene.pose_a,
                &scene.b,
                pose,
                &options,
                &mut cache,
                &mut scratch,
                &mut report,
            )
            .expect("query");
        let us = start.elapsed().as_secs_f64() * 1e6;
        contacts += report.contacts.len();
        if kind == FrameKind::Full {
            full_us += us;
        }
        if kind == FrameKind::Warm {
            warm_us += us;
            warm += 1;
            refined += report.stats.refined;
            refine_us += report.stats.refine_us;
        }
    }
    let frames = passes * FRAMES;
    eprintln!(
        "{name}: {:.2} µs per frame over {frames} frames; {warm}/{frames} frames warm ({:.2} µs each), full ones {:.2} µs each, {:.2} contacts/frame, {:.2} refinements and {:.2} µs of Stage 3 per warm frame, {} minima tracked at the end",
        all.elapsed().as_secs_f64() * 1e6 / frames as f64,
        warm_us / warm.max(1) as f64,
        full_us / (frames - warm).max(1) as f64,
        contacts as f64 / frames as f64,
        refined as f64 / warm.max(1) as f64,
        refine_us / warm.max(1) as f64,
        cache.tracked_minima()
    );
}

fn coherence(c: &mut Criterion) {
    for (name, (motion, motion_name)) in SCENES
        .into_iter()
        .flat_map(|name| Motion::ALL.map(|m| (name, m)))
    {
        let scene = load(name, motion);
        let name = format!("{name}/{motion_name}");
        census(&scene, &name);
        let mut group = c.benchmark_group(format!("coherence/{name}"));
        group
            .warm_up_time(Duration::from_millis(300))
            .measurement_time(Duration::from_millis(1500))
            .sample_size(20);
        for (label, max_warm_frames) in [("warm", 64), ("warm-only", u32::MAX)] {
            let options = CoherenceOptions {
                max_warm_frames,
                ..CoherenceOptions::default()
            };
            let mut cache = PairCache::new();
            let mut scratch = QueryScratch::default();
            let mut report = PairReport::default();
            let mut k = 0;
            group.bench_function(label, |bench| {
                bench.iter(|| {
                    k = (k + 1) % FRAMES;
                    scene
                        .pipeline
                        .query_coherent(
                            &scene.a,
                            &scene.pose_a,
                            &scene.b,
                            &scene.trajectory[k],
                            &options,
                            &mut cache,
                            &mut scratch,
                            &mut report,
                        )
                        .expect("query");
                    black_box(report.contacts.len())
                });
            });
        }
        let mut scratch = QueryScratch::default();
        let mut report = PairReport::default();
        let mut k = 0;
        group.bench_function("cold", |bench| {
            bench.iter(|| {
                k = (k + 1) % FRAMES;
                scene
                    .pipeline
                    .query_into(
                        &scene.a,
                        &scene.pose_a,
                        &scene.b,
                        &scene.trajectory[k],
                        &mut scratch,
                        &mut report,
                    )
                    .expect("query");
                black_box(report.contacts.len())
            });
        });
        group.finish();
    }
}

criterion_group!(benches, coherence);
criterion_main!(benches);
