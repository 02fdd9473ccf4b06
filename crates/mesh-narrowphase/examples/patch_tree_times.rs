//! Prints the patch-tree build time of every component of every fixture object
//! (`fixtures/objects/*.json`, chordal tolerance 0.05 mm): `cargo run --release -p
//! mesh-narrowphase --example patch_tree_times [NAME...]`.

use geom_param::{MeshOptions, ObjectFile};
use mesh_narrowphase::cones::patch_tree::PatchTree;
use std::time::Instant;

fn main() {
    let filter: Vec<String> = std::env::args().skip(1).collect();
    let dir = format!("{}/../../fixtures/objects", env!("CARGO_MANIFEST_DIR"));
    let mut paths: Vec<_> = std::fs::read_dir(&dir)
        .expect("fixture folder")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "json"))
        .collect();
    paths.sort();
    println!("object        comp  kind      triangles  pieces  nodes    build ms");
    for path in paths {
        let text = std::fs::read_to_string(&path).expect("fixture readable");
        let file = ObjectFile::from_json(&text).expect("valid fixture");
        if !filter.is_empty() && !filter.iter().any(|f| f == file.name()) {
            continue;
        }
        let model = file
            .build(&MeshOptions {
                chordal_tolerance: 0.05,
            })
            .expect("fixture builds");
        for (i, mesh) in model.meshes.iter().enumerate() {
            let start = Instant::now();
            let tree = PatchTree::build(mesh, &model.solid);
            let ms = start.elapsed().as_secs_f64() * 1e3;
            let kind = model
                .components
                .get(i)
                .map_or_else(|| "?".to_string(), |c| format!("{:?}", c.kind));
            println!(
                "{:<13} {:>4}  {:<8} {:>10} {:>7} {:>6} {:>11.1}",
                file.name(),
                i,
                kind,
                mesh.triangles.len(),
                tree.pieces.len(),
                tree.nodes.len(),
                ms
            );
        }
    }
}
