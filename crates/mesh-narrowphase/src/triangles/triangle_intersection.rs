//! Triangle–triangle intersection with exact decisions: whether two triangles meet, and the segment or coplanar polygon they share.
//!
//! # Contract
//!
//! * **Decisions are exact.** Every decision (which side of a plane a vertex lies on, whether the
//!   triangles are coplanar, whether two intervals on the line where the planes meet overlap,
//!   whether a point lies in a triangle or on a segment) is made with Shewchuk's adaptive exact
//!   predicates (`robust::orient3d`, and `robust::orient2d` after a coplanar configuration has
//!   been projected onto the axis plane where its normal is largest). Touching configurations
//!   (shared vertex, shared edge, vertex on a face, edge on edge) are therefore reported as
//!   contacts, and a gap of one unit in the last place is reported as [`TriangleContact::Disjoint`].
//!   [`triangles_intersect`] makes exactly the same decisions as [`intersect_triangles`].
//! * **Points are rounded, not exact.** A returned point is an input vertex, bit for bit, when the
//!   true point is one. Otherwise it is interpolated along an edge `[a, b]` (in f64) at the zero
//!   of two plane-side or line-side determinants whose magnitudes carry a relative error of at
//!   most 2^-40: each is evaluated in plain f64 when Shewchuk's error bound certifies that,
//!   and otherwise in double-double arithmetic (relative error about `1e-32` times its
//!   condition number). So a point lies within about 2e-12 `|b - a|` plus a few units in the
//!   last place (relative to the coordinates) of the true point, also for planes `1e-12` or
//!   even `1e-15` rad from parallel, where plain f64 determinants would misplace it by a
//!   relative `1e-4` or worse (the bound sends those to double-double). Every point is
//!   finally clamped into the intersection of the two bounding boxes, which contains the true
//!   common set. The order of a coplanar overlap polygon is decided in f64 (by angle around its
//!   centroid).
//! * **Scale.** Inputs whose largest coordinate magnitude `M` lies outside `[1, 2^64)` are first
//!   scaled by a power of two (exactly) so that it lies in `[1, 2)`, and the results scaled back,
//!   so any finite input is handled without overflow (inputs in that range are used as they
//!   are: scaling by a power of two changes no rounding). Shewchuk's predicates are exact as
//!   long as no intermediate product underflows; that is guaranteed when every non-zero
//!   coordinate, and every non-zero difference of two coordinates along the same axis, is at
//!   least `2^-250 M` (about `5e-76 M`). Smaller ones may make a decision inexact, never a
//!   panic or a NaN.
//! * **Degenerate triangles** (three collinear points or repeated points) are treated as the
//!   segment or point they are, and their contacts are reported as [`TriangleContact::Segment`]
//!   (the common set of a segment or point with anything is a segment or point).
//! * **Non-finite input** (any NaN or infinite coordinate) is reported as
//!   [`TriangleContact::Disjoint`] (and `false`). No input makes these functions panic or return a
//!   NaN.
//!
//! # Algorithm
//!
//! In the spirit of Devillers–Guigue: the vertices of each triangle are classified against the
//! other's plane with `orient3d`, and the pair is rejected if one triangle lies strictly on one
//! side. Otherwise each triangle meets the other's plane in an interval of the line `L` where the
//! planes meet. Each interval end is the point where an edge `(a, b)` of one triangle crosses the
//! other's plane, and the order along `L` of an end of the first interval and an end of the
//! second is the sign of `orient3d(a1, b1, a2, b2)`, so the overlap and its ends are decided
//! exactly, without ever computing a point. Coplanar triangles are intersected in 2D: the
//! overlap polygon's vertices are the vertices of either triangle lying in the other and the
//! proper crossings of their edges.

use core::ops::Deref;

use glam::DVec3;
use robust::{Coord, Coord3D, orient2d, orient3d};

/// How two triangles meet.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum TriangleContact {
    /// No common point (also the answer for any input with a non-finite coordinate).
    Disjoint,
    /// The common set is the segment `[a, b]` (`a == b` when it is a single point).
    ///
    /// Reported for non-coplanar triangles that cross or touch; then `a` precedes (or equals)
    /// `b` along `n1 × n2`, where `ni = (ti[1] - ti[0]) × (ti[2] - ti[0])`. Also reported for any
    /// contact involving a degenerate triangle (collinear or repeated points), whose common set
    /// is always a segment or point; the order of `a` and `b` is then unspecified.
    Segment {
        /// First end of the common segment.
        a: DVec3,
        /// Second end of the common segment.
        b: DVec3,
    },
    /// Two non-degenerate coplanar triangles that overlap, in area or only along an edge or at a
    /// vertex.
    Coplanar {
        /// The vertices of the overlap (a convex polygon, or a segment or point when the
        /// triangles only touch), 1 to 6 distinct points, counter-clockwise seen from the side
        /// `n1 = (t1[1] - t1[0]) × (t1[2] - t1[0])` points to.
        points: OverlapPolygon,
    },
}

/// The overlap of two coplanar triangles: 1 to 6 points in order, stored inline (no heap).
///
/// Dereferences to `[DVec3]`, so `points.len()`, `points[0]` and `points.iter()` work directly.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OverlapPolygon {
    buf: [DVec3; 6],
    len: usize,
}

impl OverlapPolygon {
    const EMPTY: Self = Self {
        buf: [DVec3::ZERO; 6],
        len: 0,
    };

    /// The points of the overlap, in order (see [`TriangleContact::Coplanar`]).
    pub fn points(&self) -> &[DVec3] {
        &self.buf[..self.len]
    }

    /// Appends a point; the overlap of two triangles has at most six vertices, so this never
    /// has to drop one.
    fn push(&mut self, p: DVec3) {
        if let Some(slot) = self.buf.get_mut(self.len) {
            *slot = p;
            self.len += 1;
        }
    }

