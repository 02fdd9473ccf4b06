//! Direct solves of the small (at most 4 x 4) symmetric Hessians, cheaper than their
//! eigen-decomposition: Cholesky where a Hessian is positive definite (with a bound on its
//! smallest eigenvalue), and Gaussian elimination where it is indefinite.

// Small dense matrices (at most 4 x 4): index arithmetic reads closer to the formulas.
#![allow(clippy::needless_range_loop)]

/// Calls `f::<N>(args)` for the size `n` (0 to 4; larger is taken as 4): one copy per size,
/// whose loops over a constant bound the compiler unrolls. The arithmetic is the same for all.
macro_rules! by_size {
    ($n:expr, $f:ident($($arg:expr),*)) => {
        match $n {
            0 => $f::<0>($($arg),*),
            1 => $f::<1>($($arg),*),
            2 => $f::<2>($($arg),*),
            3 => $f::<3>($($arg),*),
            _ => $f::<4>($($arg),*),
        }
    };
}

pub(crate) use by_size;

/// The lower Cholesky factor L (H = L Lᵀ) of the leading `n` x `n` block of a symmetric
/// matrix, or `None` when a pivot is not positive (or not finite): the matrix is then not
/// positive definite to rounding.
pub(crate) fn cholesky(h: &[[f64; 4]; 4], n: usize) -> Option<[[f64; 4]; 4]> {
    by_size!(n, cholesky_n(h))
}

/// [`cholesky`] of the leading `N` x `N` block.
pub(crate) fn cholesky_n<const N: usize>(h: &[[f64; 4]; 4]) -> Option<[[f64; 4]; 4]> {
    let n = N;
    let mut l = [[0.0; 4]; 4];
    for j in 0..n {
        let mut pivot = h[j][j];
        for k in 0..j {
            pivot -= l[j][k] * l[j][k];
        }
        // Also rejects NaN: every comparison with NaN is false.
        if !(pivot > 0.0 && pivot.is_finite()) {
            return None;
        }
        let root = pivot.sqrt();
        l[j][j] = root;
        for i in j + 1..n {
            let mut v = h[i][j];
            for k in 0..j {
                v -= l[i][k] * l[j][k];
            }
            l[i][j] = v / root;
        }
    }
    Some(l)
}

/// Solves L Lᵀ x = b for the first `n` entries.
pub(crate) fn cholesky_solve(l: &[[f64; 4]; 4], n: usize, b: &[f64; 4]) -> [f64; 4] {
    by_size!(n, cholesky_solve_n(l, b))
}

/// [`cholesky_solve`] for the leading `N` entries.
pub(crate) fn cholesky_solve_n<const N: usize>(l: &[[f64; 4]; 4], b: &[f64; 4]) -> [f64; 4] {
    let n = N;
    let mut x = [0.0; 4];
    for i in 0..n {
        let mut v = b[i];
        for k in 0..i {
            v -= l[i][k] * x[k];
        }
        x[i] = v / l[i][i];
    }
    for i in (0..n).rev() {
        let mut v = x[i];
        for k in i + 1..n {
            v -= l[k][i] * x[k];
        }
        x[i] = v / l[i][i];
    }
    x
}

/// A lower bound on the smallest eigenvalue of L Lᵀ (the leading `N` x `N` block):
/// 1 / ‖L⁻¹‖_F², since 1 / λ_min = ‖L⁻¹‖₂² and the Frobenius norm bounds the spectral norm from
/// above. Zero (no bound) when not finite.
pub(crate) fn smallest_eigenvalue_bound<const N: usize>(l: &[[f64; 4]; 4]) -> f64 {
    let n = N;
    // Column j of L⁻¹ by forward substitution (zero above the diagonal).
    let mut norm2 = 0.0;
    for j in 0..n {
        let mut y = [0.0; 4];
        y[j] = 1.0 / l[j][j];
        for i in j + 1..n {
            let mut v = 0.0;
            for k in j..i {
                v -= l[i][k] * y[k];
            }
            y[i] = v / l[i][i];
        }
        norm2 += y[j..n].iter().map(|c| c * c).sum::<f64>();
    }
    let bound = 1.0 / norm2;
    if bound.is_finite() { bound } else { 0.0 }
}

/// Solves M x = b for the leading `n` x `n` block by Gaussian elimination with partial
/// pivoting, or `None` when a pivot is below 64 ε x ‖M‖_F (singular to rounding) or not finite.
pub(crate) fn lu_solve(m: &[[f64; 4]; 4], n: usize, b: &[f64; 4]) -> Option<[f64; 4]> {
    let mut a = *m;
    let mut x = *b;
    let norm = a[..n]
        .iter()
        .flat_map(|row| &row[..n])
        .map(|h| h * h)
        .sum::<f64>()
        .sqrt();
    let tiny = 64.0 * f64::EPSILON * norm;
    for j in 0..n {
        let pivot_row = (j..n)
            .max_by(|&r, &s| a[r][j].abs().total_cmp(&a[s][j].abs()))
            .unwrap_or(j);
        a.swap(j, pivot_row);
        x.swap(j, pivot_row);
        let pivot = a[j][j];
        // Also rejects NaN: every comparison with NaN is false.
        if !(pivot.abs() > tiny && pivot.is_finite()) {
            return None;
        }
        for i in j + 1..n {
            let factor = a[i][j] / pivot;
            for k in j..n {
                a[i][k] -= factor * a[j][k];
            }
            x[i] -= factor * x[j];
        }
    }
    for i in (0..n).rev() {
        let mut v = x[i];
        for k in i + 1..n {
            v -= a[i][k] * x[k];
        }
        x[i] = v / a[i][i];
    }
    Some(x)
}
