//! An ellipse or elliptic arc in a placement (STEP's ELLIPSE).

use crate::curves::curve::{Curve, CurvePoint, ParamRange};
use crate::geometry_checks::{checked_range, positive};
use crate::geometry_error::GeometryError;
use crate::surfaces::placement::Placement;
use std::f64::consts::TAU;

/// C(t) = O + a cos t x + b sin t y: a = `semi_major` along the placement's x axis,
/// b = `semi_minor` along its y axis (mm; STEP's semi_axis_1 and semi_axis_2, which STEP does
/// not order, so b > a is accepted), t the eccentric angle (rad).
#[derive(Clone, Debug, PartialEq)]
pub struct EllipseCurve {
    placement: Placement,
    semi_major: f64,
    semi_minor: f64,
    range: ParamRange,
}

impl EllipseCurve {
    /// The ellipse with semi-axes `semi_major` (along x) and `semi_minor` (along y) about
    /// `placement`'s origin, for eccentric angles in `range` (at most one turn).
    ///
    /// # Errors
    /// [`GeometryError::NonPositiveRadius`] for a semi-axis <= 0, [`GeometryError::NonFinite`],
    /// [`GeometryError::EmptyRange`] or [`GeometryError::BadPeriod`].
    pub fn new(
        placement: Placement,
        semi_major: f64,
        semi_minor: f64,
        range: ParamRange,
    ) -> Result<Self, GeometryError> {
        Ok(Self {
            placement,
            semi_major: positive("ellipse semi-major axis", semi_major)?,
            semi_minor: positive("ellipse semi-minor axis", semi_minor)?,
            range: checked_range(range, Some(TAU))?,
        })
    }

    /// The frame: centre O, semi-major axis along x, semi-minor along y.
    #[must_use]
    pub fn placement(&self) -> &Placement {
        &self.placement
    }

    /// a (mm), along x.
    #[must_use]
    pub fn semi_major(&self) -> f64 {
        self.semi_major
    }

    /// b (mm), along y.
    #[must_use]
    pub fn semi_minor(&self) -> f64 {
        self.semi_minor
    }
}

impl Curve for EllipseCurve {
    fn eval(&self, t: f64) -> CurvePoint {
        let p = &self.placement;
        let (sin, cos) = t.sin_cos();
        let offset = self.semi_major * cos * p.x + self.semi_minor * sin * p.y;
        CurvePoint {
            point: p.origin + offset,
            d1: self.semi_minor * cos * p.y - self.semi_major * sin * p.x,
            d2: -offset,
        }
    }

    fn domain(&self) -> ParamRange {
        self.range
    }
}
