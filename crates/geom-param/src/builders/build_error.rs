//! Why a builder could not make a solid.

use crate::topology::feature::FaceId;
use crate::topology::solid::ParamSide;
use crate::topology::validate::TopologyError;

/// A solid a builder refuses to make, with the reason.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum BuildError {
    /// A dimension is not finite or out of its allowed range.
    #[error("{what} = {value} mm is not usable: {requirement}")]
    BadDimension {
        /// Which dimension.
        what: &'static str,
        /// The value given.
        value: f64,
        /// What it must satisfy.
        requirement: &'static str,
    },
    /// A surface or curve could not be made.
    #[error(transparent)]
    Geometry(#[from] crate::GeometryError),
    /// A side of a face meets no other face: the faces do not close.
    #[error("side {side:?} of face {face:?} meets no other face (the shell is open)")]
    UnmatchedSide {
        /// The face.
        face: FaceId,
        /// Its side.
        side: ParamSide,
    },
    /// The solid fails validation.
    #[error(transparent)]
    Topology(#[from] TopologyError),
    /// A STEP file could not be read, or holds no solid of the index or name asked for.
    #[cfg(feature = "step")]
    #[error("STEP file {file}: {reason}")]
    StepFile {
        /// The file's path.
        file: String,
        /// What went wrong (the system's message, or the solids the file holds).
        reason: String,
    },
    /// A STEP file's content cannot be mapped into a solid.
    #[cfg(feature = "step")]
    #[error("STEP file {file}: {source}")]
    Step {
        /// The file's path.
        file: String,
        /// The reader's typed error (entity type and `#id`), boxed to keep the error small.
        source: Box<crate::io::step::StepError>,
    },
}
