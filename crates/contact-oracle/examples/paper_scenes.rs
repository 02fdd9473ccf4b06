//! Runs the oracle on the paper's two-contact scenes (fixtures/scenes/*-two-contacts.json) and
//! prints every contact within 1 mm with the time per call:
//! `cargo run --release -p contact-oracle --example paper_scenes`.

use contact_oracle::{OracleOptions, find_contacts};
use geom_param::{DPose3, DQuat, DVec3, MeshOptions, ObjectDescription, Solid};
use serde_json::Value;
use std::path::Path;

fn solid(root: &Path, name: &str) -> Solid {
    let path = root.join(format!("fixtures/objects/{name}.json"));
    let text = std::fs::read_to_string(&path).expect("object file");
    let description = ObjectDescription::from_json(&text).expect("object JSON");
    description
        .build(&MeshOptions::default())
        .expect("object builds")
        .solid
}

fn pose(value: &Value) -> DPose3 {
    let numbers = |key: &str| -> Vec<f64> {
        value[key]
            .as_array()
            .expect("array")
            .iter()
            .map(|v| v.as_f64().expect("number"))
            .collect()
    };
    let (q, t) = (numbers("rotation"), numbers("translation"));
    DPose3 {
        rotation: DQuat::from_xyzw(q[0], q[1], q[2], q[3]),
        translation: DVec3::new(t[0], t[1], t[2]),
    }
}

fn main() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let mut scenes: Vec<_> = std::fs::read_dir(root.join("fixtures/scenes"))
        .expect("scenes folder")
        .map(|e| e.expect("entry").path())
        .filter(|p| p.to_string_lossy().ends_with("-two-contacts.json"))
        .collect();
    scenes.sort();
    for path in scenes {
        let scene: Value =
            serde_json::from_str(&std::fs::read_to_string(&path).expect("scene")).expect("JSON");
        let objects = scene["objects"].as_array().expect("objects");
        let a = solid(&root, objects[0]["object"].as_str().expect("name"));
        let b = solid(&root, objects[1]["object"].as_str().expect("name"));
        let (pa, pb) = (pose(&objects[0]["pose"]), pose(&objects[1]["pose"]));
        let options = OracleOptions::for_solids(&a, &b, 1.0);
        let start = std::time::Instant::now();
        let runs = 3;
        let mut report = None;
        for _ in 0..runs {
            report = Some(find_contacts(&a, &pa, &b, &pb, &options).expect("oracle runs"));
        }
        let report = report.expect("ran");
        let per_call = start.elapsed() / runs;
        println!(
            "{}: spacing {:.3} mm, {} samples, {:?} per call, state {:?}, cross-check {:?}",
            path.file_name().expect("name").to_string_lossy(),
            options.spacing,
            report.samples,
            per_call,
            report.state(-0.001, 0.1),
            report.cross_check
        );
        for c in &report.contacts {
            println!(
                "  d {:+.9} mm  A {:?} face {} {:?}  B face {} {:?}  residual {:.1e}",
                c.distance,
                c.point_a.to_array().map(|x| (x * 1e6).round() / 1e6),
                c.face_a.0,
                c.params_a.map(|x| (x * 1e6).round() / 1e6),
                c.face_b.0,
                c.params_b.map(|x| (x * 1e6).round() / 1e6),
                c.residual
            );
        }
    }
}
