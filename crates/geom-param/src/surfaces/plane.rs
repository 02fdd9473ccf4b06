//! The plane of STEP's PLANE, parametrised by its placement's x and y axes.

use crate::curves::curve::ParamRange;
use crate::geometry_checks::checked_range;
use crate::geometry_error::GeometryError;
use crate::surfaces::placement::Placement;
use crate::surfaces::surface::{PrincipalCurvatures, Surface, SurfacePoint};
use glam::DVec3;

/// S(u, v) = O + u x + v y (u, v in mm), outward normal z = x × y (the material lies on the −z
/// side).
#[derive(Clone, Debug, PartialEq)]
pub struct Plane {
    placement: Placement,
    domain: [ParamRange; 2],
}

impl Plane {
    /// The plane of `placement` restricted to `domain` (u then v, mm).
    ///
    /// # Errors
    /// [`GeometryError::NonFinite`] or [`GeometryError::EmptyRange`] for a bad range,
    /// [`GeometryError::BadPeriod`] if a range is flagged periodic.
    pub fn new(placement: Placement, domain: [ParamRange; 2]) -> Result<Self, GeometryError> {
        Ok(Self {
            placement,
            domain: [
                checked_range(domain[0], None)?,
                checked_range(domain[1], None)?,
            ],
        })
    }

    /// The frame: origin O, axes x, y, and the outward normal z.
    #[must_use]
    pub fn placement(&self) -> &Placement {
        &self.placement
    }
}

impl Surface for Plane {
    fn eval(&self, u: f64, v: f64) -> SurfacePoint {
        let p = &self.placement;
        SurfacePoint {
            point: p.origin + u * p.x + v * p.y,
            du: p.x,
            dv: p.y,
            duu: DVec3::ZERO,
            duv: DVec3::ZERO,
            dvv: DVec3::ZERO,
        }
    }

    fn domain(&self) -> [ParamRange; 2] {
        self.domain
    }

    /// z, exactly.
    fn normal(&self, _u: f64, _v: f64) -> Option<DVec3> {
        Some(self.placement.z)
    }

    /// Both 0.
    fn principal_curvatures(&self, _u: f64, _v: f64) -> Option<PrincipalCurvatures> {
        Some(PrincipalCurvatures { min: 0.0, max: 0.0 })
    }
}
