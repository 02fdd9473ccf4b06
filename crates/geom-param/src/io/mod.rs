//! Object file formats.

pub(crate) mod object_description;
pub(crate) mod object_file;
pub(crate) mod solid_description;
