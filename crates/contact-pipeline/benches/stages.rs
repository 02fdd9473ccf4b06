//! Each stage of a query timed on its own, on the paper's four two-contact scenes (objects and
//! poses from fixtures/): Stage 1 (broad phase: overlapping component pairs), Stage 2 (mesh
//! phase over those pairs, computed once beforehand) and Stage 3 (refinement of the seeds the
//! mesh phase produced, computed once beforehand), next to the whole query. Uses only the
//! pipeline's public stages (`ContactPipeline::{broad, mesh, refiner}`), as the query does.

// `criterion_group!` expands to an undocumented public function.
#![allow(missing_docs)]

use bvh_hybrid::BroadPhase;
use contact_pipeline::{ContactPipeline, PreparedObject, QueryScratch};
use criterion::{Criterion, criterion_group, criterion_main};
use exact_refine::Refiner;
use fixture_scene::{FixtureScene, load_scene};
use geom_param::{ComponentId, DPose3, Seed};
use mesh_narrowphase::{ComponentRef, ContactBand, MeshOutput, MeshPhase, MeshVerdict};
use std::hint::black_box;
use std::time::Duration;

const SCENES: [&str; 4] = [
    "pencil-paperweight-two-contacts",
    "paperweight-goblet-two-contacts",
    "pencil-bowl-two-contacts",
    "vase-vase-two-contacts",
];

struct Scene {
    pipeline: ContactPipeline,
    objects: [PreparedObject; 2],
    poses: [DPose3; 2],
}

#[path = "../tests/support/fixture_scene.rs"]
mod fixture_scene;

fn load(name: &str) -> Scene {
    let FixtureScene {
        pipeline,
        a,
        b,
        pose_a,
        pose_b,
    } = load_scene(name);
    Scene {
        pipeline,
        objects: [a, b],
        poses: [pose_a, pose_b],
    }
}

type Broad = <bvh_hybrid::HybridBvh as BroadPhase>::Scratch;
type Mesh = <mesh_narrowphase::MeshNarrowphase as MeshPhase>::Scratch;
type Refine = <exact_refine::NewtonRefiner as Refiner>::Scratch;

impl Scene {
    fn pose_ab(&self) -> DPose3 {
        self.poses[0].inverse() * self.poses[1]
    }

    fn broad(&self, scratch: &mut Broad, pairs: &mut Vec<(ComponentId, ComponentId)>) {
        let [a, b] = &self.objects;
        self.pipeline.broad.overlapping_components(
            &a.tree,
            &b.tree,
            &self.pose_ab(),
            scratch,
            pairs,
        );
    }

    /// Runs Stage 2 over `pairs`, appending the seeds; the number of pairs not separated.
    fn mesh(
        &self,
        pairs: &[(ComponentId, ComponentId)],
        scratch: &mut Mesh,
        out: &mut MeshOutput,
        seeds: &mut Vec<Seed>,
    ) -> usize {
        let [a, b] = &self.objects;
        let options = self.pipeline.options();
        let band = ContactBand {
            margin: options.margin,
            delta1: options.delta1,
            delta2: options.delta2,
        };
        let pose_ab = self.pose_ab();
        let mut touching = 0;
        for &(ca, cb) in pairs {
            let verdict = self.pipeline.mesh.query(
                ComponentRef {
                    object: &a.model,
                    prepared: &a.mesh,
                    component: ca,
                },
                ComponentRef {
                    object: &b.model,
                    prepared: &b.mesh,
                    component: cb,
                },
                &pose_ab,
                &band,
                scratch,
                out,
            );
            if !matches!(verdict, MeshVerdict::Separated) {
                touching += 1;
                seeds.extend_from_slice(&out.seeds);
            }
        }
        touching
    }

    /// Refines every seed; the smallest distance found (mm).
    fn refine(&self, seeds: &[Seed], scratch: &mut Refine) -> f64 {
        let [a, b] = &self.objects;
        let pose_ab = self.pose_ab();
        seeds
            .iter()
            .map(|seed| {
                self.pipeline
                    .refiner
                    .refine(&a.model.solid, &b.model.solid, &pose_ab, seed, scratch)
                    .distance
            })
            .fold(f64::INFINITY, f64::min)
    }
}

fn stages(c: &mut Criterion) {
    for name in SCENES {
        let scene = load(name);
        // Each stage's inputs, computed once by the stages before it.
        let (mut broad, mut mesh, mut refine) =
            (Broad::default(), Mesh::default(), Refine::default());
        let mut pairs = Vec::new();
        scene.broad(&mut broad, &mut pairs);
        let mut out = MeshOutput::default();
        let mut seeds = Vec::new();
        scene.mesh(&pairs, &mut mesh, &mut out, &mut seeds);
        assert!(!seeds.is_empty(), "{name}: the mesh phase found no seed");

        let mut group = c.benchmark_group(format!("stages/{name}"));
        group
            .warm_up_time(Duration::from_millis(300))
            .measurement_time(Duration::from_millis(1500))
            .sample_size(20);
        let mut scratch_pairs = Vec::new();
        group.bench_function("broad", |bench| {
            bench.iter(|| {
                scene.broad(&mut broad, &mut scratch_pairs);
                black_box(scratch_pairs.len())
            });
        });
        let mut scratch_seeds = Vec::new();
        group.bench_function("mesh", |bench| {
            bench.iter(|| {
                scratch_seeds.clear();
                black_box(scene.mesh(&pairs, &mut mesh, &mut out, &mut scratch_seeds))
            });
        });
        group.bench_function("refine", |bench| {
            bench.iter(|| black_box(scene.refine(&seeds, &mut refine)));
        });
        let mut query = QueryScratch::default();
        let [a, b] = &scene.objects;
        group.bench_function("whole-query", |bench| {
            bench.iter(|| {
                black_box(
                    scene
                        .pipeline
                        .query(a, &scene.poses[0], b, &scene.poses[1], &mut query)
                        .expect("query"),
                )
            });
        });
        group.finish();
        println!(
            "{name}: {} component pairs, {} seeds",
            pairs.len(),
            seeds.len()
        );
    }
}

criterion_group!(benches, stages);
criterion_main!(benches);
