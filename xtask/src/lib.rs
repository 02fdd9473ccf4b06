//! Project automation behind `cargo xtask`: fixture generation.

pub mod general_objects;
pub mod obj;
pub mod paper_objects;
pub mod report;
pub mod rng;
pub mod scenes;
pub mod settle;
pub mod soak;
pub mod world_scene;

use geom_param::{MeshOptions, ObjectFile};
use std::path::{Path, PathBuf};

/// Chordal tolerance of the meshes written as OBJ files (mm).
pub const FIXTURE_OBJ_TOLERANCE: f64 = 0.1;

/// Every fixture object: the six paper objects, then the general ones.
#[must_use]
pub fn fixture_objects() -> Vec<ObjectFile> {
    paper_objects::paper_objects()
        .into_iter()
        .map(ObjectFile::Revolved)
        .chain(
            general_objects::general_objects()
                .into_iter()
                .map(ObjectFile::General),
        )
        .collect()
}

/// Every generated fixture file: path relative to the workspace root, and contents.
///
/// # Errors
/// A message if a fixture object fails to build (a bug in its definition).
pub fn generate_fixtures() -> Result<Vec<(PathBuf, String)>, String> {
    let mut files = Vec::new();
    let options = MeshOptions {
        chordal_tolerance: FIXTURE_OBJ_TOLERANCE,
    };
    let objects = fixture_objects();
    for description in &objects {
        let name = description.name().to_string();
        let model = description
            .build(&options)
            .map_err(|e| format!("{name}: {e}"))?;
        let dir = Path::new("fixtures/objects");
        files.push((dir.join(format!("{name}.json")), description.to_json()));
        files.push((
            dir.join(format!("{name}.obj")),
            obj::to_obj(&model, paper_objects::GENERATED_NOTE),
        ));
    }
    for (name, contents) in scenes::generate_scenes(&objects)? {
        files.push((Path::new("fixtures/scenes").join(name), contents));
    }
    let (name, contents) = world_scene::generate_world_scene(&objects)?;
    files.push((Path::new("fixtures/worlds").join(name), contents));
    Ok(files)
}

/// Writes every fixture under `root`.
///
/// # Errors
/// A message naming the file that could not be written.
pub fn write_fixtures(root: &Path) -> Result<(), String> {
    for (path, contents) in generate_fixtures()? {
        let full = root.join(&path);
        if let Some(dir) = full.parent() {
            std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
        }
        std::fs::write(&full, contents).map_err(|e| format!("{}: {e}", full.display()))?;
        println!("wrote {}", path.display());
    }
    Ok(())
}
