//! Profile segments: planar curves in the (r, z) half-plane that are revolved about the z axis.
//!
//! Every segment is parametrised by s in [0, 1] from its start to its end. Points are
//! `DVec2 { x: r, y: z }` in millimetres.

use glam::DVec2;
use std::f64::consts::TAU;

/// Position and derivatives of a profile segment at one parameter s.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ProfilePoint {
    /// (r, z).
    pub point: DVec2,
    /// d(r, z)/ds.
    pub d1: DVec2,
    /// d²(r, z)/ds².
    pub d2: DVec2,
}

impl ProfilePoint {
    /// Signed curvature of the profile (1/mm): positive where it turns left (counter-clockwise),
    /// which, with the material on the left, is convex.
    #[must_use]
    pub fn signed_curvature(&self) -> f64 {
        let speed = self.d1.length();
        self.d1.perp_dot(self.d2) / (speed * speed * speed)
    }

    /// Unit outward normal in the (r, z) plane: the tangent turned clockwise, (dz, -dr)/|.|.
    #[must_use]
    pub fn outward_normal(&self) -> DVec2 {
        DVec2::new(self.d1.y, -self.d1.x).normalize_or_zero()
    }
}

/// A straight segment: revolves into a disk or annulus, a cylinder or a cone.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LineSegment {
    /// Start (r, z).
    pub from: DVec2,
    /// End (r, z).
    pub to: DVec2,
}

/// A circular arc: revolves into a sphere zone or a torus zone.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ArcSegment {
    /// Centre (r, z).
    pub center: DVec2,
    /// Radius (mm).
    pub radius: f64,
    /// Polar angle of the start about the centre (rad).
    pub start_angle: f64,
    /// Signed swept angle (rad): positive counter-clockwise, |sweep| in (0, 2π).
    pub sweep: f64,
}

/// A cubic Bezier segment: revolves into a general surface of revolution.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CubicBezier {
    /// Control points P0..P3 (r, z); the curve runs from P0 to P3.
    pub points: [DVec2; 4],
}

/// One segment of a profile.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ProfileSegment {
    /// A straight segment.
    Line(LineSegment),
    /// A circular arc.
    Arc(ArcSegment),
    /// A cubic Bezier.
    Bezier(CubicBezier),
}

impl ArcSegment {
    /// The arc about `center` from `from` to `to`, counter-clockwise when `ccw`. The radius is
    /// taken from `from`; checking that `to` is at the same distance is the caller's job.
    #[must_use]
    pub fn from_endpoints(center: DVec2, from: DVec2, to: DVec2, ccw: bool) -> Self {
        let a = from - center;
        let b = to - center;
        let start_angle = a.y.atan2(a.x);
        let delta = (b.y.atan2(b.x) - start_angle).rem_euclid(TAU);
        let sweep = if ccw { delta } else { delta - TAU };
        Self {
            center,
            radius: a.length(),
            start_angle,
            sweep,
        }
    }
}

impl ProfileSegment {
    /// Position and derivatives at s in [0, 1].
    #[must_use]
    pub fn eval(&self, s: f64) -> ProfilePoint {
        match self {
            Self::Line(l) => ProfilePoint {
                point: l.from + (l.to - l.from) * s,
                d1: l.to - l.from,
                d2: DVec2::ZERO,
            },
            Self::Arc(a) => {
                let theta = a.start_angle + a.sweep * s;
                let (sin, cos) = theta.sin_cos();
                let radial = DVec2::new(cos, sin);
                ProfilePoint {
                    point: a.center + radial * a.radius,
                    d1: DVec2::new(-sin, cos) * (a.radius * a.sweep),
                    d2: -radial * (a.radius * a.sweep * a.sweep),
                }
            }
            Self::Bezier(b) => {
                let [p0, p1, p2, p3] = b.points;
                let t = 1.0 - s;
                ProfilePoint {
                    point: p0 * (t * t * t)
                        + p1 * (3.0 * t * t * s)
                        + p2 * (3.0 * t * s * s)
                        + p3 * (s * s * s),
                    d1: (p1 - p0) * (3.0 * t * t)
                        + (p2 - p1) * (6.0 * t * s)
                        + (p3 - p2) * (3.0 * s * s),
                    d2: (p2 - 2.0 * p1 + p0) * (6.0 * t) + (p3 - 2.0 * p2 + p1) * (6.0 * s),
                }
            }
        }
    }

