//! Parametric curves: the geometry of edges (and, in two dimensions, of p-curves).

pub(crate) mod circle_curve;
pub(crate) mod circle_edge;
pub(crate) mod curve;
pub(crate) mod curve2;
pub(crate) mod ellipse_curve;
pub(crate) mod iso_curve;
pub(crate) mod line_curve;
pub(crate) mod nurbs_curve;
pub(crate) mod nurbs_curve2;
