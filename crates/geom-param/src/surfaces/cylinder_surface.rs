//! The circular cylinder of STEP's CYLINDRICAL_SURFACE.

use crate::curves::curve::ParamRange;
use crate::geometry_checks::{checked_range, positive};
use crate::geometry_error::GeometryError;
use crate::surfaces::placement::Placement;
use crate::surfaces::surface::{PrincipalCurvatures, Surface, SurfacePoint};
use glam::DVec3;
use std::f64::consts::TAU;

/// S(u, v) = O + R (cos u x + sin u y) + v z: u the angle about the placement's z axis (rad),
/// v the height along it (mm). The outward normal cos u x + sin u y points away from the axis
/// (the material is inside; wrap in [`crate::ReversedSurface`] for a hole).
#[derive(Clone, Debug, PartialEq)]
pub struct CylinderSurface {
    placement: Placement,
    radius: f64,
    domain: [ParamRange; 2],
}

impl CylinderSurface {
    /// The cylinder of radius `radius` (mm) about `placement`'s z axis over `domain`
    /// (u: angle, at most one turn, periodic only when exactly one; v: height).
    ///
    /// # Errors
    /// [`GeometryError::NonPositiveRadius`], [`GeometryError::NonFinite`],
    /// [`GeometryError::EmptyRange`] or [`GeometryError::BadPeriod`].
    pub fn new(
        placement: Placement,
        radius: f64,
        domain: [ParamRange; 2],
    ) -> Result<Self, GeometryError> {
        Ok(Self {
            placement,
            radius: positive("cylinder radius", radius)?,
            domain: [
                checked_range(domain[0], Some(TAU))?,
                checked_range(domain[1], None)?,
            ],
        })
    }

    /// The frame whose z axis is the cylinder's axis.
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

impl Surface for CylinderSurface {
    fn eval(&self, u: f64, v: f64) -> SurfacePoint {
        let p = &self.placement;
        let (sin, cos) = u.sin_cos();
        let radial = cos * p.x + sin * p.y;
        let tangent = cos * p.y - sin * p.x;
        SurfacePoint {
            point: p.origin + self.radius * radial + v * p.z,
            du: self.radius * tangent,
            dv: p.z,
            duu: -self.radius * radial,
            duv: DVec3::ZERO,
            dvv: DVec3::ZERO,
        }
    }

    fn domain(&self) -> [ParamRange; 2] {
        self.domain
    }

    /// cos u x + sin u y.
    fn normal(&self, u: f64, _v: f64) -> Option<DVec3> {
        let (sin, cos) = u.sin_cos();
        Some(cos * self.placement.x + sin * self.placement.y)
    }

    /// 0 along the rulings, 1/R around.
    fn principal_curvatures(&self, _u: f64, _v: f64) -> Option<PrincipalCurvatures> {
        Some(PrincipalCurvatures {
            min: 0.0,
            max: 1.0 / self.radius,
        })
    }
}
