//! Closest points between triangles, segments and points, with barycentric coordinates so that
//! a closest point can be located on the exact surface ([`geom_param::ComponentMesh::locate`]).

use glam::DVec3;

/// A point of a triangle with its barycentric coordinates (corner order of the triangle).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TrianglePoint {
    /// The point.
    pub point: DVec3,
    /// Its barycentric coordinates, non-negative, summing to 1.
    pub barycentric: [f64; 3],
}

/// The closest points of two triangles and their distance.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TrianglePair {
    /// On the first triangle.
    pub a: TrianglePoint,
    /// On the second triangle.
    pub b: TrianglePoint,
    /// |a - b|.
    pub distance: f64,
}

/// The point of triangle `t` nearest to `p` (Ericson, *Real-Time Collision Detection*, 5.1.5,
/// by Voronoi regions), with its barycentric coordinates. A degenerate triangle gives a point
/// of its longest edge or a corner.
#[must_use]
pub fn closest_on_triangle(p: DVec3, t: &[DVec3; 3]) -> TrianglePoint {
    let [a, b, c] = *t;
    let corner = |i: usize| {
        let mut barycentric = [0.0; 3];
        barycentric[i] = 1.0;
        TrianglePoint {
            point: t[i],
            barycentric,
        }
    };
    let on_edge = |i: usize, j: usize, s: f64| {
        let mut barycentric = [0.0; 3];
        barycentric[i] = 1.0 - s;
        barycentric[j] = s;
        TrianglePoint {
            point: t[i] + (t[j] - t[i]) * s,
            barycentric,
        }
    };
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return corner(0);
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(bp), ac.dot(bp));
    if d3 >= 0.0 && d4 <= d3 {
        return corner(1);
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return on_edge(0, 1, ratio(d1, d1 - d3));
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(cp), ac.dot(cp));
    if d6 >= 0.0 && d5 <= d6 {
        return corner(2);
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return on_edge(0, 2, ratio(d2, d2 - d6));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        return on_edge(1, 2, ratio(d4 - d3, (d4 - d3) + (d5 - d6)));
    }
    let sum = va + vb + vc;
    if sum <= 0.0 || !sum.is_finite() {
        // Degenerate (collinear) triangle: the best of its three edges.
        return [(0, 1), (0, 2), (1, 2)]
            .into_iter()
            .map(|(i, j)| on_edge(i, j, segment_parameter(p, t[i], t[j])))
            .min_by(|x, y| {
                x.point
                    .distance_squared(p)
                    .total_cmp(&y.point.distance_squared(p))
            })
            .unwrap_or_else(|| corner(0));
    }
    let (v, w) = (vb / sum, vc / sum);
    TrianglePoint {
        point: a + ab * v + ac * w,
        barycentric: [1.0 - v - w, v, w],
    }
}

/// `num / den` clamped to [0, 1]; 0 for a zero or non-finite quotient.
fn ratio(num: f64, den: f64) -> f64 {
    let r = num / den;
    if r.is_finite() {
        r.clamp(0.0, 1.0)
    } else {
        0.0
    }
}

/// The parameter s in [0, 1] of the point of segment `a`..`b` nearest to `p`.
fn segment_parameter(p: DVec3, a: DVec3, b: DVec3) -> f64 {
    let d = b - a;
    ratio((p - a).dot(d), d.length_squared())
}

/// Parameters (s, t) in [0, 1]² of the closest points of segments `p1`..`q1` and `p2`..`q2`
/// (Ericson 5.1.9; degenerate segments handled as points).
fn segment_parameters(p1: DVec3, q1: DVec3, p2: DVec3, q2: DVec3) -> (f64, f64) {
    let (d1, d2) = (q1 - p1, q2 - p2);
    segment_parameters_of(p1, d1, d1.length_squared(), p2, d2, d2.length_squared())
}

