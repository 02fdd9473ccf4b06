//! Parametric surfaces: the geometry of faces.

pub(crate) mod boxed_geometry;
pub(crate) mod cone_surface;
pub(crate) mod cylinder_surface;
pub(crate) mod linear_extrusion_surface;
pub(crate) mod nurbs_surface;
pub(crate) mod placement;
pub(crate) mod plane;
pub(crate) mod reversed_surface;
pub(crate) mod revolution_surface;
pub(crate) mod revolved_surface;
pub(crate) mod sphere_surface;
pub(crate) mod surface;
pub(crate) mod torus_surface;
