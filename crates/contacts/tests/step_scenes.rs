//! The STEP scenes (`fixtures/scenes/step-*.json`, real CAD exports from `fixtures/step/`)
//! against the independent oracle: the same state, and every oracle contact in the band matched
//! by a pipeline contact (distance within 1e-9 mm, both points within 1e-6 mm) and the other way
//! round.

use contact_oracle::{OracleOptions, OracleState, find_contacts};
use contact_pipeline::{PairState, QueryScratch};
use contacts::run::prepare_scene;
use geom_param::Solid;
use geom_param::step::read_step;
use serde_json::Value;
use std::path::{Path, PathBuf};

fn scenes() -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/scenes");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .expect("fixtures/scenes exists")
        .map(|e| e.expect("entry").path())
        .filter(|p| {
            p.file_name()
                .and_then(|n| n.to_str())
                .is_some_and(|n| n.starts_with("step-") && n.ends_with(".json"))
        })
        .collect();
    files.sort();
    assert!(files.len() >= 3, "the STEP scenes");
    files
}

/// The exact solids of a scene's two objects, read independently of the scene loader.
fn solids(file: &Path) -> [Solid; 2] {
    let text = std::fs::read_to_string(file).expect("scene");
    let scene: Value = serde_json::from_str(&text).expect("json");
    let base = file.parent().expect("folder");
    let objects = scene["objects"].as_array().expect("objects");
    let read = |o: &Value| -> Solid {
        let path = base.join(o["object"].as_str().expect("a STEP path"));
        let solids = read_step(&std::fs::read(&path).expect("STEP file")).expect("reads");
        let index = match &o["solid"] {
            Value::Null => 0,
            Value::Number(n) => usize::try_from(n.as_u64().expect("index")).expect("index"),
            Value::String(name) => solids.iter().position(|s| &s.name == name).expect("named"),
            other => panic!("solid {other}"),
        };
        solids.into_iter().nth(index).expect("solid").solid
    };
    [read(&objects[0]), read(&objects[1])]
}

#[test]
fn step_scenes_agree_with_the_oracle() {
    for file in scenes() {
        let scene = prepare_scene(&file).expect("scene loads");
        let options = scene.scene.options;
        let report = scene
            .query((0, 1), &mut QueryScratch::default())
            .expect("query");
        let [a, b] = solids(&file);
        let pose_a = scene.scene.objects[0].pose;
        let pose_b = scene.scene.objects[1].pose;
        let oracle_options = OracleOptions::for_solids(&a, &b, 2.0 * options.delta2);
        let oracle = find_contacts(&a, &pose_a, &b, &pose_b, &oracle_options).expect("oracle");
        let truth = oracle.state(options.delta1, options.delta2);
        let name = file.display();
        let state = match truth {
            OracleState::Separated => PairState::Separated,
            OracleState::Contact => PairState::Contact,
            OracleState::Penetration => PairState::Penetration,
        };
        assert_eq!(report.state, state, "{name}");
        assert_eq!(
            oracle.cross_check.unmatched, 0,
            "{name}: the oracle's two samplings agree"
        );
        let in_band: Vec<_> = oracle
            .contacts
            .iter()
            .filter(|c| options.delta1 <= c.distance && c.distance <= options.delta2)
            .collect();
        assert_eq!(
            report.contacts.len(),
            in_band.len(),
            "{name}: contact count"
        );
        for o in &in_band {
            let m = report.contacts.iter().find(|c| {
                (c.distance - o.distance).abs() <= 1e-9
                    && c.point_a.distance(o.point_a) <= 1e-6
                    && c.point_b.distance(o.point_b) <= 1e-6
            });
            assert!(
                m.is_some(),
                "{name}: oracle contact {o:?} not found in {:?}",
                report.contacts
            );
        }
    }
}

#[test]
fn a_scene_can_name_a_step_solid_by_index_or_name() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/scenes");
    let scene = prepare_scene(&dir.join("step-cube-cylinder-one-contact.json")).expect("loads");
    // "red_cube" by name and index 0 (the cylinder, first in #id order).
    let [a, b] = [&scene.objects[0], &scene.objects[1]];
    assert_eq!(a.model.solid.faces.len(), 6);
    assert_eq!(b.model.solid.faces.len(), 3);
}

#[test]
fn crossed_step_cylinders_match_the_closed_form() {
    // Axes perpendicular and 10.05 mm apart, radius 5: the gap is 0.05 mm, at (15, 5, 5) on A
    // and (15.05, 5, 5) on B, along +x.
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/scenes");
    let scene = prepare_scene(&dir.join("step-cylinder-cylinder-one-contact.json")).expect("loads");
    let report = scene
        .query((0, 1), &mut QueryScratch::default())
        .expect("query");
    assert_eq!(report.state, PairState::Contact);
    let [c] = report.contacts.as_slice() else {
        panic!("one contact: {:?}", report.contacts);
    };
    assert!((c.distance - 0.05).abs() < 1e-9, "{}", c.distance);
    assert!(c.point_a.distance(glam::DVec3::new(15.0, 5.0, 5.0)) < 1e-6);
    assert!(c.point_b.distance(glam::DVec3::new(15.05, 5.0, 5.0)) < 1e-6);
}