    /// Orders the points counter-clockwise around their centroid in the projection that drops
    /// `axis`, then reverses them if that projection flips the reference normal (`flip`).
    /// One or two points need no order.
    fn sort_ccw(&mut self, axis: usize, flip: bool) {
        let len = self.len;
        if len < 3 {
            return;
        }
        let pts = &mut self.buf[..len];
        let centre = pts.iter().fold(DVec3::ZERO, |acc, &p| acc + p) / len as f64;
        let c = proj(centre, axis);
        let angle = |p: DVec3| {
            let q = proj(p, axis);
            (q.y - c.y).atan2(q.x - c.x)
        };
        pts.sort_unstable_by(|&p, &q| angle(p).total_cmp(&angle(q)));
        if flip {
            pts.reverse();
        }
    }
}

impl Deref for OverlapPolygon {
    type Target = [DVec3];

    fn deref(&self) -> &[DVec3] {
        self.points()
    }
}

/// Intersects two closed triangles and returns their common set.
///
/// See the module documentation for the exactness contract. Returns
/// [`TriangleContact::Disjoint`] when they share no point or when any coordinate is NaN or
/// infinite. Never panics; every returned coordinate is finite.
pub fn intersect_triangles(t1: &[DVec3; 3], t2: &[DVec3; 3]) -> TriangleContact {
    let contact_of = |a: &[DVec3; 3], b: &[DVec3; 3]| match Stage::of(a, b) {
        Stage::Separated => TriangleContact::Disjoint,
        Stage::Crossing { s1, s2 } => Intervals::new(a, b, &s1, &s2).segment(a, b),
        Stage::Special => special_contact(a, b, false),
    };
    match Frame::new(t1, t2) {
        None => TriangleContact::Disjoint,
        Some(Frame::AsGiven) => clamp_into_boxes(contact_of(t1, t2), (t1, t2), 1.0),
        Some(Frame::Scaled { t1, t2, up }) => {
            clamp_into_boxes(contact_of(&t1, &t2), (&t1, &t2), up[0] * up[1])
        }
    }
}

/// Whether two closed triangles share at least one point: the same exact decision as
/// [`intersect_triangles`] (`false` exactly when it returns [`TriangleContact::Disjoint`]),
/// without computing any point in the common (non-degenerate) cases. Meant for BVH traversal.
pub fn triangles_intersect(t1: &[DVec3; 3], t2: &[DVec3; 3]) -> bool {
    let meet = |a: &[DVec3; 3], b: &[DVec3; 3]| match Stage::of(a, b) {
        Stage::Separated => false,
        Stage::Crossing { s1, s2 } => Intervals::new(a, b, &s1, &s2).overlaps(),
        Stage::Special => !matches!(special_contact(a, b, true), TriangleContact::Disjoint),
    };
    match Frame::new(t1, t2) {
        None => false,
        Some(Frame::AsGiven) => meet(t1, t2),
        Some(Frame::Scaled { t1, t2, .. }) => meet(&t1, &t2),
    }
}

// ---------------------------------------------------------------------------------------------
// Input scaling and output clamping.

/// The coordinates the predicates run on: the inputs as they are when their largest magnitude
/// `M` lies in `[1, 2^64)`, else scaled by a power of two (exactly) so that it lies in `[1, 2)`.
/// In that range no product of the predicates (of degree 3 in the coordinates, with their
/// round-off tails) overflows, and no product of coordinates or differences of at least
/// `2^-250 M` (the module's bound, at least `2^-250` as `M >= 1`) underflows; and scaling by a
/// power of two changes no rounding, so the decisions and points are those of the scaled
/// inputs. (Scaling
/// every pair was a ninth of an exact test's cost on a pencil through a bowl's wall.)
enum Frame {
    /// The inputs need no scaling.
    AsGiven,
    /// The two triangles scaled, with two factors whose product undoes the scaling (each a
    /// representable power of two).
    Scaled {
        t1: [DVec3; 3],
        t2: [DVec3; 3],
        up: [f64; 2],
    },
}

impl Frame {
    /// `None` if any coordinate is not finite.
    fn new(t1: &[DVec3; 3], t2: &[DVec3; 3]) -> Option<Self> {
        // 0 p is ±0 for a finite coordinate and NaN for an infinite or NaN one, and a NaN
        // survives the sum (where a maximum would drop it).
        let [a, b, c] = *t1;
        let [d, e, f] = *t2;
        if a * 0.0 + b * 0.0 + c * 0.0 + d * 0.0 + e * 0.0 + f * 0.0 != DVec3::ZERO {
            return None;
        }
        let m = (a.abs().max(b.abs()).max(c.abs()))
            .max(d.abs().max(e.abs()).max(f.abs()))
            .max_element();
        // m = f 2^e with f in [1, 2) (a subnormal m reads as e = -1023 and is scaled by 2^1023,
        // which is exact too).
        let e = ((m.to_bits() >> 52) & 0x7ff) as i32 - 1023;
        if (0..64).contains(&e) {
            return Some(Self::AsGiven);
        }
        // Scale by 2^-e in two steps so that each factor is a normal power of two.
        let k1 = -e / 2;
        let k2 = -e - k1;
        let (d1, d2) = (pow2(k1), pow2(k2));
        let scale = |t: &[DVec3; 3]| t.map(|p| p * d1 * d2);
        Some(Self::Scaled {
            t1: scale(t1),
            t2: scale(t2),
            up: [pow2(-k1), pow2(-k2)],
        })
    }
}

/// Clamps every point of `contact` into the intersection of the bounding boxes of `t1` and `t2`
/// (which contains the true common set) and multiplies it by `up` (undoing a [`Frame`]'s
/// scaling; a power of two, so exact, or 1).
fn clamp_into_boxes(
    contact: TriangleContact,
    (t1, t2): (&[DVec3; 3], &[DVec3; 3]),
    up: f64,
) -> TriangleContact {
    let lo = min3(t1).max(min3(t2));
    let hi = max3(t1).min(max3(t2));
    let map = |p: DVec3| p.max(lo).min(hi) * up;
    match contact {
        TriangleContact::Disjoint => TriangleContact::Disjoint,
        TriangleContact::Segment { a, b } => TriangleContact::Segment {
            a: map(a),
            b: map(b),
        },
        TriangleContact::Coplanar { mut points } => {
            let len = points.len;
            for p in &mut points.buf[..len] {
                *p = map(*p);
            }
            TriangleContact::Coplanar { points }
        }
    }
}

