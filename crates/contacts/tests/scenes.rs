//! `contacts query` on every fixture scene: snapshots, the contact counts the scenes were built
//! for, and invariance under a rigid motion of the whole scene and under swapping the objects.

use contact_pipeline::{PairState, QueryScratch};
use contacts::run::{PreparedScene, prepare_scene};
use geom_param::{DPose3, DQuat, DVec3};
use serde_json::Value;
use std::path::{Path, PathBuf};

fn scenes_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/scenes")
}

fn scene_files() -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(scenes_dir())
        .expect("fixtures/scenes exists")
        .map(|e| e.expect("readable entry").path())
        .filter(|p| p.extension().is_some_and(|x| x == "json"))
        .collect();
    files.sort();
    assert!(
        files.len() >= 13,
        "the 4 x 3 paper scenes and a penetrating one"
    );
    files
}

/// Rounds every float to 6 decimals (and -0 to 0) and drops wall times, so that snapshots are
/// stable across machines and runs.
fn stable(value: &Value) -> Value {
    match value {
        Value::Number(n) if n.is_f64() => {
            let x = (n.as_f64().unwrap_or(0.0) * 1e6).round() / 1e6;
            serde_json::json!(if x == 0.0 { 0.0 } else { x })
        }
        Value::Array(items) => Value::Array(items.iter().map(stable).collect()),
        Value::Object(map) => Value::Object(
            map.iter()
                .filter(|(k, _)| !matches!(k.as_str(), "stages_us" | "total_us" | "condition"))
                .map(|(k, v)| (k.clone(), stable(v)))
                .collect(),
        ),
        other => other.clone(),
    }
}

#[test]
fn query_snapshots_of_every_fixture_scene() {
    for file in scene_files() {
        let scene = prepare_scene(&file).expect("fixture scene loads");
        let result = scene.query_json().expect("queries run");
        let name = file
            .file_stem()
            .and_then(|s| s.to_str())
            .unwrap_or("scene")
            .to_string();
        insta::assert_json_snapshot!(format!("query_{name}"), stable(&result));
    }
}

fn expected_contacts(file: &Path) -> (PairState, usize) {
    let name = file
        .file_name()
        .and_then(|s| s.to_str())
        .unwrap_or_default();
    if name.ends_with("two-contacts.json") {
        (PairState::Contact, 2)
    } else if name.ends_with("one-contact.json") {
        (PairState::Contact, 1)
    } else if name.ends_with("separated.json") {
        (PairState::Separated, 0)
    } else {
        // One penetration region (the pencil's tip in the bowl's bottom): its depth.
        (PairState::Penetration, 1)
    }
}

#[test]
fn every_scene_has_the_contacts_it_was_built_for() {
    for file in scene_files() {
        let scene = prepare_scene(&file).expect("fixture scene loads");
        let report = scene
            .query((0, 1), &mut QueryScratch::default())
            .expect("query runs");
        let (state, count) = expected_contacts(&file);
        assert_eq!(report.state, state, "{}", file.display());
        assert_eq!(report.contacts.len(), count, "{}", file.display());
        let options = scene.scene.options;
        for c in &report.contacts {
            // In the band, or a penetration region's depth below it.
            assert!(
                (options.delta1 <= c.distance || state == PairState::Penetration)
                    && c.distance <= options.delta2,
                "{}",
                file.display()
            );
            assert!(c.diagnostics.converged && c.diagnostics.is_local_minimum);
            // Oracle-free invariants: b = a + d n, and n is A's unit normal.
            let rebuilt = c.point_a + c.normal * c.distance;
            assert!(
                rebuilt.distance(c.point_b) < 1e-9,
                "{}: b != a + d n",
                file.display()
            );
            assert!((c.normal.length() - 1.0).abs() < 1e-12);
        }
        if state == PairState::Separated {
            assert!(
                !report.stats.mesh_ran && !report.stats.refine_ran,
                "{}: stops after Stage 1",
                file.display()
            );
        }
        if state == PairState::Penetration {
            assert!(
                !report.penetration_witnesses.is_empty(),
                "{}: witnesses",
                file.display()
            );
        }
    }
}

fn moved(scene: &PreparedScene, motion: &DPose3) -> Vec<DPose3> {
    scene
        .scene
        .objects
        .iter()
        .map(|o| *motion * o.pose)
        .collect()
}

#[test]
fn same_contacts_after_a_rigid_motion_and_after_swapping() {
    let motion = DPose3 {
        rotation: DQuat::from_euler(glam::EulerRot::XYZ, 0.7, -1.1, 2.3),
        translation: DVec3::new(250.0, -40.0, 1200.0),
    };
    for file in scene_files() {
        let scene = prepare_scene(&file).expect("fixture scene loads");
        let (a, b) = (&scene.objects[0], &scene.objects[1]);
        let (pa, pb) = (scene.scene.objects[0].pose, scene.scene.objects[1].pose);
        let mut scratch = QueryScratch::default();
        let base = scene
            .pipeline
            .query(a, &pa, b, &pb, &mut scratch)
            .expect("query");
        let poses = moved(&scene, &motion);
        let after = scene
            .pipeline
            .query(a, &poses[0], b, &poses[1], &mut scratch)
            .expect("query");
        let swapped = scene
            .pipeline
            .query(b, &pb, a, &pa, &mut scratch)
            .expect("query");
        assert_eq!(base.state, after.state, "{}", file.display());
        assert_eq!(base.state, swapped.state, "{}", file.display());
        assert_eq!(
            base.contacts.len(),
            after.contacts.len(),
            "{}",
            file.display()
        );
        assert_eq!(
            base.contacts.len(),
            swapped.contacts.len(),
            "{}",
            file.display()
        );
        for c in &base.contacts {
            let point_a = motion * c.point_a;
            let m = after
                .contacts
                .iter()
                .min_by(|x, y| {
                    x.point_a
                        .distance(point_a)
                        .total_cmp(&y.point_a.distance(point_a))
                })
                .expect("a contact");
            assert!(
                m.point_a.distance(point_a) < 1e-6,
                "{}: moved point",
                file.display()
            );
            assert!(
                (m.distance - c.distance).abs() < 1e-9,
                "{}: moved distance",
                file.display()
            );
            assert!(m.normal.distance(motion.rotation * c.normal) < 1e-6);
            let s = swapped
                .contacts
                .iter()
                .min_by(|x, y| {
                    x.point_b
                        .distance(c.point_a)
                        .total_cmp(&y.point_b.distance(c.point_a))
                })
                .expect("a contact");
            assert!(
                s.point_b.distance(c.point_a) < 1e-6,
                "{}: swapped point",
                file.display()
            );
            assert!(
                s.point_a.distance(c.point_b) < 1e-6,
                "{}: swapped point",
                file.display()
            );
            assert!(
                (s.distance - c.distance).abs() < 1e-9,
                "{}: swapped distance",
                file.display()
            );
            assert!(
                s.normal.distance(-c.normal) < 1e-6,
                "{}: swapped normal",
                file.display()
            );
        }
    }
}
