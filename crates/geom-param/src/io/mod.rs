//! Object file formats.

#[cfg(feature = "json")]
pub(crate) mod nurbs_curve2_json;
pub(crate) mod object_description;
pub(crate) mod object_file;
pub(crate) mod solid_description;
#[cfg(feature = "step")]
pub mod step;
