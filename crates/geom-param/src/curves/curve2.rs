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

    /// The parameter in [`Curve2::domain`] of the curve's point nearest to `uv`, for a curve
    /// that has it in closed form (a line, a circle); `None`, the default, for the others,
    /// whose nearest points [`crate::Trim`] finds on their polylines and polishes by Newton's
    /// method.
    fn nearest_param(&self, _uv: DVec2) -> Option<f64> {
        None
    }
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

    /// The projection of `uv` onto the line, clamped to the domain (the domain's start for a
    /// line of no direction, whose points all coincide).
    fn nearest_param(&self, uv: DVec2) -> Option<f64> {
        let length_squared = self.direction.length_squared();
        let t = if length_squared > 0.0 {
            (uv - self.origin).dot(self.direction) / length_squared
        } else {
            self.range.min
        };
        Some(t.clamp(self.range.min, self.range.max))
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

    /// The parameter of the angle of `uv` about the centre, φ = phase + sense · t taken at the
    /// first t >= t_min; where that lies beyond the arc (t > t_max), the nearer of the arc's
    /// ends, as the distance grows with the angle from `uv`'s either way round. The centre
    /// itself is equally near every point: the domain's start.
    fn nearest_param(&self, uv: DVec2) -> Option<f64> {
        let d = uv - self.center;
        let range = self.range;
        if d == DVec2::ZERO {
            return Some(range.min);
        }
        let t = (d.y.atan2(d.x) - self.phase) / self.sense;
        let t = range.min + (t - range.min).rem_euclid(std::f64::consts::TAU);
        if t <= range.max {
            return Some(t);
        }
        let from_uv = |t: f64| self.eval(t).point.distance_squared(uv);
        Some(if from_uv(range.min) <= from_uv(range.max) {
            range.min
        } else {
            range.max
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The distance from `uv` to the curve by dense sampling of its domain (truth the closed
    /// forms did not produce).
    fn sampled_distance(curve: &dyn Curve2, uv: DVec2) -> f64 {
        let range = curve.domain();
        (0..=20_000)
            .map(|k| curve.eval(range.min + range.span() * f64::from(k) / 20_000.0))
            .map(|c| c.point.distance(uv))
            .fold(f64::INFINITY, f64::min)
    }

    /// Points on a grid around the curves, the centre and the arcs' ends among them.
    fn queries() -> Vec<DVec2> {
        let mut out = vec![
            DVec2::new(1.0, -2.0),
            DVec2::new(1.0, -2.0) + DVec2::X * 3.0,
        ];
        for i in -8..=8 {
            for j in -8..=8 {
                out.push(DVec2::new(
                    f64::from(i) * 0.77 + 0.1,
                    f64::from(j) * 0.61 - 2.0,
                ));
            }
        }
        out
    }

    fn range(min: f64, max: f64, periodic: bool) -> ParamRange {
        ParamRange { min, max, periodic }
    }

    #[test]
    fn closed_form_nearest_points_match_dense_sampling() {
        let arcs = [
            (0.3, 1.0, range(-1.0, 2.5, false)),
            (2.0, -1.0, range(0.5, 4.0, false)),
            (-0.7, 1.0, range(0.0, std::f64::consts::TAU, true)),
            (5.0, -1.0, range(-7.0, -7.0 + std::f64::consts::TAU, true)),
        ];
        let mut curves: Vec<Box<dyn Curve2>> = arcs
            .iter()
            .map(|&(phase, sense, range)| {
                Box::new(Circle2 {
                    center: DVec2::new(1.0, -2.0),
                    radius: 3.0,
                    phase,
                    sense,
                    range,
                }) as Box<dyn Curve2>
            })
            .collect();
        curves.push(Box::new(Line2 {
            origin: DVec2::new(-1.0, 0.5),
            direction: DVec2::new(0.8, -0.3),
            range: range(-2.0, 3.0, false),
        }));
        for curve in &curves {
            let domain = curve.domain();
            for uv in queries() {
                let t = curve.nearest_param(uv).expect("closed form");
                assert!(t >= domain.min && t <= domain.max, "{t} outside {domain:?}");
                let distance = curve.eval(t).point.distance(uv);
                let sampled = sampled_distance(curve.as_ref(), uv);
                // The samples lie 1/20000 of the domain apart: within 3e-4 of the curve's points.
                assert!(
                    distance <= sampled + 1e-12,
                    "{curve:?} at {uv}: {distance} > {sampled}"
                );
                assert!(
                    distance >= sampled - 3e-4,
                    "{curve:?} at {uv}: {distance} < {sampled}"
                );
            }
        }
    }
}
