//! Parametric surfaces: the geometry of faces.

pub(crate) mod revolved_surface;
pub(crate) mod surface;
