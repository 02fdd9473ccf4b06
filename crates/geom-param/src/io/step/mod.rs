//! The STEP reader (feature `step`): ISO 10303-21 files of AP203, AP214 and AP242 geometry
//! into validated [`crate::Solid`]s in millimetres.
//!
//! - [`part21`]: our own tokenizer and parser (every instance kept, simple or complex);
//!   `graph`: typed access with errors naming `#id` and type, reference and cycle checks;
//!   `units`: length unit to mm, angle unit to rad, uncertainty; `geometry`: curves and
//!   surfaces; `pcurve`: p-curves by projection; `brep`: faces, loops, edges into a `Solid`.
//! - Bounded: [`part21::MAX_INPUT_BYTES`] of input, [`part21::MAX_ENTITIES`] instances,
//!   [`brep::MAX_FACES`] faces per solid, [`pcurve::MAX_SEGMENTS`] segments per p-curve.
//! - Healing: the model tolerance is the file's uncertainty, raised to twice the largest gap
//!   measured (edge to face, edge end to vertex, loop closure) up to [`brep::MAX_HEAL_FACTOR`]
//!   times the uncertainty; a larger gap is an error.

pub(crate) mod brep;
pub(crate) mod error;
pub(crate) mod geometry;
pub(crate) mod graph;
pub mod part21;
pub(crate) mod pcurve;
pub(crate) mod units;

pub use brep::{DEFAULT_UNCERTAINTY_MM, MAX_FACES, MAX_HEAL_FACTOR, StepSolid};
pub use error::StepError;

use crate::io::step::graph::Graph;

/// Schema name prefixes read (AP203, AP214, AP242 and their long names).
const SCHEMAS: [&str; 6] = [
    "CONFIG_CONTROL_DESIGN",
    "AUTOMOTIVE_DESIGN",
    "AP203",
    "AP214",
    "AP242",
    "AP242_MANAGED_MODEL_BASED_3D_ENGINEERING",
];

/// Reads every solid (MANIFOLD_SOLID_BREP, BREP_WITH_VOIDS) of a STEP file, in `#id` order.
///
/// Lengths are converted to millimetres; each solid's tolerance is the file's uncertainty,
/// healed as the module documentation says; each solid passes [`crate::validate`].
///
/// # Errors
/// A [`StepError`] naming the entity type and `#id` for anything that cannot be read or
/// mapped; nothing is skipped.
pub fn read_step(bytes: &[u8]) -> Result<Vec<StepSolid>, StepError> {
    let file = part21::parse(bytes)?;
    let known = file.schema.iter().any(|s| {
        let s = s.trim().to_ascii_uppercase();
        SCHEMAS.iter().any(|k| s.starts_with(k))
    });
    if !known {
        return Err(StepError::UnsupportedSchema {
            schema: file.schema.join(", "),
        });
    }
    let graph = Graph { file: &file };
    let mut roots: Vec<u64> = file
        .records
        .iter()
        .filter(|(_, r)| {
            r.parts.len() == 1
                && matches!(
                    r.parts[0].0.as_str(),
                    "MANIFOLD_SOLID_BREP" | "BREP_WITH_VOIDS"
                )
        })
        .map(|(&id, _)| id)
        .collect();
    roots.sort_unstable();
    if roots.is_empty() {
        return Err(StepError::NoSolid);
    }
    graph.check_acyclic(&roots)?;
    roots
        .iter()
        .map(|&root| brep::read_solid(&graph, root))
        .collect()
}
