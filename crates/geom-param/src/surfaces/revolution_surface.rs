//! A curve revolved about an axis (STEP's SURFACE_OF_REVOLUTION).

use crate::curves::curve::{Curve, ParamRange};
use crate::geometry_checks::{checked_range, finite_vector, unit_direction};
use crate::geometry_error::GeometryError;
use crate::surfaces::surface::{Surface, SurfacePoint};
use glam::DVec3;
use std::f64::consts::TAU;

/// Relative size below which a point counts as on the axis, and a tangent as perpendicular to
/// it (a pole).
const AXIS_RELATIVE_EPS: f64 = 1e-12;
/// Relative size of the axial tangent component below which an on-axis point is a pole.
const POLE_RELATIVE_EPS: f64 = 1e-9;

/// S(u, v) = A + R_k(u) (C(v) − A): the curve C rotated by the angle u (rad, right-handed about
/// the unit axis k through A) — u the angle, v the curve's own parameter, as in STEP.
///
/// With w = C(v) − A and R_k(u) w = w cos u + (k × w) sin u + k (k · w)(1 − cos u)
/// (Rodrigues), r = S − A:
/// S_u = k × r, S_uu = k × (k × r), S_v = R_k(u) C'(v), S_uv = k × S_v,
/// S_vv = R_k(u) C''(v).
///
/// The outward normal is S_u × S_v normalised: with k = z and C in the half-plane through +x,
/// that is the convention of [`crate::RevolvedSurface`] (the curve runs counter-clockwise
/// around the material in the (r, z) half-plane). Where C touches the axis the cross product
/// vanishes: at a pole (C' perpendicular to k) at the start of C's domain the normal is −k, at
/// its end +k; elsewhere on the axis (a cone tip, or C crossing the axis inside its domain)
/// there is no tangent plane and [`Surface::normal`] is `None`.
#[derive(Clone, Debug, PartialEq)]
pub struct RevolutionSurface<C: Curve = Box<dyn Curve>> {
    curve: C,
    axis_point: DVec3,
    axis: DVec3,
    u_range: ParamRange,
}

impl<C: Curve> RevolutionSurface<C> {
    /// `curve` revolved about the line through `axis_point` (mm) along `axis` (normalised)
    /// over the angles `u_range` (at most one turn, periodic only when exactly one).
    ///
    /// # Errors
    /// [`GeometryError::NonFinite`], [`GeometryError::ZeroDirection`] for a zero axis,
    /// [`GeometryError::EmptyRange`] or [`GeometryError::BadPeriod`].
    pub fn new(
        curve: C,
        axis_point: DVec3,
        axis: DVec3,
        u_range: ParamRange,
    ) -> Result<Self, GeometryError> {
        Ok(Self {
            curve,
            axis_point: finite_vector("axis point", axis_point)?,
            axis: unit_direction("axis of revolution", axis)?,
            u_range: checked_range(u_range, Some(TAU))?,
        })
    }

    /// The revolved curve C.
    pub fn curve(&self) -> &C {
        &self.curve
    }

    /// A point A of the axis (mm).
    #[must_use]
    pub fn axis_point(&self) -> DVec3 {
        self.axis_point
    }

    /// The unit axis direction k.
    #[must_use]
    pub fn axis(&self) -> DVec3 {
        self.axis
    }

    /// R_k(u) x.
    fn rotate(&self, x: DVec3, sin: f64, cos: f64) -> DVec3 {
        let k = self.axis;
        x * cos + k.cross(x) * sin + k * (k.dot(x) * (1.0 - cos))
    }
}

impl<C: Curve> Surface for RevolutionSurface<C> {
    fn eval(&self, u: f64, v: f64) -> SurfacePoint {
        let k = self.axis;
        let c = self.curve.eval(v);
        let (sin, cos) = u.sin_cos();
        let r = self.rotate(c.point - self.axis_point, sin, cos);
        let du = k.cross(r);
        let dv = self.rotate(c.d1, sin, cos);
        SurfacePoint {
            point: self.axis_point + r,
            du,
            dv,
            duu: k.cross(du),
            duv: k.cross(dv),
            dvv: self.rotate(c.d2, sin, cos),
        }
    }

    fn domain(&self) -> [ParamRange; 2] {
        [self.u_range, self.curve.domain()]
    }

    fn normal(&self, u: f64, v: f64) -> Option<DVec3> {
        let k = self.axis;
        let c = self.curve.eval(v);
        let w = c.point - self.axis_point;
        let off_axis = w - k * k.dot(w);
        if off_axis.length() > AXIS_RELATIVE_EPS * w.length() {
            return self.eval(u, v).cross_normal();
        }
        // On the axis: S_u × S_v ∝ (v − v0) (C'⊥ (k · C') − k |C'⊥|²) nearby, with C'⊥ the
        // part of C' across the axis; at a pole (k · C' = 0) its limit is −k on the side
        // v > v0, +k on the side v < v0.
        let speed = c.d1.length();
        if speed.is_nan() || speed <= 0.0 || k.dot(c.d1).abs() > POLE_RELATIVE_EPS * speed {
            return None;
        }
        let domain = self.curve.domain();
        let end_slack = POLE_RELATIVE_EPS * domain.span();
        if v - domain.min <= end_slack {
            Some(-k)
        } else if domain.max - v <= end_slack {
            Some(k)
        } else {
            None
        }
    }
}
