//! Object file formats.

pub(crate) mod object_description;
pub(crate) mod solid_description;
