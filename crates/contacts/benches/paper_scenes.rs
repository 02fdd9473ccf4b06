//! Whole queries on the paper's four two-contact scenes: the exact pipeline beside the
//! mesh-only baseline (one parry `TriMesh` per object at 5k and 20k triangles, contact
//! manifolds with prediction = the scene's delta2), in one group per scene so that the ratios
//! read off directly. "warm" keeps parry's manifolds and workspace between iterations (same
//! pose: a physics engine's steady state); "cold" starts every query from an empty workspace,
//! as the exact pipeline does (its scratch is only memory, it caches no result).

// `criterion_group!` expands to an undocumented public function.
#![allow(missing_docs)]

use contact_pipeline::QueryScratch;
use contacts::run::prepare_scene;
use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use mesh_baseline::{BaselineMesh, MeshOnlyBaseline};
use std::hint::black_box;
use std::path::Path;
use std::time::Duration;

const SCENES: [&str; 4] = [
    "pencil-paperweight-two-contacts",
    "paperweight-goblet-two-contacts",
    "pencil-bowl-two-contacts",
    "vase-vase-two-contacts",
];
const TARGETS: [usize; 2] = [5_000, 20_000];

fn paper_scenes(c: &mut Criterion) {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/scenes");
    for name in SCENES {
        let prepared = prepare_scene(&dir.join(format!("{name}.json"))).expect("scene loads");
        let objects = &prepared.scene.objects;
        let (pose_a, pose_b) = (&objects[0].pose, &objects[1].pose);
        let prediction = prepared.scene.options.delta2;
        let mut group = c.benchmark_group(name);
        group
            .warm_up_time(Duration::from_millis(300))
            .measurement_time(Duration::from_millis(1500))
            .sample_size(20);

        let mut scratch = QueryScratch::default();
        group.bench_function("exact-pipeline", |b| {
            b.iter(|| black_box(prepared.query((0, 1), &mut scratch).expect("query")));
        });

        for target in TARGETS {
            let mesh = |i: usize| {
                BaselineMesh::new(&prepared.objects[i].model.solid, target).expect("meshes")
            };
            let (a, b) = (mesh(0), mesh(1));
            let mut baseline = MeshOnlyBaseline::new();
            group.bench_function(BenchmarkId::new("parry-warm", target), |bench| {
                bench.iter(|| {
                    black_box(
                        baseline
                            .contacts(&a, pose_a, &b, pose_b, prediction)
                            .expect("query"),
                    )
                });
            });
            group.bench_function(BenchmarkId::new("parry-cold", target), |bench| {
                bench.iter(|| {
                    black_box(
                        baseline
                            .contacts_cold(&a, pose_a, &b, pose_b, prediction)
                            .expect("query"),
                    )
                });
            });
        }
        group.finish();
    }
}

criterion_group!(benches, paper_scenes);
criterion_main!(benches);
