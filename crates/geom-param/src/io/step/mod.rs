//! The STEP reader (feature `step`): ISO 10303-21 files of AP203, AP214 and AP242 geometry
//! into validated [`crate::Solid`]s in millimetres.
//!
//! - [`part21`]: our own tokenizer and parser (every instance kept, simple or complex);
//!   `graph`: typed access with errors naming `#id` and type, reference and cycle checks;
//!   `units`: length unit to mm, angle unit to rad, uncertainty; `geometry`: curves and
//!   surfaces; `pcurve`: p-curves by projection; `brep`: faces, loops, edges into a `Solid`.
//! - Bounded: [`part21::MAX_INPUT_BYTES`] of input, [`part21::MAX_ENTITIES`] instances,
//!   [`brep::MAX_FACES`] faces per solid, [`pcurve::MAX_SEGMENTS`] segments per p-curve.
//! - Healing: the model tolerance is the file's uncertainty (at least [`UNCERTAINTY_FLOOR`]
//!   times the model's extent), raised to twice the largest gap
//!   measured (edge to face, edge end to vertex, loop closure) up to [`brep::MAX_HEAL_FACTOR`]
//!   times the uncertainty; a larger gap is an error.

pub(crate) mod brep;
pub(crate) mod error;
pub(crate) mod geometry;
pub(crate) mod graph;
pub mod part21;
pub(crate) mod pcurve;
pub(crate) mod units;

pub use brep::{
    DEFAULT_UNCERTAINTY_MM, MAX_FACES, MAX_HEAL_FACTOR, PCurveCount, StepSolid, UNCERTAINTY_FLOOR,
};
pub use error::StepError;

use crate::io::step::graph::Graph;

/// Schema name prefixes read (AP203, AP214, AP242 and their long names).
const SCHEMAS: [&str; 7] = [
    "CONFIG_CONTROL_DESIGN",
    // AP203's conformance-class draft names (CCD_CLA_GVP_AST, ...), as Pro/ENGINEER 2000
    // and CADDS wrote them: the same entities as CONFIG_CONTROL_DESIGN.
    "CCD_CLA_",
    "AUTOMOTIVE_DESIGN",
    "AP203",
    "AP214",
    "AP242",
    "AP242_MANAGED_MODEL_BASED_3D_ENGINEERING",
];

/// Reads every solid of a STEP file, in `#id` order: each MANIFOLD_SOLID_BREP and
/// BREP_WITH_VOIDS, and each CLOSED_SHELL of a SHELL_BASED_SURFACE_MODEL (a closed shell
/// bounds a solid whichever representation lists it).
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
    // (solid or closed shell, the item its representation lists).
    let mut roots: Vec<(u64, u64)> = file
        .records
        .iter()
        .filter(|(_, r)| {
            r.parts.len() == 1
                && matches!(
                    r.parts[0].0.as_str(),
                    "MANIFOLD_SOLID_BREP" | "BREP_WITH_VOIDS"
                )
        })
        .map(|(&id, _)| (id, id))
        .collect();
    // Shells a solid already bounds: a surface model listing one again adds no solid.
    let bounded: std::collections::HashSet<u64> = roots
        .iter()
        .filter_map(|&(id, _)| match file.records[&id].parts[0].1.get(1) {
            Some(part21::Param::Ref(shell)) => Some(*shell),
            _ => None,
        })
        .collect();
    let mut open_shell = None;
    for (&id, r) in &file.records {
        if r.parts.len() != 1 || r.parts[0].0 != "SHELL_BASED_SURFACE_MODEL" {
            continue;
        }
        let model = graph::Entity {
            id,
            record: r,
            params: &r.parts[0].1,
        };
        graph.check_acyclic(&[id])?;
        for shell in model.ref_list(1)? {
            let s = graph.get(&model, shell)?;
            if s.record.parts.len() == 1 && s.record.parts[0].0 == "CLOSED_SHELL" {
                if !bounded.contains(&shell) {
                    roots.push((shell, id));
                }
            } else if open_shell.as_ref().is_none_or(|(o, _)| shell < *o) {
                open_shell = Some((shell, s.type_name()));
            }
        }
    }
    roots.sort_unstable();
    roots.dedup_by_key(|r| r.0);
    if roots.is_empty() {
        // A surface model of open shells bounds no volume: say which shell, not just that
        // no solid was found.
        return Err(match open_shell {
            Some((id, entity)) => StepError::Unsupported {
                id,
                entity,
                role: "a solid (a SHELL_BASED_SURFACE_MODEL's open shell bounds no volume)",
            },
            None => StepError::NoSolid,
        });
    }
    let ids: Vec<u64> = roots.iter().map(|r| r.0).collect();
    graph.check_acyclic(&ids)?;
    roots
        .iter()
        .map(|&(root, item)| brep::read_solid(&graph, root, item))
        .collect()
}