/// `2^k` for `k` in `[-1022, 1023]` (the callers stay within `[-512, 512]`).
fn pow2(k: i32) -> f64 {
    f64::from_bits(((k.clamp(-1022, 1023) + 1023) as u64) << 52)
}

fn min3(t: &[DVec3; 3]) -> DVec3 {
    t[0].min(t[1]).min(t[2])
}

fn max3(t: &[DVec3; 3]) -> DVec3 {
    t[0].max(t[1]).max(t[2])
}

// ---------------------------------------------------------------------------------------------
// Exact predicates.

fn c3(p: DVec3) -> Coord3D<f64> {
    Coord3D {
        x: p.x,
        y: p.y,
        z: p.z,
    }
}

/// Exact sign (approximate magnitude) of `n · (p - t[0])` with `n = (t[1] - t[0]) × (t[2] - t[0])`:
/// positive on the side the right-hand normal of `t` points to.
fn side(t: &[DVec3; 3], p: DVec3) -> f64 {
    -orient3d(c3(t[0]), c3(t[1]), c3(t[2]), c3(p))
}

/// The magnitude of [`side`] (used only once its exact sign is known), with relative error at
/// most [`MAGNITUDE_RELATIVE_ERROR`] (about `1e-30` times the condition number where the plain
/// evaluation cannot promise that).
fn side_magnitude(t: &[DVec3; 3], p: DVec3) -> f64 {
    orient3d_f64(t[0], t[1], t[2], p).map_or_else(|| -orient3d_dd(t[0], t[1], t[2], p), |v| -v)
}

/// Sides of the vertices of `pts` relative to the plane of `t` ([`side`]'s exact signs), each
/// with its magnitude certified where the plain evaluation certifies it ([`side_magnitude`]'s
/// first step, so that a crossing point need not evaluate it again).
fn sides(t: &[DVec3; 3], pts: &[DVec3; 3]) -> Sides {
    let mut certified = [false; 3];
    let mut value = [0.0; 3];
    for k in 0..3 {
        (value[k], certified[k]) = match orient3d_f64(t[0], t[1], t[2], pts[k]) {
            Some(v) => (-v, true),
            None => (side(t, pts[k]), false),
        };
    }
    Sides { value, certified }
}

/// The sides of a triangle's three vertices relative to the other triangle's plane ([`sides`]).
#[derive(Clone, Copy)]
struct Sides {
    /// Exact in sign.
    value: [f64; 3],
    /// Whether each value's magnitude is [`side_magnitude`]'s too.
    certified: [bool; 3],
}

fn strictly_one_side(s: &[f64; 3]) -> bool {
    s.iter().all(|&v| v > 0.0) || s.iter().all(|&v| v < 0.0)
}

fn opposite(x: f64, y: f64) -> bool {
    (x > 0.0 && y < 0.0) || (x < 0.0 && y > 0.0)
}

/// Projection dropping `axis`, keeping the cyclic order of the two others, so that
/// `orient2d` of projected points has the sign of component `axis` of the 3D normal.
fn proj(p: DVec3, axis: usize) -> Coord<f64> {
    let v = p.to_array();
    Coord {
        x: v[(axis + 1) % 3],
        y: v[(axis + 2) % 3],
    }
}

fn orient(a: DVec3, b: DVec3, c: DVec3, axis: usize) -> f64 {
    orient2d(proj(a, axis), proj(b, axis), proj(c, axis))
}

/// Components of `(b - a) × (c - a)`, each with its exact sign.
fn normal(a: DVec3, b: DVec3, c: DVec3) -> [f64; 3] {
    [0, 1, 2].map(|axis| orient(a, b, c, axis))
}

/// Index of the component of largest magnitude (a non-zero one if any is non-zero).
fn dominant_axis(n: &[f64; 3]) -> usize {
    let mut k = 0;
    for i in 1..3 {
        if n[i].abs() > n[k].abs() {
            k = i;
        }
    }
    k
}

/// `approx` when it has the same strict sign as `exact` (a value with exact sign), else `exact`.
fn refine(exact: f64, approx: f64) -> f64 {
    if opposite(exact, -approx) {
        approx
    } else {
        exact
    }
}

/// The zero of the linear interpolation between `a` (value `fa`) and `b` (value `fb`), which
/// have strictly opposite signs; interpolated from the nearer end.
fn lerp_zero(a: DVec3, b: DVec3, fa: f64, fb: f64) -> DVec3 {
    if fa.abs() <= fb.abs() {
        a + (b - a) * (fa / (fa - fb))
    } else {
        b + (a - b) * (fb / (fb - fa))
    }
}

// ---------------------------------------------------------------------------------------------
// Non-coplanar triangles: intervals on the line where the planes meet.

/// Where the plane of one triangle is decided to meet the other triangle.
enum Stage {
    /// One triangle lies strictly on one side of the other's plane.
    Separated,
    /// Both triangles are non-degenerate and cross (or touch) each other's plane transversally;
    /// `s1` are the sides of t1's vertices relative to the plane of t2, `s2` the converse.
    Crossing { s1: Sides, s2: Sides },
    /// Coplanar, or at least one triangle degenerate.
    Special,
}

impl Stage {
    fn of(t1: &[DVec3; 3], t2: &[DVec3; 3]) -> Self {
        let s2 = sides(t1, t2);
        if strictly_one_side(&s2.value) {
            return Self::Separated;
        }
        let s1 = sides(t2, t1);
        if strictly_one_side(&s1.value) {
            return Self::Separated;
        }
        // A degenerate triangle has every point on its "plane": all sides against it vanish.
        // Some non-zero side on each side therefore means both triangles are non-degenerate and
        // not coplanar.
        if s1.value.iter().all(|&v| v == 0.0) || s2.value.iter().all(|&v| v == 0.0) {
            return Self::Special;
        }
        Self::Crossing { s1, s2 }
    }
}

