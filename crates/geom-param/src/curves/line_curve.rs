//! A straight line (STEP's LINE) over a parameter range.

use crate::curves::curve::{Curve, CurvePoint, ParamRange};
use crate::geometry_checks::{checked_range, finite_vector};
use crate::geometry_error::GeometryError;
use glam::DVec3;

/// C(t) = origin + t direction for t in `range`: the direction is not necessarily unit, so t is
/// in units of its length (as STEP's LINE with a VECTOR of any magnitude).
#[derive(Clone, Debug, PartialEq)]
pub struct LineCurve {
    origin: DVec3,
    direction: DVec3,
    range: ParamRange,
}

impl LineCurve {
    /// The line through `origin` (mm) along `direction` (mm per unit of t) for t in `range`.
    ///
    /// # Errors
    /// [`GeometryError::NonFinite`], [`GeometryError::ZeroDirection`],
    /// [`GeometryError::EmptyRange`] or [`GeometryError::BadPeriod`] (a line never wraps).
    pub fn new(origin: DVec3, direction: DVec3, range: ParamRange) -> Result<Self, GeometryError> {
        finite_vector("line origin", origin)?;
        if finite_vector("line direction", direction)? == DVec3::ZERO {
            return Err(GeometryError::ZeroDirection {
                what: "line direction",
            });
        }
        Ok(Self {
            origin,
            direction,
            range: checked_range(range, None)?,
        })
    }

    /// C(0) (mm).
    #[must_use]
    pub fn origin(&self) -> DVec3 {
        self.origin
    }

    /// dC/dt (mm per unit of t).
    #[must_use]
    pub fn direction(&self) -> DVec3 {
        self.direction
    }
}

impl Curve for LineCurve {
    fn eval(&self, t: f64) -> CurvePoint {
        CurvePoint {
            point: self.origin + t * self.direction,
            d1: self.direction,
            d2: DVec3::ZERO,
        }
    }

    fn domain(&self) -> ParamRange {
        self.range
    }
}
