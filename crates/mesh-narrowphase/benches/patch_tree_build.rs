//! The normal-cone Stage 2's preprocessing: [`PatchTree::build`] over the single convex
//! component of the rounded box (flat faces, quarter cylinders and sphere corners whose meshes
//! have slivers at the poles) and over the largest component of the bowl (a paper object), at
//! the pipeline's default chordal tolerance (0.05 mm).

use criterion::Criterion;
use geom_param::{MeshOptions, ObjectFile, ObjectModel};
use mesh_narrowphase::cones::patch_tree::PatchTree;
use std::hint::black_box;
use std::time::Duration;

/// A fixture object (`fixtures/objects/{name}.json`) meshed at chordal tolerance 0.05 mm.
fn fixture(name: &str) -> ObjectModel {
    let path = format!(
        "{}/../../fixtures/objects/{name}.json",
        env!("CARGO_MANIFEST_DIR")
    );
    let text = std::fs::read_to_string(&path).expect("fixture exists");
    ObjectFile::from_json(&text)
        .expect("valid fixture")
        .build(&MeshOptions {
            chordal_tolerance: 0.05,
        })
        .expect("valid tolerance")
}

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("patch_tree_build");
    group.sample_size(10);
    group.measurement_time(Duration::from_secs(5));
    for name in ["rounded-box", "bowl"] {
        let object = fixture(name);
        let Some((component, mesh)) = object
            .meshes
            .iter()
            .enumerate()
            .max_by_key(|(_, m)| m.triangles.len())
        else {
            continue;
        };
        let tree = PatchTree::build(mesh, &object.solid);
        println!(
            "{name} component {component}: {} triangles, {} pieces, {} nodes",
            mesh.triangles.len(),
            tree.pieces.len(),
            tree.nodes.len()
        );
        group.bench_function(name, |bench| {
            bench.iter(|| black_box(PatchTree::build(mesh, &object.solid)));
        });
    }
    group.finish();
}

// What `criterion_group!` / `criterion_main!` expand to, written out so that no undocumented
// public function is generated.
fn main() {
    let mut c = Criterion::default().configure_from_args();
    bench(&mut c);
    c.final_summary();
}
