//! P-curves of an edge on a face: samples of the edge's 3D curve projected onto the surface by
//! Newton's method on the squared distance, periodic parameters unwrapped along the edge and
//! next to the loop's previous entry; then the file's own PCURVE where one agrees with those
//! samples within the fit tolerance (mapped to the model's parameters, [`MappedPCurve`]),
//! else the simplest p-curve that meets the tolerance: a line or a circle in (u, v)
//! recognised from the samples, else a piecewise cubic Hermite B-spline through the
//! projected points with their (u, v) tangents, refined until its midpoints are within the
//! fit tolerance.

use crate::curves::curve::{Curve, ParamRange};
use crate::curves::curve2::{Circle2, Curve2, Curve2Point};
use crate::curves::nurbs_curve2::NurbsCurve2;
use crate::surfaces::surface::Surface;
use glam::{DVec2, DVec3};
use std::sync::Arc;

/// Newton steps of one projection.
const NEWTON_STEPS: usize = 40;
/// Grid per parameter of the search that starts a projection without a closed-form guess.
const SEARCH_GRID: usize = 24;
/// First number of segments of a fit.
const FIRST_SEGMENTS: usize = 8;
/// Most segments of a Hermite fit (doubling from [`FIRST_SEGMENTS`]).
pub(crate) const MAX_SEGMENTS: usize = 4096;

/// A projection of a point onto a surface.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Projection {
    /// The surface parameters.
    pub uv: DVec2,
    /// The surface point there.
    pub point: DVec3,
}

/// Projects `p` onto `surface` from the start `uv` (Newton on ½|S − p|², parameters kept in
/// the non-periodic ranges, periodic ones free).
pub(crate) fn project(surface: &dyn Surface, p: DVec3, start: DVec2) -> Projection {
    let [ru, rv] = surface.domain();
    let clamp = |uv: DVec2| {
        DVec2::new(
            if ru.periodic {
                uv.x
            } else {
                uv.x.clamp(ru.min, ru.max)
            },
            if rv.periodic {
                uv.y
            } else {
                uv.y.clamp(rv.min, rv.max)
            },
        )
    };
    let eval = |uv: DVec2| surface.eval(ru.normalize(uv.x), rv.normalize(uv.y));
    let mut uv = clamp(start);
    let mut s = eval(uv);
    for _ in 0..NEWTON_STEPS {
        let r = s.point - p;
        let g = DVec2::new(s.du.dot(r), s.dv.dot(r));
        let (a, b, c) = (
            s.du.dot(s.du) + s.duu.dot(r),
            s.du.dot(s.dv) + s.duv.dot(r),
            s.dv.dot(s.dv) + s.dvv.dot(r),
        );
        let det = a * c - b * b;
        // Newton where the Hessian is positive definite, else Gauss-Newton.
        let (a, b, c, det) = if a > 0.0 && det > 1e-14 * a * c.abs() {
            (a, b, c, det)
        } else {
            let (a, b, c) = (s.du.dot(s.du), s.du.dot(s.dv), s.dv.dot(s.dv));
            (a, b, c, a * c - b * b)
        };
        if !(det.is_finite() && det > 0.0) {
            break;
        }
        let step = DVec2::new(c * g.x - b * g.y, a * g.y - b * g.x) / det;
        let mut next = clamp(uv - step);
        let mut ns = eval(next);
        // Halve a step that increases the distance.
        let mut tries = 0;
        while ns.point.distance_squared(p) > s.point.distance_squared(p) && tries < 20 {
            next = uv + 0.5 * (next - uv);
            ns = eval(next);
            tries += 1;
        }
        let moved = (next - uv).length();
        uv = next;
        s = ns;
        if moved.is_nan() || moved <= 1e-15 * (1.0 + uv.length()) {
            break;
        }
    }
    Projection { uv, point: s.point }
}

