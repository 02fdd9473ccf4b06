//! Parametric curves: the geometry of edges (and, in two dimensions, of p-curves).

pub(crate) mod circle_edge;
pub(crate) mod curve;
pub(crate) mod curve2;
