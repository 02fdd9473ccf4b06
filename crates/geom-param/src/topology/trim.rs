//! Trimmed regions of a face's parameter plane: an outer loop and holes, each a cycle of edges
//! with a p-curve, and the two questions every stage asks of them: is (u, v) inside, and which
//! boundary point is nearest.
//!
//! Orientation (as in STEP and OpenCASCADE): walking along a loop in its direction, the face
//! lies on the left in the (u, v) plane, whose orientation is the one in which ∂S/∂u × ∂S/∂v
//! points out of the material. So the outer loop runs counter-clockwise and holes clockwise.
//!
//! Each p-curve is kept with a polyline of its points (sampled until the chord deviates from the
//! curve by at most [`FLATNESS`] of the loop's extent, or [`MAX_SEGMENTS_PER_ENTRY`] segments).
//! Containment is the winding number of the polylines, refined by the exact p-curve near the
//! boundary: within the polyline's flatness of an entry, the side of the exact curve's tangent at
//! the nearest exact point decides (on a trim of lines and circles alone, whose nearest points
//! are exact, that side decides everywhere). Nearest points of lines and circles are taken in
//! closed form; those of other p-curves are found on the polyline and then polished by Newton's
//! method on |c(t) - (u, v)|² over the entry's exact p-curve. Both scans skip runs of
//! [`SEGMENTS_PER_BOX`] segments by their boxes, and groups of [`BOXES_PER_GROUP`] runs by
//! theirs: a run or group farther than the best point so far, or not spanning the ray's height,
//! holds no segment that would count.

use crate::curves::curve::ParamRange;
use crate::curves::curve2::Curve2;
use crate::topology::feature::EdgeId;
use crate::topology::trim_grid::ContainmentGrid;
use glam::DVec2;

/// Largest chord deviation of a p-curve's polyline, relative to its loop's extent in (u, v).
pub const FLATNESS: f64 = 1e-4;
/// Upper bound on the segments of one entry's polyline.
pub const MAX_SEGMENTS_PER_ENTRY: usize = 4096;
/// Newton steps that polish a nearest boundary point found on the polyline.
const POLISH_STEPS: usize = 8;
/// Consecutive polyline segments under one box of [`TrimEntry`]'s second level.
///
/// Why: a face is asked for its nearest boundary point and whether it contains a point at every
/// Newton step on it, and a circle's polyline has about 160 segments at [`FLATNESS`]; scanning
/// them all was a quarter of a loft-on-tube query (its tube's annulus faces).
pub const SEGMENTS_PER_BOX: usize = 8;
/// Consecutive run boxes under one box of [`TrimEntry`]'s third level.
///
/// Why: a circle's polyline (256 segments at [`FLATNESS`]) has 32 runs, and a scan near the
/// boundary tested every run's box: most of a loft-on-tube query's nearest-point searches on
/// the tube's annulus and cylinder went to those tests.
pub const BOXES_PER_GROUP: usize = 8;

/// One edge of a loop: the edge, its p-curve on this face and the direction the loop takes it.
#[derive(Debug)]
pub struct TrimEntry {
    /// The edge.
    pub edge: EdgeId,
    /// c(t): the face's (u, v) at each parameter t of the edge's curve.
    pub pcurve: Box<dyn Curve2>,
    /// When true the loop runs along the edge from t_max to t_min.
    pub reversed: bool,
    /// Samples (t, c(t)) in increasing t; built by [`TrimLoop::new`].
    polyline: Vec<(f64, DVec2)>,
    /// The axis-aligned box of `polyline` (min, max corners; empty: +∞, −∞), built with it.
    bounds: (DVec2, DVec2),
    /// The boxes of runs of [`SEGMENTS_PER_BOX`] segments: box k holds the points
    /// k · [`SEGMENTS_PER_BOX`] ..= (k + 1) · [`SEGMENTS_PER_BOX`] (the last run fewer).
    boxes: Vec<(DVec2, DVec2)>,
    /// The boxes of groups of [`BOXES_PER_GROUP`] runs: group g holds runs
    /// g · [`BOXES_PER_GROUP`] .. (g + 1) · [`BOXES_PER_GROUP`] (the last fewer). A single
    /// group's box is the entry's `bounds`, which the scans test first, so they skip its test.
    groups: Vec<(DVec2, DVec2)>,
    /// The p-curve gives its nearest points in closed form ([`Curve2::nearest_param`]): the
    /// nearest-point search takes them from it, not from the polyline. Built with the polyline.
    closed_form: bool,
}

