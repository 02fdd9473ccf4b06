//! Dense linear algebra for the tiny (at most 4 x 4) systems of the polishers.

/// Largest system the polishers solve (two parameters per surface).
pub(crate) const N: usize = 4;

/// Solves `m x = b` on the first `n` rows and columns by Gaussian elimination with partial
/// pivoting; `None` when a pivot vanishes (relative to the matrix's largest entry) or the
/// answer is not finite.
pub(crate) fn solve(m: &[[f64; N]; N], b: &[f64; N], n: usize) -> Option<[f64; N]> {
    let mut a = *m;
    let mut x = *b;
    let scale = (0..n)
        .flat_map(|i| (0..n).map(move |j| (i, j)))
        .fold(0.0_f64, |s, (i, j)| s.max(a[i][j].abs()));
    if !(scale > 0.0 && scale.is_finite()) {
        return None;
    }
    for col in 0..n {
        let pivot = (col..n).max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))?;
        if a[pivot][col].abs() <= 1e-15 * scale {
            return None;
        }
        a.swap(col, pivot);
        x.swap(col, pivot);
        for row in col + 1..n {
            let factor = a[row][col] / a[col][col];
            for k in col..n {
                a[row][k] -= factor * a[col][k];
            }
            x[row] -= factor * x[col];
        }
    }
    for col in (0..n).rev() {
        let mut s = x[col];
        for k in col + 1..n {
            s -= a[col][k] * x[k];
        }
        x[col] = s / a[col][col];
    }
    x[..n].iter().all(|v| v.is_finite()).then_some(x)
}

/// Smallest eigenvalue of the symmetric leading `n x n` block (see [`eigenvalues`]).
pub(crate) fn min_eigenvalue(m: &[[f64; N]; N], n: usize) -> f64 {
    eigenvalues(m, n)[..n]
        .iter()
        .copied()
        .fold(f64::INFINITY, f64::min)
}

/// The eigenvalues of the symmetric leading `n x n` block, in no particular order (the first
/// `n` entries; cyclic Jacobi rotations, which converge quadratically; 50 sweeps is far more
/// than a 4 x 4 ever needs).
pub(crate) fn eigenvalues(m: &[[f64; N]; N], n: usize) -> [f64; N] {
    let mut a = *m;
    for _ in 0..50 {
        let off: f64 = (0..n)
            .flat_map(|i| (0..n).map(move |j| (i, j)))
            .filter(|(i, j)| i != j)
            .map(|(i, j)| a[i][j] * a[i][j])
            .sum();
        let diag: f64 = (0..n).map(|i| a[i][i] * a[i][i]).sum();
        if off <= 1e-30 * diag.max(f64::MIN_POSITIVE) {
            break;
        }
        for p in 0..n {
            for q in p + 1..n {
                if a[p][q] == 0.0 {
                    continue;
                }
                let theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
                let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
                let t = if theta == 0.0 { 1.0 } else { t };
                let c = 1.0 / (t * t + 1.0).sqrt();
                let s = t * c;
                for k in 0..n {
                    let (akp, akq) = (a[k][p], a[k][q]);
                    a[k][p] = c * akp - s * akq;
                    a[k][q] = s * akp + c * akq;
                }
                for k in 0..n {
                    let (apk, aqk) = (a[p][k], a[q][k]);
                    a[p][k] = c * apk - s * aqk;
                    a[q][k] = s * apk + c * aqk;
                }
            }
        }
    }
    std::array::from_fn(|i| if i < n { a[i][i] } else { 0.0 })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solves_a_pivoting_system() {
        let m = [
            [0.0, 2.0, 0.0, 0.0],
            [1.0, 0.0, 0.0, 0.0],
            [0.0, 0.0, 3.0, 1.0],
            [0.0, 0.0, 1.0, 3.0],
        ];
        let x = solve(&m, &[4.0, 1.0, 4.0, 4.0], 4).unwrap();
        for (got, want) in x.iter().zip([1.0, 2.0, 1.0, 1.0]) {
            assert!((got - want).abs() < 1e-14, "{x:?}");
        }
        assert!(solve(&[[0.0; N]; N], &[1.0; N], 4).is_none());
    }

    #[test]
    fn min_eigenvalue_of_a_known_matrix() {
        // [[2, 1], [1, 2]] has eigenvalues 1 and 3; the other block has -1 and 5.
        let m = [
            [2.0, 1.0, 0.0, 0.0],
            [1.0, 2.0, 0.0, 0.0],
            [0.0, 0.0, 2.0, 3.0],
            [0.0, 0.0, 3.0, 2.0],
        ];
        assert!((min_eigenvalue(&m, 2) - 1.0).abs() < 1e-14);
        assert!((min_eigenvalue(&m, 4) + 1.0).abs() < 1e-14);
    }
}