/// A start for projecting `p` when the surface has no closed-form guess: the nearest node of
/// a grid over the domain.
pub(crate) fn search_start(surface: &dyn Surface, p: DVec3) -> DVec2 {
    let [ru, rv] = surface.domain();
    let mut best = (f64::INFINITY, DVec2::new(ru.min, rv.min));
    for i in 0..=SEARCH_GRID {
        for j in 0..=SEARCH_GRID {
            let u = ru.min + ru.span() * i as f64 / SEARCH_GRID as f64;
            let v = rv.min + rv.span() * j as f64 / SEARCH_GRID as f64;
            let d = surface.eval(u, v).point.distance_squared(p);
            if d < best.0 {
                best = (d, DVec2::new(u, v));
            }
        }
    }
    best.1
}

/// The (u, v) rate along the curve: the least-squares solution of [S_u S_v] w = C'(t).
fn uv_rate(surface: &dyn Surface, uv: DVec2, d1: DVec3) -> DVec2 {
    let [ru, rv] = surface.domain();
    let s = surface.eval(ru.normalize(uv.x), rv.normalize(uv.y));
    let (a, b, c) = (s.du.dot(s.du), s.du.dot(s.dv), s.dv.dot(s.dv));
    let g = DVec2::new(s.du.dot(d1), s.dv.dot(d1));
    let det = a * c - b * b;
    if det.is_finite() && det > 1e-300 {
        DVec2::new(c * g.x - b * g.y, a * g.y - b * g.x) / det
    } else {
        DVec2::ZERO
    }
}

/// A fitted p-curve.
#[derive(Debug)]
pub(crate) struct FittedPCurve {
    /// c(t) over the edge's domain.
    pub curve: Box<dyn Curve2>,
    /// Largest distance between the edge and the surface at the samples (mm): the file's own
    /// gap, healed up to the model tolerance.
    pub gap: f64,
    /// Largest distance between S(c(t)) and the edge's projection at the check points (mm).
    pub fit_error: f64,
    /// True when the curve is the file's own p-curve (placed, not fitted).
    pub from_file: bool,
}

/// The inputs of one fit.
pub(crate) struct FitInput<'a> {
    /// The face's surface.
    pub surface: &'a dyn Surface,
    /// A closed-form start for a point, if the surface has one.
    pub guess: &'a dyn Fn(DVec3) -> Option<[f64; 2]>,
    /// The edge's curve.
    pub curve: &'a dyn Curve,
    /// True when the loop runs the edge from t_max to t_min.
    pub reversed: bool,
    /// Where the loop's previous entry ended in (u, v), if any.
    pub previous_end: Option<DVec2>,
    /// Largest fit error accepted (mm).
    pub tolerance: f64,
    /// Where the loop leaves this entry in (u, v), when it must end exactly there (the last
    /// entry of a loop ends where the first began).
    pub snap_end: Option<DVec2>,
    /// Largest distance (mm) on the surface over which an end is snapped to its neighbour's;
    /// farther, the ends are left apart for the loop's closure check to report.
    pub snap_limit: f64,
    /// The parameters in which the surface closes without being periodic (S(min, v) =
    /// S(max, v): a closed B-spline surface, an extrusion of a closed B-spline curve).
    pub closed: [bool; 2],
    /// The file's own p-curves of this edge on this surface (PCURVE entities), mapped to the
    /// model's (u, v) and the edge's parameter but not to a period ([`MappedPCurve`]).
    pub file_pcurves: &'a [Arc<dyn Curve2>],
    /// How far (mm, on the surface) a file p-curve may lie from the projection and be used:
    /// the file's uncertainty.
    pub agreement: f64,
}

/// A file's p-curve in the model's terms: c(t) = scale ⊙ c_file(rate · t), where `scale`
/// turns the file's (u, v) units into the model's (lengths to mm, angles to radians, the
/// cone's v from the axis to the ruling, a reversed face's v negated) and `rate` the model's
/// edge parameter into the file's (±1 for the edge's sense, over radians per angle unit for
/// a conic).
#[derive(Debug)]
pub(crate) struct MappedPCurve {
    /// The file's curve.
    pub inner: Box<dyn Curve2>,
    /// Factors on (u, v).
    pub scale: DVec2,
    /// dt_file / dt.
    pub rate: f64,
}

