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
///
/// Degrees 1 to 3 in each direction run a copy with the degrees and the scratch sizes fixed at
/// compile time (loops unrolled, only their own scratch cleared); the arithmetic is the same,
/// operation for operation, so the values are bit for bit those of the general copy.
pub(crate) fn rational_surface_derivatives<P: ControlPoint>(
    basis: &[BSplineBasis; 2],
    points: &[P],
    weights: &[f64],
    u: f64,
    v: f64,
) -> [[P; 3]; 3] {
    let net = (basis, points, weights);
    match (basis[0].degree(), basis[1].degree()) {
        (1, 1) => derivatives_of::<P, 2, 2>(net, (1, 1), u, v),
        (1, 2) => derivatives_of::<P, 2, 3>(net, (1, 2), u, v),
        (1, 3) => derivatives_of::<P, 2, 4>(net, (1, 3), u, v),
        (2, 1) => derivatives_of::<P, 3, 2>(net, (2, 1), u, v),
        (2, 2) => derivatives_of::<P, 3, 3>(net, (2, 2), u, v),
        (2, 3) => derivatives_of::<P, 3, 4>(net, (2, 3), u, v),
        (3, 1) => derivatives_of::<P, 4, 2>(net, (3, 1), u, v),
        (3, 2) => derivatives_of::<P, 4, 3>(net, (3, 2), u, v),
        (3, 3) => derivatives_of::<P, 4, 4>(net, (3, 3), u, v),
        degrees => derivatives_of::<P, MAX_ORDER, MAX_ORDER>(net, degrees, u, v),
    }
}

/// [`rational_surface_derivatives`] for degrees `(p, q)` <= (`OU` − 1, `OV` − 1), with scratch
/// arrays of `OV` entries.
#[inline(always)]
fn derivatives_of<P: ControlPoint, const OU: usize, const OV: usize>(
    (basis, points, weights): (&[BSplineBasis; 2], &[P], &[f64]),
    (p, q): (usize, usize),
    u: f64,
    v: f64,
) -> [[P; 3]; 3] {
    debug_assert!(p < OU && q < OV);
    let count_v = basis[1].count();
    let (span_u, span_v) = (basis[0].find_span(u), basis[1].find_span(v));
    let nu = basis[0].derivatives(span_u, u);
    let nv = basis[1].derivatives(span_v, v);
    // temp[k][s]: the k-th u-derivative of the homogeneous column s of the span's sub-net,
    // all three orders in one pass over the net.
    let mut temp = [[P::ZERO; OV]; 3];
    let mut temp_w = [[0.0; OV]; 3];
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

#[cfg(test)]
mod tests {
    use super::{derivatives_of, rational_surface_derivatives};
    use crate::nurbs::MAX_ORDER;
    use crate::nurbs::basis::tests::uneven_basis;
    use glam::DVec3;

    /// The copies for degrees 1 to 3 in each direction give bit for bit the values of the
    /// general copy, on a rational net with uneven knots and weights, over the whole domain.
    #[test]
    fn fixed_degree_copies_match_the_general_one_exactly() {
        for p in 1..=3 {
            for q in 1..=3 {
                let basis = [uneven_basis(p, p + 5), uneven_basis(q, q + 4)];
                let (nu, nv) = (basis[0].count(), basis[1].count());
                let points: Vec<DVec3> = (0..nu * nv)
                    .map(|k| {
                        let (i, j) = ((k / nv) as f64, (k % nv) as f64);
                        DVec3::new(i, j, (0.7 * i).sin() + (0.4 * j).cos())
                    })
                    .collect();
                let weights: Vec<f64> = (0..nu * nv).map(|k| 0.6 + 0.1 * (k % 7) as f64).collect();
                let ((u0, u1), (v0, v1)) = (basis[0].domain(), basis[1].domain());
                for a in 0..=24 {
                    for b in 0..=24 {
                        let u = u0 + (u1 - u0) * f64::from(a) / 24.0;
                        let v = v0 + (v1 - v0) * f64::from(b) / 24.0;
                        let general = derivatives_of::<DVec3, MAX_ORDER, MAX_ORDER>(
                            (&basis, &points, &weights),
                            (p, q),
                            u,
                            v,
                        );
                        let fixed = rational_surface_derivatives(&basis, &points, &weights, u, v);
                        assert_eq!(fixed, general, "degrees ({p}, {q}) at ({u}, {v})");
                    }
                }
            }
        }
    }
}
