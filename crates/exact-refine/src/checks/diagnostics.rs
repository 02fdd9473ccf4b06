//! Diagnostics of a finished solve: conditioning, second-order check, continuous-contact
//! detection and error estimates.

// Small dense matrices (at most 4 x 4): index arithmetic reads closer to the formulas.
#![allow(clippy::needless_range_loop)]

use crate::features::feature_eval::Body;
use crate::linalg::dense_solve::by_size;
use crate::linalg::sym_eigen::sym_eigenvalues_lockstep;
use crate::refined_contact::{RefineDiagnostics, RefineStatus};
use crate::solver::newton::{EPS, Outcome, Solution, State, by_pair_kind, is_touch};
use geom_param::DVec3;

/// Diagnostics of `solution` (a pair solve between `a` and `b`) whose unit normal from A to B
/// is `normal`.
pub(crate) fn diagnose(
    a: &Body,
    b: &Body,
    solution: &Solution,
    normal: DVec3,
) -> RefineDiagnostics {
    let state = &solution.state;
    let n = state.n;
    // The spectra at once (independent chains of divisions and roots): the Hessian's, the gap
    // Hessian's and, where the sliding metric factors, the gap Hessian's in that metric.
    let gap_hessian = GapHessian::new(state, normal);
    let metric = gap_metric(state, &gap_hessian.h);
    let (spectrum, gap_spectrum, metric_spectrum) = match &metric.congruent {
        Some(c) => {
            let [s, g, m] = sym_eigenvalues_lockstep([&state.hs, &gap_hessian.h, c], n);
            (s, g, Some(m))
        }
        None => {
            let [s, g] = sym_eigenvalues_lockstep([&state.hs, &gap_hessian.h], n);
            (s, g, None)
        }
    };
    let values = &spectrum[..n];
    let floor = state.eigen_floor(&spectrum);
    let largest = values.iter().fold(0.0_f64, |m, l| m.max(l.abs()));
    let smallest = values.iter().fold(f64::INFINITY, |m, l| m.min(l.abs()));
    let condition = match n {
        0 => 1.0,
        _ if smallest > 0.0 => largest / smallest,
        _ => f64::INFINITY,
    };
    let converged = solution.outcome == Outcome::Converged;
    // The inertia the answer must have: 0 for a closest pair, the witness's for a penetration.
    let penetrating = state.penetrating(a, b);
    let index = if penetrating {
        state.witness_index()
    } else {
        0
    };
    let second_order = match index {
        0 => values.first().is_none_or(|&l| l >= -floor),
        k => values[k - 1] <= floor && values.get(k).is_none_or(|&l| l >= -floor),
    };
    let (kappa, degenerate) = gap_hessian.relative_curvature(&gap_spectrum, n);
    let status = match solution.outcome {
        Outcome::Converged if degenerate => RefineStatus::ContinuousContact,
        Outcome::Converged => RefineStatus::Converged,
        Outcome::IterationLimit => RefineStatus::IterationLimit,
        // `Penetrating` is a hand-over inside `pair_solve::solve` and never ends a pair solve.
        Outcome::Stalled | Outcome::Penetrating => RefineStatus::Stalled,
        Outcome::SwitchLimit => RefineStatus::FeatureSwitchLimit,
    };
    let rounding = 16.0 * EPS * state.scale;
    let residual = state.gradient_norm() + state.gradient_floor();
    // Along the flattest direction f = ½(σ0 + ½κδ²)², so a tangential residual g allows an
    // offset δ ≤ g / λ_min (linear model) and, when not penetrating, δ ≤ (2g / κ²)^⅓ (the
    // quartic model that holds at exact touch, where λ_min → 0); the gap then errs by ½κδ².
    let point_error_estimate = if n == 0 {
        rounding
    } else if degenerate {
        f64::INFINITY
    } else {
        let linear = if smallest > 0.0 {
            residual / smallest
        } else {
            f64::INFINITY
        };
        let quartic = if !penetrating {
            (2.0 * residual / (kappa * kappa)).cbrt()
        } else {
            f64::INFINITY
        };
        rounding + linear.min(quartic)
    };
    let gap_curvature = if degenerate {
        0.0
    } else {
        metric.gap_curvature(&gap_hessian, &gap_spectrum, metric_spectrum.as_ref(), n)
    };
    // The gap errs by ½κδ² with κ the gap's curvature along the features' arc length (the
    // reported `gap_curvature`): κ above, an eigenvalue in the joint parameters of both
    // points, is up to half of that where both points slide together (a rim on a plane), and
    // alone it gave an estimate of 5.7e-9 mm for an error of 6.3e-9 mm (vase-paperweight
    // 1687297597018891653 of `soak 10000 --seed 13103`).
    let error_estimate = if degenerate || n == 0 {
        rounding + state.gradient_norm()
    } else {
        let curvature = if gap_curvature.is_finite() {
            kappa.max(gap_curvature)
        } else {
            kappa
        };
        rounding + 0.5 * curvature * point_error_estimate * point_error_estimate
    };
    // At a gap within what the solve can tell from zero (`gap_within_error`) the sign of d,
    // hence the index the second-order test wants (0 separated, the witness's when
    // penetrating), is not known (whichever `State::penetrating` says), and the eigenvalues it
    // counts (|d| x relative curvature along the sliding directions, plus the square of the
    // crossing angle) do not tell a touch from a crossing. The pair is then judged as at d = 0, where f = 0 is the global minimum of
    // f = ½|d|²: a touch when the normals are opposed, to within how far they turn over the
    // point error (curvature scale x `point_error_estimate`; never more than stationarity
    // allows). A crossing at an angle below that passes this test too: the refiner then probes
    // the surfaces next to the pair (`crossing_probe`) before calling it a touch. Where the
    // normal cones cannot tell (two edges, a vertex), the second-order test decides as above.
    let gap = state.d.length();
    let within_error = gap_within_error(state, error_estimate, point_error_estimate);
    let misalignment =
        (state.curvature * point_error_estimate).min(residual / gap.max(f64::MIN_POSITIVE));
    let touch = if converged && within_error {
        is_touch(a, b, state, misalignment)
    } else {
        None
    };
    // A pair whose points lie on different sides ([`State::sides_disagree`]) has one point
    // inside the other solid and the other outside: neither a contact nor a depth.
    let is_local_minimum =
        converged && touch.unwrap_or_else(|| second_order && !state.sides_disagree(a, b));
    RefineDiagnostics {
        iterations: solution.iterations,
        gradient_norm: state.gradient_norm(),
        condition,
        converged,
        is_local_minimum,
        error_estimate,
        point_error_estimate,
        gap_curvature,
        status,
    }
}

