//! Worlds of fixture objects (fixtures/objects/*.json) in a grid with near contacts, shared by
//! the world tests and the world bench.
//!
//! Objects stand upright (identity rotation) on a grid. Along x each row repeats one model,
//! each object `GAP` mm beyond its neighbour's mesh box, so that neighbours' widest points
//! (for solids of revolution, the same ring) face each other across about `GAP` (the exact
//! surfaces lie within the chordal error of the meshes: some pairs touch, some are a little
//! apart, a few may overlap slightly). Rows (y) and layers (z) are `GAP` apart by the boxes
//! too, with models changing from row to row.

#![allow(dead_code)]

use contact_pipeline::CoherenceOptions;
use contact_pipeline::{ContactOptions, ContactPipeline, Groups, ObjectKey, PreparedObject, World};
use geom_param::{DPose3, DQuat, DVec3, MeshOptions, ObjectFile};
use std::path::Path;
use std::sync::Arc;

/// Gap between neighbours' mesh boxes (mm).
pub const GAP: f64 = 0.05;

/// The fixture models used, smallest first.
pub const MODELS: [&str; 6] = [
    "pencil",
    "paperweight",
    "jar",
    "rounded-box",
    "tube",
    "vase",
];

/// A model and its mesh box in its own frame.
pub struct Model {
    pub name: &'static str,
    pub prepared: Arc<PreparedObject>,
    pub lo: DVec3,
    pub hi: DVec3,
}

/// The default pipeline and the first `count` of [`MODELS`], prepared.
pub fn models(count: usize) -> (ContactPipeline, Vec<Model>) {
    let pipeline = ContactPipeline::new(ContactOptions::default()).expect("options");
    let fixtures = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/objects");
    let models = MODELS[..count]
        .iter()
        .map(|&name| {
            let text =
                std::fs::read_to_string(fixtures.join(format!("{name}.json"))).expect("fixture");
            let model = ObjectFile::from_json(&text)
                .expect("object")
                .build(&MeshOptions {
                    chordal_tolerance: pipeline.options().chordal_tolerance,
                })
                .expect("builds");
            let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
            for mesh in &model.meshes {
                for p in &mesh.positions {
                    lo = lo.min(*p);
                    hi = hi.max(*p);
                }
            }
            Model {
                name,
                prepared: Arc::new(pipeline.prepare(model)),
                lo,
                hi,
            }
        })
        .collect();
    (pipeline, models)
}

/// Grid placements of `n` objects: (model index, pose), in insertion order.
pub fn grid(models: &[Model], n: usize) -> Vec<(usize, DPose3)> {
    let side = (n as f64).cbrt().ceil().max(1.0) as usize;
    let mut out = Vec::with_capacity(n);
    let mut z = 0.0;
    'layers: for iz in 0..side {
        let mut y = 0.0;
        let mut height: f64 = 0.0;
        let mut previous: Option<usize> = None;
        for iy in 0..side {
            let m = (iy + 2 * iz) % models.len();
            let model = &models[m];
            if let Some(p) = previous {
                y += models[p].hi.y - model.lo.y + GAP;
            } else {
                y = -model.lo.y;
            }
            previous = Some(m);
            height = height.max(model.hi.z - model.lo.z);
            let width = model.hi.x - model.lo.x;
            for ix in 0..side {
                if out.len() == n {
                    break 'layers;
                }
                let x = ix as f64 * (width + GAP) - model.lo.x;
                let pose = DPose3::from_parts(DVec3::new(x, y, z - model.lo.z), DQuat::IDENTITY);
                out.push((m, pose));
            }
        }
        z += height + GAP;
    }
    out
}

/// A world with `n` grid objects; their keys in insertion order.
pub fn world(n: usize, model_count: usize) -> (World, Vec<Model>, Vec<ObjectKey>) {
    let (pipeline, models) = models(model_count);
    let mut world = World::new(pipeline, Some(CoherenceOptions::default()));
    let keys = grid(&models, n)
        .into_iter()
        .map(|(m, pose)| {
            world
                .insert(Arc::clone(&models[m].prepared), pose, Groups::default())
                .expect("insert")
        })
        .collect();
    (world, models, keys)
}