impl TrimEntry {
    /// An entry with its polyline not yet built (see [`TrimLoop::new`]).
    #[must_use]
    pub fn new(edge: EdgeId, pcurve: Box<dyn Curve2>, reversed: bool) -> Self {
        Self {
            edge,
            pcurve,
            reversed,
            polyline: Vec::new(),
            bounds: (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
            boxes: Vec::new(),
            groups: Vec::new(),
            closed_form: false,
        }
    }

    /// The polyline samples (t, c(t)), increasing t.
    #[must_use]
    pub fn polyline(&self) -> &[(f64, DVec2)] {
        &self.polyline
    }

    /// The (u, v) where the loop enters this entry (t_min, or t_max when reversed).
    #[must_use]
    pub fn start(&self) -> DVec2 {
        let range = self.pcurve.domain();
        self.pcurve
            .eval(if self.reversed { range.max } else { range.min })
            .point
    }

    /// The (u, v) where the loop leaves this entry.
    #[must_use]
    pub fn end(&self) -> DVec2 {
        let range = self.pcurve.domain();
        self.pcurve
            .eval(if self.reversed { range.min } else { range.max })
            .point
    }
}

/// A closed cycle of entries, each ending where the next begins.
#[derive(Debug)]
pub struct TrimLoop {
    /// The entries in loop order.
    pub entries: Vec<TrimEntry>,
}

impl TrimLoop {
    /// A loop of `entries` in loop order, with the polylines built.
    #[must_use]
    pub fn new(mut entries: Vec<TrimEntry>) -> Self {
        let extent = loop_extent(&entries);
        for entry in &mut entries {
            entry.polyline = sample_polyline(entry.pcurve.as_ref(), FLATNESS * extent);
            entry.bounds = box_of(&entry.polyline);
            let runs = entry
                .polyline
                .len()
                .saturating_sub(1)
                .div_ceil(SEGMENTS_PER_BOX);
            entry.boxes = (0..runs)
                .map(|k| box_of(&entry.polyline[run_points(k, entry.polyline.len())]))
                .collect();
            entry.groups = entry.boxes.chunks(BOXES_PER_GROUP).map(union_of).collect();
            entry.closed_form = entry.pcurve.nearest_param(entry.start()).is_some();
        }
        Self { entries }
    }

    /// Twice the signed area enclosed by the polyline (positive counter-clockwise), following
    /// each entry in the loop's direction.
    #[must_use]
    pub fn signed_area(&self) -> f64 {
        let mut twice = 0.0;
        for (a, b) in self.segments() {
            twice += a.perp_dot(b);
        }
        0.5 * twice
    }

    /// The polyline segments in loop order, closed by a segment from the last point back to
    /// the first (the entries meet only within rounding, and a ray through such a gap would
    /// miss the loop).
    pub fn segments(&self) -> impl Iterator<Item = (DVec2, DVec2)> + '_ {
        self.entries
            .iter()
            .flat_map(entry_segments)
            .chain(self.closing_segment())
    }

    /// The segment from the last entry's last point (in loop direction) to the first entry's
    /// first point; `None` for a loop without points.
    fn closing_segment(&self) -> Option<(DVec2, DVec2)> {
        let end_point = |entry: &TrimEntry, start: bool| {
            let points = &entry.polyline;
            let first = points.first().map(|p| p.1);
            let last = points.last().map(|p| p.1);
            if start != entry.reversed { first } else { last }
        };
        match (self.entries.last(), self.entries.first()) {
            (Some(l), Some(f)) => end_point(l, false).zip(end_point(f, true)),
            _ => None,
        }
    }
}

/// One entry's polyline segments in the loop's direction.
fn entry_segments(entry: &TrimEntry) -> impl Iterator<Item = (DVec2, DVec2)> + '_ {
    let points = &entry.polyline;
    let n = points.len();
    (1..n).map(move |k| {
        if entry.reversed {
            (points[n - k].1, points[n - k - 1].1)
        } else {
            (points[k - 1].1, points[k].1)
        }
    })
}

/// The axis-aligned box of polyline points (min, max corners; empty: +∞, −∞).
fn box_of(points: &[(f64, DVec2)]) -> (DVec2, DVec2) {
    let (mut lo, mut hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
    for &(_, p) in points {
        lo = lo.min(p);
        hi = hi.max(p);
    }
    (lo, hi)
}

/// The smallest box holding every box of `boxes` (empty: +∞, −∞).
fn union_of(boxes: &[(DVec2, DVec2)]) -> (DVec2, DVec2) {
    let empty = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
    boxes
        .iter()
        .fold(empty, |(lo, hi), b| (lo.min(b.0), hi.max(b.1)))
}

/// Calls `visit` with the runs of each of `entry`'s groups whose box `keep` accepts (given the
/// scan's `state` so far), in order; an entry of one group has its runs visited at once (that
/// group's box is the entry's, which the scans test first).
#[inline(always)]
fn visit_groups<S>(
    entry: &TrimEntry,
    state: &mut S,
    keep: impl Fn(&S, (DVec2, DVec2)) -> bool,
    mut visit: impl FnMut(&mut S, std::ops::Range<usize>),
) {
    let runs = entry.boxes.len();
    if entry.groups.len() <= 1 {
        visit(state, 0..runs);
        return;
    }
    for (g, &group) in entry.groups.iter().enumerate() {
        if keep(state, group) {
            visit(
                state,
                g * BOXES_PER_GROUP..((g + 1) * BOXES_PER_GROUP).min(runs),
            );
        }
    }
}

/// The points of run `k` of a polyline of `n` points ([`TrimEntry`]'s boxes).
fn run_points(k: usize, n: usize) -> std::ops::RangeInclusive<usize> {
    k * SEGMENTS_PER_BOX..=((k + 1) * SEGMENTS_PER_BOX).min(n - 1)
}

/// The segments of run `k` of `entry`'s polyline, each in the loop's direction.
fn run_segments(entry: &TrimEntry, k: usize) -> impl Iterator<Item = (DVec2, DVec2)> + '_ {
    entry.polyline[run_points(k, entry.polyline.len())]
        .windows(2)
        .map(|w| {
            if entry.reversed {
                (w[1].1, w[0].1)
            } else {
                (w[0].1, w[1].1)
            }
        })
}

