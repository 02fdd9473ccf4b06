//! A circle or circular arc in a placement (STEP's CIRCLE).

use crate::curves::curve::{Curve, CurvePoint, ParamRange};
use crate::geometry_checks::{checked_range, positive};
use crate::geometry_error::GeometryError;
use crate::surfaces::placement::Placement;
use std::f64::consts::TAU;

/// C(t) = O + R (cos t x + sin t y): t the angle (rad) from the placement's x axis, turning
/// right-handed about its z axis; R in mm. Periodic when `range` is flagged so, which it may be
/// only when it spans a full turn.
#[derive(Clone, Debug, PartialEq)]
pub struct CircleCurve {
    placement: Placement,
    radius: f64,
    range: ParamRange,
}

impl CircleCurve {
    /// The circle of radius `radius` (mm) about `placement`'s origin in its xy plane, for
    /// angles in `range` (at most one turn).
    ///
    /// # Errors
    /// [`GeometryError::NonPositiveRadius`], [`GeometryError::NonFinite`],
    /// [`GeometryError::EmptyRange`] or [`GeometryError::BadPeriod`].
    pub fn new(
        placement: Placement,
        radius: f64,
        range: ParamRange,
    ) -> Result<Self, GeometryError> {
        Ok(Self {
            placement,
            radius: positive("circle radius", radius)?,
            range: checked_range(range, Some(TAU))?,
        })
    }

    /// The frame: centre O, the circle's plane spanned by x and y.
    #[must_use]
    pub fn placement(&self) -> &Placement {
        &self.placement
    }

    /// R (mm).
    #[must_use]
    pub fn radius(&self) -> f64 {
        self.radius
    }
}

impl Curve for CircleCurve {
    fn eval(&self, t: f64) -> CurvePoint {
        let p = &self.placement;
        let (sin, cos) = t.sin_cos();
        let radial = self.radius * (cos * p.x + sin * p.y);
        CurvePoint {
            point: p.origin + radial,
            d1: self.radius * (cos * p.y - sin * p.x),
            d2: -radial,
        }
    }

    fn domain(&self) -> ParamRange {
        self.range
    }
}
