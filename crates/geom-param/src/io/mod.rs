//! Object file formats.

pub(crate) mod object_description;
