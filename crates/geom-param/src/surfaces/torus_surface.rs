//! The ring torus of STEP's TOROIDAL_SURFACE.

use crate::curves::curve::ParamRange;
use crate::geometry_checks::{checked_range, positive};
use crate::geometry_error::GeometryError;
use crate::surfaces::placement::Placement;
use crate::surfaces::surface::{PrincipalCurvatures, Surface, SurfacePoint};
use glam::DVec3;
use std::f64::consts::TAU;

/// S(u, v) = O + (R + r cos v)(cos u x + sin u y) + r sin v z: u the angle about the
/// placement's z axis (rad), v the angle around the tube (rad), R > r > 0 (mm). The outward
/// normal cos v (cos u x + sin u y) + sin v z points away from the tube's centre circle.
#[derive(Clone, Debug, PartialEq)]
pub struct TorusSurface {
    placement: Placement,
    major_radius: f64,
    minor_radius: f64,
    domain: [ParamRange; 2],
}

impl TorusSurface {
    /// The ring torus with major radius `major_radius` and minor radius `minor_radius` (mm)
    /// about `placement`'s z axis over `domain` (both angles, each at most one turn).
    ///
    /// # Errors
    /// [`GeometryError::NonPositiveRadius`], [`GeometryError::NotRingTorus`] when R <= r,
    /// [`GeometryError::NonFinite`], [`GeometryError::EmptyRange`] or
    /// [`GeometryError::BadPeriod`].
    pub fn new(
        placement: Placement,
        major_radius: f64,
        minor_radius: f64,
        domain: [ParamRange; 2],
    ) -> Result<Self, GeometryError> {
        let major = positive("torus major radius", major_radius)?;
        let minor = positive("torus minor radius", minor_radius)?;
        if major <= minor {
            return Err(GeometryError::NotRingTorus { major, minor });
        }
        Ok(Self {
            placement,
            major_radius,
            minor_radius,
            domain: [
                checked_range(domain[0], Some(TAU))?,
                checked_range(domain[1], Some(TAU))?,
            ],
        })
    }

    /// The frame whose z axis is the torus' axis.
    #[must_use]
    pub fn placement(&self) -> &Placement {
        &self.placement
    }

    /// R (mm): the radius of the tube's centre circle.
    #[must_use]
    pub fn major_radius(&self) -> f64 {
        self.major_radius
    }

    /// r (mm): the tube's radius.
    #[must_use]
    pub fn minor_radius(&self) -> f64 {
        self.minor_radius
    }
}

impl Surface for TorusSurface {
    fn eval(&self, u: f64, v: f64) -> SurfacePoint {
        let p = &self.placement;
        let r = self.minor_radius;
        let (sin_u, cos_u) = u.sin_cos();
        let (sin_v, cos_v) = v.sin_cos();
        let radial = cos_u * p.x + sin_u * p.y;
        let tangent = cos_u * p.y - sin_u * p.x;
        let rho = self.major_radius + r * cos_v;
        let tube = cos_v * radial + sin_v * p.z;
        SurfacePoint {
            point: p.origin + self.major_radius * radial + r * tube,
            du: rho * tangent,
            dv: r * (cos_v * p.z - sin_v * radial),
            duu: -rho * radial,
            duv: -r * sin_v * tangent,
            dvv: -r * tube,
        }
    }

    fn domain(&self) -> [ParamRange; 2] {
        self.domain
    }

    /// cos v (cos u x + sin u y) + sin v z.
    fn normal(&self, u: f64, v: f64) -> Option<DVec3> {
        let p = &self.placement;
        let (sin_u, cos_u) = u.sin_cos();
        let (sin_v, cos_v) = v.sin_cos();
        Some(cos_v * (cos_u * p.x + sin_u * p.y) + sin_v * p.z)
    }

    /// 1/r around the tube and cos v / (R + r cos v) around the axis (negative on the inner,
    /// saddle-shaped half).
    fn principal_curvatures(&self, _u: f64, v: f64) -> Option<PrincipalCurvatures> {
        let tube = 1.0 / self.minor_radius;
        let cos_v = v.cos();
        let around = cos_v / (self.major_radius + self.minor_radius * cos_v);
        Some(PrincipalCurvatures {
            min: tube.min(around),
            max: tube.max(around),
        })
    }
}