impl Curve2 for MappedPCurve {
    fn eval(&self, t: f64) -> Curve2Point {
        let c = self.inner.eval(self.rate * t);
        Curve2Point {
            point: self.scale * c.point,
            d1: self.scale * c.d1 * self.rate,
            d2: self.scale * c.d2 * (self.rate * self.rate),
        }
    }

    fn domain(&self) -> ParamRange {
        let d = self.inner.domain();
        let (a, b) = (d.min / self.rate, d.max / self.rate);
        ParamRange {
            min: a.min(b),
            max: a.max(b),
            periodic: false,
        }
    }
}

/// A file p-curve placed where the projection put the edge: moved by whole periods, its ends
/// blended onto the loop's (snapped) end points and equal to them bit for bit at t_min and
/// t_max, like [`Segment2`].
#[derive(Debug)]
struct FromFile {
    inner: Arc<dyn Curve2>,
    shift: DVec2,
    e0: DVec2,
    e1: DVec2,
    p0: DVec2,
    p1: DVec2,
    range: ParamRange,
}

impl Curve2 for FromFile {
    fn eval(&self, t: f64) -> Curve2Point {
        let c = self.inner.eval(t);
        let span = self.range.span();
        let s = (t - self.range.min) / span;
        let point = if t == self.range.min {
            self.p0
        } else if t == self.range.max {
            self.p1
        } else {
            c.point + self.shift + (1.0 - s) * self.e0 + s * self.e1
        };
        Curve2Point {
            point,
            d1: c.d1 + (self.e1 - self.e0) / span,
            d2: c.d2,
        }
    }

    fn domain(&self) -> ParamRange {
        self.range
    }
}

/// A surface closed but not periodic in some parameter, seen as periodic there: projections
/// move freely across its seam and unwrap continuously along an edge, as on a cylinder; the
/// fit then places the whole entry in the domain ([`place_in_closed_domain`]).
struct ClosedAsPeriodic<'a> {
    inner: &'a dyn Surface,
    domain: [ParamRange; 2],
}

impl std::fmt::Debug for ClosedAsPeriodic<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ClosedAsPeriodic")
            .field("domain", &self.domain)
            .finish_non_exhaustive()
    }
}

impl Surface for ClosedAsPeriodic<'_> {
    fn eval(&self, u: f64, v: f64) -> crate::surfaces::surface::SurfacePoint {
        self.inner
            .eval(self.domain[0].normalize(u), self.domain[1].normalize(v))
    }

    fn domain(&self) -> [ParamRange; 2] {
        self.domain
    }
}

/// Moves an entry's samples by whole spans in the closed (non-periodic) parameters so that
/// they lie in `domain` (within `slack`). An entry on the seam itself (every sample on one
/// boundary) could lie on either side: it goes on the side that puts the face on its left,
/// as a face's loops run (outer loop counter-clockwise, holes clockwise): running up in v at
/// u = max, down at u = min; in u at v = min running right, at v = max running left.
fn place_in_closed_domain(
    uvs: &mut [DVec2],
    domain: [ParamRange; 2],
    closed: [bool; 2],
    reversed: bool,
) {
    let n = uvs.len();
    let (first, last) = if reversed { (n - 1, 0) } else { (0, n - 1) };
    let run = uvs[last] - uvs[first];
    for i in 0..2 {
        if !closed[i] {
            continue;
        }
        let (min, span) = (domain[i].min, domain[i].span());
        let slack = 1e-9 * span;
        // Bring the first sample into [min, max), then try that shift and its neighbours.
        let base = -span * ((uvs[first][i] - min) / span).floor();
        let (lo, hi) = uvs
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), q| {
                (lo.min(q[i]), hi.max(q[i]))
            });
        let fits = |shift: f64| lo + shift >= min - slack && hi + shift <= min + span + slack;
        let candidates: Vec<f64> = [base - span, base, base + span]
            .into_iter()
            .filter(|&s| fits(s))
            .collect();
        let shift = match candidates.as_slice() {
            [] => continue,
            [one] => *one,
            // On the seam: the face's side decides (the other parameter's run along the
            // entry gives the direction).
            several => {
                let at_max = if i == 0 { run.y > 0.0 } else { run.x < 0.0 };
                let target = if at_max { min + span } else { min };
                *several
                    .iter()
                    .min_by(|a, b| {
                        ((lo + *a) - target)
                            .abs()
                            .total_cmp(&((lo + *b) - target).abs())
                    })
                    .unwrap_or(&base)
            }
        };
        for q in uvs.iter_mut() {
            q[i] += shift;
        }
    }
}