/// The point where edge `[pos, neg]` of one triangle meets the other triangle's plane; `pos`
/// is on the positive side or on the plane, `neg` on the negative side or on the plane, not
/// both on it.
#[derive(Clone, Copy)]
struct Crossing {
    pos: DVec3,
    neg: DVec3,
    pos_side: f64,
    neg_side: f64,
    /// Whether `pos_side` and `neg_side` are certified magnitudes ([`Sides::certified`]).
    certified: [bool; 2],
}

impl Crossing {
    /// Whether the crossing is a vertex of the input (then it is returned exactly).
    fn is_vertex(&self) -> bool {
        self.pos_side == 0.0 || self.neg_side == 0.0
    }

    /// The crossing point, `plane` being the other triangle.
    fn point(&self, plane: &[DVec3; 3]) -> DVec3 {
        if self.neg_side == 0.0 {
            self.neg
        } else if self.pos_side == 0.0 {
            self.pos
        } else {
            let magnitude = |value: f64, certified: bool, p: DVec3| {
                if certified {
                    value
                } else {
                    refine(value, side_magnitude(plane, p))
                }
            };
            let fp = magnitude(self.pos_side, self.certified[0], self.pos);
            let fn_ = magnitude(self.neg_side, self.certified[1], self.neg);
            lerp_zero(self.pos, self.neg, fp, fn_)
        }
    }
}

/// Exact order along `D = n1 × n2` of a crossing `c1` of `t1` and a crossing `c2` of `t2`: the
/// sign of `D · (X2 - X1)` (positive when `c1` comes first).
///
/// With `u = b1 - a1` in plane 1 and `v = b2 - a2` in plane 2, `det[u, v, X2 - X1] = det[u, v,
/// a2 - a1] = orient3d(a1, b1, a2, b2)`, and `(u × v) · D = -(u · n2)(v · n1) < 0`.
fn order(c1: &Crossing, c2: &Crossing) -> f64 {
    -orient3d(c3(c1.pos), c3(c1.neg), c3(c2.pos), c3(c2.neg))
}

/// The interval `t ∩ plane(other)` as `(first, last)` crossings along `n_t × n_other`, given the
/// sides `s` of the vertices of `t` (not all zero, not all strictly of one sign).
fn interval(t: &[DVec3; 3], sides: &Sides) -> (Crossing, Crossing) {
    let (s, c) = (&sides.value, &sides.certified);
    for i in 0..3 {
        let (j, k) = ((i + 1) % 3, (i + 2) % 3);
        // (t[i], t[j], t[k]) keeps the orientation of t. With t[i] alone on the positive side,
        // edge (t[i], t[j]) meets the other plane after edge (t[i], t[k]) along n_t × n_other,
        // and the other way round with t[i] alone on the negative side.
        if s[i] > 0.0 && s[j] <= 0.0 && s[k] <= 0.0 {
            let x = Crossing {
                pos: t[i],
                neg: t[j],
                pos_side: s[i],
                neg_side: s[j],
                certified: [c[i], c[j]],
            };
            let y = Crossing {
                pos: t[i],
                neg: t[k],
                pos_side: s[i],
                neg_side: s[k],
                certified: [c[i], c[k]],
            };
            return (y, x);
        }
        if s[i] < 0.0 && s[j] >= 0.0 && s[k] >= 0.0 {
            let x = Crossing {
                pos: t[j],
                neg: t[i],
                pos_side: s[j],
                neg_side: s[i],
                certified: [c[j], c[i]],
            };
            let y = Crossing {
                pos: t[k],
                neg: t[i],
                pos_side: s[k],
                neg_side: s[i],
                certified: [c[k], c[i]],
            };
            return (x, y);
        }
    }
    // Otherwise one vertex lies on the plane and the other two strictly on one side: the
    // interval is that vertex, written as a crossing of an edge leaving it.
    let i = s.iter().position(|&v| v == 0.0).unwrap_or(0);
    let j = (i + 1) % 3;
    let c = if s[j] > 0.0 {
        Crossing {
            pos: t[j],
            neg: t[i],
            pos_side: s[j],
            neg_side: s[i],
            certified: [c[j], c[i]],
        }
    } else {
        Crossing {
            pos: t[i],
            neg: t[j],
            pos_side: s[i],
            neg_side: s[j],
            certified: [c[i], c[j]],
        }
    };
    (c, c)
}

/// The two intervals on `L`, oriented along `n1 × n2`.
struct Intervals {
    lo1: Crossing,
    hi1: Crossing,
    lo2: Crossing,
    hi2: Crossing,
}

impl Intervals {
    fn new(t1: &[DVec3; 3], t2: &[DVec3; 3], s1: &Sides, s2: &Sides) -> Self {
        let (lo1, hi1) = interval(t1, s1);
        // Along n1 × n2 the interval of t2 runs the other way (its rule is stated along n2 × n1).
        let (hi2, lo2) = interval(t2, s2);
        Self { lo1, hi1, lo2, hi2 }
    }

    fn overlaps(&self) -> bool {
        order(&self.lo1, &self.hi2) >= 0.0 && order(&self.hi1, &self.lo2) <= 0.0
    }

