//! The `contacts` binary on scenes whose STEP objects are bad: exit status 2 and one message on
//! stderr naming the entity type and `#id` (or the solid asked for), no panic.

use std::path::{Path, PathBuf};
use std::process::Command;

fn fixture(name: &str) -> String {
    let path = format!("{}/../../fixtures/step/{name}", env!("CARGO_MANIFEST_DIR"));
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"))
}

fn temp_dir() -> PathBuf {
    let dir = std::env::temp_dir().join(format!("contacts-step-bad-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}

/// A scene of the STEP text `step` (written beside it) and the tube; `solid` the scene's
/// `"solid"` field, if any.
fn scene_with(name: &str, step: &str, solid: Option<&str>) -> PathBuf {
    let dir = temp_dir();
    std::fs::write(dir.join(format!("{name}.step")), step).expect("step file");
    let solid = solid
        .map(|s| format!(r#", "solid": {s}"#))
        .unwrap_or_default();
    let scene = format!(
        r#"{{"objects": [{{"name": "part", "object": "{name}.step"{solid}}}, {{"name": "tube", "object": "tube", "pose": {{"translation": [100, 0, 0], "rotation": [0, 0, 0, 1]}}}}]}}"#
    );
    let path = dir.join(format!("{name}.json"));
    std::fs::write(&path, scene).expect("scene");
    path
}

fn assert_bad(path: &Path, needle: &str) {
    let out = Command::new(env!("CARGO_BIN_EXE_contacts"))
        .args(["query", path.to_str().expect("utf-8 path")])
        .output()
        .expect("binary runs");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(out.stdout.is_empty());
    assert!(
        stderr.contains(needle),
        "{stderr:?} should mention {needle:?}"
    );
    assert!(!stderr.contains("panicked"));
    assert_eq!(stderr.trim_end().lines().count(), 1, "{stderr}");
}

#[test]
fn truncated_step_file() {
    let text = fixture("red_cube_blue_cylinder.step");
    assert_bad(
        &scene_with("truncated", &text[..text.len() / 2], None),
        "truncated",
    );
}

#[test]
fn unsupported_entity_names_its_id() {
    let text = fixture("red_cube_blue_cylinder.step").replacen(
        "#103 = CYLINDRICAL_SURFACE( '', #143, 0.00500000000000000 );",
        "#103 = OFFSET_SURFACE( '', #143, 0.005, .F. );",
        1,
    );
    assert_bad(&scene_with("offset", &text, None), "OFFSET_SURFACE #103");
}

#[test]
fn open_shell() {
    let text = fixture("red_cube_blue_cylinder.step").replacen(
        "( #46, #40, #52, #48, #42, #38 )",
        "( #46, #40, #52, #48, #42 )",
        1,
    );
    assert_bad(
        &scene_with("open", &text, Some("1")),
        "open or non-manifold shell",
    );
}

#[test]
fn missing_solid_index_or_name() {
    let text = fixture("red_cube_blue_cylinder.step");
    assert_bad(&scene_with("index", &text, Some("5")), "no solid 5");
    assert_bad(
        &scene_with("name", &text, Some("\"green\"")),
        "no solid named \"green\"",
    );
    assert_bad(&scene_with("negative", &text, Some("-1")), "solid index");
}

#[test]
fn binary_step_file() {
    assert_bad(
        &scene_with("binary", "\u{1}\u{2}PK\u{3}\u{4}", None),
        "not a STEP file",
    );
}

#[test]
fn solid_field_without_a_step_object() {
    let dir = temp_dir();
    let path = dir.join("solid-field.json");
    std::fs::write(
        &path,
        r#"{"objects": [{"name": "a", "object": "tube", "solid": 0}, {"name": "b", "object": "tube"}]}"#,
    )
    .expect("scene");
    assert_bad(&path, "objects[0].solid");
}
