//! The circular cone of STEP's CONICAL_SURFACE.

use crate::curves::curve::ParamRange;
use crate::geometry_checks::{checked_range, finite, range_within};
use crate::geometry_error::GeometryError;
use crate::surfaces::placement::Placement;
use crate::surfaces::surface::{PrincipalCurvatures, Surface, SurfacePoint};
use glam::DVec3;
use std::f64::consts::{FRAC_PI_2, TAU};

/// Relative size below which the distance to the axis counts as zero (the apex).
const APEX_RELATIVE_EPS: f64 = 1e-12;

/// S(u, v) = O + (R + v sin a)(cos u x + sin u y) + v cos a z: u the angle about the
/// placement's z axis (rad), v the distance along a ruling from the circle of radius R in the
/// placement's plane (mm), a the semi-angle (rad). The apex is at v = −R / sin a. The outward
/// normal cos a (cos u x + sin u y) − sin a z points away from the axis (the material is
/// inside).
#[derive(Clone, Debug, PartialEq)]
pub struct ConeSurface {
    placement: Placement,
    radius: f64,
    semi_angle: f64,
    domain: [ParamRange; 2],
}

impl ConeSurface {
    /// The cone with radius `radius` (mm, >= 0) at v = 0 and semi-angle `semi_angle` (rad, in
    /// (0, π/2)) about `placement`'s z axis, over `domain` (u: angle, at most one turn; v:
    /// not below the apex).
    ///
    /// # Errors
    /// [`GeometryError::NegativeRadius`], [`GeometryError::BadSemiAngle`],
    /// [`GeometryError::NonFinite`], [`GeometryError::EmptyRange`],
    /// [`GeometryError::BadPeriod`], or [`GeometryError::RangeOutsideSurface`] when v passes
    /// the apex.
    pub fn new(
        placement: Placement,
        radius: f64,
        semi_angle: f64,
        domain: [ParamRange; 2],
    ) -> Result<Self, GeometryError> {
        if finite("cone radius", radius)? < 0.0 {
            return Err(GeometryError::NegativeRadius { radius });
        }
        let angle = finite("cone semi-angle", semi_angle)?;
        if angle <= 0.0 || angle >= FRAC_PI_2 {
            return Err(GeometryError::BadSemiAngle { angle });
        }
        let apex = -radius / angle.sin();
        Ok(Self {
            placement,
            radius,
            semi_angle,
            domain: [
                checked_range(domain[0], Some(TAU))?,
                range_within(checked_range(domain[1], None)?, apex, f64::INFINITY)?,
            ],
        })
    }

    /// The frame whose z axis is the cone's axis.
    #[must_use]
    pub fn placement(&self) -> &Placement {
        &self.placement
    }

    /// R (mm): the radius at v = 0.
    #[must_use]
    pub fn radius(&self) -> f64 {
        self.radius
    }

    /// a (rad).
    #[must_use]
    pub fn semi_angle(&self) -> f64 {
        self.semi_angle
    }

    /// Distance R + v sin a from the axis, or `None` at the apex.
    fn axis_distance(&self, v: f64) -> Option<f64> {
        let sin_a = self.semi_angle.sin();
        let rho = self.radius + v * sin_a;
        (rho.abs() > APEX_RELATIVE_EPS * (self.radius + v.abs() * sin_a)).then_some(rho)
    }
}

impl Surface for ConeSurface {
    fn eval(&self, u: f64, v: f64) -> SurfacePoint {
        let p = &self.placement;
        let (sin_a, cos_a) = self.semi_angle.sin_cos();
        let (sin, cos) = u.sin_cos();
        let radial = cos * p.x + sin * p.y;
        let tangent = cos * p.y - sin * p.x;
        let rho = self.radius + v * sin_a;
        SurfacePoint {
            point: p.origin + rho * radial + v * cos_a * p.z,
            du: rho * tangent,
            dv: sin_a * radial + cos_a * p.z,
            duu: -rho * radial,
            duv: sin_a * tangent,
            dvv: DVec3::ZERO,
        }
    }

    fn domain(&self) -> [ParamRange; 2] {
        self.domain
    }

    /// cos a (cos u x + sin u y) − sin a z; `None` at the apex.
    fn normal(&self, u: f64, v: f64) -> Option<DVec3> {
        self.axis_distance(v)?;
        let (sin_a, cos_a) = self.semi_angle.sin_cos();
        let (sin, cos) = u.sin_cos();
        Some(cos_a * (cos * self.placement.x + sin * self.placement.y) - sin_a * self.placement.z)
    }

    /// 0 along the rulings, cos a / (R + v sin a) around; `None` at the apex.
    fn principal_curvatures(&self, _u: f64, v: f64) -> Option<PrincipalCurvatures> {
        let around = self.semi_angle.cos() / self.axis_distance(v)?;
        Some(PrincipalCurvatures {
            min: around.min(0.0),
            max: around.max(0.0),
        })
    }
}