    fn segment(&self, t1: &[DVec3; 3], t2: &[DVec3; 3]) -> TriangleContact {
        let first = order(&self.lo1, &self.hi2);
        let last = order(&self.hi1, &self.lo2);
        if first < 0.0 || last > 0.0 {
            return TriangleContact::Disjoint;
        }
        // Crossings of t1 lie on the plane of t2 and vice versa. When two ends coincide
        // exactly, one point stands for both, a vertex if either is one (returned exactly).
        if first == 0.0 {
            return point_contact(coincident(&self.lo1, &self.hi2, t1, t2));
        }
        if last == 0.0 {
            return point_contact(coincident(&self.hi1, &self.lo2, t1, t2));
        }
        let o = order(&self.lo1, &self.lo2);
        let a = if o > 0.0 {
            self.lo2.point(t1)
        } else if o < 0.0 {
            self.lo1.point(t2)
        } else {
            coincident(&self.lo1, &self.lo2, t1, t2)
        };
        let o = order(&self.hi1, &self.hi2);
        let b = if o > 0.0 {
            self.hi1.point(t2)
        } else if o < 0.0 {
            self.hi2.point(t1)
        } else {
            coincident(&self.hi1, &self.hi2, t1, t2)
        };
        TriangleContact::Segment { a, b }
    }
}

/// The point of a crossing `c1` of `t1` and a crossing `c2` of `t2` known to coincide: a
/// vertex if either is one.
fn coincident(c1: &Crossing, c2: &Crossing, t1: &[DVec3; 3], t2: &[DVec3; 3]) -> DVec3 {
    if c1.is_vertex() || !c2.is_vertex() {
        c1.point(t2)
    } else {
        c2.point(t1)
    }
}

// ---------------------------------------------------------------------------------------------
// Coplanar and degenerate configurations.

/// What a triangle is once degeneracies are resolved.
enum Shape {
    Triangle([DVec3; 3]),
    /// Distinct ends.
    Segment(DVec3, DVec3),
    Point(DVec3),
}

impl Shape {
    fn of(t: &[DVec3; 3]) -> Self {
        if normal(t[0], t[1], t[2]).iter().any(|&c| c != 0.0) {
            return Self::Triangle(*t);
        }
        // Collinear: along an axis where the points are not all equal the order along the line
        // is the order of that coordinate.
        let spread = max3(t) - min3(t);
        let axis = dominant_axis(&spread.to_array());
        if spread[axis] == 0.0 {
            return Self::Point(t[0]);
        }
        let key = |i: &usize| t[*i][axis];
        let lo = (0..3).min_by(|i, j| key(i).total_cmp(&key(j))).unwrap_or(0);
        let hi = (0..3).max_by(|i, j| key(i).total_cmp(&key(j))).unwrap_or(0);
        Self::Segment(t[lo], t[hi])
    }
}

fn point_contact(p: DVec3) -> TriangleContact {
    TriangleContact::Segment { a: p, b: p }
}

/// Contact when the triangles are coplanar or one is degenerate (the [`Stage::Special`] case).
/// With `first_only`, the coplanar polygon stops at its first point (enough to decide, same
/// decision).
///
/// [`Stage::of`] has already rejected a triangle strictly on one side of the other's plane, so
/// a degenerate triangle met here has no two points strictly on the same side of a
/// non-degenerate one's plane: a point lies on it, and a segment touches or crosses it.
fn special_contact(t1: &[DVec3; 3], t2: &[DVec3; 3], first_only: bool) -> TriangleContact {
    match (Shape::of(t1), Shape::of(t2)) {
        (Shape::Triangle(a), Shape::Triangle(b)) => {
            let points = coplanar_overlap(&a, &b, first_only);
            if points.is_empty() {
                TriangleContact::Disjoint
            } else {
                TriangleContact::Coplanar { points }
            }
        }
        (Shape::Triangle(t), Shape::Segment(p, q)) | (Shape::Segment(p, q), Shape::Triangle(t)) => {
            segment_triangle(p, q, &t)
        }
        (Shape::Triangle(t), Shape::Point(x)) | (Shape::Point(x), Shape::Triangle(t)) => {
            // x lies in the plane of t (see above).
            if in_triangle(&t, x) {
                point_contact(x)
            } else {
                TriangleContact::Disjoint
            }
        }
        (Shape::Segment(p, q), Shape::Segment(r, s)) => segment_segment(p, q, r, s),
        (Shape::Segment(p, q), Shape::Point(x)) | (Shape::Point(x), Shape::Segment(p, q)) => {
            if collinear(p, q, x) && within(p, q, x) {
                point_contact(x)
            } else {
                TriangleContact::Disjoint
            }
        }
        (Shape::Point(x), Shape::Point(y)) => {
            if x == y {
                point_contact(x)
            } else {
                TriangleContact::Disjoint
            }
        }
    }
}

/// A triangle's projection axis (its dominant normal component) and orientation sign there.
fn frame_2d(t: &[DVec3; 3]) -> (usize, f64) {
    let n = normal(t[0], t[1], t[2]);
    let axis = dominant_axis(&n);
    (axis, if n[axis] < 0.0 { -1.0 } else { 1.0 })
}

/// Whether `x`, lying in the plane of the non-degenerate `t`, lies in the closed triangle.
fn in_triangle(t: &[DVec3; 3], x: DVec3) -> bool {
    let (axis, sign) = frame_2d(t);
    (0..3).all(|i| sign * orient(t[i], t[(i + 1) % 3], x, axis) >= 0.0)
}

fn collinear(a: DVec3, b: DVec3, c: DVec3) -> bool {
    normal(a, b, c).iter().all(|&v| v == 0.0)
}

/// Whether `x`, collinear with the distinct `p` and `q`, lies on the closed segment `[p, q]`.
fn within(p: DVec3, q: DVec3, x: DVec3) -> bool {
    let axis = dominant_axis(&(q - p).abs().to_array());
    let (lo, hi) = if p[axis] <= q[axis] {
        (p[axis], q[axis])
    } else {
        (q[axis], p[axis])
    };
    lo <= x[axis] && x[axis] <= hi
}