/// Whether every point of the box `(lo, hi)` is farther from `uv` than `distance`, by more than
/// the rounding of a computed segment distance (a few ε of the coordinates): then no segment in
/// it would replace a best point at that distance.
fn farther((lo, hi): (DVec2, DVec2), uv: DVec2, distance: f64) -> bool {
    let gap = (lo - uv).max(uv - hi).max(DVec2::ZERO).length();
    let coordinates = uv.abs().max(lo.abs()).max(hi.abs()).max_element();
    gap - 64.0 * f64::EPSILON * (coordinates + gap) > distance
}

/// Whether a box lies wholly above height `y` or wholly at or below it: then no segment in it
/// crosses the ray at that height as [`Trim::winding`] counts crossings.
fn off_height((lo, hi): (DVec2, DVec2), y: f64) -> bool {
    lo.y > y || hi.y <= y
}

/// The region of a face's parameter plane inside its outer loop and outside its holes.
#[derive(Debug)]
pub struct Trim {
    /// Loop 0 is the outer boundary (counter-clockwise); the others are holes (clockwise).
    pub loops: Vec<TrimLoop>,
    /// Periods of (u, v) where the surface is periodic (0 otherwise): a point is classified at
    /// every shift by whole periods that brings it near the loops.
    pub periods: [f64; 2],
    /// The box of every loop's polyline ([`Trim::bounds`]), built with the trim.
    bounds: (DVec2, DVec2),
    /// The cells of the loops' box that no polyline comes near, with their side of the trim
    /// ([`Trim::contains`]'s first answer); built with the trim.
    grid: Option<ContainmentGrid>,
    /// Some entry has no closed-form nearest point ([`TrimEntry`]'s `closed_form`), so that
    /// nearest points are also searched on polylines.
    polyline_entries: bool,
}

/// The boundary point of a trim nearest to a (u, v).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TrimNearest {
    /// Loop index.
    pub loop_index: usize,
    /// Entry index in the loop.
    pub index: usize,
    /// The edge parameter of the nearest point.
    pub t: f64,
    /// The nearest point c(t), shifted by whole periods to lie next to the query point.
    pub point: DVec2,
    /// Distance in the (u, v) plane.
    pub distance: f64,
}

impl Trim {
    /// A trim of `loops` on a surface with the parameter `domain`.
    #[must_use]
    pub fn new(loops: Vec<TrimLoop>, domain: &[ParamRange; 2]) -> Self {
        let period = |r: &ParamRange| if r.periodic { r.span() } else { 0.0 };
        let mut lo = DVec2::splat(f64::INFINITY);
        let mut hi = DVec2::splat(f64::NEG_INFINITY);
        for e in loops.iter().flat_map(|l| &l.entries) {
            lo = lo.min(e.bounds.0);
            hi = hi.max(e.bounds.1);
        }
        let polyline_entries = loops
            .iter()
            .flat_map(|l| &l.entries)
            .any(|e| !e.closed_form);
        let mut trim = Self {
            loops,
            periods: [period(&domain[0]), period(&domain[1])],
            bounds: (lo, hi),
            grid: None,
            polyline_entries,
        };
        trim.grid = ContainmentGrid::new(
            trim.bounds,
            |uv| trim.polyline_distance(uv),
            |uv| trim.winding(uv) != 0,
        );
        trim
    }

    /// The axis-aligned box of every loop's polyline: (min, max). From the entries' boxes, in
    /// the order of the points: the same corners as folding every point.
    #[must_use]
    pub fn bounds(&self) -> (DVec2, DVec2) {
        self.bounds
    }

    /// The shift by whole periods that brings `uv` closest to the middle of the loops' box.
    #[must_use]
    pub fn unwrap(&self, uv: DVec2) -> DVec2 {
        let (lo, hi) = self.bounds();
        let mid = 0.5 * (lo + hi);
        let mut out = uv;
        for i in 0..2 {
            let p = self.periods[i];
            if p > 0.0 {
                out[i] = uv[i] - p * ((uv[i] - mid[i]) / p).round();
            }
        }
        out
    }

