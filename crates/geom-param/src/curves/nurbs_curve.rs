//! A NURBS curve in the object frame (STEP's B_SPLINE_CURVE_WITH_KNOTS, rational or not).

use crate::curves::curve::{Curve, CurvePoint, ParamRange};
use crate::nurbs::rational_bspline_curve::RationalBSplineCurve;
use glam::DVec3;

/// A rational B-spline curve in 3D (mm): see [`RationalBSplineCurve`] for the definition,
/// domain and periodicity. Build with [`RationalBSplineCurve::new`] or
/// [`NurbsCurve::circle_arc`].
pub type NurbsCurve = RationalBSplineCurve<DVec3>;

impl Curve for NurbsCurve {
    fn eval(&self, t: f64) -> CurvePoint {
        let [point, d1, d2] = self.derivatives(t);
        CurvePoint { point, d1, d2 }
    }

    fn domain(&self) -> ParamRange {
        self.param_range()
    }
}