/// The point where the interiors of the coplanar segments `[p, q]` and `[r, s]` cross, if they
/// do at a single point interior to both (projected on `axis`, where their plane projects 1:1).
fn proper_crossing(p: DVec3, q: DVec3, r: DVec3, s: DVec3, axis: usize) -> Option<DVec3> {
    if !opposite(orient(p, q, r, axis), orient(p, q, s, axis)) {
        return None;
    }
    let (op, oq) = (orient(r, s, p, axis), orient(r, s, q, axis));
    if !opposite(op, oq) {
        return None;
    }
    let (pr, ps) = (proj(r, axis), proj(s, axis));
    let fp = refine(op, orient2d_magnitude(pr, ps, proj(p, axis)));
    let fq = refine(oq, orient2d_magnitude(pr, ps, proj(q, axis)));
    Some(lerp_zero(p, q, fp, fq))
}

/// Overlap of two coplanar non-degenerate triangles: its vertices are the vertices of either
/// triangle lying in the other and the proper crossings of their edges (all distinct except a
/// vertex shared by both triangles, kept once).
fn coplanar_overlap(t1: &[DVec3; 3], t2: &[DVec3; 3], first_only: bool) -> OverlapPolygon {
    let (axis, sign1) = frame_2d(t1);
    let sign2 = if orient(t2[0], t2[1], t2[2], axis) < 0.0 {
        -1.0
    } else {
        1.0
    };
    let inside = |t: &[DVec3; 3], sign: f64, x: DVec3| {
        (0..3).all(|i| sign * orient(t[i], t[(i + 1) % 3], x, axis) >= 0.0)
    };
    let mut poly = OverlapPolygon::EMPTY;
    let candidates = t1
        .iter()
        .filter(|&&v| inside(t2, sign2, v))
        .chain(
            t2.iter()
                .filter(|&&v| !t1.contains(&v) && inside(t1, sign1, v)),
        )
        .copied();
    for v in candidates {
        poly.push(v);
        if first_only {
            return poly;
        }
    }
    for i in 0..3 {
        for j in 0..3 {
            let crossing = proper_crossing(t1[i], t1[(i + 1) % 3], t2[j], t2[(j + 1) % 3], axis);
            if let Some(x) = crossing {
                poly.push(x);
                if first_only {
                    return poly;
                }
            }
        }
    }
    poly.sort_ccw(axis, sign1 < 0.0);
    poly
}

/// Segment `[p, q]` (distinct ends, not strictly on one side of the plane) against the
/// non-degenerate triangle `t`.
fn segment_triangle(p: DVec3, q: DVec3, t: &[DVec3; 3]) -> TriangleContact {
    let (sp, sq) = (side(t, p), side(t, q));
    if sp == 0.0 && sq == 0.0 {
        return segment_in_plane(p, q, t);
    }
    // The line crosses the plane at one point X; the volumes orient3d(p, q, t_i, t_i+1) have
    // the sign of (q - p) · n times the signed area of (X, t_i, t_i+1): X is in the triangle
    // exactly when no two of them have strictly opposite signs.
    let v = [0, 1, 2].map(|i| orient3d(c3(p), c3(q), c3(t[i]), c3(t[(i + 1) % 3])));
    if opposite(v[0], v[1]) || opposite(v[1], v[2]) || opposite(v[2], v[0]) {
        return TriangleContact::Disjoint;
    }
    let x = if sp == 0.0 {
        p
    } else if sq == 0.0 {
        q
    } else {
        lerp_zero(
            p,
            q,
            refine(sp, side_magnitude(t, p)),
            refine(sq, side_magnitude(t, q)),
        )
    };
    point_contact(x)
}

/// Segment `[p, q]` lying in the plane of the non-degenerate triangle `t`: the common segment's
/// ends are among `p`, `q` (if in `t`), the vertices of `t` on `[p, q]` and the proper crossings
/// of `[p, q]` with the edges of `t`.
fn segment_in_plane(p: DVec3, q: DVec3, t: &[DVec3; 3]) -> TriangleContact {
    let (axis, _) = frame_2d(t);
    let ends = [p, q].into_iter().filter(|&x| in_triangle(t, x));
    let vertices = t
        .iter()
        .copied()
        .filter(|&v| orient(p, q, v, axis) == 0.0 && within(p, q, v));
    let crossings = (0..3).filter_map(|i| proper_crossing(p, q, t[i], t[(i + 1) % 3], axis));
    let dir = q - p;
    let mut span: Option<((f64, DVec3), (f64, DVec3))> = None;
    for x in ends.chain(vertices).chain(crossings) {
        let key = (x - p).dot(dir);
        span = Some(match span {
            None => ((key, x), (key, x)),
            Some((lo, hi)) => (
                if key < lo.0 { (key, x) } else { lo },
                if key > hi.0 { (key, x) } else { hi },
            ),
        });
    }
    match span {
        Some(((_, a), (_, b))) => TriangleContact::Segment { a, b },
        None => TriangleContact::Disjoint,
    }
}

/// Two segments with distinct ends.
fn segment_segment(p: DVec3, q: DVec3, r: DVec3, s: DVec3) -> TriangleContact {
    if orient3d(c3(p), c3(q), c3(r), c3(s)) != 0.0 {
        return TriangleContact::Disjoint;
    }
    let nr = normal(p, q, r);
    let ns = normal(p, q, s);
    let r_on_line = nr.iter().all(|&v| v == 0.0);
    let s_on_line = ns.iter().all(|&v| v == 0.0);
    if r_on_line && s_on_line {
        // Same line: overlap of the two ranges along an axis where the line is not flat.
        let axis = dominant_axis(&(q - p).abs().to_array());
        let sorted = |a: DVec3, b: DVec3| if a[axis] <= b[axis] { (a, b) } else { (b, a) };
        let ((p, q), (r, s)) = (sorted(p, q), sorted(r, s));
        let lo = if r[axis] > p[axis] { r } else { p };
        let hi = if s[axis] < q[axis] { s } else { q };
        return if lo[axis] <= hi[axis] {
            TriangleContact::Segment { a: lo, b: hi }
        } else {
            TriangleContact::Disjoint
        };
    }
    // Distinct coplanar lines: project along the dominant normal of the plane they span.
    let axis = dominant_axis(if r_on_line { &ns } else { &nr });
    let (o1, o2) = (orient(p, q, r, axis), orient(p, q, s, axis));
    let (o3, o4) = (orient(r, s, p, axis), orient(r, s, q, axis));
    if opposite(o1, -o2) || opposite(o3, -o4) {
        return TriangleContact::Disjoint;
    }
    // The lines meet at one point, which both segments contain; name it.
    if o1 == 0.0 {
        point_contact(r)
    } else if o2 == 0.0 {
        point_contact(s)
    } else if o3 == 0.0 {
        point_contact(p)
    } else if o4 == 0.0 {
        point_contact(q)
    } else {
        proper_crossing(p, q, r, s, axis).map_or(TriangleContact::Disjoint, point_contact)
    }
}