    /// Winding number of the polylines around `uv` (1 inside, 0 outside, for a valid trim):
    /// the crossings of [`TrimLoop::segments`] with the ray from `uv` along +u. An entry or a
    /// run whose box lies wholly above `uv` or wholly at or below it has no segment that
    /// crosses.
    fn winding(&self, uv: DVec2) -> i32 {
        let crossing = |(a, b): (DVec2, DVec2)| {
            if a.y <= uv.y {
                i32::from(b.y > uv.y && (b - a).perp_dot(uv - a) > 0.0)
            } else {
                -i32::from(b.y <= uv.y && (b - a).perp_dot(uv - a) < 0.0)
            }
        };
        let mut w = 0;
        for l in &self.loops {
            for entry in &l.entries {
                if off_height(entry.bounds, uv.y) {
                    continue;
                }
                let near_height = |_: &i32, group| !off_height(group, uv.y);
                visit_groups(entry, &mut w, near_height, |w, runs| {
                    for k in runs {
                        if !off_height(entry.boxes[k], uv.y) {
                            *w += run_segments(entry, k).map(crossing).sum::<i32>();
                        }
                    }
                });
            }
            w += l.closing_segment().map_or(0, crossing);
        }
        w
    }

    /// Whether `uv` (shifted by periods, see [`Trim::unwrap`]) lies in the region, boundary
    /// included within `tolerance` (parameter units).
    ///
    /// Away from the boundary (farther than the polylines' flatness) the polylines' winding
    /// number decides; nearer, the side of the exact p-curve at the nearest exact point does,
    /// and where that point is a corner (two entries' common end), the corner's sector: the left
    /// of both entries' directions there at a convex corner, of either at a reflex one.
    #[must_use]
    pub fn contains(&self, uv: DVec2, tolerance: f64) -> bool {
        let uv = self.unwrap(uv);
        if self.loops.iter().all(|l| l.entries.is_empty()) {
            return false;
        }
        let (lo, hi) = self.bounds();
        let band = 2.0 * FLATNESS * (hi - lo).max_element();
        // Only a boundary point within the tolerance or the band matters, and a polyline lies
        // within its flatness (half the band) of its curve: a point with no polyline point
        // within one more band is classified by the winding number, without a nearest point;
        // in a grid cell clear by that much, by the cell's (the same answer).
        let limit = tolerance.max(band) + band;
        if let Some(inside) = self.grid.as_ref().and_then(|g| g.side(uv, limit)) {
            return inside;
        }
        self.contains_by_scan(uv, tolerance, band)
    }

    /// [`Trim::contains`] for an unwrapped `uv` of a trim with points, without the grid: from
    /// the nearest polyline point within `tolerance.max(band) + band`, else the winding number.
    /// On a trim whose entries all have closed-form nearest points (lines and circles) the
    /// nearest boundary point is exact at any distance, and its side decides wherever it lies
    /// (the segment from `uv` to it crosses no boundary, or a nearer point would lie on it):
    /// the winding scan of the circles' polylines was a tenth of a loft-in-tube query.
    fn contains_by_scan(&self, uv: DVec2, tolerance: f64, band: f64) -> bool {
        let limit = if self.polyline_entries {
            tolerance.max(band) + band
        } else {
            f64::INFINITY
        };
        let Some(near) = self.nearest_within(uv, limit) else {
            return self.winding(uv) != 0;
        };
        if near.distance <= tolerance {
            return true;
        }
        if near.distance > band && self.polyline_entries {
            return self.winding(uv) != 0;
        }
        let l = &self.loops[near.loop_index];
        let entry = &l.entries[near.index];
        let range = entry.pcurve.domain();
        let at_end = |t: f64| (t - near.t).abs() <= 1e-12 * range.span();
        // The traversal direction of an entry at one of its parameters.
        let along = |e: &TrimEntry, t: f64| {
            let d1 = e.pcurve.eval(t).d1;
            if e.reversed { -d1 } else { d1 }
        };
        let w = uv - near.point;
        let left = |d: DVec2| d.perp_dot(w) > 0.0;
        // At a corner the nearest point is the end of two entries: the face is the sector on
        // the left of both directions (a convex corner) or of either (a reflex one).
        let corner = if at_end(range.max) || at_end(range.min) {
            let n = l.entries.len();
            let leaving = at_end(range.max) != entry.reversed;
            let (before, after) = if leaving {
                (entry, &l.entries[(near.index + 1) % n])
            } else {
                (&l.entries[(near.index + n - 1) % n], entry)
            };
            let end_t = |e: &TrimEntry, start: bool| {
                let r = e.pcurve.domain();
                if start != e.reversed { r.min } else { r.max }
            };
            Some((
                along(before, end_t(before, false)),
                along(after, end_t(after, true)),
            ))
        } else {
            None
        };
        match corner {
            Some((incoming, outgoing)) if incoming.perp_dot(outgoing) >= 0.0 => {
                left(incoming) && left(outgoing)
            }
            Some((incoming, outgoing)) => left(incoming) || left(outgoing),
            None => left(along(entry, near.t)),
        }
    }

    /// The exact boundary point nearest to `uv` (after [`Trim::unwrap`]), or `None` for a trim
    /// without loops.
    #[must_use]
    pub fn nearest(&self, uv: DVec2) -> Option<TrimNearest> {
        let uv = self.unwrap(uv);
        // Closed-form entries are each searched whole; only polylines need a bound to skip by.
        let limit = if self.polyline_entries {
            self.nearest_bound(uv)
        } else {
            f64::INFINITY
        };
        self.nearest_within(uv, limit)
    }

