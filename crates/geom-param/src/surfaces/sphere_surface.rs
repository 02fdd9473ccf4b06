//! The sphere of STEP's SPHERICAL_SURFACE.

use crate::curves::curve::ParamRange;
use crate::geometry_checks::{checked_range, positive, range_within};
use crate::geometry_error::GeometryError;
use crate::surfaces::placement::Placement;
use crate::surfaces::surface::{PrincipalCurvatures, Surface, SurfacePoint};
use glam::DVec3;
use std::f64::consts::{FRAC_PI_2, TAU};

/// S(u, v) = O + R cos v (cos u x + sin u y) + R sin v z: u the longitude about the
/// placement's z axis (rad), v the latitude in [−π/2, π/2] (rad). The outward normal
/// (S − O) / R points away from the centre, and is ±z at the poles v = ±π/2 where ∂S/∂u = 0.
#[derive(Clone, Debug, PartialEq)]
pub struct SphereSurface {
    placement: Placement,
    radius: f64,
    domain: [ParamRange; 2],
}

impl SphereSurface {
    /// The sphere of radius `radius` (mm) centred on `placement`'s origin over `domain`
    /// (u: longitude, at most one turn; v: latitude inside [−π/2, π/2], never periodic).
    ///
    /// # Errors
    /// [`GeometryError::NonPositiveRadius`], [`GeometryError::NonFinite`],
    /// [`GeometryError::EmptyRange`], [`GeometryError::BadPeriod`], or
    /// [`GeometryError::RangeOutsideSurface`] for a latitude beyond ±π/2.
    pub fn new(
        placement: Placement,
        radius: f64,
        domain: [ParamRange; 2],
    ) -> Result<Self, GeometryError> {
        Ok(Self {
            placement,
            radius: positive("sphere radius", radius)?,
            domain: [
                checked_range(domain[0], Some(TAU))?,
                range_within(checked_range(domain[1], None)?, -FRAC_PI_2, FRAC_PI_2)?,
            ],
        })
    }

    /// The frame at the centre; z points to the pole v = π/2.
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

impl Surface for SphereSurface {
    fn eval(&self, u: f64, v: f64) -> SurfacePoint {
        let p = &self.placement;
        let r = self.radius;
        let (sin_u, cos_u) = u.sin_cos();
        let (sin_v, cos_v) = v.sin_cos();
        let radial = cos_u * p.x + sin_u * p.y;
        let tangent = cos_u * p.y - sin_u * p.x;
        let outward = cos_v * radial + sin_v * p.z;
        SurfacePoint {
            point: p.origin + r * outward,
            du: r * cos_v * tangent,
            dv: r * (cos_v * p.z - sin_v * radial),
            duu: -r * cos_v * radial,
            duv: -r * sin_v * tangent,
            dvv: -r * outward,
        }
    }

    fn domain(&self) -> [ParamRange; 2] {
        self.domain
    }

    /// cos v (cos u x + sin u y) + sin v z, defined at the poles too.
    fn normal(&self, u: f64, v: f64) -> Option<DVec3> {
        let p = &self.placement;
        let (sin_u, cos_u) = u.sin_cos();
        let (sin_v, cos_v) = v.sin_cos();
        Some(cos_v * (cos_u * p.x + sin_u * p.y) + sin_v * p.z)
    }

    /// Both 1/R, at the poles too.
    fn principal_curvatures(&self, _u: f64, _v: f64) -> Option<PrincipalCurvatures> {
        let k = 1.0 / self.radius;
        Some(PrincipalCurvatures { min: k, max: k })
    }
}