/// Shift by whole periods that brings `x` nearest `near` (0 for a non-periodic parameter).
fn wrap_near(x: DVec2, near: DVec2, periods: [f64; 2]) -> DVec2 {
    let mut out = x;
    for i in 0..2 {
        if periods[i] > 0.0 {
            out[i] -= periods[i] * ((x[i] - near[i]) / periods[i]).round();
        }
    }
    out
}

/// Projects the edge onto the surface and fits its p-curve.
///
/// # Errors
/// A description when no fit within the tolerance exists with [`MAX_SEGMENTS`] segments, or
/// a projection is not finite.
pub(crate) fn fit(input: &FitInput<'_>) -> Result<FittedPCurve, String> {
    let true_domain = input.surface.domain();
    let seen_periodic = ClosedAsPeriodic {
        inner: input.surface,
        domain: [0, 1].map(|i| ParamRange {
            periodic: true_domain[i].periodic || input.closed[i],
            ..true_domain[i]
        }),
    };
    let surface: &dyn Surface = &seen_periodic;
    let domain = surface.domain();
    let periods = [0, 1].map(|i| {
        if domain[i].periodic {
            domain[i].span()
        } else {
            0.0
        }
    });
    let range = input.curve.domain();
    let mut segments = FIRST_SEGMENTS;
    loop {
        // 2 * segments + 1 projections, in increasing t, unwrapped continuously.
        let count = 2 * segments + 1;
        let mut ts = Vec::with_capacity(count);
        let mut uvs: Vec<DVec2> = Vec::with_capacity(count);
        let mut gap: f64 = 0.0;
        let mut rates = Vec::with_capacity(count);
        for k in 0..count {
            let t = range.min + range.span() * k as f64 / (count - 1) as f64;
            let c = input.curve.eval(t);
            let start = match uvs.last() {
                Some(&prev) => prev,
                None => match (input.guess)(c.point) {
                    Some([u, v]) => DVec2::new(u, v),
                    None => search_start(surface, c.point),
                },
            };
            let p = project(surface, c.point, start);
            if !(p.uv.is_finite() && p.point.is_finite()) {
                return Err(format!("the projection at t = {t} is not finite"));
            }
            let uv = match uvs.last() {
                Some(&prev) => wrap_near(p.uv, prev, periods),
                None => p.uv,
            };
            gap = gap.max(p.point.distance(c.point));
            rates.push(uv_rate(surface, uv, c.d1));
            ts.push(t);
            uvs.push(uv);
        }
        // Shift so the loop's entry point is next to the previous entry's end, or in the
        // domain.
        let entry = if input.reversed {
            uvs[count - 1]
        } else {
            uvs[0]
        };
        let anchor = input.previous_end.unwrap_or_else(|| {
            DVec2::new(
                if periods[0] > 0.0 {
                    domain[0].min + 0.5 * periods[0]
                } else {
                    entry.x
                },
                if periods[1] > 0.0 {
                    domain[1].min + 0.5 * periods[1]
                } else {
                    entry.y
                },
            )
        });
        let shift = wrap_near(entry, anchor, periods) - entry;
        for uv in &mut uvs {
            *uv += shift;
        }
        place_in_closed_domain(&mut uvs, true_domain, input.closed, input.reversed);
        // Consecutive entries meet exactly in (u, v): the entry point is the previous end, the
        // exit point the given one (both within the healed gap of the projections).
        let (first, last) = if input.reversed {
            (count - 1, 0)
        } else {
            (0, count - 1)
        };
        let on = |uv: DVec2| {
            surface
                .eval(domain[0].normalize(uv.x), domain[1].normalize(uv.y))
                .point
        };
        // Near on the surface, and on the same side of a closed surface's seam (where
        // points a span apart in (u, v) are one point in space).
        let same_side = |a: DVec2, b: DVec2| {
            (0..2).all(|i| {
                !input.closed[i]
                    || true_domain[i].periodic
                    || (a[i] - b[i]).abs() < 0.5 * true_domain[i].span()
            })
        };
        let near =
            |a: DVec2, b: DVec2| same_side(a, b) && on(a).distance(on(b)) <= input.snap_limit;
        if let Some(prev) = input.previous_end.filter(|&p| near(p, uvs[first])) {
            uvs[first] = prev;
        }
        if let Some(end) = input.snap_end {
            let end = wrap_near(end, uvs[last], periods);
            if near(end, uvs[last]) {
                uvs[last] = end;
            }
        }
        let edge_range = ParamRange {
            min: range.min,
            max: range.max,
            periodic: false,
        };
        let error_of = |c: &dyn Curve2| -> f64 {
            let mut worst: f64 = 0.0;
            for k in 0..count {
                let q = c.eval(ts[k]).point;
                let on = surface
                    .eval(domain[0].normalize(q.x), domain[1].normalize(q.y))
                    .point;
                let target = surface
                    .eval(domain[0].normalize(uvs[k].x), domain[1].normalize(uvs[k].y))
                    .point;
                let d = on.distance(target);
                worst = if d.is_nan() {
                    f64::INFINITY
                } else {
                    worst.max(d)
                };
            }
            worst
        };
        let (t0, t1) = (ts[0], ts[count - 1]);
        // The file's own p-curve, where it agrees with the projection within the file's
        // uncertainty at every sample: exact where the fits below approximate. Where none
        // agrees (another convention, a p-curve on a neighbouring surface, a careless
        // exporter) the projection is the truth: the 3D curve defines the edge.
        for candidate in input.file_pcurves {
            let c0 = candidate.eval(t0).point;
            let c1 = candidate.eval(t1).point;
            if !(c0.is_finite() && c1.is_finite()) {
                continue;
            }
            let shift = wrap_near(c0, uvs[0], periods) - c0;
            let placed = FromFile {
                inner: Arc::clone(candidate),
                shift,
                e0: uvs[0] - (c0 + shift),
                e1: uvs[count - 1] - (c1 + shift),
                p0: uvs[0],
                p1: uvs[count - 1],
                range: edge_range,
            };
            let e = error_of(&placed);
            if e <= input.agreement {
                return Ok(FittedPCurve {
                    curve: Box::new(placed),
                    gap,
                    fit_error: e,
                    from_file: true,
                });
            }
        }
        // A line in (u, v).
        let line = Segment2 {
            start: uvs[0],
            end: uvs[count - 1],
            range: edge_range,
        };
        let e = error_of(&line);
        if e <= input.tolerance {
            return Ok(FittedPCurve {
                curve: Box::new(line),
                gap,
                fit_error: e,
                from_file: false,
            });
        }
        // A circle in (u, v) with its angle affine in t at unit rate.
        if let Some(circle) = circle_through(&ts, &uvs, edge_range) {
            // Through the (snapped) end samples exactly, so consecutive entries meet.
            let at0 = circle.eval(t0).point;
            let at1 = circle.eval(t1).point;
            let circle = EndCorrected {
                inner: circle,
                e0: uvs[0] - at0,
                e1: uvs[count - 1] - at1,
                p0: uvs[0],
                p1: uvs[count - 1],
                range: edge_range,
            };
            let e = error_of(&circle);
            if e <= input.tolerance {
                return Ok(FittedPCurve {
                    curve: Box::new(circle),
                    gap,
                    fit_error: e,
                    from_file: false,
                });
            }
        }
        // Piecewise cubic Hermite through the even samples.
        let hermite = hermite(&ts, &uvs, &rates)?;
        let e = error_of(&hermite);
        if e <= input.tolerance {
            return Ok(FittedPCurve {
                curve: Box::new(hermite),
                gap,
                fit_error: e,
                from_file: false,
            });
        }
        if segments >= MAX_SEGMENTS {
            return Err(format!(
                "the best fit with {segments} cubic segments is {e:.3e} mm off"
            ));
        }
        segments *= 2;
    }
}

