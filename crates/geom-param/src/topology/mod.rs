//! Boundary representation: faces, edges, vertices, their convexity and the surface components.

pub(crate) mod components;
pub(crate) mod convexity;
pub(crate) mod feature;
pub(crate) mod pole_meridians;
pub(crate) mod solid;
pub(crate) mod trim;
pub(crate) mod trim_grid;
pub(crate) mod validate;
