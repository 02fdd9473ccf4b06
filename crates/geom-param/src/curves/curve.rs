//! Parametric curves: the geometry of edges.

use glam::DVec3;

/// Position and derivatives of a curve at one parameter value, in the object frame (mm).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CurvePoint {
    /// C(t).
    pub point: DVec3,
    /// dC/dt.
    pub d1: DVec3,
    /// d²C/dt².
    pub d2: DVec3,
}

/// A closed interval of one parameter, possibly periodic.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ParamRange {
    /// Smallest parameter value.
    pub min: f64,
    /// Largest parameter value.
    pub max: f64,
    /// When true, `min` and `max` are the same point and the parameter wraps.
    pub periodic: bool,
}

impl ParamRange {
    /// Brings `t` into the range: wraps a periodic parameter into `[min, max)`, clamps otherwise.
    #[must_use]
    pub fn normalize(&self, t: f64) -> f64 {
        if self.periodic {
            let period = self.max - self.min;
            let wrapped = (t - self.min).rem_euclid(period) + self.min;
            // rem_euclid can round up to exactly `max` for tiny negative inputs.
            if wrapped >= self.max {
                self.min
            } else {
                wrapped
            }
        } else {
            t.clamp(self.min, self.max)
        }
    }

    /// Length of the range.
    #[must_use]
    pub fn span(&self) -> f64 {
        self.max - self.min
    }
}

/// A twice-differentiable parametric curve C(t) in the object frame.
///
/// Implementors supply [`Curve::eval`] and [`Curve::domain`]; tangent and curvature follow.
pub trait Curve: Send + Sync + std::fmt::Debug {
    /// Point, first and second derivative at `t` (which must lie in [`Curve::domain`]).
    fn eval(&self, t: f64) -> CurvePoint;

    /// The parameter domain.
    fn domain(&self) -> ParamRange;

    /// Unit tangent dC/dt / |dC/dt|, or `None` where the curve is singular (|dC/dt| = 0).
    fn tangent(&self, t: f64) -> Option<DVec3> {
        self.eval(t).d1.try_normalize()
    }

    /// Curvature |C' x C''| / |C'|³ (1/mm); 0 where the curve is singular.
    fn curvature(&self, t: f64) -> f64 {
        let c = self.eval(t);
        let speed = c.d1.length();
        if speed == 0.0 {
            return 0.0;
        }
        c.d1.cross(c.d2).length() / (speed * speed * speed)
    }
}