/// The circle through three of the samples, if every sample's angle is phase ± t.
fn circle_through(ts: &[f64], uvs: &[DVec2], range: ParamRange) -> Option<Circle2> {
    let n = uvs.len();
    let (a, b, c) = (uvs[0], uvs[n / 3], uvs[2 * n / 3]);
    let d = 2.0 * (a.x * (b.y - c.y) + b.x * (c.y - a.y) + c.x * (a.y - b.y));
    if d.abs() < 1e-300 {
        return None;
    }
    let (a2, b2, c2) = (a.length_squared(), b.length_squared(), c.length_squared());
    let center = DVec2::new(
        (a2 * (b.y - c.y) + b2 * (c.y - a.y) + c2 * (a.y - b.y)) / d,
        (a2 * (c.x - b.x) + b2 * (a.x - c.x) + c2 * (b.x - a.x)) / d,
    );
    let radius = a.distance(center);
    if !(radius.is_finite() && radius > 0.0) {
        return None;
    }
    let angle = |p: DVec2| (p - center).to_angle();
    let (phi0, phi1) = (angle(uvs[0]), angle(uvs[1]));
    let mut dphi = phi1 - phi0;
    dphi -= std::f64::consts::TAU * (dphi / std::f64::consts::TAU).round();
    let sense = (dphi / (ts[1] - ts[0])).signum();
    if ((dphi / (ts[1] - ts[0])).abs() - 1.0).abs() > 1e-6 {
        return None;
    }
    Some(Circle2 {
        center,
        radius,
        phase: phi0 - sense * ts[0],
        sense,
        range,
    })
}

