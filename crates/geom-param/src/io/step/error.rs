//! The typed errors of the STEP reader: each names the entity type and `#id` it is about.

use crate::geometry_error::GeometryError;
use crate::topology::validate::TopologyError;

/// Why a STEP file (ISO 10303-21) cannot be read into solids.
///
/// Every variant about one entity carries its `#id` and type name, so a user can find it in
/// the file. Nothing is skipped silently: an entity inside a B-rep that the reader cannot map
/// is [`StepError::Unsupported`].
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum StepError {
    /// The bytes are not a Part 21 exchange structure (no `ISO-10303-21;` at the start).
    #[error("not a STEP file: {reason}")]
    NotStep {
        /// What was found instead.
        reason: String,
    },
    /// A character or token that Part 21 does not allow here (binary data, a non-ASCII byte
    /// outside a string, a missing separator).
    #[error("STEP syntax error at line {line}: {message}")]
    Syntax {
        /// 1-based line number.
        line: usize,
        /// What is wrong.
        message: String,
    },
    /// The file ends inside a section, an entity or a string.
    #[error("the STEP file is truncated: it ends {inside}")]
    Truncated {
        /// Where the file ended.
        inside: String,
    },
    /// The header names no schema this reader maps (AP203, AP214, AP242).
    #[error("unsupported STEP schema {schema:?} (AP203, AP214 and AP242 geometry are read)")]
    UnsupportedSchema {
        /// The schema names of FILE_SCHEMA.
        schema: String,
    },
    /// A size limit of the reader is exceeded (bounded time and memory).
    #[error("the STEP file exceeds the reader's limit: {what} (limit {limit})")]
    TooLarge {
        /// Which quantity.
        what: &'static str,
        /// The limit.
        limit: usize,
    },
    /// Two entity instances have the same `#id`.
    #[error("entity #{id} is defined twice")]
    DuplicateId {
        /// The id.
        id: u64,
    },
    /// An entity references an `#id` that no instance defines.
    #[error("{entity} #{id} references #{target}, which the file does not define")]
    MissingReference {
        /// The referencing entity's id.
        id: u64,
        /// Its type.
        entity: String,
        /// The missing id.
        target: u64,
    },
    /// Entities reference each other in a cycle.
    #[error("{entity} #{id} is on a reference cycle")]
    ReferenceCycle {
        /// An entity on the cycle.
        id: u64,
        /// Its type.
        entity: String,
    },
    /// An entity inside a B-rep that the reader cannot map into the general model.
    #[error("{entity} #{id} is not supported as {role}")]
    Unsupported {
        /// The entity's id.
        id: u64,
        /// Its type (for a complex instance, its parts joined by `+`).
        entity: String,
        /// What it was referenced as (a surface, a curve, a face bound...).
        role: &'static str,
    },
    /// An entity's parameters do not have the shape its type requires.
    #[error("{entity} #{id} is malformed: {reason}")]
    Malformed {
        /// The entity's id.
        id: u64,
        /// Its type.
        entity: String,
        /// What is wrong.
        reason: String,
    },
    /// A curve or surface whose data the geometry constructors refuse (bad knots, weights,
    /// degenerate placements, radii).
    #[error("{entity} #{id} has invalid geometry: {source}")]
    Geometry {
        /// The entity's id.
        id: u64,
        /// Its type.
        entity: String,
        /// The constructor's error.
        source: GeometryError,
    },
    /// The file's length unit or uncertainty cannot be read.
    #[error("units of #{id}: {reason}")]
    Units {
        /// The context or unit entity.
        id: u64,
        /// What is wrong.
        reason: String,
    },
    /// The file holds no `MANIFOLD_SOLID_BREP`, `BREP_WITH_VOIDS` or closed shell of a
    /// `SHELL_BASED_SURFACE_MODEL` (a surface model of open shells is
    /// [`StepError::Unsupported`] naming its first open shell).
    #[error(
        "the STEP file holds no solid (MANIFOLD_SOLID_BREP, BREP_WITH_VOIDS or a SHELL_BASED_SURFACE_MODEL's CLOSED_SHELL)"
    )]
    NoSolid,
    /// An edge bounds other than two face positions of its solid: the shell is open (or not
    /// manifold).
    #[error(
        "EDGE_CURVE #{edge} bounds {count} face positions of solid #{solid} (a closed shell needs 2): open or non-manifold shell"
    )]
    OpenShell {
        /// The solid (MANIFOLD_SOLID_BREP) id.
        solid: u64,
        /// The edge's id.
        edge: u64,
        /// How many loop entries use it.
        count: usize,
    },
    /// Consecutive edges of a loop do not meet within the model tolerance.
    #[error(
        "EDGE_LOOP #{id} does not close: a gap of {gap:.3e} mm after ORIENTED_EDGE #{after} (tolerance {tolerance:.1e} mm)"
    )]
    LoopNotClosed {
        /// The loop's id.
        id: u64,
        /// The oriented edge the gap follows.
        after: u64,
        /// The gap (mm).
        gap: f64,
        /// The model tolerance (mm).
        tolerance: f64,
    },
    /// An edge lies farther from a face than the healing accepts.
    #[error(
        "EDGE_CURVE #{edge} lies {gap:.3e} mm from the surface of ADVANCED_FACE #{face} (accepted up to {limit:.1e} mm)"
    )]
    EdgeOffFace {
        /// The face's id.
        face: u64,
        /// The edge's id.
        edge: u64,
        /// Largest sampled distance (mm).
        gap: f64,
        /// The largest gap healed (mm).
        limit: f64,
    },
    /// No p-curve within tolerance could be fitted to an edge's projection onto a face.
    #[error(
        "EDGE_CURVE #{edge} on ADVANCED_FACE #{face}: no p-curve within {tolerance:.1e} mm ({reason})"
    )]
    PCurve {
        /// The face's id.
        face: u64,
        /// The edge's id.
        edge: u64,
        /// The tolerance the fit must meet (mm).
        tolerance: f64,
        /// What failed.
        reason: String,
    },
    /// The assembled solid fails the general model's validation.
    #[error("solid #{id} ({name:?}) is not a valid B-rep: {source}")]
    Topology {
        /// The MANIFOLD_SOLID_BREP's id.
        id: u64,
        /// Its name.
        name: String,
        /// The validation error.
        source: TopologyError,
    },
}
