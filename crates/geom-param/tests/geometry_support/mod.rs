//! Shared checks for the geometry tests: a seeded PRNG and finite-difference checks of the
//! derivatives every `Surface`, `Curve` and `Curve2` reports, run the same way on every
//! implementation.
//!
//! Error model. A central difference (g(x+h) − g(x−h)) / 2h differs from g'(x) by at most
//! h² M3 / 6 (truncation, M3 ≥ |g'''| on the stencil) plus about ε A / h (rounding, A the size
//! of the terms in g). Each parameter direction gets h = 1e-5 times its smallest smooth piece
//! (the domain, or the shortest knot interval of a B-spline), so for a function smooth on that
//! scale L the truncation is ~1e-10 of |g'| and the rounding ~1e-11 |g| / L: far below the
//! tolerance 1e-6 (|analytic| + the largest derivative of that order over the samples), while
//! any wrong term in a derivative is of the order of the derivative itself. Samples keep 2h
//! away from the ends of every smooth piece, so no stencil crosses a knot or leaves the domain.

#![allow(dead_code)]

use geom_param::{Curve, Curve2, DVec2, DVec3, Surface};

/// Relative tolerance of a finite-difference derivative check.
pub const FD_RELATIVE_TOL: f64 = 1e-6;
/// Samples per surface or curve.
pub const SAMPLES: usize = 400;

/// SplitMix64 (Steele, Lea, Flood 2014): a tiny, seedable, portable PRNG.
pub struct SplitMix64(pub u64);

impl SplitMix64 {
    /// Next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1) with 53 random bits.
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }

    /// Uniform in [lo, hi).
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }

    /// Uniform unit vector.
    pub fn direction(&mut self) -> DVec3 {
        let z = self.range(-1.0, 1.0);
        let phi = self.range(0.0, std::f64::consts::TAU);
        let s = (1.0 - z * z).sqrt();
        DVec3::new(s * phi.cos(), s * phi.sin(), z)
    }
}

/// The smooth pieces of one parameter: the sorted distinct break points (domain ends and
/// interior knots), a finite-difference step for them, and a sampler that keeps every stencil
/// inside one piece.
pub struct Pieces {
    breaks: Vec<f64>,
    /// The step h.
    pub h: f64,
}

impl Pieces {
    /// Pieces of [min, max] split at `interior` (values outside (min, max) are ignored).
    pub fn new(min: f64, max: f64, interior: &[f64]) -> Self {
        let mut breaks: Vec<f64> = interior
            .iter()
            .copied()
            .filter(|&t| t > min && t < max)
            .collect();
        breaks.push(min);
        breaks.push(max);
        breaks.sort_by(f64::total_cmp);
        breaks.dedup();
        let shortest = breaks
            .windows(2)
            .map(|w| w[1] - w[0])
            .fold(f64::INFINITY, f64::min);
        Self {
            breaks,
            h: 1e-5 * shortest,
        }
    }

    /// A random parameter at least 2h inside a random piece.
    pub fn sample(&self, rng: &mut SplitMix64) -> f64 {
        let piece = (rng.next_u64() % (self.breaks.len() as u64 - 1)) as usize;
        let (lo, hi) = (self.breaks[piece], self.breaks[piece + 1]);
        rng.range(lo + 2.0 * self.h, hi - 2.0 * self.h)
    }
}

/// Central difference of `g` at `x`, divided by the exact representable step.
pub fn central<V>(g: impl Fn(f64) -> V, x: f64, h: f64) -> V
where
    V: std::ops::Sub<Output = V> + std::ops::Div<f64, Output = V>,
{
    let (xp, xm) = (x + h, x - h);
    (g(xp) - g(xm)) / (xp - xm)
}

#[track_caller]
fn check(what: &str, analytic: DVec3, numeric: DVec3, scale: f64) {
    let err = (analytic - numeric).length();
    let tol = FD_RELATIVE_TOL * (analytic.length() + scale);
    assert!(
        err <= tol,
        "{what}: analytic {analytic:?} vs finite difference {numeric:?}: error {err:e} > {tol:e}"
    );
}

