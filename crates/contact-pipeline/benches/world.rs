//! Worlds of 10, 100 and 1000 fixture objects on a grid with near contacts
//! (`tests/support/grid.rs`): time per step with every object moving a little each step
//! (a few micrometres and 1e-5 rad, oscillating), on 1 and 2 rayon threads
//! (`World::step_parallel`), and the one-thread `World::step`; plus, printed, the objects,
//! pairs in range and queried, warm pairs and contacts of a step. Needs the `parallel` feature
//! (on by default): `cargo bench -p contact-pipeline --bench world`.

// `criterion_group!` expands to an undocumented public function.
#![allow(missing_docs)]

#[path = "../tests/support/grid.rs"]
mod grid;

use contact_pipeline::{ObjectKey, World};
use criterion::{Criterion, criterion_group, criterion_main};
use geom_param::{DPose3, DQuat, DVec3};
use std::time::Duration;

/// Moves every object to its wobble pose of step `k` about its grid pose.
fn wobble(world: &mut World, keys: &[ObjectKey], base: &[DPose3], k: usize) {
    for (n, (&key, pose)) in keys.iter().zip(base).enumerate() {
        let phase = 0.3 * k as f64 + n as f64;
        let turn = DQuat::from_axis_angle(DVec3::Z, 1e-5 * phase.sin());
        let shift = DVec3::new(0.003 * phase.cos(), 0.003 * phase.sin(), 0.0);
        world
            .set_pose(
                key,
                DPose3::from_parts(pose.translation + shift, turn * pose.rotation),
            )
            .expect("pose");
    }
}

fn worlds(c: &mut Criterion) {
    for n in [10, 100, 1000] {
        let (mut world, _models, keys) = grid::world(n, grid::MODELS.len());
        let base: Vec<DPose3> = keys.iter().map(|&k| world.pose(k).expect("pose")).collect();
        let stats = world.step().expect("step");
        wobble(&mut world, &keys, &base, 1);
        let next = world.step().expect("step");
        eprintln!(
            "world of {n}: {} pairs in range, {} queried, {} touching, {} contacts; next step {} of {} pairs warm, {:.0} µs broad phase, {:.0} µs pairs",
            stats.pairs_in_range,
            stats.pairs_queried,
            stats.pairs_touching,
            stats.contacts,
            next.warm,
            next.pairs_queried,
            next.broad_us,
            next.pairs_us
        );
        let mut group = c.benchmark_group(format!("world/{n}"));
        group
            .warm_up_time(Duration::from_millis(500))
            .measurement_time(Duration::from_secs(if n >= 1000 { 6 } else { 2 }))
            .sample_size(10);
        let mut k = 2;
        group.bench_function("step", |bench| {
            bench.iter(|| {
                wobble(&mut world, &keys, &base, k);
                k += 1;
                world.step().expect("step").contacts
            });
        });
        for threads in [1, 2] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .expect("pool");
            group.bench_function(format!("step_parallel/{threads}-threads"), |bench| {
                bench.iter(|| {
                    wobble(&mut world, &keys, &base, k);
                    k += 1;
                    pool.install(|| world.step_parallel())
                        .expect("step")
                        .contacts
                });
            });
        }
        group.finish();
    }
}

criterion_group!(benches, worlds);
criterion_main!(benches);
