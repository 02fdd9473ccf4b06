//! Scaling of the tree-vs-tree check with the number of components and (not) with the mesh
//! resolution: a column of n bumps (one convex component each; n = 10, 100, 1000) against a
//! sphere of radius 1 touching the middle bump, at two chordal tolerances. Expect the cost to
//! grow about like log n and not at all with the tolerance.

#[path = "../tests/support/mod.rs"]
mod support;

use bvh_hybrid::{BroadPhase, HybridBvh, TraversalScratch};
use criterion::{BenchmarkId, Criterion};
use geom_param::{DPose3, DVec3};
use std::hint::black_box;
use support::{Rng, bump_tip, bumpy_column, sphere};

const MARGIN: f64 = 0.5;

fn scaling(c: &mut Criterion) {
    let phase = HybridBvh::default();
    let mut group = c.benchmark_group("scaling_bumps_vs_sphere");
    for tolerance in [0.1, 0.02] {
        let ball = phase.build(&sphere(1.0, tolerance), MARGIN);
        for n in [10, 100, 1000] {
            let column = phase.build(&bumpy_column(n, tolerance), MARGIN);
            let (z, tip) = bump_tip(n / 2);
            let mut rng = Rng(n as u64);
            let poses: Vec<DPose3> = (0..32)
                .map(|_| {
                    let angle = rng.range(0.0, std::f64::consts::TAU);
                    let out = DVec3::new(angle.cos(), angle.sin(), 0.0);
                    let gap = rng.range(-0.2, MARGIN);
                    DPose3::from_parts(out * (tip + 1.0 + gap) + DVec3::Z * z, rng.rotation())
                })
                .collect();
            let mut scratch = TraversalScratch::default();
            let mut out = Vec::new();
            let id = BenchmarkId::new(format!("tol_{tolerance}"), n);
            group.bench_with_input(id, &poses, |bencher, poses| {
                let mut i = 0;
                bencher.iter(|| {
                    i = (i + 1) % poses.len();
                    phase.overlapping_components(
                        &column,
                        &ball,
                        black_box(&poses[i]),
                        &mut scratch,
                        &mut out,
                    );
                    out.len()
                });
            });
        }
    }
    group.finish();
}

fn main() {
    let mut c = Criterion::default().configure_from_args();
    scaling(&mut c);
    c.final_summary();
}
