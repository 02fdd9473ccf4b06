//! How well the oracle knows its own points: an error bound from the conditioning of its
//! polished pair, computed from the oracle's own Hessian (nothing from the stages).
//!
//! The polish stops with a tangential residual: in arc-length variables (each parameter scaled
//! by its speed |c_k|) the gradient of f = ½|r|², r = S_a − S_b, is g_k = r · c_k / |c_k| (mm),
//! and the Hessian H has smallest eigenvalue magnitude λ (no unit), so the parameters may be
//! off by |g| / λ (linear model), which moves a point by at most √2 times that (the sum of
//! its two components). Near touch λ is
//! about |d| κ, with κ (1/mm) the curvature of the gap function along that direction, and
//! vanishes at exact touch, where f is quartic along it: f ≈ ⅛κ²δ⁴ allows an offset
//! δ ≤ (2|g| / κ²)^⅓. The bound is the smaller of the two, plus the rounding of the coordinates.
//! The gap's curvature κ is the smallest eigenvalue of H evaluated at a separation
//! ℓ = max(|d|, 1e3 x tolerance) along the contact normal, divided by ℓ.

use crate::polishing::linalg::{self, N};
use crate::polishing::polish::Polished;
use glam::DVec3;

/// Relative rounding of coordinates in the residual (16 ε).
const ROUNDING: f64 = 16.0 * f64::EPSILON;

/// The oracle's error bound (mm) on the points of `polished`, a pair at signed distance
/// `distance` with unit normal `normal` (point_b = point_a + distance · normal), polished to the
/// stationarity `tolerance` (mm). Infinite where the pair's Hessian is singular along a
/// direction in which the gap is flat (a continuous contact, where any point of the set is an
/// answer); the rounding floor alone when no parameter is free (a vertex against a vertex).
///
/// `snapped` (mm) is how far a point lies from the edge or vertex it is reported on (0 when
/// reported on its face): moving a point by δ changes the arc-length gradient by at most δ,
/// so it enters the bound as a residual, and the bound is never below it.
pub(crate) fn point_error_bound(
    polished: &Polished,
    distance: f64,
    normal: DVec3,
    tolerance: f64,
    snapped: f64,
) -> f64 {
    let e = &polished.eval;
    let floor = ROUNDING * e.pa.point.length().max(e.pb.point.length()).max(1.0);
    let scale = e.cols.iter().map(|c| c.length()).fold(0.0, f64::max);
    let dims = polished.pair.dims();
    let free: Vec<usize> = (0..N)
        .filter(|&k| dims[k] && !polished.active[k] && e.cols[k].length() > 1e-9 * scale)
        .collect();
    let n = free.len();
    if n == 0 {
        return floor + snapped;
    }
    // The gradient in arc-length variables, g_k / |c_k| over the free parameters (mm): the
    // offset it allows is |δ| <= |g| / λ in those variables, and a point moves by at most the
    // sum of its two components, √2 |δ|.
    let gradient = free
        .iter()
        .map(|&k| (e.g[k] / e.cols[k].length()).powi(2))
        .sum::<f64>()
        .sqrt();
    let residual = gradient.max(polished.residual).max(snapped) + floor;
    // The Hessian in arc-length variables, as evaluated (r = −d n).
    let arc = |m: &dyn Fn(usize, usize) -> f64| {
        let mut out = [[0.0; N]; N];
        for (i, &ki) in free.iter().enumerate() {
            for (j, &kj) in free.iter().enumerate() {
                out[i][j] = m(ki, kj) / (e.cols[ki].length() * e.cols[kj].length());
            }
        }
        out
    };
    let smallest = |m: &[[f64; N]; N]| {
        linalg::eigenvalues(m, n)[..n]
            .iter()
            .fold(f64::INFINITY, |s, l| s.min(l.abs()))
    };
    let lambda = smallest(&arc(&|i, j| e.h[i][j]));
    // The same Hessian at separation ℓ along the normal: cᵀc + ℓ (−n · S_a,ij ⊕ n · S_b,ij).
    let ell = distance.abs().max(1e3 * tolerance);
    let second = |i: usize, j: usize| -> f64 {
        let (pa, pb) = (&e.pa, &e.pb);
        let pick = |p: &geom_param::SurfacePoint, i: usize, j: usize| match (i, j) {
            (0, 0) => p.duu,
            (1, 1) => p.dvv,
            _ => p.duv,
        };
        match (i < 2, j < 2) {
            (true, true) => -normal.dot(pick(pa, i, j)),
            (false, false) => normal.dot(pick(pb, i - 2, j - 2)),
            _ => 0.0,
        }
    };
    let at_ell = arc(&|i, j| e.cols[i].dot(e.cols[j]) + ell * second(i, j));
    let kappa = smallest(&at_ell) / ell;
    // Zero to the rounding of the eigenvalue (256 ε relative to the unit-speed columns): flat.
    let flat = smallest(&at_ell) <= 256.0 * f64::EPSILON * (1.0 + ell * kappa);
    if flat && lambda <= 256.0 * f64::EPSILON {
        return f64::INFINITY;
    }
    let linear = if lambda > 0.0 {
        residual / lambda
    } else {
        f64::INFINITY
    };
    let quartic = if distance >= 0.0 && kappa > 0.0 {
        (2.0 * residual / (kappa * kappa)).cbrt()
    } else {
        f64::INFINITY
    };
    floor + snapped.max(std::f64::consts::SQRT_2 * linear.min(quartic))
}
