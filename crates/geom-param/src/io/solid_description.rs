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
//! The other builders: `{"rounded_box": {"half_extents": [20, 15, 10], "radius": 3}}` and
//! `{"tube": {"outer_radius": 12, "inner_radius": 8, "length": 30}}`.

use crate::builders::build_error::BuildError;
use crate::builders::extrusion::{PlanarProfile, extrude};
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