/// [`segment_parameters`] of the segments from `p1` along `d1` (squared length `a`) and from
/// `p2` along `d2` (squared length `e`).
fn segment_parameters_of(p1: DVec3, d1: DVec3, a: f64, p2: DVec3, d2: DVec3, e: f64) -> (f64, f64) {
    let r = p1 - p2;
    let f = d2.dot(r);
    let tiny = f64::EPSILON * (a + e).max(f64::MIN_POSITIVE);
    if a <= tiny && e <= tiny {
        return (0.0, 0.0);
    }
    if a <= tiny {
        return (0.0, ratio(f, e));
    }
    let c = d1.dot(r);
    if e <= tiny {
        return (ratio(-c, a), 0.0);
    }
    let b = d1.dot(d2);
    let denom = a * e - b * b;
    let mut s = if denom > tiny * (a * e) {
        ratio(b * f - c * e, denom)
    } else {
        0.0
    };
    let mut t = (b * s + f) / e;
    if t < 0.0 {
        t = 0.0;
        s = ratio(-c, a);
    } else if t > 1.0 {
        t = 1.0;
        s = ratio(b - c, a);
    }
    (s, t.clamp(0.0, 1.0))
}

/// The closest points of two triangles (Ericson 5.1.10's case analysis: the six corners against
/// the other triangle and the nine edge pairs). Exact for disjoint triangles up to rounding;
/// for intersecting triangles the distance found may be positive (an edge piercing the other
/// triangle's interior is not among the cases), so callers test intersection separately.
///
/// A corner is tested against the other triangle's interior only ([`FacePlane`]): where its
/// nearest point lies on the other's boundary, that point is on an edge and the corner on two
/// edges of its own, so an edge pair attains the same distance. The edge vectors and their
/// squared lengths are formed once per triangle, not per pair. The cases are compared by
/// squared distance and only the best one's points and barycentric coordinates are built (a
/// leaf pair's closest points are most of the normal-cone path's cost on long contacts, a
/// pencil leaning in a tube: 28 pairs per query, 2.0k instructions each with the six corners
/// run through [`closest_on_triangle`]'s Voronoi regions).
#[must_use]
pub fn closest_between_triangles(t1: &[DVec3; 3], t2: &[DVec3; 3]) -> TrianglePair {
    /// The best case so far: a corner of either triangle over the other's interior (with its
    /// barycentric coordinates there), or an edge pair with its two segment parameters.
    #[derive(Clone, Copy)]
    enum Case {
        CornerOfFirst(usize, [f64; 3]),
        CornerOfSecond(usize, [f64; 3]),
        Edges(usize, usize, f64, f64),
    }
    let edges = |t: &[DVec3; 3]| [t[1] - t[0], t[2] - t[1], t[0] - t[2]];
    let (d1, d2) = (edges(t1), edges(t2));
    let (l1, l2) = (d1.map(DVec3::length_squared), d2.map(DVec3::length_squared));
    let mut best = (f64::INFINITY, Case::Edges(0, 0, 0.0, 0.0));
    for i in 0..3 {
        for j in 0..3 {
            let (s, t) = segment_parameters_of(t1[i], d1[i], l1[i], t2[j], d2[j], l2[j]);
            let squared = (t1[i] + d1[i] * s).distance_squared(t2[j] + d2[j] * t);
            if squared < best.0 {
                best = (squared, Case::Edges(i, j, s, t));
            }
        }
    }
    if let Some(plane) = FacePlane::new(t2, &d2) {
        for (i, &p) in t1.iter().enumerate() {
            if let Some((squared, b)) = plane.over_interior(p, t2) {
                if squared < best.0 {
                    best = (squared, Case::CornerOfFirst(i, b));
                }
            }
        }
    }
    if let Some(plane) = FacePlane::new(t1, &d1) {
        for (i, &p) in t2.iter().enumerate() {
            if let Some((squared, b)) = plane.over_interior(p, t1) {
                if squared < best.0 {
                    best = (squared, Case::CornerOfSecond(i, b));
                }
            }
        }
    }
    let corner = |t: &[DVec3; 3], i: usize| {
        let mut barycentric = [0.0; 3];
        barycentric[i] = 1.0;
        TrianglePoint {
            point: t[i],
            barycentric,
        }
    };
    let inside = |t: &[DVec3; 3], b: [f64; 3]| TrianglePoint {
        point: t[0] * b[0] + t[1] * b[1] + t[2] * b[2],
        barycentric: b,
    };
    let on_edge = |t: &[DVec3; 3], d: &[DVec3; 3], i: usize, s: f64| {
        let mut barycentric = [0.0; 3];
        barycentric[i] = 1.0 - s;
        barycentric[(i + 1) % 3] = s;
        TrianglePoint {
            point: t[i] + d[i] * s,
            barycentric,
        }
    };
    let (a, b) = match best.1 {
        Case::CornerOfFirst(i, b) => (corner(t1, i), inside(t2, b)),
        Case::CornerOfSecond(i, a) => (inside(t1, a), corner(t2, i)),
        Case::Edges(i, j, s, t) => (on_edge(t1, &d1, i, s), on_edge(t2, &d2, j, t)),
    };
    TrianglePair {
        distance: a.point.distance(b.point),
        a,
        b,
    }
}

