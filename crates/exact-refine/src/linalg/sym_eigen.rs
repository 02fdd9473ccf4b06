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
    match n {
        0 => jacobi::<0, true>(matrix),
        1 => jacobi::<1, true>(matrix),
        2 => jacobi::<2, true>(matrix),
        3 => jacobi::<3, true>(matrix),
        _ => jacobi::<4, true>(matrix),
    }
}

/// The eigenvalues of [`sym_eigen`] (ascending, entries from `n` on zero) without the
/// eigenvectors: the same rotations, so bit for bit the same values, for callers that need
/// only the spectrum (conditioning, the second-order test). The vectors' updates are about
/// half the work of a rotation.
pub(crate) fn sym_eigenvalues(matrix: &[[f64; 4]; 4], n: usize) -> [f64; 4] {
    match n {
        0 => jacobi::<0, false>(matrix),
        1 => jacobi::<1, false>(matrix),
        2 => jacobi::<2, false>(matrix),
        3 => jacobi::<3, false>(matrix),
        _ => jacobi::<4, false>(matrix),
    }
    .values
}

/// [`sym_eigenvalues`] of `K` matrices at once (the leading `n` x `n` blocks of each): each
/// gets exactly the rotations [`sym_eigenvalues`] would give it, so the same bits, but they run
/// in lockstep. A rotation is a chain of divisions and square roots, each waiting for the
/// last; independent chains side by side keep the processor busy in each other's waits.
pub(crate) fn sym_eigenvalues_lockstep<const K: usize>(
    matrices: [&[[f64; 4]; 4]; K],
    n: usize,
) -> [[f64; 4]; K] {
    match n {
        0 => jacobi_lockstep::<0, K>(matrices),
        1 => jacobi_lockstep::<1, K>(matrices),
        2 => jacobi_lockstep::<2, K>(matrices),
        3 => jacobi_lockstep::<3, K>(matrices),
        _ => jacobi_lockstep::<4, K>(matrices),
    }
}

/// [`sym_eigenvalues_lockstep`] on the leading `N` x `N` blocks: each matrix stops rotating at
/// the first sweep that finds it converged, as [`jacobi`] stops, and gets at most `MAX_SWEEPS`.
fn jacobi_lockstep<const N: usize, const K: usize>(matrices: [&[[f64; 4]; 4]; K]) -> [[f64; 4]; K] {
    let mut a = matrices.map(|m| *m);
    let norm2 = a.map(|m| {
        let mut norm2 = 0.0;
        for i in 0..N {
            for j in 0..N {
                norm2 += m[i][j] * m[i][j];
            }
        }
        norm2
    });
    let mut done = [false; K];
    for _ in 0..MAX_SWEEPS {
        for (m, (finished, norm2)) in a.iter().zip(done.iter_mut().zip(norm2)) {
            if !*finished {
                let mut off = 0.0;
                for i in 0..N {
                    for j in i + 1..N {
                        off += 2.0 * m[i][j] * m[i][j];
                    }
                }
                *finished = off.is_nan() || off <= 16.0 * f64::EPSILON * f64::EPSILON * norm2;
            }
        }
        if done.iter().all(|&finished| finished) {
            break;
        }
        for p in 0..N {
            for q in p + 1..N {
                for (m, finished) in a.iter_mut().zip(done) {
                    if !finished {
                        rotate::<N>(m, p, q);
                    }
                }
            }
        }
    }
    a.map(|m| sorted_diagonal::<N>(&m))
}

/// The diagonal of `a`'s leading `N` x `N` block in ascending order (entries from `N` on
/// zero), by the stable insertion sort of [`jacobi`].
fn sorted_diagonal<const N: usize>(a: &[[f64; 4]; 4]) -> [f64; 4] {
    let mut order = [0, 1, 2, 3];
    for i in 1..N {
        let mut j = i;
        while j > 0
            && a[order[j - 1]][order[j - 1]]
                .total_cmp(&a[order[j]][order[j]])
                .is_gt()
        {
            order.swap(j - 1, j);
            j -= 1;
        }
    }
    let mut values = [0.0; 4];
    for (col, &src) in order.iter().enumerate().take(N) {
        values[col] = a[src][src];
    }
    values
}

/// Sweeps of [`jacobi`] at most; 4 x 4 matrices need about 4-6, so the cap is never the limit
/// on finite input.
const MAX_SWEEPS: usize = 32;

/// The Jacobi rotation of [`jacobi`] that zeroes `a[p][q]` (nothing when it is zero already),
/// applied to the leading `N` x `N` block of `a`, which it keeps exactly symmetric; returns
/// (s, τ) for the eigenvectors' update, `None` when there was no rotation.
fn rotate<const N: usize>(a: &mut [[f64; 4]; 4], p: usize, q: usize) -> Option<(f64, f64)> {
    let apq = a[p][q];
    if apq == 0.0 {
        return None;
    }
    // Rotation that zeroes a[p][q] (the stable form of Rutishauser), applied to the two rows
    // and columns it changes: x' = x - s (y + τ x), y' = y + s (x - τ y) with τ = s / (1 + c),
    // i.e. (c x - s y, s x + c y).
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
    for k in 0..N {
        if k != p && k != q {
            let (x, y) = (a[k][p], a[k][q]);
            a[k][p] = x - s * (y + tau * x);
            a[k][q] = y + s * (x - tau * y);
            a[p][k] = a[k][p];
            a[q][k] = a[k][q];
        }
    }
    Some((s, tau))
}