    /// Start point (r, z).
    #[must_use]
    pub fn start(&self) -> DVec2 {
        match self {
            Self::Line(l) => l.from,
            Self::Bezier(b) => b.points[0],
            Self::Arc(_) => self.eval(0.0).point,
        }
    }

    /// End point (r, z).
    #[must_use]
    pub fn end(&self) -> DVec2 {
        match self {
            Self::Line(l) => l.to,
            Self::Bezier(b) => b.points[3],
            Self::Arc(_) => self.eval(1.0).point,
        }
    }

    /// A short name of the segment kind: "line", "arc" or "bezier".
    #[must_use]
    pub fn kind_name(&self) -> &'static str {
        match self {
            Self::Line(_) => "line",
            Self::Arc(_) => "arc",
            Self::Bezier(_) => "bezier",
        }
    }

    /// Parameters in (0, 1) where the profile might change the sign of its signed curvature or of
    /// dz/ds, together with 0 and 1: evaluating a sign-relevant quantity there and at the
    /// midpoints between them decides its sign over the whole segment.
    ///
    /// For a line both are constant; for an arc dz/ds vanishes where the arc passes the
    /// horizontal tangent angles; for a Bezier r' z'' - z' r'' and z' are quadratics in s.
    #[must_use]
    pub fn sign_breakpoints(&self) -> Vec<f64> {
        let mut out = vec![0.0, 1.0];
        match self {
            Self::Line(_) => {}
            Self::Arc(a) => {
                // dz/ds ∝ cos θ: zero at θ = π/2 + kπ.
                for k in -4..=4 {
                    let theta = std::f64::consts::FRAC_PI_2 + f64::from(k) * std::f64::consts::PI;
                    let s = (theta - a.start_angle) / a.sweep;
                    if s > 0.0 && s < 1.0 {
                        out.push(s);
                    }
                }
            }
            Self::Bezier(b) => {
                let [p0, p1, p2, p3] = b.points;
                // z'(s)/3 = A t² + 2 B t s + C s² with t = 1 - s; as a polynomial in s:
                let (a, bb, c) = (p1.y - p0.y, p2.y - p1.y, p3.y - p2.y);
                push_quadratic_roots(a - 2.0 * bb + c, 2.0 * (bb - a), a, &mut out);
                // r'z'' - z'r'' is a quadratic in s: fit it through three samples.
                let cross = |s: f64| {
                    let e = self.eval(s);
                    e.d1.perp_dot(e.d2)
                };
                let (f0, fh, f1) = (cross(0.0), cross(0.5), cross(1.0));
                let qa = 2.0 * f0 - 4.0 * fh + 2.0 * f1;
                let qb = -3.0 * f0 + 4.0 * fh - f1;
                push_quadratic_roots(qa, qb, f0, &mut out);
                // r'(s): where r has its extrema (used for the r >= 0 check).
                let (a, bb, c) = (p1.x - p0.x, p2.x - p1.x, p3.x - p2.x);
                push_quadratic_roots(a - 2.0 * bb + c, 2.0 * (bb - a), a, &mut out);
            }
        }
        if let Self::Arc(a) = self {
            // dr/ds ∝ sin θ: zero at θ = kπ (extremes of r).
            for k in -4..=4 {
                let s = (f64::from(k) * std::f64::consts::PI - a.start_angle) / a.sweep;
                if s > 0.0 && s < 1.0 {
                    out.push(s);
                }
            }
        }
        out.sort_by(f64::total_cmp);
        out.dedup();
        out
    }
}

/// Pushes the roots in (0, 1) of a s² + b s + c.
fn push_quadratic_roots(a: f64, b: f64, c: f64, out: &mut Vec<f64>) {
    let scale = a.abs().max(b.abs()).max(c.abs());
    if scale == 0.0 {
        return;
    }
    let mut push = |s: f64| {
        if s.is_finite() && s > 0.0 && s < 1.0 {
            out.push(s);
        }
    };
    if a.abs() <= 1e-12 * scale {
        if b != 0.0 {
            push(-c / b);
        }
        return;
    }
    let disc = b * b - 4.0 * a * c;
    if disc < 0.0 {
        return;
    }
    // Numerically stable pair of roots.
    let q = -0.5 * (b + b.signum() * disc.sqrt());
    push(q / a);
    if q != 0.0 {
        push(c / q);
    }
}
