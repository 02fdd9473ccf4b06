//! A curve swept along a fixed vector (STEP's SURFACE_OF_LINEAR_EXTRUSION).

use crate::curves::curve::{Curve, ParamRange};
use crate::geometry_checks::{checked_range, finite_vector};
use crate::geometry_error::GeometryError;
use crate::surfaces::surface::{Surface, SurfacePoint};
use glam::DVec3;

/// S(u, v) = C(u) + v d: u the curve's own parameter (its domain is the u domain), v the
/// multiple of the extrusion vector d (d in mm per unit of v, not necessarily unit, so v = 1
/// is one full extrusion vector as in STEP's `extrusion_axis` magnitude).
///
/// Derivatives: S_u = C'(u), S_v = d, S_uu = C''(u), S_uv = S_vv = 0. The outward normal is
/// C'(u) × d normalised: orient the curve so the material is on the other side, or wrap in
/// [`crate::ReversedSurface`]. It does not exist where C' is zero or parallel to d (a cusp or
/// fold of the surface), and the default [`Surface::normal`] then returns `None`.
#[derive(Clone, Debug, PartialEq)]
pub struct LinearExtrusionSurface<C: Curve = Box<dyn Curve>> {
    curve: C,
    direction: DVec3,
    v_range: ParamRange,
}

impl<C: Curve> LinearExtrusionSurface<C> {
    /// The extrusion of `curve` along `direction` (mm per unit of v) for v in `v_range`.
    ///
    /// # Errors
    /// [`GeometryError::NonFinite`] or [`GeometryError::ZeroDirection`] for a bad direction,
    /// [`GeometryError::EmptyRange`] or [`GeometryError::BadPeriod`] for a bad `v_range`.
    pub fn new(curve: C, direction: DVec3, v_range: ParamRange) -> Result<Self, GeometryError> {
        if finite_vector("extrusion direction", direction)? == DVec3::ZERO {
            return Err(GeometryError::ZeroDirection {
                what: "extrusion direction",
            });
        }
        Ok(Self {
            curve,
            direction,
            v_range: checked_range(v_range, None)?,
        })
    }

    /// The swept curve C.
    pub fn curve(&self) -> &C {
        &self.curve
    }

    /// d (mm per unit of v).
    #[must_use]
    pub fn direction(&self) -> DVec3 {
        self.direction
    }
}

impl<C: Curve> Surface for LinearExtrusionSurface<C> {
    fn eval(&self, u: f64, v: f64) -> SurfacePoint {
        let c = self.curve.eval(u);
        SurfacePoint {
            point: c.point + v * self.direction,
            du: c.d1,
            dv: self.direction,
            duu: c.d2,
            duv: DVec3::ZERO,
            dvv: DVec3::ZERO,
        }
    }

    fn domain(&self) -> [ParamRange; 2] {
        [self.curve.domain(), self.v_range]
    }
}
