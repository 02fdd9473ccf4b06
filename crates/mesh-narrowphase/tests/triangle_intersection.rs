//! Tests of `mesh_narrowphase::triangles::triangle_intersection` against truth computed
//! independently: closed forms, an exact integer separating-axis test, f64 reference clipping, and
//! point–triangle distances.

use glam::DVec3;
use mesh_narrowphase::triangles::triangle_intersection::{
    TriangleContact, intersect_triangles, triangles_intersect,
};

type Tri = [DVec3; 3];

fn v(x: f64, y: f64, z: f64) -> DVec3 {
    DVec3::new(x, y, z)
}

/// The reference triangle of most tests: right angle at the origin, in z = 0.
fn base() -> Tri {
    [v(0.0, 0.0, 0.0), v(4.0, 0.0, 0.0), v(0.0, 4.0, 0.0)]
}

// ---------------------------------------------------------------------------------------------
// Independent helpers.

/// SplitMix64: seeded, reproducible.
struct Rng(u64);

impl Rng {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1).
    fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Uniform in [-1, 1).
    fn signed(&mut self) -> f64 {
        2.0 * self.unit() - 1.0
    }

    /// Uniform integer in [lo, hi].
    fn int(&mut self, lo: i64, hi: i64) -> i64 {
        lo + (self.next_u64() % (hi - lo + 1) as u64) as i64
    }

    fn index(&mut self, n: usize) -> usize {
        (self.next_u64() % n as u64) as usize
    }

    fn point(&mut self) -> DVec3 {
        v(self.signed(), self.signed(), self.signed())
    }

    fn tri(&mut self) -> Tri {
        [self.point(), self.point(), self.point()]
    }

    fn int_point(&mut self, r: i64) -> [i64; 3] {
        [self.int(-r, r), self.int(-r, r), self.int(-r, r)]
    }

    fn unit_vector(&mut self) -> DVec3 {
        loop {
            let p = self.point();
            let l = p.length();
            if l > 0.1 && l <= 1.0 {
                return p / l;
            }
        }
    }
}

fn closest_on_segment(p: DVec3, a: DVec3, b: DVec3) -> DVec3 {
    let ab = b - a;
    let l2 = ab.length_squared();
    if l2 == 0.0 {
        return a;
    }
    a + ab * ((p - a).dot(ab) / l2).clamp(0.0, 1.0)
}

/// Distance from `p` to a closed triangle (degenerate ones are the union of their edges):
/// the distance to the plane when `p` projects inside, else the distance to the nearest edge.
/// (Barycentric closest-point formulas lose accuracy on thin triangles; this does not.)
fn dist(p: DVec3, t: &Tri) -> f64 {
    let edges = (0..3)
        .map(|i| (closest_on_segment(p, t[i], t[(i + 1) % 3]) - p).length())
        .fold(f64::INFINITY, f64::min);
    let n = normal(t);
    if n.length_squared() == 0.0 {
        return edges;
    }
    let inside = (0..3).all(|i| (p - t[i]).dot(n.cross(t[(i + 1) % 3] - t[i])) >= 0.0);
    if inside {
        edges.min((p - t[0]).dot(n).abs() / n.length())
    } else {
        edges
    }
}

fn normal(t: &Tri) -> DVec3 {
    (t[1] - t[0]).cross(t[2] - t[0])
}

/// Vector area of a closed polygon (half the sum of cross products).
fn vector_area(pts: &[DVec3]) -> DVec3 {
    let n = pts.len();
    (0..n).fold(DVec3::ZERO, |acc, i| acc + pts[i].cross(pts[(i + 1) % n])) * 0.5
}

/// Area of the overlap of two coplanar triangles by Sutherland–Hodgman clipping in f64.
fn clipped_area(t1: &Tri, t2: &Tri) -> f64 {
    let n = normal(t2);
    let mut poly: Vec<DVec3> = t1.to_vec();
    for i in 0..3 {
        let (a, b) = (t2[i], t2[(i + 1) % 3]);
        let inward = n.cross(b - a);
        let f = |p: DVec3| (p - a).dot(inward);
        let mut out = Vec::new();
        for j in 0..poly.len() {
            let (p, q) = (poly[j], poly[(j + 1) % poly.len()]);
            let (fp, fq) = (f(p), f(q));
            if fp >= 0.0 {
                out.push(p);
            }
            if (fp > 0.0 && fq < 0.0) || (fp < 0.0 && fq > 0.0) {
                out.push(p + (q - p) * (fp / (fp - fq)));
            }
        }
        poly = out;
        if poly.is_empty() {
            return 0.0;
        }
    }
    vector_area(&poly).length()
}

/// Reference segment of two generic (non-degenerate, non-coplanar) triangles in plain f64:
/// clip each triangle by the other's plane, intersect the intervals along `n1 × n2`. Returns
/// the segment and the signed overlap length (negative: gap).
fn reference_segment(t1: &Tri, t2: &Tri) -> Option<(DVec3, DVec3, f64)> {
    let (n1, n2) = (normal(t1), normal(t2));
    let d = n1.cross(n2).normalize();
    let clip = |t: &Tri, n: DVec3, o: DVec3| -> Option<(DVec3, DVec3)> {
        let s = t.map(|p| (p - o).dot(n));
        let mut pts = Vec::new();
        for i in 0..3 {
            let j = (i + 1) % 3;
            if s[i] == 0.0 {
                pts.push(t[i]);
            }
            if (s[i] > 0.0 && s[j] < 0.0) || (s[i] < 0.0 && s[j] > 0.0) {
                pts.push(t[i] + (t[j] - t[i]) * (s[i] / (s[i] - s[j])));
            }
        }
        let lo = pts
            .iter()
            .copied()
            .min_by(|a, b| a.dot(d).total_cmp(&b.dot(d)))?;
        let hi = pts
            .iter()
            .copied()
            .max_by(|a, b| a.dot(d).total_cmp(&b.dot(d)))?;
        Some((lo, hi))
    };
    let (lo1, hi1) = clip(t1, n2.normalize(), t2[0])?;
    let (lo2, hi2) = clip(t2, n1.normalize(), t1[0])?;
    let lo = if lo1.dot(d) >= lo2.dot(d) { lo1 } else { lo2 };
    let hi = if hi1.dot(d) <= hi2.dot(d) { hi1 } else { hi2 };
    Some((lo, hi, (hi - lo).dot(d)))
}

