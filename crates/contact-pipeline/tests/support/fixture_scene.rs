//! A two-object fixture scene (`fixtures/scenes/NAME.json`) loaded into a pipeline with the
//! scene's options and its two objects prepared and posed, shared by the coherence tests and the
//! stage and coherence benches (which include this file with `#[path]`).

#![allow(dead_code)]

use contact_pipeline::{ContactOptions, ContactPipeline, PreparedObject};
use geom_param::{DPose3, DQuat, DVec3, MeshOptions, ObjectFile};
use serde_json::Value;
use std::path::Path;

/// A pipeline with the scene's options, and its two objects with their world poses.
pub struct FixtureScene {
    /// Default stages, the scene's margin, band and chordal tolerance.
    pub pipeline: ContactPipeline,
    /// The scene's first object.
    pub a: PreparedObject,
    /// The scene's second object.
    pub b: PreparedObject,
    /// A's pose (world frame, mm).
    pub pose_a: DPose3,
    /// B's pose (world frame, mm).
    pub pose_b: DPose3,
}

fn numbers(value: &Value) -> Vec<f64> {
    value
        .as_array()
        .expect("array")
        .iter()
        .map(|x| x.as_f64().expect("number"))
        .collect()
}

/// Loads `fixtures/scenes/{name}.json` and its objects (`fixtures/objects/{object}.json`, a
/// profile or a general solid). Panics on a missing or malformed fixture.
pub fn load_scene(name: &str) -> FixtureScene {
    let fixtures = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures");
    let read = |path: &Path| std::fs::read_to_string(path).expect("fixture");
    let scene: Value =
        serde_json::from_str(&read(&fixtures.join(format!("scenes/{name}.json")))).expect("json");
    let option = |key: &str| scene["options"][key].as_f64().expect("option");
    let pipeline = ContactPipeline::new(ContactOptions {
        margin: option("margin"),
        delta1: option("delta1"),
        delta2: option("delta2"),
        chordal_tolerance: option("chordal_tolerance"),
        ..ContactOptions::default()
    })
    .expect("options");
    let object = |k: usize| {
        let entry = &scene["objects"][k];
        let file = entry["object"].as_str().expect("object name");
        let text = read(&fixtures.join(format!("objects/{file}.json")));
        let model = ObjectFile::from_json(&text)
            .expect("object")
            .build(&MeshOptions {
                chordal_tolerance: option("chordal_tolerance"),
            })
            .expect("builds");
        let q = numbers(&entry["pose"]["rotation"]);
        let t = numbers(&entry["pose"]["translation"]);
        let pose = DPose3 {
            rotation: DQuat::from_xyzw(q[0], q[1], q[2], q[3]),
            translation: DVec3::new(t[0], t[1], t[2]),
        };
        (pipeline.prepare(model), pose)
    };
    let ((a, pose_a), (b, pose_b)) = (object(0), object(1));
    FixtureScene {
        pipeline,
        a,
        b,
        pose_a,
        pose_b,
    }
}
