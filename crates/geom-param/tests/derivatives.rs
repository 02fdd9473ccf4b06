//! Finite-difference checks of the analytic first and second derivatives of profile segments
//! (line, ccw and cw arcs, cubic Beziers), of revolved surfaces (du, dv, duu, duv, dvv for each
//! segment kind) and of circle edges, at seeded random parameters.
//!
//! Error model (used for every tolerance below). For a function g with |g'''| ≤ M3 near x, the
//! central difference (g(x+h) - g(x-h)) / (2h) differs from g'(x) by at most
//!   h² M3 / 6                (Taylor truncation, O(h²))
//! plus the rounding of the two evaluations divided by 2h. Each evaluation is a short sum of
//! terms (Bernstein products, centre + radius·(cos, sin), r·(cos u, sin u)) whose magnitudes add
//! up to at most A; a term is computed with a relative error of a few ulps (one product, sin_cos
//! within 1 ulp, the argument θ0 + φs within ε|θ|, which A includes), so |error of g| ≤ 4εA and
//! the quotient carries at most 2·4εA / (2h) = 4εA/h; the bound takes C = 8 (a factor 2 over
//! that estimate for the additions not counted). The step is the exact difference of the two
//! representable abscissae (x ± h are within a factor 2 of each other, so Sterbenz makes
//! (x + h) - (x - h) exact). So
//!   tol = h² M3 / 6 + C ε A / h.
//! With h = 1e-5 (near the optimum (3εA/M3)^(1/3) for the unit-scale parameters s, u, v) this is
//! ~1e-8 of the derivatives' size, while any wrong term in a derivative is O(1) of it.
//!
//! Second derivatives are checked twice: as the central difference of the analytic first
//! derivative (same bound with the next derivative), and directly from the point by the second
//! difference (g(x+k) - 2g(x) + g(x-k)) / k², whose error is k² M4 / 12 + 4·4εA/k²; there
//! k = 1e-4 (near the optimum (48·4εA/M4)^(1/4)), so that bound is ~1e-6 relative.

use geom_param::{
    ArcSegment, CircleEdge, CubicBezier, Curve, DVec2, DVec3, LineSegment, ProfileSegment,
    RevolvedSurface, Surface,
};
use std::f64::consts::{PI, TAU};

/// First-difference step.
const H: f64 = 1e-5;
/// Second-difference step.
const K: f64 = 1e-4;
/// Rounding safety constant C of the error model.
const C: f64 = 8.0;
const EPS: f64 = f64::EPSILON;
/// Random samples per segment.
const SAMPLES: usize = 1000;

/// SplitMix64 (Steele, Lea, Flood 2014): a tiny, seedable, portable PRNG.
struct SplitMix64(u64);

impl SplitMix64 {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1) with 53 random bits.
    fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }

    /// Uniform in [lo, hi).
    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }
}

/// Central difference of `g` at `x` with step `h`, divided by the exact representable step.
fn central(g: impl Fn(f64) -> DVec3, x: f64, h: f64) -> DVec3 {
    let (xp, xm) = (x + h, x - h);
    (g(xp) - g(xm)) / (xp - xm)
}

/// Second difference of `g` at `x` with step `k`.
fn second(g: impl Fn(f64) -> DVec3, x: f64, k: f64) -> DVec3 {
    let (xp, xm) = (x + k, x - k);
    // x ± k are representable neighbours; use their actual distances (equal to k up to an ulp
    // of x, which is below the rounding term).
    let (hp, hm) = (xp - x, x - xm);
    ((g(xp) - g(x)) / hp - (g(x) - g(xm)) / hm) * (2.0 / (hp + hm))
}

/// Tolerance of a central first difference: truncation with |g'''| ≤ m3, rounding with term
/// magnitude a.
fn tol_first(m3: f64, a: f64) -> f64 {
    H * H * m3 / 6.0 + C * EPS * a / H
}

/// Tolerance of a second difference: truncation with |g''''| ≤ m4, rounding with term
/// magnitude a.
fn tol_second(m4: f64, a: f64) -> f64 {
    K * K * m4 / 12.0 + 4.0 * C * EPS * a / (K * K)
}

use std::cell::Cell;