    /// An upper bound on the distance from `uv` to the polylines: the distance to the first
    /// point of the run whose box lies nearest (∞ for no polyline). Scanning with it as the
    /// limit skips the runs beyond it from the start, where a scan in loop order narrows its
    /// bound only as it goes (a circle's trim: half its runs before the near side).
    fn nearest_bound(&self, uv: DVec2) -> f64 {
        let gap = |(lo, hi): (DVec2, DVec2)| (lo - uv).max(uv - hi).max(DVec2::ZERO).length();
        let mut nearest: Option<(f64, &TrimEntry, usize)> = None;
        for l in &self.loops {
            for e in &l.entries {
                if nearest.is_some_and(|(g, _, _)| gap(e.bounds) >= g) {
                    continue;
                }
                // A run's gap is at least its group's: none in a farther group would be taken.
                let nearer = |nearest: &Option<(f64, &TrimEntry, usize)>, group| {
                    nearest.is_none_or(|(g, _, _)| gap(group) < g)
                };
                visit_groups(e, &mut nearest, nearer, |nearest, runs| {
                    for k in runs {
                        let g = gap(e.boxes[k]);
                        if nearest.is_none_or(|(best, _, _)| g < best) {
                            *nearest = Some((g, e, k));
                        }
                    }
                });
            }
        }
        nearest
            .and_then(|(_, e, k)| e.polyline.get(*run_points(k, e.polyline.len()).start()))
            // Slack for the rounding of the scan's own distance to that point.
            .map_or(f64::INFINITY, |&(_, p)| {
                let d = p.distance(uv);
                d + 64.0 * f64::EPSILON * (d + uv.abs().max(p.abs()).max_element())
            })
    }

    /// [`Trim::nearest`] for a `uv` already unwrapped, when some boundary point lies within
    /// `limit` of it (for a polyline's entry, a point of its polyline); `None` otherwise. The
    /// limit only skips what lies beyond it.
    ///
    /// Entries whose p-curves have closed-form nearest points ([`Curve2::nearest_param`]: lines
    /// and circles) give their exact nearest point; the others, their polyline's nearest point
    /// polished on the exact p-curve ([`Trim::polish`]), searched within the band of the
    /// closed-form answer so that both are compared on exact points.
    ///
    /// Why: a Newton iterate that leaves a face asks for its nearest boundary point, and the
    /// tube's annulus faces (two circles of 256 segments each) made those scans and polishes a
    /// sixth of a loft-in-tube query.
    fn nearest_within(&self, uv: DVec2, limit: f64) -> Option<TrimNearest> {
        let (lo, hi) = self.bounds();
        // A polyline lies within half of this of its curve, so that a curve lies within it of
        // its polyline's box.
        let band = 2.0 * FLATNESS * (hi - lo).max_element();
        let mut best: Option<TrimNearest> = None;
        for (loop_index, l) in self.loops.iter().enumerate() {
            for (index, e) in l.entries.iter().enumerate() {
                let bound = best.as_ref().map_or(limit, |b| b.distance.min(limit));
                if !e.closed_form || farther(e.bounds, uv, bound + band) {
                    continue;
                }
                let Some(t) = e.pcurve.nearest_param(uv) else {
                    continue;
                };
                let point = e.pcurve.eval(t).point;
                let distance = point.distance(uv);
                if distance <= bound && best.as_ref().is_none_or(|b| distance < b.distance) {
                    best = Some(TrimNearest {
                        loop_index,
                        index,
                        t,
                        point,
                        distance,
                    });
                }
            }
        }
        if !self.polyline_entries {
            return best;
        }
        let polyline_limit = best
            .as_ref()
            .map_or(limit, |b| (b.distance + band).min(limit));
        let polished = self
            .polyline_nearest(uv, polyline_limit, false)
            .map(|near| self.polish(uv, near));
        match (best, polished) {
            (Some(b), Some(p)) if b.distance <= p.distance => Some(b),
            (b, p) => p.or(b),
        }
    }

    /// A polyline's nearest point `near` to `uv` moved onto its entry's exact p-curve: Newton's
    /// method on |c(t) − uv|² from the polyline's parameter.
    fn polish(&self, uv: DVec2, mut near: TrimNearest) -> TrimNearest {
        let entry = &self.loops[near.loop_index].entries[near.index];
        let range = entry.pcurve.domain();
        let mut t = near.t;
        // Each evaluation is used once (a p-curve read from a file is a mapped rational
        // spline): the first is the point at the polyline's parameter, and the last, when
        // Newton stopped there, the polished point.
        let mut c = entry.pcurve.eval(t);
        let start = c.point;
        let mut evaluated_at = t;
        for step in 0..POLISH_STEPS {
            let r = c.point - uv;
            let g = r.dot(c.d1);
            let h = c.d1.length_squared() + r.dot(c.d2);
            // A non-positive (or NaN) curvature term: no Newton step towards a minimum.
            if h.is_nan() || h <= 0.0 {
                break;
            }
            let next = (t - g / h).clamp(range.min, range.max);
            if next == t {
                break;
            }
            t = next;
            if step + 1 < POLISH_STEPS {
                c = entry.pcurve.eval(t);
                evaluated_at = t;
            }
        }
        // The answer is a point of the exact p-curve: the polished one, unless Newton ended
        // farther than the exact point at the polyline's parameter. (Not the polyline's point
        // itself: a query on a chord is up to the flatness from the curve, and that point
        // passed for the boundary; a bracket's cap took a point 2e-3 mm inside its fillet
        // arc for a point of the face.)
        let polished = if evaluated_at == t {
            c.point
        } else {
            entry.pcurve.eval(t).point
        };
        if polished.distance(uv) <= start.distance(uv) {
            near.t = t;
            near.point = polished;
        } else {
            near.point = start;
        }
        near.distance = near.point.distance(uv);
        near
    }

