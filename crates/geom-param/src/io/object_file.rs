//! Any object file: a solid of revolution ([`ObjectDescription`], a `profile`) or a general
//! solid made by a builder ([`SolidDescription`], e.g. `rounded_box`). The JSON forms are told
//! apart by the `profile` field.

use crate::io::object_description::{LoadError, ObjectDescription};
use crate::io::solid_description::{SolidDescription, SolidLoadError};
use crate::object_model::{MeshOptions, ObjectModel};

/// An object as a file describes it, not yet built.
#[derive(Clone, Debug, PartialEq)]
pub enum ObjectFile {
    /// A solid of revolution.
    Revolved(ObjectDescription),
    /// A general solid from a builder.
    General(SolidDescription),
}

/// Why an object file could not be read or built.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ObjectFileError {
    /// A solid of revolution's file or profile is wrong.
    #[error(transparent)]
    Revolved(#[from] LoadError),
    /// A general solid's file or builder parameters are wrong.
    #[error(transparent)]
    General(#[from] SolidLoadError),
}

impl ObjectFile {
    /// The object's name.
    #[must_use]
    pub fn name(&self) -> &str {
        match self {
            Self::Revolved(d) => &d.name,
            Self::General(d) => &d.name,
        }
    }

    /// Builds the solid and prepares the object (components, meshes, hulls).
    ///
    /// # Errors
    /// The description's own error.
    pub fn build(&self, options: &MeshOptions) -> Result<ObjectModel, ObjectFileError> {
        Ok(match self {
            Self::Revolved(d) => d.build(options)?,
            Self::General(d) => d.build(options)?,
        })
    }
}

#[cfg(feature = "json")]
mod json {
    use super::{ObjectFile, ObjectFileError};
    use crate::io::object_description::{LoadError, ObjectDescription};
    use crate::io::solid_description::{SolidDescription, SolidLoadError};
    use serde_json::Value;

    impl ObjectFile {
        /// Reads either JSON form.
        ///
        /// # Errors
        /// [`ObjectFileError`] for malformed JSON or a description that does not load.
        pub fn from_json(text: &str) -> Result<Self, ObjectFileError> {
            let value: Value = serde_json::from_str(text).map_err(|e| LoadError::Syntax {
                line: e.line(),
                column: e.column(),
                message: e.to_string(),
            })?;
            Self::from_json_value(&value, "object")
        }

        /// As [`ObjectFile::from_json`] from a parsed value; `path` names it in errors.
        ///
        /// # Errors
        /// As [`ObjectFile::from_json`].
        pub fn from_json_value(value: &Value, path: &str) -> Result<Self, ObjectFileError> {
            if value.get("profile").is_some() {
                return Ok(Self::Revolved(ObjectDescription::from_json_value(
                    value, path,
                )?));
            }
            let general: SolidDescription = serde_json::from_value(value.clone())
                .map_err(|e| SolidLoadError::Format(format!("{path}: {e}")))?;
            Ok(Self::General(general))
        }

        /// The JSON form, pretty-printed with a final newline.
        #[must_use]
        pub fn to_json(&self) -> String {
            match self {
                Self::Revolved(d) => d.to_json(),
                Self::General(d) => d.to_json(),
            }
        }
    }
}