// ---------------------------------------------------------------------------------------------
// The predicates' magnitudes (for constructing points): plain f64 where its error bound allows,
// else double-double.

/// Largest relative error of a determinant's magnitude taken from its plain f64 evaluation
/// (2^-40): beyond it the determinant is evaluated in double-double.
///
/// A crossing point is interpolated at the zero of two such magnitudes, so its offset along its
/// edge `[a, b]` errs by at most about twice this times `|b - a|` (1.8e-12 x the edge length),
/// besides the interpolation's own rounding (a few units in the last place).
const MAGNITUDE_RELATIVE_ERROR: f64 = 1.0 / 1_099_511_627_776.0;

/// Shewchuk's error bound factor for orient3d's plain f64 evaluation: |computed - exact| <=
/// `O3D_ERRBOUND` x the permanent (the same sum with every product's absolute value).
const O3D_ERRBOUND: f64 = (7.0 + 56.0 * HALF_EPSILON) * HALF_EPSILON;
/// Shewchuk's error bound factor for orient2d's plain f64 evaluation.
const O2D_ERRBOUND: f64 = (3.0 + 16.0 * HALF_EPSILON) * HALF_EPSILON;
/// The unit roundoff 2^-53 (Shewchuk's epsilon).
const HALF_EPSILON: f64 = f64::EPSILON / 2.0;

