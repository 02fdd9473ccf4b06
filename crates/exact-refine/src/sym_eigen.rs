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
    // Plain loops (no iterator adapters): this runs once or twice per Newton step. The
    // rotations keep `a` exactly symmetric, so only the upper triangle is summed.
    let mut norm2 = 0.0;
    for i in 0..n {
        for j in 0..n {
            norm2 += a[i][j] * a[i][j];
        }
    }
    for _ in 0..MAX_SWEEPS {
        let mut off = 0.0;
        for i in 0..n {
            for j in i + 1..n {
                off += 2.0 * a[i][j] * a[i][j];
            }
        }
        if off.is_nan() || off <= 16.0 * f64::EPSILON * f64::EPSILON * norm2 {
            break;
        }
        for p in 0..n {
            for q in p + 1..n {
                let apq = a[p][q];
                if apq == 0.0 {
                    continue;
                }
                // Rotation that zeroes a[p][q] (the stable form of Rutishauser), applied to the
                // two rows and columns it changes: x' = x - s (y + τ x), y' = y + s (x - τ y)
                // with τ = s / (1 + c), i.e. (c x - s y, s x + c y).
                let theta = (a[q][q] - a[p][p]) / (2.0 * apq);
                let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
                let t = if theta == 0.0 { 1.0 } else { t };
                let c = 1.0 / (t * t + 1.0).sqrt();
                let s = t * c;
                let tau = s / (1.0 + c);
                a[p][p] -= t * apq;
                a[q][q] += t * apq;
                a[p][q] = 0.0;
                a[q][p] = 0.0;
                for k in 0..n {
                    if k != p && k != q {
                        let (x, y) = (a[k][p], a[k][q]);
                        a[k][p] = x - s * (y + tau * x);
                        a[k][q] = y + s * (x - tau * y);
                        a[p][k] = a[k][p];
                        a[q][k] = a[k][q];
                    }
                }
                for row in v.iter_mut().take(n) {
                    let (x, y) = (row[p], row[q]);
                    row[p] = x - s * (y + tau * x);
                    row[q] = y + s * (x - tau * y);
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