/// Whether the gap |d| of `state` is within what the solve can tell from zero: its
/// `error_estimate` (mm) plus the gap's rate along the features times `point_error_estimate`.
///
/// Stationarity bounds the gap's rate along the parameters (per mm of motion: the component of
/// d's direction along the features' tangents) by residual / |d|. At a minimum that rate is
/// rounding and `error_estimate` (the curvature's share, ½κδ²) is the whole error. Where the
/// features cross at a small angle α, the solve stops stationary to tolerance at
/// |d| ≈ α x point error, not at a minimum of the gap (an edge 5e-3 rad into a face stopped at
/// d = 8e-11 mm), and the gap errs by up to α x point error.
pub(crate) fn gap_within_error(
    state: &State,
    error_estimate: f64,
    point_error_estimate: f64,
) -> bool {
    let gap = state.d.length();
    let residual = state.gradient_norm() + state.gradient_floor();
    let slope = (residual / gap.max(f64::MIN_POSITIVE)).min(1.0);
    gap <= error_estimate + slope * point_error_estimate
}

/// The Hessian whose spectrum gives the relative curvature of the gap (see
/// [`GapHessian::relative_curvature`]), with the gap ℓ and curvature scale it was built with.
struct GapHessian {
    h: [[f64; 4]; 4],
    ell: f64,
    curvature: f64,
}

impl GapHessian {
    /// With the features a distance ℓ apart along `normal`, the Hessian of f has a Schur
    /// complement of about ℓ(K_a + K_b) − ℓ²K_a² in the rolling directions, so its smallest
    /// eigenvalue over ℓ is the curvature of the gap. ℓ is the actual gap |σ| (which makes
    /// concentric spheres of different radii exactly degenerate), floored at √ε / (curvature
    /// scale) at touch, where the rounding of the eigenvalue (256 ε (1 + ℓ·curvature)) then
    /// resolves relative curvatures down to about 4e-6 of the curvature scale. (No variables:
    /// an empty matrix.)
    fn new(state: &State, normal: DVec3) -> Self {
        let (n, na) = (state.n, state.na);
        let curvature = state.curvature.max(1.0 / state.scale);
        let ell = state.d.length().max(EPS.sqrt() / curvature);
        let h = if n == 0 {
            [[0.0; 4]; 4]
        } else {
            by_pair_kind!(na, n - na, gap_hessian(state, -normal * ell))
        };
        Self { h, ell, curvature }
    }

