//! Builders for the solids users make most, each a validated [`crate::Solid`]. Their faces' and
//! edges' convexity is a placeholder until [`crate::ObjectModel::from_solid`] (or
//! [`crate::classify_convexity`]) assigns it from the geometry.

pub(crate) mod build_error;
pub(crate) mod extrusion;
pub(crate) mod rounded_box;
pub(crate) mod sew;
pub(crate) mod tube;
