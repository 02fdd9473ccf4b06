//! Parametric surfaces: the geometry of faces.
//!
//! Sign convention used throughout the library: normals point out of the material, and a
//! principal curvature is **positive where the surface is convex seen from outside** (it bends
//! away from its outward normal, like a sphere), negative where it is concave (like the inside of
//! a bowl). With the first and second fundamental forms I = [[E, F], [F, G]] and
//! II = [[L, M], [M, N]] (L = S_uu · n, ...), the principal curvatures are the eigenvalues of
//! -I⁻¹ II.

use crate::curves::curve::ParamRange;
use glam::DVec3;

/// Position and partial derivatives of a surface at one (u, v), in the object frame (mm).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfacePoint {
    /// S(u, v).
    pub point: DVec3,
    /// ∂S/∂u.
    pub du: DVec3,
    /// ∂S/∂v.
    pub dv: DVec3,
    /// ∂²S/∂u².
    pub duu: DVec3,
    /// ∂²S/∂u∂v.
    pub duv: DVec3,
    /// ∂²S/∂v².
    pub dvv: DVec3,
}

/// The two principal curvatures (1/mm), `min <= max`, positive where convex seen from outside.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PrincipalCurvatures {
    /// The smaller principal curvature.
    pub min: f64,
    /// The larger principal curvature.
    pub max: f64,
}

impl SurfacePoint {
    /// Unit outward normal (∂S/∂u × ∂S/∂v normalised), or `None` where the parametrisation is
    /// singular. Parametrisations are oriented so that this cross product points outwards.
    #[must_use]
    pub fn cross_normal(&self) -> Option<DVec3> {
        self.du.cross(self.dv).try_normalize()
    }

    /// Principal curvatures from the fundamental forms with respect to the unit outward normal
    /// `n`, or `None` where the first fundamental form is singular (EG - F² = 0).
    #[must_use]
    pub fn principal_curvatures_with(&self, n: DVec3) -> Option<PrincipalCurvatures> {
        let (e, f, g) = (
            self.du.dot(self.du),
            self.du.dot(self.dv),
            self.dv.dot(self.dv),
        );
        let (l, m, nn) = (self.duu.dot(n), self.duv.dot(n), self.dvv.dot(n));
        let det = e * g - f * f;
        // Also rejects NaN derivatives: every comparison with NaN is false.
        let regular = det > f64::EPSILON * e * g;
        if !regular {
            return None;
        }
        // Mean and Gauss curvature of -I⁻¹ II.
        let mean = -(e * nn - 2.0 * f * m + g * l) / (2.0 * det);
        let gauss = (l * nn - m * m) / det;
        let disc = (mean * mean - gauss).max(0.0).sqrt();
        Some(PrincipalCurvatures {
            min: mean - disc,
            max: mean + disc,
        })
    }
}

/// A twice-differentiable parametric surface S(u, v) in the object frame.
///
/// Implementors supply [`Surface::eval`] and [`Surface::domain`]; normal and curvatures have
/// default implementations from the derivatives, which a surface overrides where its
/// parametrisation degenerates (a pole of a surface of revolution, for instance).
pub trait Surface: Send + Sync + std::fmt::Debug {
    /// Point and first and second partial derivatives at (u, v) inside [`Surface::domain`].
    fn eval(&self, u: f64, v: f64) -> SurfacePoint;

    /// Parameter domains of u and v, with their periodicity.
    fn domain(&self) -> [ParamRange; 2];

    /// Unit outward normal at (u, v), or `None` where the surface has no tangent plane
    /// (a cone apex, for instance).
    fn normal(&self, u: f64, v: f64) -> Option<DVec3> {
        self.eval(u, v).cross_normal()
    }

    /// Principal curvatures at (u, v), or `None` where the surface has no tangent plane.
    fn principal_curvatures(&self, u: f64, v: f64) -> Option<PrincipalCurvatures> {
        let n = self.normal(u, v)?;
        self.eval(u, v).principal_curvatures_with(n)
    }
}

/// A shared surface is a surface: lets a face and the iso-curves of its sides
/// ([`crate::IsoCurve`]) evaluate one geometry.
impl<S: Surface + ?Sized> Surface for std::sync::Arc<S> {
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