/// The C1 piecewise cubic through the even samples with the (u, v) rates there, as a
/// B-spline with triple interior knots (each piece a Bezier segment).
fn hermite(ts: &[f64], uvs: &[DVec2], rates: &[DVec2]) -> Result<NurbsCurve2, String> {
    let n = (ts.len() - 1) / 2;
    let mut knots = vec![ts[0]; 4];
    let mut points = Vec::with_capacity(3 * n + 1);
    for k in 0..n {
        let (i, j) = (2 * k, 2 * k + 2);
        let h = ts[j] - ts[i];
        points.push(uvs[i]);
        points.push(uvs[i] + rates[i] * (h / 3.0));
        points.push(uvs[j] - rates[j] * (h / 3.0));
        if k + 1 < n {
            knots.extend([ts[j]; 3]);
        }
    }
    points.push(uvs[2 * n]);
    knots.extend([ts[2 * n]; 4]);
    let weights = vec![1.0; points.len()];
    NurbsCurve2::new(3, knots, points, weights, false).map_err(|e| e.to_string())
}

/// The straight p-curve from `start` at t_min to `end` at t_max, c(t) = (1 − s) start + s end
/// with s = (t − t_min) / span: unlike origin + t · direction it gives both end points bit for
/// bit, so consecutive entries of a loop that were snapped together meet exactly (a gap of one
/// rounding unit can put a loop's closing point on its first segment, which the validation
/// rightly counts as a crossing; SolidWorks' `box_sides.STEP` did).
#[derive(Debug)]
struct Segment2 {
    start: DVec2,
    end: DVec2,
    range: ParamRange,
}

impl Curve2 for Segment2 {
    fn eval(&self, t: f64) -> crate::curves::curve2::Curve2Point {
        let span = self.range.span();
        let s = (t - self.range.min) / span;
        crate::curves::curve2::Curve2Point {
            point: (1.0 - s) * self.start + s * self.end,
            d1: (self.end - self.start) / span,
            d2: DVec2::ZERO,
        }
    }

    fn domain(&self) -> ParamRange {
        self.range
    }

