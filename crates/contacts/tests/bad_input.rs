//! The `contacts` binary on bad input: exit status 2 and one clear message on stderr, no panic.

use std::path::{Path, PathBuf};
use std::process::Command;

fn temp_file(name: &str, text: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("contacts-bad-input-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let path = dir.join(name);
    std::fs::write(&path, text).expect("temp file");
    path
}

fn run(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_contacts"))
        .args(args)
        .output()
        .expect("binary runs");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

fn assert_bad(path: &Path, needle: &str) {
    let (code, stdout, stderr) = run(&["query", path.to_str().expect("utf-8 path")]);
    assert_eq!(code, 2, "status for {}: stderr {stderr}", path.display());
    assert!(stdout.is_empty(), "nothing on stdout");
    assert!(
        stderr.contains(needle),
        "stderr {stderr:?} should mention {needle:?}"
    );
    assert!(!stderr.contains("panicked"), "no panic: {stderr}");
    assert_eq!(
        stderr.trim_end().lines().count(),
        1,
        "one message: {stderr}"
    );
}

const POSE: &str = r#""pose": {"translation": [0, 0, 0], "rotation": [0, 0, 0, 1]}"#;

#[test]
fn unreadable_file() {
    assert_bad(Path::new("/nonexistent/scene.json"), "cannot read");
}

#[test]
fn malformed_json() {
    assert_bad(
        &temp_file("malformed.json", "{ \"objects\": [ "),
        "malformed JSON",
    );
}

#[test]
fn unknown_object() {
    let text = format!(
        r#"{{"objects": [{{"name": "a", "object": "teapot", {POSE}}}, {{"name": "b", "object": "bowl", {POSE}}}]}}"#
    );
    assert_bad(&temp_file("unknown.json", &text), "unknown object `teapot`");
}

#[test]
fn bad_pose() {
    let text = format!(
        r#"{{"objects": [{{"name": "a", "object": "pencil", "pose": {{"rotation": [0, 0, 0, 2]}}}}, {{"name": "b", "object": "bowl", {POSE}}}]}}"#
    );
    assert_bad(&temp_file("pose.json", &text), "bad pose");
    let text = format!(
        r#"{{"objects": [{{"name": "a", "object": "pencil", "pose": {{"rotation": [0, 0, 0, 0]}}}}, {{"name": "b", "object": "bowl", {POSE}}}]}}"#
    );
    assert_bad(&temp_file("zero.json", &text), "bad pose");
}

#[test]
fn invalid_profile() {
    let text = format!(
        r#"{{"objects": [{{"name": "a", "object": {{"name": "gap", "profile": [
            {{"line": {{"from": [0, 0], "to": [10, 0]}}}},
            {{"line": {{"from": [10, 1], "to": [0, 10]}}}}]}}, {POSE}}},
          {{"name": "b", "object": "bowl", {POSE}}}]}}"#
    );
    assert_bad(&temp_file("profile.json", &text), "segment 1 starts at");
}

#[test]
fn bad_options_and_unknown_fields() {
    let text = format!(
        r#"{{"objects": [{{"name": "a", "object": "pencil", {POSE}}}, {{"name": "b", "object": "bowl", {POSE}}}],
            "options": {{"delta1": 0.5, "delta2": 0.1}}}}"#
    );
    assert_bad(&temp_file("options.json", &text), "delta1 <= delta2");
    let text =
        format!(r#"{{"objects": [{{"name": "a", "object": "pencil", "colour": "red", {POSE}}}]}}"#);
    assert_bad(&temp_file("field.json", &text), "unknown field `colour`");
}

#[test]
fn usage_errors_exit_with_2() {
    let (code, _, stderr) = run(&["frobnicate"]);
    assert_eq!(code, 2);
    assert!(!stderr.contains("panicked"));
}
