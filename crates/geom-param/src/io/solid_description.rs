//! A general (not revolved) object as its user describes it: a name and one of the builders
//! with its parameters. With the `json` feature this is the general object file format
//! (lengths in mm):
//!
//! ```json
//! { "name": "bracket",
//!   "note": "optional free text",
//!   "extrusion": { "profile": { "outer": [ {"line": {"from": [0, 0], "to": [40, 0]}}, ... ],
//!                               "holes": [ [ {"arc": {"center": [28, 4], "from": [31, 4],
//!                                                     "to": [31, 4], "ccw": false}} ] ] },
//!                  "z": [0, 20] } }
//! ```
//!
//! The other builders: `{"rounded_box": {"half_extents": [20, 15, 10], "radius": 3}}`,
//! `{"tube": {"outer_radius": 12, "inner_radius": 8, "length": 30}}` and
//! `{"loft": {"sections": [{"center": [0, 0], "semi_axes": [13, 9], "rotation": 0, "z": 0},
//! ...]}}`. A profile segment may also be a NURBS curve in the xy plane:
//! `{"nurbs": {"degree": 2, "knots": [0, 0, 0, 1, 1, 1], "points": [[0, 0], [5, 3], [10, 0]],
//! "weights": [1, 0.7, 1]}}` (weights optional, `"periodic": true` for a closed curve).
//! With the `step` feature, a solid of a STEP file: `{"step": {"file": "part.step",
//! "solid": 0}}` (`solid` an index or a name, the first solid when left out; a relative path
//! is relative to the working directory, and a scene resolves it against its own folder).

use crate::builders::build_error::BuildError;
use crate::builders::extrusion::{PlanarProfile, extrude};
use crate::builders::loft::{EllipseSection, loft};
use crate::builders::rounded_box::rounded_box;
use crate::builders::tube::tube;
use crate::object_model::{MeshOptions, ModelError, ObjectModel};
use crate::topology::solid::Solid;
use glam::DVec3;

/// Which builder makes the solid, with its parameters (mm).
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(
    feature = "json",
    derive(serde::Serialize, serde::Deserialize),
    serde(rename_all = "snake_case", deny_unknown_fields)
)]
pub enum SolidSpec {
    /// [`rounded_box`]: a box of these half extents with every edge rounded at `radius`.
    RoundedBox {
        /// Half extents along x, y, z.
        half_extents: DVec3,
        /// Fillet radius.
        radius: f64,
    },
    /// [`tube`]: a cylinder with a coaxial through hole.
    Tube {
        /// Outer radius.
        outer_radius: f64,
        /// Hole radius.
        inner_radius: f64,
        /// Length along z.
        length: f64,
    },
    /// [`extrude`]: a planar profile swept from z\[0\] to z\[1\].
    Extrusion {
        /// The region in the xy plane.
        profile: PlanarProfile,
        /// The two planes.
        z: [f64; 2],
    },
    /// [`loft`]: a free-form solid whose one NURBS side face passes through horizontal
    /// ellipses, closed by two planar caps.
    Loft {
        /// The cross-sections, bottom to top (strictly increasing z).
        sections: Vec<EllipseSection>,
    },
    /// A solid read from a STEP file ([`crate::step::read_step`]).
    #[cfg(feature = "step")]
    Step {
        /// The file's path.
        file: String,
        /// Which of the file's solids: its index or name; the first when `None`.
        #[cfg_attr(
            feature = "json",
            serde(default, skip_serializing_if = "Option::is_none")
        )]
        solid: Option<StepSolidRef>,
    },
}

/// Which solid of a STEP file: by index (in `#id` order) or by name.
#[cfg(feature = "step")]
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(
    feature = "json",
    derive(serde::Serialize, serde::Deserialize),
    serde(untagged)
)]
pub enum StepSolidRef {
    /// The index among the file's solids.
    Index(usize),
    /// The B-rep's name.
    Name(String),
}

