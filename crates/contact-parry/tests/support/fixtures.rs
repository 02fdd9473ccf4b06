//! Fixture objects and two-object scenes (`fixtures/`) as exact shapes.

#![allow(dead_code)]

use contact_parry::ExactShape;
use contact_pipeline::{ContactOptions, ContactPipeline};
use geom_param::{DPose3, DQuat, DVec3, MeshOptions, ObjectFile};
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// The workspace's `fixtures/` folder.
pub fn fixtures() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures")
}

/// `fixtures/objects/{name}.json` as an exact shape of `pipeline`.
pub fn object(pipeline: &Arc<ContactPipeline>, name: &str) -> ExactShape {
    let text = std::fs::read_to_string(fixtures().join(format!("objects/{name}.json")))
        .expect("fixture object");
    let model = ObjectFile::from_json(&text)
        .expect("object")
        .build(&MeshOptions {
            chordal_tolerance: pipeline.options().chordal_tolerance,
        })
        .expect("builds");
    ExactShape::from_model(Arc::clone(pipeline), model).expect("closed mesh")
}

/// A two-object scene: the pipeline with its options, both shapes and their world poses.
pub struct Scene {
    pub pipeline: Arc<ContactPipeline>,
    pub a: ExactShape,
    pub b: ExactShape,
    pub pose_a: DPose3,
    pub pose_b: DPose3,
}

/// `fixtures/scenes/{name}.json`.
pub fn scene(name: &str) -> Scene {
    let text = std::fs::read_to_string(fixtures().join(format!("scenes/{name}.json")))
        .expect("fixture scene");
    let scene: Value = serde_json::from_str(&text).expect("json");
    let option = |key: &str| scene["options"][key].as_f64().expect("option");
    let pipeline = Arc::new(
        ContactPipeline::new(ContactOptions {
            margin: option("margin"),
            delta1: option("delta1"),
            delta2: option("delta2"),
            chordal_tolerance: option("chordal_tolerance"),
            ..ContactOptions::default()
        })
        .expect("options"),
    );
    let numbers = |v: &Value| -> Vec<f64> {
        v.as_array()
            .expect("array")
            .iter()
            .map(|x| x.as_f64().expect("number"))
            .collect()
    };
    let entry = |k: usize| {
        let e = &scene["objects"][k];
        let q = numbers(&e["pose"]["rotation"]);
        let t = numbers(&e["pose"]["translation"]);
        let pose = DPose3 {
            rotation: DQuat::from_xyzw(q[0], q[1], q[2], q[3]),
            translation: DVec3::new(t[0], t[1], t[2]),
        };
        (object(&pipeline, e["object"].as_str().expect("name")), pose)
    };
    let ((a, pose_a), (b, pose_b)) = (entry(0), entry(1));
    Scene {
        pipeline,
        a,
        b,
        pose_a,
        pose_b,
    }
}