/// `robust::orient3d(a, b, c, d)` in plain f64 (the same formula and sign convention), when
/// Shewchuk's bound certifies its relative error within [`MAGNITUDE_RELATIVE_ERROR`]; `None`
/// otherwise (or for a non-finite value).
fn orient3d_f64(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> Option<f64> {
    let (ad, bd, cd) = (a - d, b - d, c - d);
    let (bc, ca, ab) = (
        bd.x * cd.y - cd.x * bd.y,
        cd.x * ad.y - ad.x * cd.y,
        ad.x * bd.y - bd.x * ad.y,
    );
    let det = ad.z * bc + bd.z * ca + cd.z * ab;
    let permanent = ad.z.abs() * ((bd.x * cd.y).abs() + (cd.x * bd.y).abs())
        + bd.z.abs() * ((cd.x * ad.y).abs() + (ad.x * cd.y).abs())
        + cd.z.abs() * ((ad.x * bd.y).abs() + (bd.x * ad.y).abs());
    certified(det, O3D_ERRBOUND * permanent)
}

/// `robust::orient2d(a, b, c)` in plain f64, as [`orient3d_f64`].
fn orient2d_f64(a: Coord<f64>, b: Coord<f64>, c: Coord<f64>) -> Option<f64> {
    let (left, right) = ((a.x - c.x) * (b.y - c.y), (a.y - c.y) * (b.x - c.x));
    certified(left - right, O2D_ERRBOUND * (left.abs() + right.abs()))
}

/// `value` when its absolute error bound `error` is within [`MAGNITUDE_RELATIVE_ERROR`] of it.
/// (Below 1e-250 in magnitude, where a product may have underflowed and the bound no longer
/// holds, `None`: the inputs are scaled so that their largest coordinate is in [1, 2).)
fn certified(value: f64, error: f64) -> Option<f64> {
    (error.is_finite() && value.abs() >= 1e-250 && error <= MAGNITUDE_RELATIVE_ERROR * value.abs())
        .then_some(value)
}

/// The magnitude of `robust::orient2d(a, b, c)` (used once its exact sign is known), with
/// relative error at most [`MAGNITUDE_RELATIVE_ERROR`].
fn orient2d_magnitude(a: Coord<f64>, b: Coord<f64>, c: Coord<f64>) -> f64 {
    orient2d_f64(a, b, c).unwrap_or_else(|| orient2d_dd(a, b, c))
}

/// 2^27 + 1, Dekker's splitter for f64.
const SPLITTER: f64 = 134_217_729.0;

/// Unevaluated sum `hi + lo` with `|lo| <= ulp(hi) / 2`.
#[derive(Clone, Copy)]
struct Dd {
    hi: f64,
    lo: f64,
}

fn two_sum(a: f64, b: f64) -> Dd {
    let s = a + b;
    let bv = s - a;
    let av = s - bv;
    Dd {
        hi: s,
        lo: (a - av) + (b - bv),
    }
}

/// `two_sum` for `|a| >= |b|` (or `a == 0`).
fn fast_two_sum(a: f64, b: f64) -> Dd {
    let s = a + b;
    Dd {
        hi: s,
        lo: b - (s - a),
    }
}

fn split(a: f64) -> (f64, f64) {
    let c = SPLITTER * a;
    let big = c - a;
    let hi = c - big;
    (hi, a - hi)
}

fn two_product(a: f64, b: f64) -> Dd {
    let p = a * b;
    let (ah, al) = split(a);
    let (bh, bl) = split(b);
    let err = al * bl - (((p - ah * bh) - al * bh) - ah * bl);
    Dd { hi: p, lo: err }
}

impl Dd {
    /// `a - b`, exactly.
    fn diff(a: f64, b: f64) -> Self {
        two_sum(a, -b)
    }

    fn add(self, o: Self) -> Self {
        let s = two_sum(self.hi, o.hi);
        let t = two_sum(self.lo, o.lo);
        let u = fast_two_sum(s.hi, s.lo + t.hi);
        fast_two_sum(u.hi, u.lo + t.lo)
    }

    fn sub(self, o: Self) -> Self {
        self.add(Self {
            hi: -o.hi,
            lo: -o.lo,
        })
    }

    fn mul(self, o: Self) -> Self {
        let p = two_product(self.hi, o.hi);
        fast_two_sum(p.hi, p.lo + (self.hi * o.lo + self.lo * o.hi))
    }
}

/// `robust::orient3d(a, b, c, d)` evaluated in double-double (same formula and sign convention).
fn orient3d_dd(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> f64 {
    let [adx, ady, adz] = [0, 1, 2].map(|i| Dd::diff(a[i], d[i]));
    let [bdx, bdy, bdz] = [0, 1, 2].map(|i| Dd::diff(b[i], d[i]));
    let [cdx, cdy, cdz] = [0, 1, 2].map(|i| Dd::diff(c[i], d[i]));
    let bc = bdx.mul(cdy).sub(cdx.mul(bdy));
    let ca = cdx.mul(ady).sub(adx.mul(cdy));
    let ab = adx.mul(bdy).sub(bdx.mul(ady));
    adz.mul(bc).add(bdz.mul(ca)).add(cdz.mul(ab)).hi
}

/// `robust::orient2d(a, b, c)` evaluated in double-double (same formula and sign convention).
fn orient2d_dd(a: Coord<f64>, b: Coord<f64>, c: Coord<f64>) -> f64 {
    let (acx, acy) = (Dd::diff(a.x, c.x), Dd::diff(a.y, c.y));
    let (bcx, bcy) = (Dd::diff(b.x, c.x), Dd::diff(b.y, c.y));
    acx.mul(bcy).sub(acy.mul(bcx)).hi
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Uniform numbers in [-0.5, 0.5) from an xorshift generator started at `state`.
    fn uniform(mut state: u64) -> impl FnMut() -> f64 {
        move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        }
    }

    /// A plain f64 magnitude is taken only where it is within its promised relative error of
    /// the double-double one, and close to a plane (where it is not) double-double decides.
    #[test]
    fn plain_magnitudes_are_taken_only_within_their_bound() {
        let mut next = uniform(0x2545_f491_4f6c_dd1d_u64);
        let (mut plain, mut doubled) = (0, 0);
        for k in 0..40_000 {
            let a = DVec3::new(next(), next(), next());
            let b = DVec3::new(next(), next(), next());
            let c = DVec3::new(next(), next(), next());
            // Half the points lie within 10^-(k mod 16) of the plane of (a, b, c).
            let off = 10f64.powi(-(k % 16));
            let d = if k % 2 == 0 {
                DVec3::new(next(), next(), next())
            } else {
                a + (b - a) * next() + (c - a) * next() + DVec3::splat(next() * off)
            };
            let dd = orient3d_dd(a, b, c, d);
            match orient3d_f64(a, b, c, d) {
                Some(v) => {
                    plain += 1;
                    assert!(
                        (v - dd).abs() <= MAGNITUDE_RELATIVE_ERROR * dd.abs(),
                        "{v} vs {dd}"
                    );
                }
                None => doubled += 1,
            }
            let (pa, pb, pc) = (proj(a, 2), proj(b, 2), proj(d, 2));
            let dd2 = orient2d_dd(pa, pb, pc);
            if let Some(v) = orient2d_f64(pa, pb, pc) {
                assert!(
                    (v - dd2).abs() <= MAGNITUDE_RELATIVE_ERROR * dd2.abs(),
                    "{v} vs {dd2}"
                );
            }
        }
        // Both evaluations are exercised: most points are clear of the plane.
        assert!(
            plain > 20_000 && doubled > 2_000,
            "{plain} plain, {doubled} doubled"
        );
    }

    /// The double-double determinants agree in sign with the exact predicates on nearly
    /// degenerate inputs, and are accurate where plain f64 is not.
    #[test]
    fn double_double_determinants_match_exact_signs() {
        let mut next = uniform(0x9e37_79b9_7f4a_7c15_u64);
        for _ in 0..20_000 {
            let a = DVec3::new(next(), next(), next());
            let b = DVec3::new(next(), next(), next());
            let c = DVec3::new(next(), next(), next());
            // A point very close to the plane of (a, b, c).
            let d = a + (b - a) * next() + (c - a) * next() + DVec3::splat(next() * 1e-14);
            let exact = orient3d(c3(a), c3(b), c3(c), c3(d));
            let dd = orient3d_dd(a, b, c, d);
            assert_eq!(exact > 0.0, dd > 0.0, "{exact} vs {dd}");
            assert_eq!(exact < 0.0, dd < 0.0, "{exact} vs {dd}");
            let (pa, pb, pc) = (proj(a, 2), proj(b, 2), proj(d, 2));
            let exact2 = orient2d(pa, pb, pc);
            let dd2 = orient2d_dd(pa, pb, pc);
            assert_eq!(exact2 > 0.0, dd2 > 0.0);
            assert_eq!(exact2 < 0.0, dd2 < 0.0);
        }
        // (1 + e)(1 - e) - 1 = -e^2 with e = 2^-52: lost entirely by a plain f64 evaluation.
        let e = f64::EPSILON;
        let a = DVec3::new(1.0 + e, 1.0, 0.0);
        let b = DVec3::new(1.0, 1.0 - e, 0.0);
        let (o, d) = (DVec3::ZERO, DVec3::Z);
        assert_eq!((1.0 + e) * (1.0 - e) - 1.0, 0.0);
        assert_eq!(orient2d_dd(proj(a, 2), proj(b, 2), proj(o, 2)), -e * e);
        assert!(orient2d(proj(a, 2), proj(b, 2), proj(o, 2)) < 0.0);
        assert_eq!(orient3d_dd(a, b, o, d), e * e);
        assert!(orient3d(c3(a), c3(b), c3(o), c3(d)) > 0.0);
    }
}