/// [`sym_eigen`] on the leading `N` x `N` block, accumulating the eigenvectors when `VECTORS`
/// (otherwise `vectors` is zero). A constant size lets the compiler unroll the loops; the
/// arithmetic, and its order, is the same for every `N`.
fn jacobi<const N: usize, const VECTORS: bool>(matrix: &[[f64; 4]; 4]) -> SymEigen {
    let mut a = *matrix;
    let mut v = [[0.0; 4]; 4];
    if VECTORS {
        for i in 0..N {
            v[i][i] = 1.0;
        }
    }
    // The rotations keep `a` exactly symmetric, so only the upper triangle is summed.
    let mut norm2 = 0.0;
    for i in 0..N {
        for j in 0..N {
            norm2 += a[i][j] * a[i][j];
        }
    }
    for _ in 0..MAX_SWEEPS {
        let mut off = 0.0;
        for i in 0..N {
            for j in i + 1..N {
                off += 2.0 * a[i][j] * a[i][j];
            }
        }
        if off.is_nan() || off <= 16.0 * f64::EPSILON * f64::EPSILON * norm2 {
            break;
        }
        for p in 0..N {
            for q in p + 1..N {
                let Some((s, tau)) = rotate::<N>(&mut a, p, q) else {
                    continue;
                };
                if VECTORS {
                    for row in v.iter_mut().take(N) {
                        let (x, y) = (row[p], row[q]);
                        row[p] = x - s * (y + tau * x);
                        row[q] = y + s * (x - tau * y);
                    }
                }
            }
        }
    }
    // Sort ascending (at most 4 entries; a stable insertion sort, so equal values keep their
    // columns' order).
    let mut order = [0, 1, 2, 3];
    for i in 1..N {
        let mut j = i;
        while j > 0
            && a[order[j - 1]][order[j - 1]]
                .total_cmp(&a[order[j]][order[j]])
                .is_gt()
        {
            order.swap(j - 1, j);
            j -= 1;
        }
    }
    let mut out = SymEigen::default();
    for (col, &src) in order.iter().enumerate().take(N) {
        out.values[col] = a[src][src];
        if VECTORS {
            for row in 0..N {
                out.vectors[row][col] = v[row][src];
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::{sym_eigen, sym_eigenvalues, sym_eigenvalues_lockstep};

    /// A symmetric matrix with a planted spectrum: Q diag(λ) Qᵀ for a rotation Q (a product
    /// of plane rotations), so the eigenvalues are known without this module.
    fn planted(values: [f64; 4], n: usize) -> [[f64; 4]; 4] {
        let mut q = [[0.0; 4]; 4];
        for i in 0..n {
            q[i][i] = 1.0;
        }
        for (p, r, angle) in [
            (0, 1, 0.7),
            (1, 2, -1.1),
            (0, 3, 0.4),
            (2, 3, 2.3),
            (0, 2, 0.9),
        ] {
            if r >= n {
                continue;
            }
            let (s, c) = f64::sin_cos(angle);
            for row in q.iter_mut().take(n) {
                let (x, y) = (row[p], row[r]);
                row[p] = c * x - s * y;
                row[r] = s * x + c * y;
            }
        }
        let mut m = [[0.0; 4]; 4];
        for i in 0..n {
            for j in 0..n {
                m[i][j] = (0..n).map(|k| q[i][k] * values[k] * q[j][k]).sum();
            }
        }
        m
    }

    /// Every size finds the planted spectrum (ascending, to rounding of the norm), the
    /// vectors satisfy M v = λ v, and the values-only variant gives the same bits.
    #[test]
    fn planted_spectra_are_found_and_the_values_only_variants_agree() {
        let values = [-3.0, 1e-9, 2.5, 40.0];
        for n in 0..=4 {
            let mut sorted = values[..n].to_vec();
            sorted.sort_by(f64::total_cmp);
            let m = planted(values, n);
            let eigen = sym_eigen(&m, n);
            let only = sym_eigenvalues(&m, n);
            // Paired with a matrix that converges in fewer sweeps (nearly diagonal), and with
            // itself: each keeps its own bits.
            let mut near_diagonal = [[0.0; 4]; 4];
            for i in 0..n {
                for j in 0..n {
                    near_diagonal[i][j] = if i == j { 1.0 + i as f64 } else { 1e-9 };
                }
            }
            for (x, y) in [(m, near_diagonal), (near_diagonal, m), (m, m)] {
                let pair = sym_eigenvalues_lockstep([&x, &y], n);
                let single = [sym_eigenvalues(&x, n), sym_eigenvalues(&y, n)];
                assert_eq!(
                    pair.map(|v| v.map(f64::to_bits)),
                    single.map(|v| v.map(f64::to_bits))
                );
                let triple = sym_eigenvalues_lockstep([&x, &near_diagonal, &y], n);
                assert_eq!(triple[0].map(f64::to_bits), single[0].map(f64::to_bits));
                assert_eq!(triple[2].map(f64::to_bits), single[1].map(f64::to_bits));
            }
            for k in 0..n {
                assert!(
                    (eigen.values[k] - sorted[k]).abs() <= 1e-13 * 40.0,
                    "n {n} k {k}"
                );
                assert_eq!(eigen.values[k].to_bits(), only[k].to_bits(), "n {n} k {k}");
                for i in 0..n {
                    let mv: f64 = (0..n).map(|j| m[i][j] * eigen.vectors[j][k]).sum();
                    assert!((mv - eigen.values[k] * eigen.vectors[i][k]).abs() <= 1e-12 * 40.0);
                }
            }
        }
    }
}
