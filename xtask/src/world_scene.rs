//! The many-object scene `fixtures/worlds/world-300.json` (apart from the pair scenes of
//! `fixtures/scenes/`, whose tests expect two objects): 300 upright instances of six
//! fixture objects on a grid with near contacts, for `contacts query` through a `World`.
//!
//! Along x each row repeats one object, each instance [`GAP`] mm beyond its neighbour's mesh
//! box (so neighbours' widest points, on solids of revolution the same ring, face each other
//! across about [`GAP`], within the chordal errors); rows (y) and layers (z) are [`GAP`]
//! apart by the boxes too, the object changing from row to row.

use contact_pipeline::ContactOptions;
use geom_param::{DVec3, MeshOptions, ObjectFile};
use serde_json::{Value, json};

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
    let mut boxes = Vec::new();
    for name in OBJECTS {
        let model = objects
            .iter()
            .find(|o| o.name() == name)
            .ok_or(format!("no object {name}"))?
            .build(&mesh)
            .map_err(|e| format!("{name}: {e}"))?;
        let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
        for p in model.meshes.iter().flat_map(|m| &m.positions) {
            lo = lo.min(*p);
            hi = hi.max(*p);
        }
        boxes.push((lo, hi));
    }
    // Rows of 8 along x, 6 rows along y, layers along z until COUNT.
    let (per_row, rows) = (8, 6);
    let mut entries: Vec<Value> = Vec::with_capacity(COUNT);
    let mut z = 0.0;
    'layers: for layer in 0.. {
        let mut y = 0.0;
        let mut height: f64 = 0.0;
        for row in 0..rows {
            let m = (row + layer) % OBJECTS.len();
            let (lo, hi) = boxes[m];
            if row == 0 {
                y = -lo.y;
            } else {
                let (_, previous_hi) = boxes[(row - 1 + layer) % OBJECTS.len()];
                y += previous_hi.y - lo.y + GAP;
            }
            height = height.max(hi.z - lo.z);
            for column in 0..per_row {
                if entries.len() == COUNT {
                    break 'layers;
                }
                let x = column as f64 * (hi.x - lo.x + GAP) - lo.x;
                let n = entries.len();
                entries.push(json!({
                    "name": format!("{}-{n}", OBJECTS[m]),
                    "object": OBJECTS[m],
                    "pose": {"translation": [x, y, z - lo.z], "rotation": [0.0, 0.0, 0.0, 1.0]},
                }));
            }
        }
        z += height + GAP;
    }
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