thread_local! {
    /// Largest error / tolerance seen by `check` in this test (printed with --nocapture).
    static WORST: Cell<f64> = const { Cell::new(0.0) };
}

#[track_caller]
fn check(what: &str, analytic: DVec3, numeric: DVec3, tol: f64) {
    let err = (analytic - numeric).length();
    assert!(
        err <= tol,
        "{what}: analytic {analytic:?} vs finite difference {numeric:?}: error {err:e} > tol {tol:e}"
    );
    WORST.with(|w| w.set(w.get().max(err / tol)));
}

fn report(test: &str) {
    eprintln!(
        "{test}: worst error / tolerance = {:.3e}",
        WORST.with(Cell::get)
    );
}

/// Bounds of one segment over its parameter range: `m[j]` ≥ |d^j(r, z)/ds^j| for j = 0..=4
/// (m[0] bounds |r| too), and `a[j]` ≥ the summed magnitude of the terms that make up the
/// computed j-th derivative (the A of the error model).
struct Bounds {
    m: [f64; 5],
    a: [f64; 3],
}

fn bounds(segment: &ProfileSegment) -> Bounds {
    match *segment {
        ProfileSegment::Line(l) => {
            let (f, t) = (l.from.length(), l.to.length());
            let d = (l.to - l.from).length();
            Bounds {
                m: [f.max(t), d, 0.0, 0.0, 0.0],
                a: [f + t + d, f + t, 0.0],
            }
        }
        ProfileSegment::Arc(a) => {
            // |θ| over the segment, for the rounding of θ = θ0 + φ s.
            let theta = a.start_angle.abs() + a.sweep.abs();
            let (r, phi) = (a.radius, a.sweep.abs());
            let m = [
                a.center.length() + r,
                r * phi,
                r * phi.powi(2),
                r * phi.powi(3),
                r * phi.powi(4),
            ];
            let grow = 1.0 + theta;
            Bounds {
                m,
                a: [a.center.length() + r * grow, m[1] * grow, m[2] * grow],
            }
        }
        ProfileSegment::Bezier(b) => {
            let [p0, p1, p2, p3] = b.points;
            let pmax = b.points.iter().map(|p| p.length()).fold(0.0, f64::max);
            // Derivatives are 3, 6 and 6 times differences of the control points; each
            // difference is bounded by the sum of the points' magnitudes.
            let leg = [(p1 - p0).length(), (p2 - p1).length(), (p3 - p2).length()];
            let m1 = 3.0 * leg.iter().fold(0.0_f64, |m, &l| m.max(l));
            let m2 = 6.0
                * (p2 - 2.0 * p1 + p0)
                    .length()
                    .max((p3 - 2.0 * p2 + p1).length());
            let m3 = 6.0 * (p3 - 3.0 * p2 + 3.0 * p1 - p0).length();
            Bounds {
                m: [pmax, m1, m2, m3, 0.0],
                a: [pmax, 6.0 * pmax, 24.0 * pmax],
            }
        }
    }
}

fn arc(center: [f64; 2], radius: f64, start_angle: f64, sweep: f64) -> ProfileSegment {
    ProfileSegment::Arc(ArcSegment {
        center: center.into(),
        radius,
        start_angle,
        sweep,
    })
}

fn line(from: [f64; 2], to: [f64; 2]) -> ProfileSegment {
    ProfileSegment::Line(LineSegment {
        from: from.into(),
        to: to.into(),
    })
}

fn bezier(points: [[f64; 2]; 4]) -> ProfileSegment {
    ProfileSegment::Bezier(CubicBezier {
        points: points.map(DVec2::from),
    })
}

