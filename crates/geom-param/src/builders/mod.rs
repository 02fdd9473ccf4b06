//! Builders for the solids users make most, each a validated [`crate::Solid`]. Their faces' and
//! edges' convexity is a placeholder until [`crate::ObjectModel::from_solid`] (or
//! [`crate::classify_convexity`]) assigns it from the geometry.

pub(crate) mod build_error;
pub(crate) mod extrusion;
pub(crate) mod loft;
pub(crate) mod rounded_box;
pub(crate) mod sew;
pub(crate) mod tube;

/// The smallest feature a builder makes (a fillet radius, a wall), relative to the solid's
/// size: below it a feature is numerically an edge, and meshing it at any usable chordal
/// tolerance is degenerate.
pub(crate) const MIN_RELATIVE_FEATURE: f64 = 1e-6;
/// How far a trimmed cap plane's parameter domain reaches, as a multiple of the largest
/// coordinate of its trim: well beyond the trim on every side, so that no trim loop touches a
/// side of its surface's domain. (Stage 3 cuts a Newton step where a parameter reaches its
/// domain's side; a point held there on the trim could not move on to the edge or vertex, and
/// a ball over the corner of an extruded block was missed.)
pub(crate) const CAP_DOMAIN_FACTOR: f64 = 2.0;