    /// The projection of `uv` onto the segment, clamped to it.
    fn nearest_param(&self, uv: DVec2) -> Option<f64> {
        let along = self.end - self.start;
        let length_squared = along.length_squared();
        let s = if length_squared > 0.0 {
            ((uv - self.start).dot(along) / length_squared).clamp(0.0, 1.0)
        } else {
            0.0
        };
        Some((self.range.min + s * self.range.span()).clamp(self.range.min, self.range.max))
    }
}

/// A p-curve moved by a linear blend of two small corrections so that it passes exactly
/// through given end points: c(t) = inner(t) + (1 − s) e0 + s e1, s = (t − t_min) / span.
#[derive(Debug)]
struct EndCorrected<C: Curve2> {
    inner: C,
    e0: DVec2,
    e1: DVec2,
    /// The end points the curve passes through at t_min and t_max.
    p0: DVec2,
    p1: DVec2,
    range: ParamRange,
}

impl<C: Curve2> Curve2 for EndCorrected<C> {
    fn eval(&self, t: f64) -> crate::curves::curve2::Curve2Point {
        let c = self.inner.eval(t);
        let span = self.range.span();
        let s = (t - self.range.min) / span;
        // At the ends, the end points bit for bit (see `Segment2`).
        let point = if t == self.range.min {
            self.p0
        } else if t == self.range.max {
            self.p1
        } else {
            c.point + (1.0 - s) * self.e0 + s * self.e1
        };
        crate::curves::curve2::Curve2Point {
            point,
            d1: c.d1 + (self.e1 - self.e0) / span,
            d2: c.d2,
        }
    }

    fn domain(&self) -> ParamRange {
        self.range
    }
}

#[cfg(test)]
mod tests {
    //! Planted answers: points of each analytic surface at known (u, v) are found again by the
    //! closed-form start and the Newton projection (the inverse maps follow the surfaces'
    //! conventions: STEP's u about the axis from ref_direction, the sphere's latitude, the
    //! torus's tube angle, the cone's v along the ruling).

    use super::project;
    use crate::io::step::geometry::{SurfaceSpec, range};
    use crate::surfaces::placement::Placement;
    use glam::{DVec2, DVec3};

    #[test]
    fn closed_form_starts_and_projection_recover_planted_parameters() {
        let placement = Placement::new(
            DVec3::new(1.0, -2.0, 3.0),
            DVec3::new(0.3, -0.4, 0.85),
            DVec3::new(1.0, 0.2, 0.0),
        )
        .expect("placement");
        let specs = [
            SurfaceSpec::Plane(placement),
            SurfaceSpec::Cylinder(placement, 4.0),
            SurfaceSpec::Cone(placement, 4.0, 0.4),
            SurfaceSpec::Sphere(placement, 4.0),
            SurfaceSpec::Torus(placement, 6.0, 2.0),
        ];
        let planted = [[0.3, 0.7], [-2.5, 1.2], [2.9, -0.6], [1.4, -1.1]];
        for spec in &specs {
            let surface = spec
                .build([range(-50.0, 50.0), range(-50.0, 50.0)])
                .expect("surface");
            for [u, v] in planted {
                let p = surface.eval(u, v).point;
                let [gu, gv] = spec.guess(p).expect("closed form");
                let q = project(surface.as_ref(), p, DVec2::new(gu, gv));
                assert!(q.point.distance(p) < 1e-12, "{spec:?} at ({u}, {v})");
                let tau = std::f64::consts::TAU;
                let du = (q.uv.x - u) - tau * ((q.uv.x - u) / tau).round();
                let periodic_v = matches!(spec, SurfaceSpec::Torus(..));
                let dv = if periodic_v {
                    (q.uv.y - v) - tau * ((q.uv.y - v) / tau).round()
                } else {
                    q.uv.y - v
                };
                let du = if matches!(spec, SurfaceSpec::Plane(_)) {
                    q.uv.x - u
                } else {
                    du
                };
                assert!(
                    du.abs() < 1e-10 && dv.abs() < 1e-10,
                    "{spec:?}: ({u}, {v}) -> {}",
                    q.uv
                );
            }
        }
    }
}
