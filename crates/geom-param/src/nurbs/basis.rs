//! A validated knot vector with its B-spline basis functions and their derivatives.

use crate::geometry_checks::finite;
use crate::geometry_error::GeometryError;
use crate::nurbs::{MAX_DEGREE, MAX_ORDER};

/// The non-zero basis functions of one knot span and their first two derivatives:
/// `ders[k][j]` = N^(k)_{span − p + j}(t) for k = 0, 1, 2 and j = 0..=p (entries beyond the
/// degree are 0).
pub type BasisDerivatives = [[f64; MAX_ORDER]; 3];

/// A B-spline basis of degree p over a knot vector U = (u_0, ..., u_{n+p+1}) for n + 1 control
/// points, knots repeated to give their multiplicity. The parameter domain is [u_p, u_{n+1}]
/// (clamped or not).
#[derive(Clone, Debug, PartialEq)]
pub struct BSplineBasis {
    degree: usize,
    knots: Vec<f64>,
}

impl BSplineBasis {
    /// The basis of degree `degree` over `knots` for `count` control points.
    ///
    /// # Errors
    /// [`GeometryError::BadDegree`] (0 or above [`MAX_DEGREE`]),
    /// [`GeometryError::TooFewControlPoints`] (count <= degree), [`GeometryError::KnotCount`]
    /// (length != count + degree + 1), [`GeometryError::NonFinite`],
    /// [`GeometryError::DecreasingKnots`], [`GeometryError::KnotMultiplicity`] (above
    /// degree + 1, or above degree strictly inside the domain, where the curve would break) and
    /// [`GeometryError::EmptyRange`] (u_p = u_{n+1}).
    pub fn new(degree: usize, knots: Vec<f64>, count: usize) -> Result<Self, GeometryError> {
        if degree == 0 || degree > MAX_DEGREE {
            return Err(GeometryError::BadDegree {
                degree,
                max: MAX_DEGREE,
            });
        }
        if count <= degree {
            return Err(GeometryError::TooFewControlPoints { count, degree });
        }
        let expected = count + degree + 1;
        if knots.len() != expected {
            return Err(GeometryError::KnotCount {
                expected,
                found: knots.len(),
            });
        }
        for &knot in &knots {
            finite("knot", knot)?;
        }
        if let Some(index) = (1..knots.len()).find(|&i| knots[i] < knots[i - 1]) {
            return Err(GeometryError::DecreasingKnots {
                index,
                knot: knots[index],
            });
        }
        let (start, end) = (knots[degree], knots[count]);
        if start >= end {
            return Err(GeometryError::EmptyRange {
                min: start,
                max: end,
            });
        }
        let mut first = 0;
        while first < knots.len() {
            let knot = knots[first];
            let multiplicity = knots[first..].iter().take_while(|&&k| k == knot).count();
            let max = if knot > start && knot < end {
                degree
            } else {
                degree + 1
            };
            if multiplicity > max {
                return Err(GeometryError::KnotMultiplicity {
                    knot,
                    multiplicity,
                    max,
                });
            }
            first += multiplicity;
        }
        Ok(Self { degree, knots })
    }

    /// The degree p.
    #[must_use]
    pub fn degree(&self) -> usize {
        self.degree
    }

    /// The knot vector, repeated knots included.
    #[must_use]
    pub fn knots(&self) -> &[f64] {
        &self.knots
    }

    /// Number of control points n + 1.
    #[must_use]
    pub fn count(&self) -> usize {
        self.knots.len() - self.degree - 1
    }

    /// The parameter domain [u_p, u_{n+1}].
    #[must_use]
    pub fn domain(&self) -> (f64, f64) {
        (self.knots[self.degree], self.knots[self.count()])
    }

    /// The knot span index i with u_i <= t < u_{i+1} and p <= i <= n (The NURBS Book A2.1,
    /// binary search): t at or beyond the domain's end gives the last span, t at or before its
    /// start the first. A NaN `t` gives some valid span (and NaN basis values), never a panic.
    #[must_use]
    pub fn find_span(&self, t: f64) -> usize {
        let (p, n) = (self.degree, self.count() - 1);
        let u = &self.knots;
        if t >= u[n + 1] {
            return n;
        }
        if t <= u[p] {
            return p;
        }
        let (mut low, mut high) = (p, n + 1);
        let mut mid = (low + high) / 2;
        while t < u[mid] || t >= u[mid + 1] {
            if t < u[mid] {
                high = mid;
            } else {
                low = mid;
            }
            mid = (low + high) / 2;
        }
        mid
    }

