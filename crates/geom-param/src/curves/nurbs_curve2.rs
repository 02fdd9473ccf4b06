//! A NURBS p-curve in a face's (u, v) parameter plane (STEP's PCURVE of a B-spline).

use crate::curves::curve::ParamRange;
use crate::curves::curve2::{Curve2, Curve2Point};
use crate::nurbs::rational_bspline_curve::RationalBSplineCurve;
use glam::DVec2;

/// A rational B-spline curve in a face's (u, v) plane, with the same numerics as
/// [`crate::NurbsCurve`]: see [`RationalBSplineCurve`].
pub type NurbsCurve2 = RationalBSplineCurve<DVec2>;

impl Curve2 for NurbsCurve2 {
    fn eval(&self, t: f64) -> Curve2Point {
        let [point, d1, d2] = self.derivatives(t);
        Curve2Point { point, d1, d2 }
    }

    fn domain(&self) -> ParamRange {
        self.param_range()
    }
}
