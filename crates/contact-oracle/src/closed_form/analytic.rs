//! The few analytic surfaces and curves the closed-form B-rep scenes need (plane, cylinder,
//! straight line, and ellipse p-curves), kept here until geom-param has its own.

use geom_param::{Curve, Curve2, Curve2Point, CurvePoint, ParamRange, Surface, SurfacePoint};
use glam::{DVec2, DVec3};

/// S(u, v) = origin + u x + v y over `domain`; x and y orthonormal, so the outward normal
/// (∂S/∂u × ∂S/∂v) is x × y.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct PlaneSurface {
    pub origin: DVec3,
    pub x: DVec3,
    pub y: DVec3,
    pub domain: [ParamRange; 2],
}

impl PlaneSurface {
    /// The (u, v) of a point of the plane.
    pub fn params_of(&self, p: DVec3) -> DVec2 {
        let d = p - self.origin;
        DVec2::new(d.dot(self.x), d.dot(self.y))
    }
}

impl Surface for PlaneSurface {
    fn eval(&self, u: f64, v: f64) -> SurfacePoint {
        SurfacePoint {
            point: self.origin + u * self.x + v * self.y,
            du: self.x,
            dv: self.y,
            duu: DVec3::ZERO,
            duv: DVec3::ZERO,
            dvv: DVec3::ZERO,
        }
    }

    fn domain(&self) -> [ParamRange; 2] {
        self.domain
    }
}

/// S(u, v) = origin + radius (cos u x + sin u y) + v z, u in [0, 2π) periodic, v in `height`;
/// x, y, z orthonormal. The outward normal ∂S/∂u × ∂S/∂v points away from the axis when
/// (x, y, z) is right-handed and towards it (a hole's wall) when left-handed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct CylinderSurface {
    pub origin: DVec3,
    pub x: DVec3,
    pub y: DVec3,
    pub z: DVec3,
    pub radius: f64,
    pub height: ParamRange,
}

impl Surface for CylinderSurface {
    fn eval(&self, u: f64, v: f64) -> SurfacePoint {
        let (sin, cos) = u.sin_cos();
        let radial = cos * self.x + sin * self.y;
        let tangent = -sin * self.x + cos * self.y;
        SurfacePoint {
            point: self.origin + self.radius * radial + v * self.z,
            du: self.radius * tangent,
            dv: self.z,
            duu: -self.radius * radial,
            duv: DVec3::ZERO,
            dvv: DVec3::ZERO,
        }
    }

    fn domain(&self) -> [ParamRange; 2] {
        [
            ParamRange {
                min: 0.0,
                max: std::f64::consts::TAU,
                periodic: true,
            },
            self.height,
        ]
    }
}

/// C(t) = origin + t direction for t in `range`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct LineCurve {
    pub origin: DVec3,
    pub direction: DVec3,
    pub range: ParamRange,
}

impl Curve for LineCurve {
    fn eval(&self, t: f64) -> CurvePoint {
        CurvePoint {
            point: self.origin + t * self.direction,
            d1: self.direction,
            d2: DVec3::ZERO,
        }
    }

    fn domain(&self) -> ParamRange {
        self.range
    }
}

/// c(t) = centre + a cos t + b sin t, t in [0, 2π) periodic: the p-curve of a circle on a
/// plane (a and b are the circle's x and y axes times its radius, in the plane's (u, v)).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct EllipseCurve2 {
    pub centre: DVec2,
    pub a: DVec2,
    pub b: DVec2,
}

impl Curve2 for EllipseCurve2 {
    fn eval(&self, t: f64) -> Curve2Point {
        let (sin, cos) = t.sin_cos();
        Curve2Point {
            point: self.centre + cos * self.a + sin * self.b,
            d1: -sin * self.a + cos * self.b,
            d2: -cos * self.a - sin * self.b,
        }
    }

    fn domain(&self) -> ParamRange {
        ParamRange {
            min: 0.0,
            max: std::f64::consts::TAU,
            periodic: true,
        }
    }
}