/// A fixed set of segments of every kind, plus random Beziers.
fn segments() -> Vec<(String, ProfileSegment)> {
    let mut out = vec![
        ("line (cylinder)".into(), line([8.0, -3.0], [8.0, 17.0])),
        ("line (cone)".into(), line([6.0, 0.0], [0.0, 14.0])),
        ("line (slanted)".into(), line([31.0, -7.5], [12.0, 40.25])),
        (
            "arc ccw (sphere)".into(),
            arc([0.0, 3.0], 7.0, -PI / 2.0, PI),
        ),
        ("arc ccw (torus)".into(), arc([20.0, 1.0], 5.0, 0.3, 2.5)),
        (
            "arc ccw (near-full)".into(),
            arc([20.0, 0.0], 5.0, -PI / 2.0 + 0.01, TAU - 0.02),
        ),
        (
            "arc cw (socket)".into(),
            arc([0.0, 12.0], 5.0, PI / 2.0, -PI),
        ),
        ("arc cw (fillet)".into(), arc([14.0, -6.0], 0.75, 2.0, -3.0)),
        (
            "bezier".into(),
            bezier([[35.0, 5.0], [40.0, 20.0], [45.0, 30.0], [45.0, 40.0]]),
        ),
        (
            "bezier (s-curve)".into(),
            bezier([[2.0, 0.0], [12.0, 1.0], [-3.0, 9.0], [6.0, 10.0]]),
        ),
    ];
    let mut rng = SplitMix64(0xDE41_0001);
    for i in 0..4 {
        let mut p = || [rng.range(0.5, 50.0), rng.range(-50.0, 50.0)];
        out.push((format!("bezier (random {i})"), bezier([p(), p(), p(), p()])));
    }
    out
}

fn v3(p: DVec2) -> DVec3 {
    p.extend(0.0)
}

#[test]
fn profile_segment_derivatives_match_finite_differences() {
    let mut rng = SplitMix64(0xDE41_0002);
    for (name, seg) in segments() {
        let b = bounds(&seg);
        let point = |s: f64| v3(seg.eval(s).point);
        let d1 = |s: f64| v3(seg.eval(s).d1);
        for _ in 0..SAMPLES {
            // Inside (0, 1) with room for the steps (and Sterbenz-exact steps).
            let s = rng.range(0.01, 0.99);
            let e = seg.eval(s);
            let what = format!("{name} at s = {s}");
            check(
                &format!("{what}: d1"),
                v3(e.d1),
                central(point, s, H),
                tol_first(b.m[3], b.a[0]),
            );
            check(
                &format!("{what}: d2"),
                v3(e.d2),
                central(d1, s, H),
                tol_first(b.m[4], b.a[1]),
            );
            check(
                &format!("{what}: d2 from points"),
                v3(e.d2),
                second(point, s, K),
                tol_second(b.m[4], b.a[0]),
            );
        }
    }
    report("profile");
}

/// The arc's derivatives also satisfy the circle's identities exactly: d1 ⊥ radius with
/// |d1| = R|φ|, d2 = -φ² (point - centre). Independent of finite differences, and sensitive to the
/// sign of the sweep.
#[test]
fn arc_derivatives_satisfy_circle_identities() {
    let mut rng = SplitMix64(0xDE41_0003);
    for _ in 0..SAMPLES {
        let center = DVec2::new(rng.range(0.0, 30.0), rng.range(-30.0, 30.0));
        let radius = rng.range(0.1, 20.0);
        let start_angle = rng.range(-PI, PI);
        let sweep = rng.range(0.1, TAU - 0.1) * if rng.unit() < 0.5 { -1.0 } else { 1.0 };
        let seg = ProfileSegment::Arc(ArcSegment {
            center,
            radius,
            start_angle,
            sweep,
        });
        let s = rng.unit();
        let e = seg.eval(s);
        let rel = e.point - center;
        let scale = radius * (1.0 + start_angle.abs() + sweep.abs());
        let tol = 1e-12 * scale;
        assert!(
            (rel.length() - radius).abs() <= tol,
            "radius {} vs {radius}",
            rel.length()
        );
        assert!(
            rel.dot(e.d1).abs() <= tol * radius * sweep.abs(),
            "d1 not tangent"
        );
        // Direction of travel: counter-clockwise when sweep > 0 (d1 is rel turned left).
        let expected_d1 = rel.perp() * sweep;
        assert!(
            (e.d1 - expected_d1).length() <= tol * sweep.abs(),
            "{:?} vs {expected_d1:?}",
            e.d1
        );
        let expected_d2 = -rel * (sweep * sweep);
        assert!(
            (e.d2 - expected_d2).length() <= tol * sweep * sweep,
            "{:?} vs {expected_d2:?}",
            e.d2
        );
    }
}