/// Exact decision for integer triangles (possibly degenerate) by the separating axis theorem:
/// the Minkowski difference of two polytopes has facet normals among `u × v` and, when it is
/// flat, among `(u × v) × w` and `u`, with `u, v, w` edge directions or vertex differences.
fn sat_intersect(t1: &[[i64; 3]; 3], t2: &[[i64; 3]; 3]) -> bool {
    fn sub(a: [i64; 3], b: [i64; 3]) -> [i64; 3] {
        [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
    }
    fn cross(a: [i64; 3], b: [i64; 3]) -> [i64; 3] {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    }
    fn dot(a: [i64; 3], b: [i64; 3]) -> i64 {
        a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
    }
    let mut dirs = Vec::new();
    for t in [t1, t2] {
        for i in 0..3 {
            dirs.push(sub(t[(i + 1) % 3], t[i]));
        }
    }
    for a in t1 {
        for b in t2 {
            dirs.push(sub(*a, *b));
        }
    }
    dirs.retain(|d| *d != [0, 0, 0]);
    let separates = |axis: [i64; 3]| {
        if axis == [0, 0, 0] {
            return false;
        }
        let p1 = t1.map(|p| dot(p, axis));
        let p2 = t2.map(|p| dot(p, axis));
        let (min1, max1) = (p1.iter().min(), p1.iter().max());
        let (min2, max2) = (p2.iter().min(), p2.iter().max());
        max1 < min2 || max2 < min1
    };
    for (i, &u) in dirs.iter().enumerate() {
        if separates(u) {
            return false;
        }
        for &w in &dirs[i + 1..] {
            let c = cross(u, w);
            if separates(c) {
                return false;
            }
            if c != [0, 0, 0] && dirs.iter().any(|&x| separates(cross(c, x))) {
                return false;
            }
        }
    }
    true
}

fn to_tri(t: &[[i64; 3]; 3]) -> Tri {
    t.map(|p| v(p[0] as f64, p[1] as f64, p[2] as f64))
}

/// The six orderings of a triangle's vertices (three keep the orientation, three flip it).
fn permutations(t: &Tri) -> [Tri; 6] {
    let [a, b, c] = *t;
    [
        [a, b, c],
        [b, c, a],
        [c, a, b],
        [a, c, b],
        [c, b, a],
        [b, a, c],
    ]
}

fn close(p: DVec3, q: DVec3, tol: f64) -> bool {
    (p - q).length() <= tol
}

fn same_segment(got: (DVec3, DVec3), want: (DVec3, DVec3), tol: f64) -> bool {
    (close(got.0, want.0, tol) && close(got.1, want.1, tol))
        || (close(got.0, want.1, tol) && close(got.1, want.0, tol))
}

fn expect_segment(t1: &Tri, t2: &Tri) -> (DVec3, DVec3) {
    match intersect_triangles(t1, t2) {
        TriangleContact::Segment { a, b } => {
            assert!(triangles_intersect(t1, t2));
            (a, b)
        }
        other => panic!("expected a segment for {t1:?} / {t2:?}, got {other:?}"),
    }
}

fn expect_polygon(t1: &Tri, t2: &Tri) -> Vec<DVec3> {
    match intersect_triangles(t1, t2) {
        TriangleContact::Coplanar { points } => {
            assert!(triangles_intersect(t1, t2));
            points.points().to_vec()
        }
        other => panic!("expected a coplanar overlap for {t1:?} / {t2:?}, got {other:?}"),
    }
}

fn expect_disjoint(t1: &Tri, t2: &Tri) {
    assert_eq!(
        intersect_triangles(t1, t2),
        TriangleContact::Disjoint,
        "{t1:?} / {t2:?}"
    );
    assert!(!triangles_intersect(t1, t2), "{t1:?} / {t2:?}");
}

/// Checks a non-coplanar segment under all 36 vertex orderings and both argument orders:
/// same segment (as a set), ordered along n1 × n2 of the arguments as given.
fn check_segment_all_orders(t1: &Tri, t2: &Tri, want: (DVec3, DVec3), tol: f64) {
    for p1 in permutations(t1) {
        for p2 in permutations(t2) {
            for (x, y) in [(&p1, &p2), (&p2, &p1)] {
                let (a, b) = expect_segment(x, y);
                assert!(
                    same_segment((a, b), want, tol),
                    "{x:?} / {y:?}: got {a:?}..{b:?}, want {want:?}"
                );
                let d = normal(x).cross(normal(y));
                assert!((b - a).dot(d) >= -tol * d.length(), "order along n1 × n2");
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Non-coplanar configurations with closed-form answers.

#[test]
fn crossing_triangles_closed_form_segment() {
    // t2 in the plane y = 1; it meets z = 0 at x in [1.25, 2.75], inside t1 (x in [0, 3]).
    let t2 = [v(1.0, 1.0, -1.0), v(3.0, 1.0, -1.0), v(2.0, 1.0, 3.0)];
    let want = (v(1.25, 1.0, 0.0), v(2.75, 1.0, 0.0));
    assert_eq!(
        intersect_triangles(&base(), &t2),
        TriangleContact::Segment {
            a: want.0,
            b: want.1
        }
    );
    check_segment_all_orders(&base(), &t2, want, 1e-15);

    // Shifted: t2 meets z = 0 at x in [2.5, 5.5]; t1's hypotenuse cuts y = 1 at x = 3.
    let t2 = [v(2.0, 1.0, -1.0), v(6.0, 1.0, -1.0), v(4.0, 1.0, 3.0)];
    check_segment_all_orders(&base(), &t2, (v(2.5, 1.0, 0.0), v(3.0, 1.0, 0.0)), 1e-15);

    // Oblique planes: t1 in x + y + z = 3, t2 in z = 1/2, meeting along x + y = 5/2.
    let t1 = [v(3.0, 0.0, 0.0), v(0.0, 3.0, 0.0), v(0.0, 0.0, 3.0)];
    let t2 = [v(-1.0, -1.0, 0.5), v(4.0, -1.0, 0.5), v(-1.0, 4.0, 0.5)];
    check_segment_all_orders(&t1, &t2, (v(2.5, 0.0, 0.5), v(0.0, 2.5, 0.5)), 1e-15);

    // Same planes, but t2 too small to reach t1 along the line: disjoint.
    let t2 = [v(2.0, 2.0, 0.5), v(3.0, 2.0, 0.5), v(2.0, 3.0, 0.5)];
    expect_disjoint(&t1, &t2);
}

#[test]
fn touching_vertex_on_face_interior() {
    let t2 = [v(1.0, 1.0, 0.0), v(2.0, 1.0, 1.0), v(1.0, 2.0, 1.0)];
    let p = v(1.0, 1.0, 0.0);
    check_segment_all_orders(&base(), &t2, (p, p), 0.0);
    // The same vertex one tiny step above the plane: no contact.
    let lifted = [v(1.0, 1.0, 1e-300), t2[1], t2[2]];
    expect_disjoint(&base(), &lifted);
    // Through the face instead: the segment starts on the far side.
    let through = [v(1.0, 1.0, -1.0), t2[1], t2[2]];
    let (a, b) = expect_segment(&base(), &through);
    assert!(dist(a, &through) < 1e-15 && dist(b, &through) < 1e-15);
    assert!((a - b).length() > 0.1);
}

#[test]
fn touching_vertex_on_edge_and_shared_vertex() {
    // t2's vertex on the interior of t1's edge y = 0, t2 otherwise above and outside.
    let t2 = [v(2.0, 0.0, 0.0), v(2.0, -1.0, 1.0), v(3.0, -1.0, 2.0)];
    let p = v(2.0, 0.0, 0.0);
    check_segment_all_orders(&base(), &t2, (p, p), 0.0);

    // t2's vertex on t1's edge at a parameter (1/5) where interpolating along the edge does not
    // reproduce it exactly: the contact is still the vertex itself, bit for bit.
    let t1 = [v(0.0, 0.0, 0.0), v(5.0, 10.0, 0.0), v(-3.0, 7.0, 0.0)];
    let (p, out) = (v(1.0, 2.0, 0.0), v(10.0, -5.0, 0.0));
    let t2 = [p, p + out + DVec3::Z, p + out * 2.0 + v(0.3, 0.0, -1.0)];
    check_segment_all_orders(&t1, &t2, (p, p), 0.0);

    // Shared vertex, t2 above the plane.
    let o = DVec3::ZERO;
    let t2 = [o, v(-1.0, -1.0, 1.0), v(-1.0, 0.0, 2.0)];
    check_segment_all_orders(&base(), &t2, (o, o), 0.0);

    // Shared vertex, t2 crossing the plane of t1 outside t1.
    let t2 = [o, v(-1.0, -1.0, 1.0), v(-1.0, -2.0, -1.0)];
    check_segment_all_orders(&base(), &t2, (o, o), 0.0);
}

#[test]
fn shared_edge_non_coplanar() {
    let (p, q) = (v(4.0, 0.0, 0.0), v(0.0, 4.0, 0.0));
    for apex in [v(3.0, 3.0, 5.0), v(3.0, 3.0, -5.0), v(1.0, 1.0, 7.0)] {
        check_segment_all_orders(&base(), &[p, q, apex], (p, q), 0.0);
    }
    // Half of an edge shared: t2's edge covers x in [1, 3] of t1's edge y = 0.
    let t2 = [v(1.0, 0.0, 0.0), v(3.0, 0.0, 0.0), v(2.0, -1.0, 3.0)];
    check_segment_all_orders(&base(), &t2, (t2[0], t2[1]), 0.0);
}

#[test]
fn edge_crossing_edge() {
    // t1 moved to y in [1, 5]. t2 (plane x = 2) meets z = 0 along x = 2, y in [-7/3, 1];
    // t1 along y in [1, 3]: they meet where edge crosses edge, at (2, 1, 0).
    let t1 = base().map(|p| p + DVec3::Y);
    let t2 = [v(2.0, 1.0, -1.0), v(2.0, 1.0, 1.0), v(2.0, -4.0, 0.5)];
    let p = v(2.0, 1.0, 0.0);
    check_segment_all_orders(&t1, &t2, (p, p), 1e-15);
    // t2's edge moved by one unit in the last place away from t1: no contact.
    let y = f64::from_bits(1f64.to_bits() - 1);
    let t2 = [v(2.0, y, -1.0), v(2.0, y, 1.0), v(2.0, -4.0, 0.5)];
    expect_disjoint(&t1, &t2);
}

// ---------------------------------------------------------------------------------------------
// Coplanar configurations.

/// Checks a coplanar overlap polygon: expected points (as a set), counter-clockwise about the
/// normal of the first triangle, convex, and of the expected area.
fn check_polygon(t1: &Tri, t2: &Tri, want: &[DVec3], area: f64) {
    for (x, y) in [(t1, t2), (t2, t1)] {
        let pts = expect_polygon(x, y);
        assert_eq!(pts.len(), want.len(), "{pts:?} vs {want:?}");
        for w in want {
            assert!(
                pts.iter().any(|p| close(*p, *w, 1e-12)),
                "{w:?} missing in {pts:?}"
            );
        }
        let n = normal(x).normalize();
        assert!((vector_area(&pts).dot(n) - area).abs() <= 1e-12 * (1.0 + area));
        if pts.len() >= 3 {
            for i in 0..pts.len() {
                let (a, b, c) = (pts[i], pts[(i + 1) % pts.len()], pts[(i + 2) % pts.len()]);
                assert!((b - a).cross(c - b).dot(n) > 0.0, "not convex ccw: {pts:?}");
            }
        }
    }
}

#[test]
fn coplanar_overlap_hexagon_area() {
    // t2 is t1 mirrored through (1, 1): the overlap is 0 <= x, y <= 2, 1 <= x + y <= 3, a
    // hexagon of area 4 - 1/2 - 1/2 = 3.
    let flat = |x: f64, y: f64| v(x, y, 0.0);
    let t1 = [flat(0.0, 0.0), flat(3.0, 0.0), flat(0.0, 3.0)];
    let t2 = [flat(2.0, 2.0), flat(-1.0, 2.0), flat(2.0, -1.0)];
    let hex = [
        (1.0, 0.0),
        (2.0, 0.0),
        (2.0, 1.0),
        (1.0, 2.0),
        (0.0, 2.0),
        (0.0, 1.0),
    ];
    let want: Vec<DVec3> = hex.iter().map(|&(x, y)| flat(x, y)).collect();
    check_polygon(&t1, &t2, &want, 3.0);
    // Reversed orientation of t1: still counter-clockwise about its own normal.
    check_polygon(&[t1[0], t1[2], t1[1]], &t2, &want, 3.0);

    // The same in the tilted plane z = x + 2y (exact in f64): areas scale by sqrt(6).
    let tilt = |p: DVec3| v(p.x, p.y, p.x + 2.0 * p.y);
    let want: Vec<DVec3> = want.iter().map(|&p| tilt(p)).collect();
    check_polygon(&t1.map(tilt), &t2.map(tilt), &want, 3.0 * 6f64.sqrt());
    // And in a plane whose dominant normal axis is x: (x, y) -> ((x + y) / 4, x, y), normal
    // (1, -1/4, -1/4), areas scale by sqrt(9/8).
    let side = |p: DVec3| v(0.25 * (p.x + p.y), p.x, p.y);
    let want: Vec<DVec3> = hex.iter().map(|&(x, y)| side(flat(x, y))).collect();
    check_polygon(&t1.map(side), &t2.map(side), &want, 3.0 * 1.125f64.sqrt());
}

#[test]
fn coplanar_containment_and_touching() {
    let t1 = base();
    // t2 inside t1: the overlap is t2, area 1/2.
    let t2 = [v(1.0, 1.0, 0.0), v(2.0, 1.0, 0.0), v(1.0, 2.0, 0.0)];
    check_polygon(&t1, &t2, &t2, 0.5);
    // Identical triangles.
    check_polygon(&t1, &t1, &t1, 8.0);
    // Touching at one point of the hypotenuse.
    let t2 = [v(2.0, 2.0, 0.0), v(5.0, 2.0, 0.0), v(2.0, 5.0, 0.0)];
    check_polygon(&t1, &t2, &[v(2.0, 2.0, 0.0)], 0.0);
    // Sharing the hypotenuse.
    let t2 = [v(4.0, 0.0, 0.0), v(0.0, 4.0, 0.0), v(4.0, 4.0, 0.0)];
    check_polygon(&t1, &t2, &[t2[0], t2[1]], 0.0);
    // Sharing part of an edge (x in [1, 3] of y = 0).
    let t2 = [v(1.0, 0.0, 0.0), v(3.0, 0.0, 0.0), v(2.0, -2.0, 0.0)];
    check_polygon(&t1, &t2, &[t2[0], t2[1]], 0.0);
    // Sharing a vertex only.
    let t2 = [v(0.0, 0.0, 0.0), v(-1.0, 0.0, 0.0), v(0.0, -1.0, 0.0)];
    check_polygon(&t1, &t2, &[DVec3::ZERO], 0.0);
    // A thin triangle from t1's edge x = 0 out through its hypotenuse: the overlap is the
    // quadrilateral (0,1) (2,0) (4,0) (3,1), of area 2.5 (shoelace: (-2 + 0 + 4 + 3) / 2).
    let t2 = [v(0.0, 1.0, 0.0), v(5.0, -1.5, 0.0), v(5.0, 1.0, 0.0)];
    let quad = [
        v(0.0, 1.0, 0.0),
        v(2.0, 0.0, 0.0),
        v(4.0, 0.0, 0.0),
        v(3.0, 1.0, 0.0),
    ];
    check_polygon(&t1, &t2, &quad, 2.5);
    assert!((clipped_area(&t1, &t2) - 2.5).abs() < 1e-12);
}

#[test]
fn coplanar_disjoint() {
    let t1 = base();
    expect_disjoint(&t1, &t1.map(|p| p + v(10.0, 10.0, 0.0)));
    // Overlapping bounding boxes, separated by the hypotenuse by one unit in the last place.
    let x = f64::from_bits(2f64.to_bits() + 1);
    let t2 = [v(x, 2.0, 0.0), v(5.0, 2.0, 0.0), v(2.0, 5.0, 0.0)];
    expect_disjoint(&t1, &t2);
    // In a tilted plane, separated along a shared line.
    let tilt = |p: DVec3| v(p.x, p.y, p.x + 2.0 * p.y);
    expect_disjoint(&t1.map(tilt), &t2.map(tilt));
}

// ---------------------------------------------------------------------------------------------
// Nearly parallel and parallel planes.

#[test]
fn nearly_parallel_planes_closed_form() {
    // t2 lies exactly in z = s (y - 1) with s = tan(1e-12): it meets z = 0 along y = 1, where
    // t1 spans x in [0, 3] and t2 spans x in [-1/3, 11/3]. Plain f64 arithmetic would misplace
    // the ends along the edges of t1 by about 1e-16 / 1e-12 = 1e-4.
    for angle in [1e-12, 1e-15, 1e-9] {
        let s = f64::tan(angle);
        let t2 = [v(-1.0, 0.0, -s), v(5.0, 0.0, -s), v(1.0, 3.0, 2.0 * s)];
        check_segment_all_orders(&base(), &t2, (v(0.0, 1.0, 0.0), v(3.0, 1.0, 0.0)), 1e-14);
    }
}

#[test]
fn nearly_parallel_tilted_planes_closed_form() {
    // Plane 1: x + y + z = 3. Plane 2: (1 + s) x + y + (1 + s) z = 3 + 2s, tilted from it by
    // about 0.47 s rad about the line x + z = 2, y = 1. Points of plane 2 with integer x and z
    // are exact in f64: y = 3 - (x + z) + s (2 - x - z). t1 meets the line at x in [0, 2]
    // (ends (2, 1, 0) and (0, 1, 2), crossings of its edges with plane 2); t2 at x in
    // [-0.2, 2.2]. Here orient3d's terms cancel to 1e-12, so plain f64 magnitudes would misplace
    // the ends by about 1e-4; double-double keeps them to rounding.
    let t1 = [v(3.0, 0.0, 0.0), v(0.0, 3.0, 0.0), v(0.0, 0.0, 3.0)];
    let want = (v(2.0, 1.0, 0.0), v(0.0, 1.0, 2.0));
    // A second t1 in plane 1 with 20-bit fractions (exactly on it, but its products with t2's
    // coordinates round, unlike the integers above). Within plane 1, plane 2 is y = 1, so its
    // ends are where the edges from the vertex above y = 1 reach y = 1.
    let q = |x: f64| (x * pow2(20)).round() / pow2(20);
    let on1 = |x: f64, y: f64| v(q(x), q(y), 3.0 - q(x) - q(y));
    let t1b = [on1(1.9, 0.2), on1(0.1, 0.1), on1(0.8, 1.9)];
    let at_y1 = |a: DVec3, b: DVec3| a + (b - a) * ((1.0 - a.y) / (b.y - a.y));
    let want_b = (at_y1(t1b[2], t1b[0]), at_y1(t1b[2], t1b[1]));
    for s in [pow2(-20), pow2(-39), pow2(-50)] {
        let on2 = |x: f64, z: f64| v(x, 3.0 - (x + z) + s * (2.0 - x - z), z);
        let t2 = [on2(1.0, -3.0), on2(-3.0, 1.0), on2(4.0, 4.0)];
        check_segment_all_orders(&t1, &t2, want, 1e-14);
        check_segment_all_orders(&t1b, &t2, want_b, 1e-14);
    }
}

#[test]
fn parallel_planes_are_exact() {
    let t1 = base();
    // Distinct parallel planes, however close: disjoint.
    expect_disjoint(&t1, &t1.map(|p| p + v(0.5, 0.5, 1e-300)));
    let up = f64::from_bits(1f64.to_bits() + 1);
    let lifted = |z: f64| t1.map(|p| v(p.x + 0.5, p.y, z));
    expect_disjoint(&t1.map(|p| p + DVec3::Z), &lifted(up));
    // The same plane: coplanar overlap.
    let pts = expect_polygon(&t1.map(|p| p + DVec3::Z), &lifted(1.0));
    assert!(pts.len() >= 3);
}

#[test]
fn nearly_parallel_random_rotations() {
    // t2 is t1 rotated by 1e-12 rad about a line of t1's plane through its centroid: they cross
    // along (almost) that line. Endpoints must lie on both triangles to rounding.
    let mut rng = Rng(7);
    for _ in 0..2_000 {
        let t1 = rng.tri();
        let n = normal(&t1);
        if n.length() < 0.1 {
            continue;
        }
        let n = n.normalize();
        let centre = (t1[0] + t1[1] + t1[2]) / 3.0;
        let axis = rng.unit_vector().cross(n).normalize();
        let rot = glam::DQuat::from_axis_angle(axis, 1e-12);
        let t2 = t1.map(|p| centre + rot * (p - centre));
        let (a, b) = expect_segment(&t1, &t2);
        for p in [a, b] {
            assert!(dist(p, &t1) < 1e-14, "{}", dist(p, &t1));
            assert!(dist(p, &t2) < 1e-14, "{}", dist(p, &t2));
        }
        // The chord of t1 along the rotation axis (within the 1e-4 by which rounding the input
        // may move the line of intersection of such planes).
        let chord = t1_chord(&t1, centre, axis);
        assert!(((b - a).length() - chord).abs() < 1e-2 * (1.0 + chord));
    }
}

/// Length of the chord of triangle `t` along the line `c + s * dir` (c inside t).
fn t1_chord(t: &Tri, c: DVec3, dir: DVec3) -> f64 {
    let n = normal(t);
    let mut lo = f64::NEG_INFINITY;
    let mut hi = f64::INFINITY;
    for i in 0..3 {
        let (a, b) = (t[i], t[(i + 1) % 3]);
        let inward = n.cross(b - a);
        // (c + s dir - a) . inward >= 0
        let f0 = (c - a).dot(inward);
        let fd = dir.dot(inward);
        if fd > 0.0 {
            lo = lo.max(-f0 / fd);
        } else if fd < 0.0 {
            hi = hi.min(-f0 / fd);
        }
    }
    hi - lo
}

// ---------------------------------------------------------------------------------------------
// Degenerate triangles.

#[test]
fn degenerate_triangles_as_segments_and_points() {
    let t = base();
    let p = v(1.0, 1.0, 0.0);
    // Collinear, with a vertex on the plane of t.
    let (a, b) = expect_segment(&[v(1.0, 1.0, -1.0), v(1.0, 1.0, 1.0), p], &t);
    assert_eq!((a, b), (p, p));
    // Collinear, crossing computed; and with a repeated point.
    for d in [
        [v(1.0, 1.0, -1.0), v(1.0, 1.0, 3.0), v(1.0, 1.0, 1.0)],
        [v(1.0, 1.0, -1.0), v(1.0, 1.0, -1.0), v(1.0, 1.0, 3.0)],
    ] {
        for q in permutations(&d) {
            let (a, b) = expect_segment(&q, &t);
            assert!(close(a, p, 1e-15) && close(b, p, 1e-15));
            let (a, b) = expect_segment(&t, &q);
            assert!(close(a, p, 1e-15) && close(b, p, 1e-15));
        }
    }
    // Collinear, missing the triangle, or stopping just short of the plane.
    expect_disjoint(&[v(5.0, 5.0, -1.0), v(5.0, 5.0, 1.0), v(5.0, 5.0, 0.0)], &t);
    expect_disjoint(
        &[v(1.0, 1.0, -1.0), v(1.0, 1.0, -1e-300), v(1.0, 1.0, -0.5)],
        &t,
    );
    // A segment lying in the plane, clipped by the triangle; one touching a vertex; one along
    // an edge.
    let s = [v(-1.0, 1.0, 0.0), v(5.0, 1.0, 0.0), v(2.0, 1.0, 0.0)];
    let got = expect_segment(&s, &t);
    assert!(same_segment(
        got,
        (v(0.0, 1.0, 0.0), v(3.0, 1.0, 0.0)),
        1e-15
    ));
    let s = [v(-1.0, 3.0, 0.0), v(1.0, 5.0, 0.0), v(0.0, 4.0, 0.0)];
    assert!(same_segment(expect_segment(&t, &s), (t[2], t[2]), 0.0));
    let s = [v(-1.0, 5.0, 0.0), v(1.0, 3.0, 0.0), v(0.0, 4.0, 0.0)];
    assert!(same_segment(
        expect_segment(&t, &s),
        (t[2], v(1.0, 3.0, 0.0)),
        0.0
    ));
    let s = [v(-1.0, 0.0, 0.0), v(2.0, 0.0, 0.0), v(2.0, 0.0, 0.0)];
    assert!(same_segment(
        expect_segment(&s, &t),
        (t[0], v(2.0, 0.0, 0.0)),
        0.0
    ));
    let s = [v(-1.0, 1.0, 0.0), v(-3.0, 1.0, 0.0), v(-2.0, 1.0, 0.0)];
    expect_disjoint(&s, &t);
    // Points.
    let pt = |q: DVec3| [q, q, q];
    for q in [p, t[1], v(2.0, 0.0, 0.0), v(2.0, 2.0, 0.0)] {
        assert_eq!(expect_segment(&pt(q), &t), (q, q));
        assert_eq!(expect_segment(&t, &pt(q)), (q, q));
    }
    expect_disjoint(&pt(v(1.0, 1.0, 1e-300)), &t);
    expect_disjoint(&pt(v(2.0, 2.0 + 1e-15, 0.0)), &t);
    // Segment against segment: crossing at a shared vertex, at a computed point, skew,
    // collinear overlapping, collinear touching, collinear apart.
    let m = v(1.0, 1.0, 1.0);
    let s1 = [v(0.0, 0.0, 0.0), v(2.0, 2.0, 2.0), m];
    assert_eq!(
        expect_segment(&s1, &[v(0.0, 2.0, 0.0), v(2.0, 0.0, 2.0), m]),
        (m, m)
    );
    let s2 = [v(0.0, 2.0, 0.0), v(2.0, 0.0, 2.0), v(2.0, 0.0, 2.0)];
    let (a, b) = expect_segment(&s1, &s2);
    assert!(close(a, m, 1e-15) && close(b, m, 1e-15));
    expect_disjoint(&s1, &[v(0.0, 2.0, 0.0), v(2.0, 0.0, 2.1), v(2.0, 0.0, 2.1)]);
    let x = |a: f64| v(a, 0.0, 0.0);
    let line1 = [x(0.0), x(2.0), x(1.0)];
    assert!(same_segment(
        expect_segment(&line1, &[x(1.5), x(3.0), x(3.0)]),
        (x(1.5), x(2.0)),
        0.0
    ));
    assert_eq!(
        expect_segment(&line1, &[x(2.0), x(3.0), x(2.5)]),
        (x(2.0), x(2.0))
    );
    expect_disjoint(&line1, &[x(2.5), x(3.0), x(3.0)]);
    // Segment against point, point against point (also all at the origin).
    assert_eq!(expect_segment(&line1, &pt(x(0.5))), (x(0.5), x(0.5)));
    expect_disjoint(&line1, &pt(v(0.5, 1e-300, 0.0)));
    assert_eq!(expect_segment(&pt(m), &pt(m)), (m, m));
    expect_disjoint(&pt(m), &pt(m + DVec3::X));
    let o = DVec3::ZERO;
    assert_eq!(expect_segment(&pt(o), &pt(o)), (o, o));
}

// ---------------------------------------------------------------------------------------------
// Random pairs.

#[test]
fn random_pairs_segment_lies_on_both_triangles_and_matches_reference() {
    let mut rng = Rng(42);
    let (mut checked, mut crossing, mut apart) = (0, 0, 0);
    for _ in 0..50_000 {
        let t1 = rng.tri();
        let shift = rng.point() * 0.5;
        let t2 = rng.tri().map(|p| p * 0.7 + shift);
        let got = intersect_triangles(&t1, &t2);
        assert_eq!(
            got != TriangleContact::Disjoint,
            triangles_intersect(&t1, &t2)
        );
        if let TriangleContact::Segment { a, b } = got {
            for p in [a, b, (a + b) * 0.5] {
                assert!(
                    dist(p, &t1) < 1e-9 && dist(p, &t2) < 1e-9,
                    "{t1:?} {t2:?} {p:?}"
                );
            }
        }
        // Compare with the plain f64 reference where it is well conditioned.
        let (n1, n2) = (normal(&t1), normal(&t2));
        let sin = n1.cross(n2).length() / (n1.length() * n2.length());
        if n1.length() < 1e-3 || n2.length() < 1e-3 || sin < 1e-3 {
            continue;
        }
        checked += 1;
        match (reference_segment(&t1, &t2), got) {
            (Some((lo, hi, len)), TriangleContact::Segment { a, b }) if len > 1e-9 => {
                crossing += 1;
                assert!(
                    close(a, lo, 1e-9) && close(b, hi, 1e-9),
                    "{a} {b} vs {lo} {hi}"
                );
            }
            (Some((_, _, len)), got) if len.abs() > 1e-9 => {
                assert_eq!(len > 0.0, got != TriangleContact::Disjoint, "{t1:?} {t2:?}");
                if len < 0.0 {
                    apart += 1;
                }
            }
            (None, got) => {
                apart += 1;
                assert_eq!(got, TriangleContact::Disjoint, "{t1:?} {t2:?}");
            }
            _ => {}
        }
    }
    assert!(
        checked > 30_000 && crossing > 5_000 && apart > 5_000,
        "{checked} {crossing} {apart}"
    );
}

/// Kinds of random pairs, many built to touch exactly.
const KINDS: usize = 7;

fn random_int_tri(rng: &mut Rng, r: i64) -> [[i64; 3]; 3] {
    [rng.int_point(r), rng.int_point(r), rng.int_point(r)]
}

/// An integer pair of kind `kind` (0..5); see `random_pair`.
fn random_int_pair(rng: &mut Rng, kind: usize) -> ([[i64; 3]; 3], [[i64; 3]; 3]) {
    let t1 = random_int_tri(rng, 3);
    let mut t2 = random_int_tri(rng, 3);
    match kind {
        // Shared vertex.
        1 => t2[rng.index(3)] = t1[rng.index(3)],
        // Shared edge.
        2 => {
            let i = rng.index(3);
            t2[0] = t1[i];
            t2[1] = t1[(i + 1) % 3];
        }
        // Vertices exactly on the plane of t1, at integer points a + i (b - a) + j (c - a);
        // all three sometimes (coplanar).
        3 => {
            let all = rng.index(3) == 0;
            for p in &mut t2 {
                if all || rng.index(3) != 0 {
                    let (i, j) = (rng.int(-1, 2), rng.int(-1, 2));
                    for k in 0..3 {
                        p[k] = t1[0][k] + i * (t1[1][k] - t1[0][k]) + j * (t1[2][k] - t1[0][k]);
                    }
                }
            }
        }
        // Degenerate t1 or t2: collinear points a + k d, or a repeated point; a is a vertex
        // of the other triangle half of the time.
        4 => {
            let a = if rng.index(2) == 0 {
                t1[rng.index(3)]
            } else {
                rng.int_point(3)
            };
            let d = rng.int_point(2);
            let deg = [0, 1, 2].map(|_| {
                let k = rng.int(-1, 2);
                [a[0] + k * d[0], a[1] + k * d[1], a[2] + k * d[2]]
            });
            if rng.index(2) == 0 {
                t2 = deg;
            } else {
                return (t2, deg);
            }
        }
        _ => {}
    }
    (t1, t2)
}

/// A random pair: kinds 0..5 integer (random, shared vertex, shared edge, on-plane lattice,
/// degenerate), 5 generic floats, 6 floats with vertices placed exactly on the other's plane.
fn random_pair(rng: &mut Rng, kind: usize) -> (Tri, Tri) {
    match kind {
        5 => (rng.tri(), rng.tri().map(|p| p * 0.8)),
        6 => {
            let z = rng.signed();
            let t1 = [0, 1, 2].map(|_| v(rng.signed(), rng.signed(), z));
            let mut t2 = rng.tri();
            for p in &mut t2 {
                if rng.index(2) == 0 {
                    p.z = z;
                }
            }
            if rng.index(4) == 0 {
                t2[0] = t1[rng.index(3)];
            }
            (t1, t2)
        }
        _ => {
            let (a, b) = random_int_pair(rng, kind);
            (to_tri(&a), to_tri(&b))
        }
    }
}

#[test]
fn boolean_agrees_with_full_on_100k_seeded_pairs() {
    let mut rng = Rng(2024);
    let mut hits = [[0usize; 2]; KINDS];
    let mut coplanar = 0;
    for n in 0..100_000 {
        let kind = n % KINDS;
        let (t1, t2) = random_pair(&mut rng, kind);
        let full = intersect_triangles(&t1, &t2);
        let quick = triangles_intersect(&t1, &t2);
        assert_eq!(
            full != TriangleContact::Disjoint,
            quick,
            "{t1:?} {t2:?}: {full:?}"
        );
        // The decision does not depend on argument or vertex order.
        let (p1, p2) = (
            permutations(&t1)[rng.index(6)],
            permutations(&t2)[rng.index(6)],
        );
        assert_eq!(triangles_intersect(&p2, &p1), quick, "{t1:?} {t2:?}");
        let pts = match full {
            TriangleContact::Disjoint => vec![],
            TriangleContact::Segment { a, b } => vec![a, b],
            TriangleContact::Coplanar { points } => {
                coplanar += 1;
                assert!((1..=6).contains(&points.len()));
                points.to_vec()
            }
        };
        // Every point is finite and inside both bounding boxes (as documented).
        for p in pts {
            assert!(p.is_finite());
            for t in [&t1, &t2] {
                let (lo, hi) = (t[0].min(t[1]).min(t[2]), t[0].max(t[1]).max(t[2]));
                assert!(
                    p.cmpge(lo).all() && p.cmple(hi).all(),
                    "{p} outside {lo}..{hi}"
                );
            }
        }
        hits[kind][usize::from(quick)] += 1;
    }
    eprintln!("(disjoint, touching or crossing) per kind: {hits:?}");
    for (kind, h) in hits.iter().enumerate() {
        // Kinds 1 and 2 share a vertex or an edge, so they always meet.
        let disjoint_expected = if kind == 1 || kind == 2 { 0 } else { 1_000 };
        assert!(
            h[0] >= disjoint_expected && h[1] > 1_000,
            "kind {kind}: {h:?}"
        );
        if disjoint_expected == 0 {
            assert_eq!(h[0], 0, "kind {kind}");
        }
    }
    assert!(coplanar > 1_000, "{coplanar}");
}

#[test]
fn integer_pairs_match_exact_separating_axis_truth() {
    let mut rng = Rng(99);
    let mut counts = [0usize; 3];
    for n in 0..40_000 {
        let (i1, i2) = random_int_pair(&mut rng, n % 5);
        let (t1, t2) = (to_tri(&i1), to_tri(&i2));
        let truth = sat_intersect(&i1, &i2);
        let got = intersect_triangles(&t1, &t2);
        assert_eq!(
            got != TriangleContact::Disjoint,
            truth,
            "{i1:?} {i2:?}: {got:?}"
        );
        assert_eq!(triangles_intersect(&t1, &t2), truth, "{i1:?} {i2:?}");
        match got {
            TriangleContact::Disjoint => counts[0] += 1,
            TriangleContact::Segment { a, b } => {
                counts[1] += 1;
                for p in [a, b, (a + b) * 0.5] {
                    assert!(
                        dist(p, &t1) < 1e-12 && dist(p, &t2) < 1e-12,
                        "{i1:?} {i2:?}"
                    );
                }
            }
            TriangleContact::Coplanar { points } => {
                counts[2] += 1;
                for p in points.iter() {
                    assert!(
                        dist(*p, &t1) < 1e-12 && dist(*p, &t2) < 1e-12,
                        "{i1:?} {i2:?}"
                    );
                }
                // Area (which depends on the order of the points) against clipping, and
                // counter-clockwise about n1.
                let n1 = normal(&t1).normalize();
                let area = vector_area(&points).dot(n1);
                let want = clipped_area(&t1, &t2);
                assert!(
                    (area - want).abs() < 1e-9,
                    "{i1:?} {i2:?}: {area} vs {want}"
                );
            }
        }
    }
    assert!(counts.iter().all(|&c| c > 1_000), "{counts:?}");
}

// ---------------------------------------------------------------------------------------------
// Non-finite and extreme inputs.

#[test]
fn non_finite_input_is_disjoint() {
    let t1 = base();
    let t2 = [v(1.0, 1.0, -1.0), v(3.0, 1.0, -1.0), v(2.0, 1.0, 3.0)];
    assert!(triangles_intersect(&t1, &t2));
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        for which in 0..2 {
            for i in 0..3 {
                for k in 0..3 {
                    let (mut a, mut b) = (t1, t2);
                    let t = if which == 0 { &mut a } else { &mut b };
                    t[i][k] = bad;
                    expect_disjoint(&a, &b);
                    expect_disjoint(&b, &a);
                }
            }
        }
        expect_disjoint(&[DVec3::splat(bad); 3], &[DVec3::splat(bad); 3]);
    }
}

#[test]
fn extreme_magnitudes_are_scale_invariant() {
    let t2 = [v(2.0, 1.0, -1.0), v(6.0, 1.0, -1.0), v(4.0, 1.0, 3.0)];
    let (a0, b0) = expect_segment(&base(), &t2);
    // Powers of two scale exactly, so the answer scales exactly, from subnormal to near-max.
    for k in [-1060, -1000, -600, -151, -150, 0, 150, 151, 600, 1000, 1020] {
        let s = pow2(k);
        let (x, y) = (base().map(|p| p * s), t2.map(|p| p * s));
        assert_eq!(expect_segment(&x, &y), (a0 * s, b0 * s), "2^{k}");
        // Touching decisions too: shared vertex and coplanar overlap.
        let shared = [x[1], v(5.0, -1.0, 1.0) * s, v(5.0, 1.0, 2.0) * s];
        assert_eq!(expect_segment(&x, &shared), (x[1], x[1]), "2^{k}");
        let flat = [
            v(1.0, 1.0, 0.0) * s,
            v(2.0, 1.0, 0.0) * s,
            v(1.0, 2.0, 0.0) * s,
        ];
        assert_eq!(expect_polygon(&x, &flat).len(), 3);
    }
    // Other large factors: finite and close to the scaled answer.
    for s in [1e300, 1e-300, f64::MAX / 8.0, 1e-310] {
        let (a, b) = expect_segment(&base().map(|p| p * s), &t2.map(|p| p * s));
        assert!(a.is_finite() && b.is_finite());
        assert!(
            close(a, a0 * s, 1e-10 * s) && close(b, b0 * s, 1e-10 * s),
            "{s}"
        );
    }
    // Coordinates near the largest finite value, with a crossing computed between them: t1
    // meets y = 0 at x in [-m/2, m/2], t2 meets z = 0 at x in [0, m].
    let m = f64::MAX / 4.0;
    let big = [v(-m, -m, 0.0), v(m, -m, 0.0), v(0.0, m, 0.0)];
    let cross = [v(0.0, 0.0, -m), v(0.0, 0.0, m), v(m, 0.0, 0.0)];
    // n1 × n2 = +z × +y points along -x: the segment runs from x = m/2 down to 0.
    let (a, b) = expect_segment(&big, &cross);
    assert!(close(a, v(m / 2.0, 0.0, 0.0), 1e-15 * m), "{a}");
    assert_eq!(b, DVec3::ZERO);
}

/// `2^k` by repeated exact doubling or halving (`powi` may overflow an intermediate).
fn pow2(k: i32) -> f64 {
    let mut x = 1.0;
    for _ in 0..k.unsigned_abs() {
        x = if k < 0 { x * 0.5 } else { x * 2.0 };
    }
    x
}
