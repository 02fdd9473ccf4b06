//! Curves in a face's parameter plane (p-curves): where an edge runs on each of its faces.

use crate::curves::curve::ParamRange;
use glam::DVec2;

/// Position and derivatives of a parameter-plane curve at one parameter value, in the (u, v)
/// coordinates of the face it lies on.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Curve2Point {
    /// c(t) = (u(t), v(t)).
    pub point: DVec2,
    /// dc/dt.
    pub d1: DVec2,
    /// d²c/dt².
    pub d2: DVec2,
}

/// A twice-differentiable curve c(t) in a face's (u, v) parameter plane.
///
/// The parameter t is the edge's own parameter: the point of the edge at t is the face's
/// surface at c(t), within the model tolerance.
pub trait Curve2: Send + Sync + std::fmt::Debug {
    /// Point, first and second derivative at `t` (which must lie in [`Curve2::domain`]).
    fn eval(&self, t: f64) -> Curve2Point;

    /// The parameter domain.
    fn domain(&self) -> ParamRange;
}

/// The straight p-curve c(t) = origin + t · direction, for t in `range`: a side of a parameter
/// rectangle, or any edge whose parameter maps affinely onto the face's.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Line2 {
    /// c(0).
    pub origin: DVec2,
    /// dc/dt (parameter units per unit of t).
    pub direction: DVec2,
    /// The domain of t.
    pub range: ParamRange,
}

impl Curve2 for Line2 {
    fn eval(&self, t: f64) -> Curve2Point {
        Curve2Point {
            point: self.origin + t * self.direction,
            d1: self.direction,
            d2: DVec2::ZERO,
        }
    }

    fn domain(&self) -> ParamRange {
        self.range
    }
}

/// The circular p-curve c(t) = centre + radius (cos φ, sin φ) with φ = phase + sense · t: a
/// circular edge on a plane whose (u, v) are lengths, with the edge's angle as t. `sense` is +1
/// when the circle runs counter-clockwise in (u, v) as t grows, −1 when clockwise.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Circle2 {
    /// Centre in (u, v).
    pub center: DVec2,
    /// Radius in parameter units (> 0).
    pub radius: f64,
    /// The angle φ at t = 0 (rad, from the u axis towards the v axis).
    pub phase: f64,
    /// +1 or −1.
    pub sense: f64,
    /// The domain of t.
    pub range: ParamRange,
}

impl Curve2 for Circle2 {
    fn eval(&self, t: f64) -> Curve2Point {
        let (sin, cos) = (self.phase + self.sense * t).sin_cos();
        let (r, s) = (self.radius, self.sense);
        Curve2Point {
            point: self.center + r * DVec2::new(cos, sin),
            d1: r * s * DVec2::new(-sin, cos),
            d2: -r * DVec2::new(cos, sin),
        }
    }

    fn domain(&self) -> ParamRange {
        self.range
    }
}
