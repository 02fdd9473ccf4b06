//! The many-object scene `fixtures/worlds/world-300.json` (apart from the pair scenes of
//! `fixtures/scenes/`, whose tests expect two objects): 300 upright instances of six
//! fixture objects on a grid with near contacts, for `contacts query` through a `World`.
//!
//! Along x each row repeats one object, each instance [`GAP`] mm beyond its neighbour's mesh
//! box (so neighbours' widest points, on solids of revolution the same ring, face each other
//! across about [`GAP`], within the chordal errors); rows (y) and layers (z) are [`GAP`]
//! apart by the boxes too, the object changing from row to row.

use contact_pipeline::{
    CoherenceOptions, ContactOptions, ContactPipeline, Groups, PreparedObject, World,
};
use geom_param::{DPose3, DQuat, DVec3, MeshOptions, ObjectFile, ObjectModel};
use serde_json::{Value, json};
use std::sync::Arc;
use std::time::Instant;

/// Gap between neighbours' mesh boxes (mm).
pub const GAP: f64 = 0.05;

/// Objects of the scene, by fixture name.
pub const OBJECTS: [&str; 6] = [
    "pencil",
    "paperweight",
    "jar",
    "rounded-box",
    "tube",
    "vase",
];

/// Instances in the scene.
pub const COUNT: usize = 300;

/// The scene file: (file name, contents).
///
/// # Errors
/// A message when an object is missing or fails to build.
pub fn generate_world_scene(objects: &[ObjectFile]) -> Result<(String, String), String> {
    let options = ContactOptions::default();
    let mesh = MeshOptions {
        chordal_tolerance: options.chordal_tolerance,
    };
    let boxes = build(objects, &mesh)?
        .iter()
        .map(mesh_box)
        .collect::<Vec<_>>();
    let entries: Vec<Value> = layout(&boxes, COUNT)
        .into_iter()
        .enumerate()
        .map(|(n, (m, t))| {
            json!({
                "name": format!("{}-{n}", OBJECTS[m]),
                "object": OBJECTS[m],
                "pose": {"translation": [t.x, t.y, t.z], "rotation": [0.0, 0.0, 0.0, 1.0]},
            })
        })
        .collect();
    let value = json!({
        "note": format!(
            "{} (world of {COUNT} objects on a grid with near contacts)",
            crate::paper_objects::GENERATED_NOTE
        ),
        "objects": entries,
        "options": {"margin": options.margin, "delta1": options.delta1, "delta2": options.delta2,
                    "chordal_tolerance": options.chordal_tolerance},
    });
    let mut text = serde_json::to_string_pretty(&value).map_err(|e| e.to_string())?;
    text.push('\n');
    Ok((format!("world-{COUNT}.json"), text))
}

/// Builds the scene's objects, in [`OBJECTS`] order.
fn build(objects: &[ObjectFile], mesh: &MeshOptions) -> Result<Vec<ObjectModel>, String> {
    OBJECTS
        .iter()
        .map(|&name| {
            objects
                .iter()
                .find(|o| o.name() == name)
                .ok_or(format!("no object {name}"))?
                .build(mesh)
                .map_err(|e| format!("{name}: {e}"))
        })
        .collect()
}

/// The box of a model's mesh vertices (its own frame).
fn mesh_box(model: &ObjectModel) -> (DVec3, DVec3) {
    let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
    for p in model.meshes.iter().flat_map(|m| &m.positions) {
        lo = lo.min(*p);
        hi = hi.max(*p);
    }
    (lo, hi)
}

/// `count` placements (object index, translation) on the grid of the module documentation:
/// rows of 8 along x, 6 rows along y, layers along z.
fn layout(boxes: &[(DVec3, DVec3)], count: usize) -> Vec<(usize, DVec3)> {
    let (per_row, rows) = (8, 6);
    let mut out = Vec::with_capacity(count);
    let mut z = 0.0;
    for layer in 0.. {
        let mut y = 0.0;
        let mut height: f64 = 0.0;
        for row in 0..rows {
            let m = (row + layer) % boxes.len();
            let (lo, hi) = boxes[m];
            if row == 0 {
                y = -lo.y;
            } else {
                let (_, previous_hi) = boxes[(row - 1 + layer) % boxes.len()];
                y += previous_hi.y - lo.y + GAP;
            }
            height = height.max(hi.z - lo.z);
            for column in 0..per_row {
                if out.len() == count {
                    return out;
                }
                let x = column as f64 * (hi.x - lo.x + GAP) - lo.x;
                out.push((m, DVec3::new(x, y, z - lo.z)));
            }
        }
        z += height + GAP;
    }
    out
}