    /// The smallest curvature of the gap function (1/mm) over the directions of the pair's
    /// parameters, from the eigenvalues `spectrum` of the first `n` rows and columns of `h`,
    /// and whether it is zero to rounding (a continuous contact). Zero for parallel cylinders,
    /// flat faces and concentric spheres.
    fn relative_curvature(&self, spectrum: &[f64; 4], n: usize) -> (f64, bool) {
        if n == 0 {
            return (f64::INFINITY, false);
        }
        let smallest = spectrum[..n]
            .iter()
            .fold(f64::INFINITY, |m, l| m.min(l.abs()));
        let rounding = 256.0 * EPS * (1.0 + self.ell * self.curvature);
        (smallest / self.ell, smallest <= rounding)
    }
}

/// The scaled Hessian of f at `state` with the connecting vector replaced by `d` (A's frame,
/// mm), for `NA` parameters on A and `NB` on B: H_ij = (s_i s_j ∂P/∂x_i · ∂P/∂x_j + s_i d ·
/// ∂²P/∂x_i∂x_j) / (speed_i speed_j), s = +1 on A and −1 on B, the second term only within one
/// side. Symmetric term by term, so the upper triangle is mirrored.
fn gap_hessian<const NA: usize, const NB: usize>(state: &State, d: DVec3) -> [[f64; 4]; 4] {
    let n = NA + NB;
    let mut first = [DVec3::ZERO; 4];
    first[..NA].copy_from_slice(&state.ea.d[..NA]);
    first[NA..n].copy_from_slice(&state.eb.d[..NB]);
    let mut h = [[0.0; 4]; 4];
    for i in 0..n {
        for j in i..n {
            let (si, sj) = (
                if i < NA { 1.0 } else { -1.0 },
                if j < NA { 1.0 } else { -1.0 },
            );
            let second = match (i < NA, j < NA) {
                (true, true) => d.dot(state.ea.dd[i][j]),
                (false, false) => -d.dot(state.eb.dd[i - NA][j - NA]),
                _ => 0.0,
            };
            h[i][j] =
                (si * sj * first[i].dot(first[j]) + second) / (state.speed[i] * state.speed[j]);
            h[j][i] = h[i][j];
        }
    }
    h
}

/// The metric of the gap function's smallest curvature (1/mm,
/// [`RefineDiagnostics::gap_curvature`]): that curvature is the smallest eigenvalue of the
/// scaled Hessian at separation ℓ ([`GapHessian`])
/// measured against the squared length the pair slides, divided by ℓ. A parameter step v (arc
/// lengths) moves A's point by J_a v_a and B's by J_b v_b; rolling both points by the same
/// unit tangent t has vᵀ G v = 2 (G = blockdiag(J_aᵀJ_a, J_bᵀJ_b), the first fundamental forms
/// in arc-length variables), so the metric is G / 2 when both sides have parameters and G when
/// one side is a vertex (then only the other point slides). The generalised eigenproblem
/// H v = λ (G / w) v is solved as the ordinary one of L⁻¹ H L⁻ᵀ with G / w = L Lᵀ (Cholesky);
/// where G is singular (a parameter whose direction vanishes, at a pole) the smallest
/// eigenvalue of H itself stands in (the rolling direction's norm is then 2, not 1, on
/// orthonormal parameters: an estimate within a factor 2).
struct GapMetric {
    /// 1/2 when both sides have parameters, 1 otherwise.
    weight: f64,
    /// L⁻¹ H L⁻ᵀ with G / w = L Lᵀ, `None` where G does not factor (or there are no variables).
    congruent: Option<[[f64; 4]; 4]>,
}

/// The [`GapMetric`] of `state`, whose gap Hessian ([`GapHessian::h`]) is `h`.
fn gap_metric(state: &State, h: &[[f64; 4]; 4]) -> GapMetric {
    by_size!(state.n, gap_metric_n(state, h))
}