/// Reads solid `which` of the STEP file at `file`.
#[cfg(feature = "step")]
fn read_step_solid(file: &str, which: Option<&StepSolidRef>) -> Result<Solid, BuildError> {
    let fail = |reason: String| BuildError::StepFile {
        file: file.to_string(),
        reason,
    };
    let limit = crate::io::step::part21::MAX_INPUT_BYTES as u64;
    let meta = std::fs::metadata(file).map_err(|e| fail(e.to_string()))?;
    if !meta.is_file() || meta.len() > limit {
        return Err(fail(format!("not a regular file of at most {limit} bytes")));
    }
    let bytes = std::fs::read(file).map_err(|e| fail(e.to_string()))?;
    let solids = crate::io::step::read_step(&bytes).map_err(|source| BuildError::Step {
        file: file.to_string(),
        source: Box::new(source),
    })?;
    let names = || {
        solids
            .iter()
            .enumerate()
            .map(|(i, s)| format!("{i}: {}", s.name))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let index = match which {
        None => 0,
        Some(StepSolidRef::Index(i)) => *i,
        Some(StepSolidRef::Name(name)) => solids
            .iter()
            .position(|s| &s.name == name)
            .ok_or_else(|| fail(format!("no solid named {name:?} (solids: {})", names())))?,
    };
    if index >= solids.len() {
        return Err(fail(format!("no solid {index} (solids: {})", names())));
    }
    let count = solids.len();
    solids
        .into_iter()
        .nth(index)
        .map(|s| s.solid)
        .ok_or_else(|| fail(format!("no solid {index} (the file holds {count})")))
}

/// A named general solid, not yet built.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "json", derive(serde::Serialize, serde::Deserialize))]
pub struct SolidDescription {
    /// The object's name.
    pub name: String,
    /// Free text carried along.
    #[cfg_attr(
        feature = "json",
        serde(default, skip_serializing_if = "Option::is_none")
    )]
    pub note: Option<String>,
    /// The builder and its parameters.
    #[cfg_attr(feature = "json", serde(flatten))]
    pub spec: SolidSpec,
}

/// Why a general object could not be read or built.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SolidLoadError {
    /// The text is not a valid description (malformed JSON, unknown or missing field, wrong
    /// type), with the parser's line and column.
    #[error("invalid general object description: {0}")]
    Format(String),
    /// The builder refused the parameters.
    #[error(transparent)]
    Build(#[from] BuildError),
    /// The meshing options are not usable for this object, or a face could not be meshed.
    #[error(transparent)]
    Model(#[from] ModelError),
}

impl SolidSpec {
    /// Runs the builder.
    ///
    /// # Errors
    /// The builder's [`BuildError`].
    pub fn build_solid(&self) -> Result<Solid, BuildError> {
        match self {
            Self::RoundedBox {
                half_extents,
                radius,
            } => rounded_box(*half_extents, *radius),
            Self::Tube {
                outer_radius,
                inner_radius,
                length,
            } => tube(*outer_radius, *inner_radius, *length),
            Self::Extrusion { profile, z } => extrude(profile, z[0], z[1]),
            Self::Loft { sections } => loft(sections),
            #[cfg(feature = "step")]
            Self::Step { file, solid } => read_step_solid(file, solid.as_ref()),
        }
    }
}

impl SolidDescription {
    /// Builds the solid and prepares the object (components, meshes, hulls).
    ///
    /// # Errors
    /// [`SolidLoadError::Build`] or [`SolidLoadError::Model`].
    pub fn build(&self, options: &MeshOptions) -> Result<ObjectModel, SolidLoadError> {
        let solid = self.spec.build_solid()?;
        Ok(ObjectModel::from_solid(self.name.clone(), solid, options)?)
    }

    /// Reads the JSON form.
    ///
    /// # Errors
    /// [`SolidLoadError::Format`] for text that is not a valid description.
    #[cfg(feature = "json")]
    pub fn from_json(text: &str) -> Result<Self, SolidLoadError> {
        serde_json::from_str(text).map_err(|e| SolidLoadError::Format(e.to_string()))
    }

    /// The JSON form, pretty-printed with a final newline.
    #[cfg(feature = "json")]
    #[must_use]
    pub fn to_json(&self) -> String {
        let mut text = serde_json::to_string_pretty(self).expect("descriptions serialise");
        text.push('\n');
        text
    }
}
