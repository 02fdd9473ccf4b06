//! Global B-spline interpolation of points at given parameters (The NURBS Book A9.1, knots by
//! averaging, eq. 9.8).

use crate::nurbs::basis::BSplineBasis;
use crate::nurbs::control_point::ControlPoint;

/// Pivot below which the collocation matrix (entries in [0, 1], rows summing to 1) counts as
/// singular.
const SINGULAR_PIVOT: f64 = 1e-14;

/// The clamped knot vector of degree `degree` for interpolating at the increasing parameters
/// `params` (ū_0 < ... < ū_n, n + 1 = `params.len()` > `degree`) by averaging (eq. 9.8):
/// u_0 = ... = u_p = ū_0, u_{m−p} = ... = u_m = ū_n and u_{j+p} = (ū_j + ... + ū_{j+p−1}) / p
/// for j = 1, ..., n − p. With these knots the interpolation problem has a unique solution
/// (Schoenberg–Whitney), and because the spline space holds every polynomial of degree <= p,
/// interpolating a polynomial's values reproduces it (in particular v ↦ v itself).
pub(crate) fn averaged_knots(params: &[f64], degree: usize) -> Vec<f64> {
    let n = params.len() - 1;
    let (first, last) = (params[0], params[n]);
    let mut knots = vec![first; degree + 1];
    for j in 1..=n - degree {
        let sum: f64 = params[j..j + degree].iter().sum();
        knots.push(sum / degree as f64);
    }
    knots.extend(std::iter::repeat_n(last, degree + 1));
    knots
}

/// The control points Q_0..Q_n of the non-rational B-spline over `basis` that passes through
/// `data[k]` at parameter `params[k]` (A9.1: the collocation system Σ_j N_j(ū_k) Q_j = D_k,
/// solved by Gaussian elimination with partial pivoting; the matrix is totally positive and
/// banded, so the elimination is stable). `data` holds one row of n + 1 values per column to
/// interpolate (all columns share the matrix); the result has the same shape. The first and
/// last control points of a clamped basis are the first and last data points exactly.
///
/// Returns `None` when the system is singular to rounding (parameters that violate
/// Schoenberg–Whitney for `basis`).
pub(crate) fn interpolate_columns<P: ControlPoint>(
    basis: &BSplineBasis,
    params: &[f64],
    data: &[Vec<P>],
) -> Option<Vec<Vec<P>>> {
    let count = params.len();
    let p = basis.degree();
    let mut matrix = vec![vec![0.0; count]; count];
    for (k, &t) in params.iter().enumerate() {
        let span = basis.find_span(t);
        let n = basis.derivatives(span, t);
        for (r, &value) in n[0].iter().enumerate().take(p + 1) {
            matrix[k][span - p + r] = value;
        }
    }
    let mut rhs: Vec<Vec<P>> = (0..count)
        .map(|k| data.iter().map(|column| column[k]).collect())
        .collect();
    for col in 0..count {
        let pivot =
            (col..count).max_by(|&a, &b| matrix[a][col].abs().total_cmp(&matrix[b][col].abs()))?;
        let size = matrix[pivot][col].abs();
        if size.is_nan() || size <= SINGULAR_PIVOT {
            return None;
        }
        matrix.swap(col, pivot);
        rhs.swap(col, pivot);
        let (upper, lower) = matrix.split_at_mut(col + 1);
        let (rhs_upper, rhs_lower) = rhs.split_at_mut(col + 1);
        let (pivot_row, pivot_rhs) = (&upper[col], &rhs_upper[col]);
        for (row, row_rhs) in lower.iter_mut().zip(rhs_lower.iter_mut()) {
            let factor = row[col] / pivot_row[col];
            if factor == 0.0 {
                continue;
            }
            for (entry, &above) in row.iter_mut().zip(pivot_row).skip(col) {
                *entry -= factor * above;
            }
            for (value, &above) in row_rhs.iter_mut().zip(pivot_rhs) {
                *value = *value - above * factor;
            }
        }
    }
    let mut solution = vec![vec![P::ZERO; count]; data.len()];
    for row in (0..count).rev() {
        for c in 0..data.len() {
            let mut value = rhs[row][c];
            for k in row + 1..count {
                value = value - solution[c][k] * matrix[row][k];
            }
            solution[c][row] = value * (1.0 / matrix[row][row]);
        }
    }
    // Clamped ends: N_0(ū_0) = N_n(ū_n) = 1, so the ends are the data's ends; set them
    // exactly rather than to the elimination's rounding of them.
    for (column, values) in solution.iter_mut().zip(data) {
        column[0] = values[0];
        column[count - 1] = values[count - 1];
    }
    Some(solution)
}