/// [`gap_metric`] for `N` = `state.n` variables (loops of constant length, unrolled; the same
/// arithmetic).
fn gap_metric_n<const N: usize>(state: &State, h: &[[f64; 4]; 4]) -> GapMetric {
    let (n, na) = (N, state.na);
    let weight = if na > 0 && na < n { 0.5 } else { 1.0 };
    if n == 0 {
        return GapMetric {
            weight,
            congruent: None,
        };
    }
    let mut first = [DVec3::ZERO; 4];
    first[..na].copy_from_slice(&state.ea.d[..na]);
    first[na..n].copy_from_slice(&state.eb.d[..n - na]);
    let mut g = [[0.0; 4]; 4];
    for i in 0..n {
        for j in 0..n {
            if (i < na) == (j < na) {
                let scale = state.speed[i] * state.speed[j];
                g[i][j] = weight * first[i].dot(first[j]) / scale;
            }
        }
    }
    GapMetric {
        weight,
        congruent: cholesky::<N>(&g).map(|l| congruence::<N>(h, &l)),
    }
}

impl GapMetric {
    /// The gap curvature (1/mm) from the spectra of the gap Hessian (`gap_spectrum`) and of
    /// [`Self::congruent`] (`metric_spectrum`, when it exists), of their first `n` rows and
    /// columns; ∞ with no variables.
    fn gap_curvature(
        &self,
        gap: &GapHessian,
        gap_spectrum: &[f64; 4],
        metric_spectrum: Option<&[f64; 4]>,
        n: usize,
    ) -> f64 {
        if n == 0 {
            return f64::INFINITY;
        }
        let smallest = |values: &[f64; 4]| {
            values[..n]
                .iter()
                .fold(f64::INFINITY, |s, l| s.min(l.abs()))
        };
        match metric_spectrum {
            Some(values) => smallest(values) / gap.ell,
            None => 2.0 * self.weight * smallest(gap_spectrum) / gap.ell,
        }
    }
}

/// The lower-triangular L with L Lᵀ = m (leading n x n block), `None` when m is not positive
/// definite to 1e-12 of its diagonal.
fn cholesky<const N: usize>(m: &[[f64; 4]; 4]) -> Option<[[f64; 4]; 4]> {
    let n = N;
    let mut l = [[0.0; 4]; 4];
    for i in 0..n {
        for j in 0..=i {
            let mut s = m[i][j];
            for k in 0..j {
                s -= l[i][k] * l[j][k];
            }
            if i == j {
                // Also refuses NaN: the comparison is false for it.
                if s.partial_cmp(&(1e-12 * m[i][i].abs())) != Some(std::cmp::Ordering::Greater) {
                    return None;
                }
                l[i][i] = s.sqrt();
            } else {
                l[i][j] = s / l[j][j];
            }
        }
    }
    Some(l)
}

/// L⁻¹ h L⁻ᵀ for lower-triangular L (leading n x n block), by forward substitution on the
/// columns and then on the rows.
fn congruence<const N: usize>(h: &[[f64; 4]; 4], l: &[[f64; 4]; 4]) -> [[f64; 4]; 4] {
    let n = N;
    // x = L⁻¹ h: solve L x = h column by column.
    let solve = |b: [f64; 4]| {
        let mut x = [0.0; 4];
        for i in 0..n {
            let mut s = b[i];
            for k in 0..i {
                s -= l[i][k] * x[k];
            }
            x[i] = s / l[i][i];
        }
        x
    };
    let mut x = [[0.0; 4]; 4];
    for j in 0..n {
        let col = solve(std::array::from_fn(|i| h[i][j]));
        for i in 0..n {
            x[i][j] = col[i];
        }
    }
    // y = L⁻¹ xᵀ = L⁻¹ (L⁻¹ h)ᵀ = L⁻¹ hᵀ L⁻ᵀ... then yᵀ = L⁻¹ h L⁻ᵀ (h symmetric).
    let mut y = [[0.0; 4]; 4];
    for j in 0..n {
        let col = solve(std::array::from_fn(|i| x[j][i]));
        for i in 0..n {
            y[i][j] = col[i];
        }
    }
    let mut out = [[0.0; 4]; 4];
    for i in 0..n {
        for j in 0..n {
            out[i][j] = 0.5 * (y[i][j] + y[j][i]);
        }
    }
    out
}
