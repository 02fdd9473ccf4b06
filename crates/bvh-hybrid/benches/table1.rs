//! The paper's Table 1: time of the whole tree-vs-tree check between the paperweight (3
//! components, 5 nodes) and the goblet (8 components, 15 nodes), grouped by the number of
//! colliding leaf pairs, beside the paper's figures (2.8 GHz Pentium, C++). Poses are seeded
//! random near-contact poses; each benchmark cycles through up to 64 poses of its group.

#[path = "../tests/support/mod.rs"]
mod support;

use bvh_hybrid::{BroadPhase, HybridBvh, LeafShape, TraversalScratch, TreeOptions};
use criterion::{BenchmarkId, Criterion};
use geom_param::DPose3;
use std::hint::black_box;
use support::{Rng, near_contact_pose, paper};

const MARGIN: f64 = 0.5;
/// Table 1 of the paper: average time (ms) for 0..=6 colliding leaf pairs.
const PAPER_MS: [f64; 7] = [0.01, 0.15, 0.3, 0.33, 0.42, 0.46, 0.51];
const PER_GROUP: usize = 64;

fn table1(c: &mut Criterion) {
    let paperweight = paper("paperweight", 0.05);
    let goblet = paper("goblet", 0.05);
    for (label, leaf_shape) in [("bevelled", LeafShape::Bevelled), ("box", LeafShape::Box)] {
        let phase = HybridBvh {
            options: TreeOptions { leaf_shape },
        };
        let (a, b) = (
            phase.build(&paperweight, MARGIN),
            phase.build(&goblet, MARGIN),
        );
        let mut scratch = TraversalScratch::default();
        let mut out = Vec::new();
        let mut groups: [Vec<DPose3>; 7] = Default::default();
        let mut rng = Rng(0x7ab1e1);
        for _ in 0..200_000 {
            if groups.iter().all(|g| g.len() >= PER_GROUP) {
                break;
            }
            let spread = rng.range(0.1, 30.0);
            let pose = near_contact_pose(&mut rng, &paperweight, &goblet, spread);
            phase.overlapping_components(&a, &b, &pose, &mut scratch, &mut out);
            if let Some(g) = groups.get_mut(out.len()) {
                if g.len() < PER_GROUP {
                    g.push(pose);
                }
            }
        }
        let mut group = c.benchmark_group(format!("table1_paperweight_goblet_{label}"));
        for (pairs, poses) in groups.iter().enumerate() {
            if poses.is_empty() {
                println!("{label}: no pose with {pairs} colliding leaf pairs found");
                continue;
            }
            let id = BenchmarkId::new(
                format!("pairs_{pairs}"),
                format!("paper_{}ms", PAPER_MS[pairs]),
            );
            group.bench_with_input(id, poses, |bencher, poses| {
                let mut i = 0;
                bencher.iter(|| {
                    i = (i + 1) % poses.len();
                    phase.overlapping_components(
                        &a,
                        &b,
                        black_box(&poses[i]),
                        &mut scratch,
                        &mut out,
                    );
                    out.len()
                });
            });
        }
        group.finish();
    }
}

fn main() {
    let mut c = Criterion::default().configure_from_args();
    table1(&mut c);
    c.final_summary();
}