/// Checks du, dv against differences of the point, duu, duv, dvv against differences of du and
/// dv (duv both ways), at `SAMPLES` seeded points inside the smooth pieces `pieces` = [u, v];
/// also that [`Surface::normal`], where the cross product is well conditioned, is du × dv
/// normalised (to 1e-9), and that [`Surface::principal_curvatures`] agrees with the
/// fundamental forms (to 1e-7 relative).
pub fn check_surface(name: &str, s: &dyn Surface, pieces: [&Pieces; 2], seed: u64) {
    let mut rng = SplitMix64(seed);
    let params: Vec<(f64, f64)> = (0..SAMPLES)
        .map(|_| (pieces[0].sample(&mut rng), pieces[1].sample(&mut rng)))
        .collect();
    let (mut first, mut second) = (0.0_f64, 0.0_f64);
    for &(u, v) in &params {
        let p = s.eval(u, v);
        first = first.max(p.du.length()).max(p.dv.length());
        second = second
            .max(p.duu.length())
            .max(p.duv.length())
            .max(p.dvv.length());
    }
    let (hu, hv) = (pieces[0].h, pieces[1].h);
    for &(u, v) in &params {
        let p = s.eval(u, v);
        let at = format!("{name} at (u, v) = ({u}, {v})");
        check(
            &format!("{at} du"),
            p.du,
            central(|x| s.eval(x, v).point, u, hu),
            first,
        );
        check(
            &format!("{at} dv"),
            p.dv,
            central(|x| s.eval(u, x).point, v, hv),
            first,
        );
        check(
            &format!("{at} duu"),
            p.duu,
            central(|x| s.eval(x, v).du, u, hu),
            second,
        );
        check(
            &format!("{at} duv (of du)"),
            p.duv,
            central(|x| s.eval(u, x).du, v, hv),
            second,
        );
        check(
            &format!("{at} duv (of dv)"),
            p.duv,
            central(|x| s.eval(x, v).dv, u, hu),
            second,
        );
        check(
            &format!("{at} dvv"),
            p.dvv,
            central(|x| s.eval(u, x).dv, v, hv),
            second,
        );
        let cross = p.du.cross(p.dv);
        if cross.length() > 1e-6 * p.du.length() * p.dv.length() {
            let n = s.normal(u, v).unwrap_or_else(|| panic!("{at}: no normal"));
            assert!(
                (n - cross.normalize()).length() < 1e-9,
                "{at}: normal {n:?} is not du x dv normalised {:?}",
                cross.normalize()
            );
            if let (Some(k), Some(forms)) =
                (s.principal_curvatures(u, v), p.principal_curvatures_with(n))
            {
                let scale = forms.min.abs().max(forms.max.abs()).max(1e-12);
                assert!(
                    (k.min - forms.min).abs() <= 1e-7 * scale
                        && (k.max - forms.max).abs() <= 1e-7 * scale,
                    "{at}: curvatures {k:?} disagree with the fundamental forms {forms:?}"
                );
            }
        }
    }
}

/// Checks d1 against differences of the point and d2 against differences of d1 at `SAMPLES`
/// seeded parameters inside `pieces`.
pub fn check_curve(name: &str, c: &dyn Curve, pieces: &Pieces, seed: u64) {
    let mut rng = SplitMix64(seed);
    let params: Vec<f64> = (0..SAMPLES).map(|_| pieces.sample(&mut rng)).collect();
    let first = params
        .iter()
        .map(|&t| c.eval(t).d1.length())
        .fold(0.0, f64::max);
    let second = params
        .iter()
        .map(|&t| c.eval(t).d2.length())
        .fold(0.0, f64::max);
    for &t in &params {
        let p = c.eval(t);
        let at = format!("{name} at t = {t}");
        check(
            &format!("{at} d1"),
            p.d1,
            central(|x| c.eval(x).point, t, pieces.h),
            first,
        );
        check(
            &format!("{at} d2"),
            p.d2,
            central(|x| c.eval(x).d1, t, pieces.h),
            second,
        );
    }
}

/// [`check_curve`] for a parameter-plane curve.
pub fn check_curve2(name: &str, c: &dyn Curve2, pieces: &Pieces, seed: u64) {
    let lift = |v: DVec2| v.extend(0.0);
    let mut rng = SplitMix64(seed);
    let params: Vec<f64> = (0..SAMPLES).map(|_| pieces.sample(&mut rng)).collect();
    let first = params
        .iter()
        .map(|&t| c.eval(t).d1.length())
        .fold(0.0, f64::max);
    let second = params
        .iter()
        .map(|&t| c.eval(t).d2.length())
        .fold(0.0, f64::max);
    for &t in &params {
        let p = c.eval(t);
        let at = format!("{name} at t = {t}");
        let d1 = central(|x| lift(c.eval(x).point), t, pieces.h);
        let d2 = central(|x| lift(c.eval(x).d1), t, pieces.h);
        check(&format!("{at} d1"), lift(p.d1), d1, first);
        check(&format!("{at} d2"), lift(p.d2), d2, second);
    }
}

/// The pieces of a parameter range without interior breaks.
pub fn whole(range: geom_param::ParamRange) -> Pieces {
    Pieces::new(range.min, range.max, &[])
}

/// The pieces of a B-spline basis: split at its distinct interior knots.
pub fn knot_pieces(basis: &geom_param::BSplineBasis) -> Pieces {
    let (min, max) = basis.domain();
    Pieces::new(min, max, basis.knots())
}