    /// The point of the polylines nearest to `uv` (its entry, parameter and distance), when
    /// one lies within `limit`; `None` otherwise. Over every entry when `all`, otherwise over
    /// the entries without a closed-form nearest point.
    fn polyline_nearest(&self, uv: DVec2, limit: f64, all: bool) -> Option<TrimNearest> {
        let mut best: Option<TrimNearest> = None;
        // An entry whose box is farther than the limit or the best distance so far, by more
        // than the rounding of a computed segment distance (a few ε of the coordinates), has no
        // segment that would be taken; nor has a run of them.
        let bound =
            |best: &Option<TrimNearest>| best.as_ref().map_or(limit, |b| b.distance.min(limit));
        for (li, l) in self.loops.iter().enumerate() {
            for (ei, e) in l.entries.iter().enumerate() {
                if (e.closed_form && !all) || farther(e.bounds, uv, bound(&best)) {
                    continue;
                }
                // Every segment of a group lies in its box, as a run's in the run's.
                let near = |best: &Option<TrimNearest>, group| !farther(group, uv, bound(best));
                visit_groups(e, &mut best, near, |best, runs| {
                    nearest_on_runs(e, runs, uv, limit, (li, ei), best);
                });
            }
        }
        best.filter(|b| b.distance <= limit)
    }

    /// The distance from `uv` to the polylines, the loops' closing segments included (∞ for
    /// a trim without points).
    fn polyline_distance(&self, uv: DVec2) -> f64 {
        let closing = (self.loops.iter())
            .filter_map(TrimLoop::closing_segment)
            .map(|ab| closest_on_segment(uv, ab).1.distance(uv))
            .fold(f64::INFINITY, f64::min);
        self.polyline_nearest(uv, self.nearest_bound(uv), true)
            .map_or(closing, |n| n.distance.min(closing))
    }
}

/// [`Trim::polyline_nearest`]'s scan of the `runs` of `e` (entry `index` of loop `loop_index`):
/// `best` becomes a nearer point of theirs, skipping the runs whose box is farther than `limit`
/// or `best` ([`farther`]).
#[inline(always)]
fn nearest_on_runs(
    e: &TrimEntry,
    runs: std::ops::Range<usize>,
    uv: DVec2,
    limit: f64,
    (loop_index, index): (usize, usize),
    best: &mut Option<TrimNearest>,
) {
    for k in runs {
        let bound = best.as_ref().map_or(limit, |b| b.distance.min(limit));
        if farther(e.boxes[k], uv, bound) {
            continue;
        }
        for w in e.polyline[run_points(k, e.polyline.len())].windows(2) {
            let ((t0, a), (t1, b)) = (w[0], w[1]);
            let (s, p) = closest_on_segment(uv, (a, b));
            let d = p.distance(uv);
            if best.is_none_or(|bst| d < bst.distance) {
                *best = Some(TrimNearest {
                    loop_index,
                    index,
                    t: t0 + s * (t1 - t0),
                    point: p,
                    distance: d,
                });
            }
        }
    }
}

