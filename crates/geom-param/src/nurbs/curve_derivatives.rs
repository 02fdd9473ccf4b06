//! Point, first and second derivative of a rational B-spline curve (The NURBS Book A3.2 on the
//! homogeneous control points, then A4.2).

use crate::nurbs::BINOMIAL;
use crate::nurbs::basis::BSplineBasis;
use crate::nurbs::control_point::ControlPoint;

/// [C(t), C'(t), C''(t)] of the curve with control points `points` and weights `weights` over
/// `basis` (t already inside the basis domain; no allocation).
///
/// A3.2 (CurveDerivsAlg1) on the homogeneous points P^w_i = (w_i P_i, w_i) gives
/// A^(k) = Σ_i N^(k)_i w_i P_i and w^(k) = Σ_i N^(k)_i w_i; A4.2 (RatCurveDerivs) divides out
/// the weight: C^(k) = (A^(k) − Σ_{i=1..k} C(k, i) w^(i) C^(k−i)) / w^(0).
pub(crate) fn rational_curve_derivatives<P: ControlPoint>(
    basis: &BSplineBasis,
    points: &[P],
    weights: &[f64],
    t: f64,
) -> [P; 3] {
    let p = basis.degree();
    let span = basis.find_span(t);
    let n = basis.derivatives(span, t);
    let mut a = [P::ZERO; 3];
    let mut w = [0.0; 3];
    let first = span - p;
    let local = points[first..=span].iter().zip(&weights[first..=span]);
    for (j, (&point, &weight)) in local.enumerate() {
        for k in 0..3 {
            let nw = n[k][j] * weight;
            a[k] = a[k] + point * nw;
            w[k] += nw;
        }
    }
    let mut c = [P::ZERO; 3];
    for k in 0..3 {
        let mut value = a[k];
        for i in 1..=k {
            value = value - c[k - i] * (BINOMIAL[k][i] * w[i]);
        }
        c[k] = value * (1.0 / w[0]);
    }
    c
}