/// `cargo xtask world`: worlds of `counts` objects on the grid, each stepped `steps` times with
/// every object moving a little each step (a few micrometres and 1e-5 rad, oscillating):
/// median time per step with `World::step` and with `World::step_parallel` on 1 and 2 threads,
/// and the pairs and contacts of the last step, as a markdown table.
///
/// # Errors
/// A message when an object fails to build or a step fails.
pub fn world_table(
    objects: &[ObjectFile],
    counts: &[usize],
    steps: usize,
) -> Result<String, String> {
    let options = ContactOptions::default();
    let pipeline = ContactPipeline::new(options).map_err(|e| e.to_string())?;
    let mesh = MeshOptions {
        chordal_tolerance: options.chordal_tolerance,
    };
    let models = build(objects, &mesh)?;
    let boxes: Vec<_> = models.iter().map(mesh_box).collect();
    let prepared: Vec<Arc<PreparedObject>> = models
        .into_iter()
        .map(|m| Arc::new(pipeline.prepare(m)))
        .collect();
    let mut text = String::from(
        "| objects | pairs in range | pairs touching | contacts | warm pairs | step, 1 thread (ms) | step_parallel, 1 thread (ms) | step_parallel, 2 threads (ms) | speed-up 2 / 1 |\n|---|---|---|---|---|---|---|---|---|\n",
    );
    for &count in counts {
        let placements = layout(&boxes, count);
        let mut timings = Vec::new();
        let mut last = None;
        for mode in 0..3 {
            let pipeline = ContactPipeline::new(options).map_err(|e| e.to_string())?;
            let mut world = World::new(pipeline, Some(CoherenceOptions::default()));
            let mut keys = Vec::with_capacity(count);
            for &(m, t) in &placements {
                let key = world
                    .insert(
                        Arc::clone(&prepared[m]),
                        DPose3::from_parts(t, DQuat::IDENTITY),
                        Groups::default(),
                    )
                    .map_err(|e| e.to_string())?;
                keys.push((key, t));
            }
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(if mode == 2 { 2 } else { 1 })
                .build()
                .map_err(|e| e.to_string())?;
            let mut times = Vec::with_capacity(steps);
            for step in 0..=steps {
                for (n, &(key, t)) in keys.iter().enumerate() {
                    let phase = 0.3 * step as f64 + n as f64;
                    let shift = DVec3::new(0.003 * phase.cos(), 0.003 * phase.sin(), 0.0);
                    let turn = DQuat::from_axis_angle(DVec3::Z, 1e-5 * phase.sin());
                    world
                        .set_pose(key, DPose3::from_parts(t + shift, turn))
                        .map_err(|e| e.to_string())?;
                }
                let start = Instant::now();
                let stats = if mode == 0 {
                    world.step()
                } else {
                    pool.install(|| world.step_parallel())
                }
                .map_err(|e| e.to_string())?;
                // The first step builds every pair's cache: not timed.
                if step > 0 {
                    times.push(start.elapsed().as_secs_f64() * 1e3);
                }
                last = Some(stats);
            }
            times.sort_by(f64::total_cmp);
            timings.push(times.get(times.len() / 2).copied().unwrap_or(f64::NAN));
        }
        let s = last.unwrap_or_default();
        text.push_str(&format!(
            "| {count} | {} | {} | {} | {} | {:.2} | {:.2} | {:.2} | {:.2}x |\n",
            s.pairs_queried,
            s.pairs_touching,
            s.contacts,
            s.warm,
            timings[0],
            timings[1],
            timings[2],
            timings[1] / timings[2]
        ));
    }
    Ok(text)
}
