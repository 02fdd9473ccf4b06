//! What the oracle looks for and how finely.

use crate::samples::sampling::object_extent;
use geom_param::Solid;

/// Sampling and acceptance parameters (all mm).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OracleOptions {
    /// Target distance between neighbouring samples on each surface, in the world frame (mm).
    /// Two local minima of distance closer together than about 1.5 x spacing may be reported
    /// as one; a penetration region narrower than the spacing is still found when the surfaces
    /// cross near a sampled minimum (see the crate docs).
    pub spacing: f64,
    /// Largest (signed) distance of a reported contact (mm); also sets how much of each solid
    /// is sampled (the parts within `reach` + a few spacings of the other's bounding box).
    pub reach: f64,
    /// Largest tangential component of the connecting vector at an accepted point (mm): the
    /// stationarity residual. Points closer than 100 x `tolerance` are one minimum.
    pub tolerance: f64,
}

impl OracleOptions {
    /// Spacing 1/150 of the smaller solid's extent (largest bounding-box side, object frame),
    /// tolerance 1e-10 x the larger extent, and the given `reach`.
    #[must_use]
    pub fn for_solids(a: &Solid, b: &Solid, reach: f64) -> Self {
        let (ea, eb) = (object_extent(a), object_extent(b));
        let small = ea.min(eb);
        let large = ea.max(eb);
        Self {
            spacing: small / 150.0,
            reach,
            tolerance: 1e-10 * large,
        }
    }
}
