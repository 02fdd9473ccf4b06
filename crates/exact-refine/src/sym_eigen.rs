//! Eigen-decomposition of the small (at most 4 x 4) symmetric Hessians of the refinement.

// Small dense matrices (at most 4 x 4): index arithmetic reads closer to the formulas.
#![allow(clippy::needless_range_loop)]

/// Eigenvalues (ascending) and eigenvectors (columns of `vectors`, `vectors[row][col]`) of the
/// leading `n` x `n` block of a symmetric matrix.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct SymEigen {
    pub values: [f64; 4],
    pub vectors: [[f64; 4]; 4],
}

/// Cyclic Jacobi rotations. Stops when the off-diagonal mass is below (4ε)² of the Frobenius norm
/// squared (the eigenvalues are then exact to a few roundings, Golub & Van Loan §8.5; a tighter
/// bound can sit at the rounding floor and never be met) or after
/// `MAX_SWEEPS` sweeps; 4 x 4 matrices need about 4-6 sweeps, so the cap is never the limit on
/// finite input. Non-finite input gives non-finite values, which the caller checks.
pub(crate) fn sym_eigen(matrix: &[[f64; 4]; 4], n: usize) -> SymEigen {
    const MAX_SWEEPS: usize = 32;
    let mut a = *matrix;
    let mut v = [[0.0; 4]; 4];
    for (i, row) in v.iter_mut().enumerate().take(n) {
        row[i] = 1.0;
    }
    let norm2: f64 = (0..n)
        .flat_map(|i| (0..n).map(move |j| (i, j)))
        .map(|(i, j)| a[i][j] * a[i][j])
        .sum();
    for _ in 0..MAX_SWEEPS {
        let off: f64 = (0..n)
            .flat_map(|i| (0..n).map(move |j| (i, j)))
            .filter(|(i, j)| i != j)
            .map(|(i, j)| a[i][j] * a[i][j])
            .sum();
        if off.is_nan() || off <= 16.0 * f64::EPSILON * f64::EPSILON * norm2 {
            break;
        }
        for p in 0..n {
            for q in p + 1..n {
                if a[p][q] == 0.0 {
                    continue;
                }
                // Rotation that zeroes a[p][q] (the stable form of Rutishauser).
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
                for row in v.iter_mut().take(n) {
                    let (vkp, vkq) = (row[p], row[q]);
                    row[p] = c * vkp - s * vkq;
                    row[q] = s * vkp + c * vkq;
                }
            }
        }
    }
    // Sort ascending (selection sort on at most 4 entries).
    let mut out = SymEigen::default();
    let mut order = [0, 1, 2, 3];
    order[..n].sort_by(|&i, &j| a[i][i].total_cmp(&a[j][j]));
    for (col, &src) in order.iter().enumerate().take(n) {
        out.values[col] = a[src][src];
        for row in 0..n {
            out.vectors[row][col] = v[row][src];
        }
    }
    out
}
