//! Pictures of the paper scenes (like the paper's Figs. 3-6), drawn by `contacts render`.

use contacts::render::{RenderOptions, render_scene};
use contacts::run::prepare_scene;
use std::path::Path;

/// Renders fixtures/scenes/`name`-two-contacts.json to `out` (PNG).
///
/// # Errors
/// A message if the scene does not load or the picture cannot be drawn or written.
pub fn render_paper_scene(
    root: &Path,
    name: &str,
    (width, height): (u32, u32),
    out: &Path,
) -> Result<(), String> {
    let path = root.join(format!("fixtures/scenes/{name}-two-contacts.json"));
    let scene = prepare_scene(&path).map_err(|e| format!("{name}: {e}"))?;
    let options = RenderOptions {
        width,
        height,
        ..RenderOptions::default()
    };
    render_scene(&scene, &options)
        .and_then(|picture| picture.write_png(out))
        .map_err(|e| format!("{name}: {e}"))
}