/// The point of the segment `(a, b)` nearest to `uv`, with its fraction s along it:
/// a + s (b - a), s in [0, 1] (0 for a segment of no length).
fn closest_on_segment(uv: DVec2, (a, b): (DVec2, DVec2)) -> (f64, DVec2) {
    let ab = b - a;
    let len2 = ab.length_squared();
    let s = if len2 > 0.0 {
        ((uv - a).dot(ab) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (s, a + s * ab)
}

/// The largest extent in u or v of the entries' end points and midpoints (at least 1e-300).
fn loop_extent(entries: &[TrimEntry]) -> f64 {
    let mut lo = DVec2::splat(f64::INFINITY);
    let mut hi = DVec2::splat(f64::NEG_INFINITY);
    for e in entries {
        let r = e.pcurve.domain();
        for k in 0..=8 {
            let p = e.pcurve.eval(r.min + r.span() * f64::from(k) / 8.0).point;
            lo = lo.min(p);
            hi = hi.max(p);
        }
    }
    (hi - lo).max_element().max(1e-300)
}

/// Samples `curve` over its domain, halving every piece whose midpoint deviates from its chord
/// by more than `flatness`, up to [`MAX_SEGMENTS_PER_ENTRY`] pieces. Non-finite evaluations stop
/// the subdivision (validation reports them).
fn sample_polyline(curve: &dyn Curve2, flatness: f64) -> Vec<(f64, DVec2)> {
    let range = curve.domain();
    let at = |t: f64| (t, curve.eval(t).point);
    // Start from 8 pieces so that a closed p-curve (a full circle) is not taken for a point.
    let mut points: Vec<(f64, DVec2)> = (0..=8)
        .map(|k| at(range.min + range.span() * f64::from(k) / 8.0))
        .collect();
    let mut k = 0;
    while k + 1 < points.len() && points.len() <= MAX_SEGMENTS_PER_ENTRY {
        let ((t0, a), (t1, b)) = (points[k], points[k + 1]);
        let mid = at(0.5 * (t0 + t1));
        let ab = b - a;
        let deviation = if ab.length_squared() > 0.0 {
            ab.perp_dot(mid.1 - a).abs() / ab.length()
        } else {
            mid.1.distance(a)
        };
        if deviation > flatness && mid.1.is_finite() {
            points.insert(k + 1, mid);
        } else {
            k += 1;
        }
    }
    points
}

#[cfg(test)]
mod tests {
    use super::{Trim, TrimEntry, TrimLoop};
    use crate::curves::curve::ParamRange;
    use crate::curves::curve2::{Circle2, Line2};
    use crate::topology::feature::EdgeId;
    use glam::DVec2;

    fn range(min: f64, max: f64) -> ParamRange {
        ParamRange {
            min,
            max,
            periodic: false,
        }
    }

    /// The square [0, 10]² cut into `pieces` line entries per side (counter-clockwise), with
    /// circular holes (clockwise), each circle in 3 arcs.
    fn plate(pieces: usize, holes: &[(DVec2, f64)]) -> Trim {
        let corners = [
            DVec2::new(0.0, 0.0),
            DVec2::new(10.0, 0.0),
            DVec2::new(10.0, 10.0),
            DVec2::new(0.0, 10.0),
        ];
        let mut edge = 0;
        let mut next = || {
            edge += 1;
            EdgeId(edge)
        };
        let mut outer = Vec::new();
        for k in 0..4 {
            let (a, b) = (corners[k], corners[(k + 1) % 4]);
            for i in 0..pieces {
                let from = a + (b - a) * (i as f64 / pieces as f64);
                let length = 10.0 / pieces as f64;
                let line = Line2 {
                    origin: from,
                    direction: (b - a) / 10.0,
                    range: range(0.0, length),
                };
                outer.push(TrimEntry::new(next(), Box::new(line), false));
            }
        }
        let mut loops = vec![TrimLoop::new(outer)];
        for &(center, radius) in holes {
            let third = std::f64::consts::TAU / 3.0;
            let arcs = (0..3)
                .map(|k| {
                    let arc = Circle2 {
                        center,
                        radius,
                        phase: -third * k as f64,
                        sense: -1.0,
                        range: range(0.0, third),
                    };
                    TrimEntry::new(next(), Box::new(arc), false)
                })
                .collect();
            loops.push(TrimLoop::new(arcs));
        }
        Trim::new(loops, &[range(-5.0, 15.0), range(-5.0, 15.0)])
    }

    /// The closed-form distance from `p` to the boundary of [`plate`]'s region: the square's
    /// sides and the holes' circles.
    fn boundary_distance(p: DVec2, holes: &[(DVec2, f64)]) -> f64 {
        let to_square = if (0.0..=10.0).contains(&p.x) && (0.0..=10.0).contains(&p.y) {
            p.x.min(10.0 - p.x).min(p.y).min(10.0 - p.y)
        } else {
            (DVec2::ZERO.max(-p).max(p - DVec2::splat(10.0))).length()
        };
        holes
            .iter()
            .map(|(c, r)| (p.distance(*c) - r).abs())
            .fold(to_square, f64::min)
    }

    /// Whether `p` lies in [`plate`]'s region: inside the square, outside every hole.
    fn inside(p: DVec2, holes: &[(DVec2, f64)]) -> bool {
        (0.0..=10.0).contains(&p.x)
            && (0.0..=10.0).contains(&p.y)
            && holes.iter().all(|(c, r)| p.distance(*c) >= *r)
    }

    /// The grid answers exactly as the scan it skips: at every point of a fine lattice over
    /// and around the plate (cells clear of the boundary, cells it crosses, points outside the
    /// grid) and at tolerances from none to wider than a cell, and some cells do answer.
    #[test]
    fn the_grid_gives_the_scans_answers() {
        let holes = [(DVec2::new(3.0, 3.0), 1.5), (DVec2::new(7.0, 6.5), 2.0)];
        let trim = plate(5, &holes);
        let grid = trim.grid.as_ref().expect("a plate has a grid");
        let (lo, hi) = trim.bounds();
        let band = 2.0 * super::FLATNESS * (hi - lo).max_element();
        let mut answered = 0;
        for i in 0..=300 {
            for j in 0..=300 {
                let p = DVec2::new(
                    -0.5 + 11.0 * f64::from(i) / 300.0,
                    -0.5 + 11.0 * f64::from(j) / 300.0,
                );
                for tolerance in [0.0, 1e-9, 0.05, 0.5] {
                    let scan = trim.contains_by_scan(p, tolerance, band);
                    assert_eq!(trim.contains(p, tolerance), scan, "{p} at {tolerance}");
                    if let Some(side) = grid.side(p, tolerance.max(band) + band) {
                        assert_eq!(side, scan, "{p} at {tolerance}");
                        answered += 1;
                    }
                }
            }
        }
        // Most of the plate lies clear of its boundary by more than a cell.
        assert!(answered > 4 * 301 * 301 / 2, "{answered}");
    }

    /// The scans that skip groups and runs by their boxes find what a scan of every segment
    /// finds: the nearest polyline distance, the bound's run, and the winding number, around a
    /// plate with a hole that is one circle (its entry has several groups of runs).
    #[test]
    fn grouped_scans_match_every_segment() {
        let mut trim = plate(1, &[]);
        let circle = Circle2 {
            center: DVec2::new(4.0, 5.0),
            radius: 2.5,
            phase: 0.0,
            sense: -1.0,
            range: range(0.0, std::f64::consts::TAU),
        };
        trim.loops.push(TrimLoop::new(vec![TrimEntry::new(
            EdgeId(99),
            Box::new(circle),
            false,
        )]));
        let trim = Trim::new(trim.loops, &[range(-5.0, 15.0), range(-5.0, 15.0)]);
        assert!(trim.loops[1].entries[0].groups.len() > 2);
        for i in 0..=120 {
            for j in 0..=120 {
                let p = DVec2::new(
                    -1.0 + 12.0 * f64::from(i) / 120.0,
                    -1.0 + 12.0 * f64::from(j) / 120.0,
                );
                let segments = trim.loops.iter().flat_map(TrimLoop::segments);
                let crossings: i32 = segments
                    .map(|(a, b)| {
                        if a.y <= p.y {
                            i32::from(b.y > p.y && (b - a).perp_dot(p - a) > 0.0)
                        } else {
                            -i32::from(b.y <= p.y && (b - a).perp_dot(p - a) < 0.0)
                        }
                    })
                    .sum();
                assert_eq!(trim.winding(p), crossings, "{p}");
                let open = trim.loops.iter().flat_map(|l| &l.entries);
                let brute = open
                    .flat_map(|e| e.polyline().windows(2))
                    .map(|w| super::closest_on_segment(p, (w[0].1, w[1].1)).1.distance(p))
                    .fold(f64::INFINITY, f64::min);
                let bound = trim.nearest_bound(p);
                let near = trim
                    .polyline_nearest(p, bound, true)
                    .expect("within its bound");
                assert_eq!(near.distance, brute, "{p}");
            }
        }
    }

    /// The nearest boundary point and containment agree with the closed forms (distance to
    /// the square's sides and to each circle, inside the square and outside every hole, up to
    /// rounding: the point is polished on the exact p-curve) and never farther than the nearest
    /// polyline point of a brute-force scan of every segment, at a grid of points inside,
    /// outside and near the boundary: skipping entries by their boxes loses no nearest point
    /// and no crossing.
    #[test]
    fn nearest_and_contains_match_the_closed_forms() {
        let holes = [(DVec2::new(3.0, 3.0), 1.5), (DVec2::new(7.0, 6.5), 2.0)];
        let trim = plate(7, &holes);
        let chord_error = 2.0 * super::FLATNESS * 10.0;
        let mut worst: f64 = 0.0;
        for i in 0..=60 {
            for j in 0..=60 {
                let p = DVec2::new(
                    -2.0 + 14.0 * f64::from(i) / 60.0,
                    -2.0 + 14.0 * f64::from(j) / 60.0,
                );
                let truth = boundary_distance(p, &holes);
                let brute = trim
                    .loops
                    .iter()
                    .flat_map(|l| &l.entries)
                    .flat_map(|e| e.polyline().windows(2))
                    .map(|w| {
                        let (a, b) = (w[0].1, w[1].1);
                        let s = ((p - a).dot(b - a) / (b - a).length_squared()).clamp(0.0, 1.0);
                        p.distance(a + s * (b - a))
                    })
                    .fold(f64::INFINITY, f64::min);
                let near = trim.nearest(p).expect("a trim with loops");
                assert!(
                    near.distance <= brute + chord_error
                        && (near.distance - truth).abs() <= chord_error,
                    "{p}: {} vs {truth} (polylines {brute})",
                    near.distance
                );
                // The answer is a point of the exact p-curve, not of a polyline's chord.
                let entry = &trim.loops[near.loop_index].entries[near.index];
                assert_eq!(entry.pcurve.eval(near.t).point, near.point, "{p}");
                worst = worst.max((near.distance - truth).abs());
                if truth > chord_error {
                    assert_eq!(trim.contains(p, 0.0), inside(p, &holes), "{p}");
                }
            }
        }
        // Polished on the exact curves, the distances are exact, not chord-accurate.
        assert!(worst <= 1e-12, "{worst}");
    }
}