    /// The p + 1 non-zero basis functions on knot span `span` at `t` and their first and second
    /// derivatives (The NURBS Book A2.3, DersBasisFuns, with n = min(2, p); higher orders are
    /// identically 0). Stack arrays only.
    ///
    /// Degrees 1 to 3 (every analytic conversion and most CAD surfaces) run a copy of the
    /// algorithm with the degree and the array sizes fixed at compile time, so that its loops
    /// unroll and only their own scratch is cleared; the arithmetic is the same, operation for
    /// operation, so the values are bit for bit those of the general copy.
    #[must_use]
    pub fn derivatives(&self, span: usize, t: f64) -> BasisDerivatives {
        match self.degree {
            1 => ders_basis::<2>(&self.knots, 1, span, t),
            2 => ders_basis::<3>(&self.knots, 2, span, t),
            3 => ders_basis::<4>(&self.knots, 3, span, t),
            p => ders_basis::<MAX_ORDER>(&self.knots, p, span, t),
        }
    }
}

/// [`BSplineBasis::derivatives`] for degree `p` <= `O` − 1 over `knots`, with scratch arrays of
/// `O` entries.
#[inline(always)]
fn ders_basis<const O: usize>(knots: &[f64], p: usize, span: usize, t: f64) -> BasisDerivatives {
    let order = p.min(2);
    let u = knots;
    // ndu[r][j] (r <= j): the basis functions of degree j; ndu[j][r] (r < j): the
    // reciprocal knot differences 1 / (u_{i+r+1} − u_{i+1−j+r}) (the book stores the
    // differences; they are only ever divisors, so one division each is enough).
    let mut ndu = [[0.0; O]; O];
    let mut left = [0.0; O];
    let mut right = [0.0; O];
    ndu[0][0] = 1.0;
    for j in 1..=p {
        left[j] = t - u[span + 1 - j];
        right[j] = u[span + j] - t;
        let mut saved = 0.0;
        for r in 0..j {
            ndu[j][r] = 1.0 / (right[r + 1] + left[j - r]);
            let temp = ndu[r][j - 1] * ndu[j][r];
            ndu[r][j] = saved + right[r + 1] * temp;
            saved = left[j - r] * temp;
        }
        ndu[j][j] = saved;
    }
    let mut ders = [[0.0; MAX_ORDER]; 3];
    for j in 0..=p {
        ders[0][j] = ndu[j][p];
    }
    // a[s][*]: two rows of the coefficients a_{k,j} (The NURBS Book eq. 2.9), alternated.
    let mut a = [[0.0; O]; 2];
    for r in 0..=p {
        let (mut s1, mut s2) = (0, 1);
        a[0][0] = 1.0;
        for k in 1..=order {
            let mut d = 0.0;
            let pk = p - k;
            if r >= k {
                let rk = r - k;
                a[s2][0] = a[s1][0] * ndu[pk + 1][rk];
                d = a[s2][0] * ndu[rk][pk];
            }
            // j1 = 1 if r − k >= −1 else k − r; j2 = k − 1 if r − 1 <= p − k else p − r.
            let j1 = if r + 1 >= k { 1 } else { k - r };
            let j2 = if r <= pk + 1 { k - 1 } else { p - r };
            for j in j1..=j2 {
                // r − k + j >= 0 for j >= j1.
                let rkj = r + j - k;
                a[s2][j] = (a[s1][j] - a[s1][j - 1]) * ndu[pk + 1][rkj];
                d += a[s2][j] * ndu[rkj][pk];
            }
            if r <= pk {
                a[s2][k] = -a[s1][k - 1] * ndu[pk + 1][r];
                d += a[s2][k] * ndu[r][pk];
            }
            ders[k][r] = d;
            std::mem::swap(&mut s1, &mut s2);
        }
    }
    // Multiply by p!/(p − k)!.
    let mut factor = p as f64;
    for (k, row) in ders.iter_mut().enumerate().take(order + 1).skip(1) {
        for value in row.iter_mut().take(p + 1) {
            *value *= factor;
        }
        factor *= (p - k) as f64;
    }
    ders
}

#[cfg(test)]
pub(crate) mod tests {
    use super::{BSplineBasis, ders_basis};
    use crate::nurbs::MAX_ORDER;

    /// A clamped basis of `degree` over `count` control points with uneven interior knots.
    pub(crate) fn uneven_basis(degree: usize, count: usize) -> BSplineBasis {
        let interior = count - degree - 1;
        let mut knots = vec![0.0; degree + 1];
        let mut at = 0.0;
        for k in 0..interior {
            at += 0.5 + 0.37 * ((k * 7 + degree) % 5) as f64;
            knots.push(at);
        }
        let end = at + 1.3;
        knots.extend(std::iter::repeat_n(end, degree + 1));
        BSplineBasis::new(degree, knots, count).expect("a valid basis")
    }

    /// The copies for degrees 1 to 3 give bit for bit the values of the general copy, on every
    /// span and at its ends.
    #[test]
    fn fixed_degree_copies_match_the_general_one_exactly() {
        for degree in 1..=3 {
            let basis = uneven_basis(degree, degree + 6);
            let (start, end) = basis.domain();
            for k in 0..=200 {
                let t = start + (end - start) * f64::from(k) / 200.0;
                let span = basis.find_span(t);
                let general = ders_basis::<MAX_ORDER>(&basis.knots, degree, span, t);
                assert_eq!(
                    basis.derivatives(span, t),
                    general,
                    "degree {degree}, t {t}"
                );
            }
        }
    }
}
