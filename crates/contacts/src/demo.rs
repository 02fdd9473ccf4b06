//! `contacts demo`: the paper's four two-contact scenes beside its Table 3.

use crate::output::state_name;
use crate::run::{PreparedScene, prepare_scene_text};
use std::fmt::Write as _;

/// (scene, paper's Table 3 total time in ms, scene text).
const PAPER_SCENES: [(&str, f64, &str); 4] = [
    (
        "pencil-paperweight",
        2.68,
        include_str!("../../../fixtures/scenes/pencil-paperweight-two-contacts.json"),
    ),
    (
        "paperweight-goblet",
        3.13,
        include_str!("../../../fixtures/scenes/paperweight-goblet-two-contacts.json"),
    ),
    (
        "pencil-bowl",
        2.95,
        include_str!("../../../fixtures/scenes/pencil-bowl-two-contacts.json"),
    ),
    (
        "vase-vase",
        4.87,
        include_str!("../../../fixtures/scenes/vase-vase-two-contacts.json"),
    ),
];

/// Runs the four scenes, timing `iterations` queries each, and returns the table.
///
/// # Errors
/// A message if a built-in scene fails to load (a packaging bug).
pub fn run(iterations: usize) -> Result<String, String> {
    let mut out = String::new();
    let _ = writeln!(
        out,
        "| scene | state | contacts | distances (mm) | broad µs | mesh µs | refine µs | total µs (median) | paper Table 3 (µs) | paper / ours |"
    );
    let _ = writeln!(out, "|---|---|---|---|---|---|---|---|---|---|");
    for (name, paper_ms, text) in PAPER_SCENES {
        let scene: PreparedScene = prepare_scene_text(text).map_err(|e| format!("{name}: {e}"))?;
        let (median, _min, report) = scene
            .time_pair((0, 1), iterations)
            .map_err(|e| format!("{name}: {e}"))?;
        let distances: Vec<String> = report
            .contacts
            .iter()
            .map(|c| format!("{:.6}", c.distance))
            .collect();
        let s = report.stats;
        let paper_us = paper_ms * 1000.0;
        let _ = writeln!(
            out,
            "| {name} | {} | {} | {} | {:.1} | {:.1} | {:.1} | {:.1} | {:.0} | {:.0}x |",
            state_name(report.state),
            report.contacts.len(),
            distances.join(", "),
            s.broad_us,
            s.mesh_us,
            s.refine_us,
            median,
            paper_us,
            paper_us / median,
        );
    }
    let _ = writeln!(
        out,
        "\nStage times are from the last query; total is the median wall time of {iterations} queries after as many warm-up queries, on this machine. The paper's figures are from a 2.8 GHz Pentium (2007)."
    );
    Ok(out)
}