/// A non-degenerate triangle's plane with its inward edge normals, for projecting points onto
/// its interior: with n = e0 × (c − a) and m_k = n × e_k for the edges e0 = b − a, e1 = c − b,
/// e2 = a − c, the barycentric coordinate of the corner opposite e_k at a point p is
/// m_k · (p − start of e_k) / |n|², whatever p's height over the plane.
struct FacePlane {
    normal: DVec3,
    /// |n|².
    norm_squared: f64,
    /// m_k / |n|² for the edges e0, e1, e2 (opposite corners c, a, b).
    inward: [DVec3; 3],
}

impl FacePlane {
    /// `None` for a degenerate (collinear) triangle, whose nearest points its edges give.
    fn new(t: &[DVec3; 3], d: &[DVec3; 3]) -> Option<Self> {
        let normal = d[0].cross(t[2] - t[0]);
        let norm_squared = normal.length_squared();
        let scale = d[0].length_squared().max(d[1].length_squared());
        (norm_squared > 1e-24 * scale * scale && norm_squared.is_finite()).then(|| {
            let inward = d.map(|e| normal.cross(e) / norm_squared);
            Self {
                normal,
                norm_squared,
                inward,
            }
        })
    }

    /// The squared distance from `p` to its projection onto the plane and the projection's
    /// barycentric coordinates in `t`, when the projection lies in the closed triangle.
    fn over_interior(&self, p: DVec3, t: &[DVec3; 3]) -> Option<(f64, [f64; 3])> {
        let bc = self.inward[0].dot(p - t[0]);
        let ba = self.inward[1].dot(p - t[1]);
        let bb = self.inward[2].dot(p - t[2]);
        (ba >= 0.0 && bb >= 0.0 && bc >= 0.0).then(|| {
            let height = self.normal.dot(p - t[0]);
            (height * height / self.norm_squared, [ba, bb, bc])
        })
    }
}

/// The closest points of segment `p`..`q` and triangle `t`: the segment's parameter s in
/// [0, 1] (its point is p + s (q − p)), the triangle's point and their distance (Ericson
/// 5.1.10's cases for a segment: its two ends against the triangle and the segment against the
/// triangle's three edges). Exact up to rounding for a segment that does not pierce the
/// triangle; for one that does, the distance found may be positive.
#[must_use]
pub fn closest_between_segment_and_triangle(
    p: DVec3,
    q: DVec3,
    t: &[DVec3; 3],
) -> (f64, TrianglePoint, f64) {
    let mut best = (f64::INFINITY, 0.0, closest_on_triangle(p, t));
    for (s, end) in [(0.0, p), (1.0, q)] {
        let on = closest_on_triangle(end, t);
        let squared = end.distance_squared(on.point);
        if squared < best.0 {
            best = (squared, s, on);
        }
    }
    for (i, j) in [(0, 1), (1, 2), (2, 0)] {
        let (s, u) = segment_parameters(p, q, t[i], t[j]);
        let (on_segment, on_edge) = (p + (q - p) * s, t[i] + (t[j] - t[i]) * u);
        let squared = on_segment.distance_squared(on_edge);
        if squared < best.0 {
            let mut barycentric = [0.0; 3];
            barycentric[i] = 1.0 - u;
            barycentric[j] = u;
            let point = TrianglePoint {
                point: on_edge,
                barycentric,
            };
            best = (squared, s, point);
        }
    }
    (best.1, best.2, best.0.sqrt())
}

