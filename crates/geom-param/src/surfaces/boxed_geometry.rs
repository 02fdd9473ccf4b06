//! `Box<dyn Surface>` and `Box<dyn Curve>` are surfaces and curves themselves, so that the
//! decorators ([`crate::ReversedSurface`], [`crate::LinearExtrusionSurface`],
//! [`crate::RevolutionSurface`]) take either a boxed trait object or a concrete type.

use crate::curves::curve::{Curve, CurvePoint, ParamRange};
use crate::surfaces::surface::{PrincipalCurvatures, Surface, SurfacePoint};
use glam::DVec3;

impl<S: Surface + ?Sized> Surface for Box<S> {
    fn eval(&self, u: f64, v: f64) -> SurfacePoint {
        (**self).eval(u, v)
    }

    fn domain(&self) -> [ParamRange; 2] {
        (**self).domain()
    }

    fn normal(&self, u: f64, v: f64) -> Option<DVec3> {
        (**self).normal(u, v)
    }

    fn principal_curvatures(&self, u: f64, v: f64) -> Option<PrincipalCurvatures> {
        (**self).principal_curvatures(u, v)
    }
}

impl<C: Curve + ?Sized> Curve for Box<C> {
    fn eval(&self, t: f64) -> CurvePoint {
        (**self).eval(t)
    }

    fn domain(&self) -> ParamRange {
        (**self).domain()
    }

    fn tangent(&self, t: f64) -> Option<DVec3> {
        (**self).tangent(t)
    }

    fn curvature(&self, t: f64) -> f64 {
        (**self).curvature(t)
    }
}