#[test]
fn revolved_surface_derivatives_match_finite_differences() {
    let mut rng = SplitMix64(0xDE41_0004);
    for (name, seg) in segments() {
        let surface = RevolvedSurface { segment: seg };
        let b = bounds(&seg);
        // Bounds of the partial derivatives of S: a u-derivative only rotates (r, 0) and
        // multiplies by cos or sin, so |∂^(i+j) S / ∂u^i ∂v^j| ≤ m[j] (m[0] ≥ r). The computed
        // terms are those of the profile times cos u or sin u (one more rounding, inside C).
        let [m0, m1, _, m3, m4] = b.m;
        let [a0, a1, _] = b.a;
        for _ in 0..SAMPLES {
            let u = rng.range(0.01, TAU);
            let v = rng.range(0.01, 0.99);
            let e = surface.eval(u, v);
            let what = format!("{name} at (u, v) = ({u}, {v})");
            let at_u =
                |f: fn(&geom_param::SurfacePoint) -> DVec3| move |x: f64| f(&surface.eval(x, v));
            let at_v =
                |f: fn(&geom_param::SurfacePoint) -> DVec3| move |x: f64| f(&surface.eval(u, x));
            let point: fn(&geom_param::SurfacePoint) -> DVec3 = |p| p.point;
            let du: fn(&geom_param::SurfacePoint) -> DVec3 = |p| p.du;
            let dv: fn(&geom_param::SurfacePoint) -> DVec3 = |p| p.dv;

            // ∂³S/∂u³ = r·(…) → m0; ∂³S/∂v³ → m3.
            check(
                &format!("{what}: du"),
                e.du,
                central(at_u(point), u, H),
                tol_first(m0, a0),
            );
            check(
                &format!("{what}: dv"),
                e.dv,
                central(at_v(point), v, H),
                tol_first(m3, a0),
            );
            // ∂³(S_u)/∂u³ → m0; ∂³(S_u)/∂v³ → m3; ∂³(S_v)/∂u³ → m1; ∂³(S_v)/∂v³ → m4.
            check(
                &format!("{what}: duu"),
                e.duu,
                central(at_u(du), u, H),
                tol_first(m0, a0),
            );
            check(
                &format!("{what}: duv (d/dv of du)"),
                e.duv,
                central(at_v(du), v, H),
                tol_first(m3, a0),
            );
            check(
                &format!("{what}: duv (d/du of dv)"),
                e.duv,
                central(at_u(dv), u, H),
                tol_first(m1, a1),
            );
            check(
                &format!("{what}: dvv"),
                e.dvv,
                central(at_v(dv), v, H),
                tol_first(m4, a1),
            );
            // Second derivatives straight from the point.
            check(
                &format!("{what}: duu from points"),
                e.duu,
                second(at_u(point), u, K),
                tol_second(m0, a0),
            );
            check(
                &format!("{what}: dvv from points"),
                e.dvv,
                second(at_v(point), v, K),
                tol_second(m4, a0),
            );
        }
    }
    report("revolved");
}

#[test]
fn circle_edge_derivatives_match_finite_differences() {
    let mut rng = SplitMix64(0xDE41_0005);
    for (radius, z) in [(1.0, 0.0), (37.5, -12.0), (0.003, 4.0), (250.0, 1e3)] {
        let edge = CircleEdge { radius, z };
        let point = |t: f64| edge.eval(t).point;
        let d1 = |t: f64| edge.eval(t).d1;
        // Every derivative of C has magnitude r; the point's terms add up to r + |z|.
        let (m, a0, a1) = (radius, radius + z.abs(), radius);
        for _ in 0..SAMPLES {
            let t = rng.range(0.01, TAU);
            let c = edge.eval(t);
            let what = format!("circle r = {radius}, z = {z} at t = {t}");
            check(
                &format!("{what}: d1"),
                c.d1,
                central(point, t, H),
                tol_first(m, a0),
            );
            check(
                &format!("{what}: d2"),
                c.d2,
                central(d1, t, H),
                tol_first(m, a1),
            );
            check(
                &format!("{what}: d2 from points"),
                c.d2,
                second(point, t, K),
                tol_second(m, a0),
            );
        }
    }
    report("circle");
}
