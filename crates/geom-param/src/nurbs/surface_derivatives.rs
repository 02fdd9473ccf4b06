//! Point and partial derivatives up to order 2 of a rational B-spline surface (The NURBS Book
//! A3.6 on the homogeneous control net, then A4.4).

use crate::nurbs::basis::BSplineBasis;
use crate::nurbs::control_point::ControlPoint;
use crate::nurbs::{BINOMIAL, MAX_ORDER};

/// `skl[k][l]` = ∂^(k+l) S / ∂u^k ∂v^l at (u, v) for k + l <= 2 (other entries 0), for the
/// surface with row-major control net `points[i * count_v + j]` = P_ij (i along u) and weights
/// `weights` over `basis` = [u basis, v basis]; (u, v) already inside the domain; no
/// allocation.
///
/// A3.6 (SurfaceDerivsAlg1) on P^w_ij = (w_ij P_ij, w_ij) gives the derivatives A_kl of the
/// weighted point and w_kl of the weight; A4.4 (RatSurfaceDerivs) divides out the weight:
/// S_kl = (A_kl − Σ_{j=1..l} C(l,j) w_0j S_k,l−j − Σ_{i=1..k} C(k,i) w_i0 S_k−i,l
///         − Σ_{i=1..k} C(k,i) Σ_{j=1..l} C(l,j) w_ij S_k−i,l−j) / w_00.
pub(crate) fn rational_surface_derivatives<P: ControlPoint>(
    basis: &[BSplineBasis; 2],
    points: &[P],
    weights: &[f64],
    u: f64,
    v: f64,
) -> [[P; 3]; 3] {
    let (p, q) = (basis[0].degree(), basis[1].degree());
    let count_v = basis[1].count();
    let (span_u, span_v) = (basis[0].find_span(u), basis[1].find_span(v));
    let nu = basis[0].derivatives(span_u, u);
    let nv = basis[1].derivatives(span_v, v);
    // temp[k][s]: the k-th u-derivative of the homogeneous column s of the span's sub-net,
    // all three orders in one pass over the net.
    let mut temp = [[P::ZERO; MAX_ORDER]; 3];
    let mut temp_w = [[0.0; MAX_ORDER]; 3];
    for s in 0..=q {
        for (r, row) in (span_u - p..=span_u).enumerate() {
            let index = row * count_v + span_v - q + s;
            let weight = weights[index];
            let weighted = points[index] * weight;
            for k in 0..3 {
                temp[k][s] = temp[k][s] + weighted * nu[k][r];
                temp_w[k][s] += weight * nu[k][r];
            }
        }
    }
    let mut a = [[P::ZERO; 3]; 3];
    let mut w = [[0.0; 3]; 3];
    for k in 0..3 {
        for l in 0..3 - k {
            for s in 0..=q {
                a[k][l] = a[k][l] + temp[k][s] * nv[l][s];
                w[k][l] += temp_w[k][s] * nv[l][s];
            }
        }
    }
    let mut skl = [[P::ZERO; 3]; 3];
    for k in 0..3 {
        for l in 0..3 - k {
            let mut value = a[k][l];
            for j in 1..=l {
                value = value - skl[k][l - j] * (BINOMIAL[l][j] * w[0][j]);
            }
            for i in 1..=k {
                value = value - skl[k - i][l] * (BINOMIAL[k][i] * w[i][0]);
                let mut mixed = P::ZERO;
                for j in 1..=l {
                    mixed = mixed + skl[k - i][l - j] * (BINOMIAL[l][j] * w[i][j]);
                }
                value = value - mixed * BINOMIAL[k][i];
            }
            skl[k][l] = value * (1.0 / w[0][0]);
        }
    }
    skl
}