/// A lower bound (mm) on the distance between two triangles: the distance between their
/// axis-aligned bounding boxes (per axis, the gap between the two coordinate ranges, 0 where
/// they overlap), since every point of a triangle lies in its box. A few dozen instructions, a
/// fiftieth of [`closest_between_triangles`], and as tight as the triangles' closest points
/// where they lie side by side along an axis: of a pencil's leaf pairs beside a tube's rim whose
/// closest points lay beyond the reach, it told most apart (pencil-tube-two's Stage 2, 6% of
/// its query).
#[must_use]
pub fn boxes_gap(t1: &[DVec3; 3], t2: &[DVec3; 3]) -> f64 {
    let low = |t: &[DVec3; 3]| t[0].min(t[1]).min(t[2]);
    let high = |t: &[DVec3; 3]| t[0].max(t[1]).max(t[2]);
    (low(t1) - high(t2))
        .max(low(t2) - high(t1))
        .max(DVec3::ZERO)
        .length()
}

/// A lower bound (mm) on the distance between two triangles by the separating axes of their
/// two normals only: the larger gap between their projections onto either normal (0 when
/// neither separates them). A fraction of [`separating_gap`]'s cost, and as tight for nearly
/// parallel triangles facing each other, the common case of close surfaces.
#[must_use]
pub fn normals_gap(t1: &[DVec3; 3], t2: &[DVec3; 3]) -> f64 {
    let normal = |t: &[DVec3; 3]| (t[1] - t[0]).cross(t[2] - t[1]);
    axis_gap(t1, t2, normal(t1)).max(axis_gap(t1, t2, normal(t2)))
}

/// The gap (mm) between the projections of two triangles onto `axis` (any length), 0 where
/// they overlap or the axis vanishes. The projections are taken onto the unnormalised axis;
/// the square root only for a separating one.
fn axis_gap(t1: &[DVec3; 3], t2: &[DVec3; 3], axis: DVec3) -> f64 {
    let (p, q, r) = (axis.dot(t1[0]), axis.dot(t1[1]), axis.dot(t1[2]));
    let (u, v, w) = (axis.dot(t2[0]), axis.dot(t2[1]), axis.dot(t2[2]));
    let gap = (u.min(v).min(w) - p.max(q).max(r)).max(p.min(q).min(r) - u.max(v).max(w));
    if gap > 0.0 {
        let length = axis.length();
        if length > 0.0 {
            return gap / length;
        }
    }
    0.0
}

/// A lower bound (mm) on the distance between two triangles by separating axes: the largest
/// gap between their projections onto the two triangles' normals ([`normals_gap`]) and the nine
/// cross products of an edge of each, over the axes' lengths (a projection onto a unit vector
/// does not increase distances). Two triangles are disjoint exactly when one of these axes
/// separates them (the separating axis theorem for convex polytopes), so the bound is positive
/// exactly for disjoint triangles, up to rounding; 0 when no axis separates them (and for
/// degenerate triangles whose axes all vanish).
#[must_use]
pub fn separating_gap(t1: &[DVec3; 3], t2: &[DVec3; 3]) -> f64 {
    let e1 = [t1[1] - t1[0], t1[2] - t1[1], t1[0] - t1[2]];
    let e2 = [t2[1] - t2[0], t2[2] - t2[1], t2[0] - t2[2]];
    let mut best = normals_gap(t1, t2);
    for a in e1 {
        for b in e2 {
            best = best.max(axis_gap(t1, t2, a.cross(b)));
        }
    }
    best
}
