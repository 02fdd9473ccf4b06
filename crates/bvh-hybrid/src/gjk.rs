//! Boolean GJK (Gilbert, Johnson and Keerthi 1988) between the convex hulls of two vertex
//! sets: the fast exact overlap test of the leaf volumes. Each answer carries a certificate:
//! a separating axis whose projection gap exceeds the slack, or a point of the hull of the
//! Minkowski difference `A - B` within the slack of the origin. The closest point on a
//! simplex follows Ericson, *Real-Time Collision Detection* (2005), sections 5.1.2 to 5.1.6,
//! with every result kept a convex combination of the simplex points so that the overlap
//! certificate holds whatever the rounding.

use glam::{DMat3, DVec3};

/// Iteration cap. On polytopes GJK terminates in a few steps (2 to 8 on the leaf volumes);
/// reaching the cap means rounding made it cycle.
const MAX_ITERATIONS: usize = 48;

/// An iteration has stalled when the new support point `w` lowers the bound `|v|^2 - v.w`
/// by no more than this fraction of `|v|^2` (then `|v|` is the distance to about this
/// relative accuracy, and more iterations would only see rounding).
const MIN_PROGRESS: f64 = 1e-12;

/// Outcome of [`gjk_overlap`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum GjkOutcome {
    /// An axis separates the projections of the two hulls by more than the slack; the gap
    /// (mm) by which they are apart beyond it.
    Separated(f64),
    /// A point of the Minkowski difference of the hulls lies within the slack of the origin:
    /// the hulls come within the slack (plus rounding) of each other.
    Overlapping,
    /// The iteration stalled or reached [`MAX_ITERATIONS`] (the hulls are then within about
    /// the slack of touching), or the inputs are not finite: no certificate was found.
    Undecided,
}

/// The convex hull of a vertex set, as GJK sees it.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Hull<'a> {
    /// The vertices (at least one).
    pub(crate) vertices: &'a [DVec3],
    /// For hill-climbing support points: the three vertices joined to each vertex by an edge
    /// of the hull (fewer padded with the vertex itself). Empty (always when some vertex
    /// has more than three) means every support point is a full scan.
    pub(crate) neighbours: &'a [[u8; 3]],
    /// Where climbs start: for each octant of directions (bit `k` set for a positive
    /// coordinate `k`), a vertex extreme along the octant's diagonal.
    pub(crate) octant_starts: &'a [u8; 8],
}

/// Neighbours of the corners of a box (corner `i` as in [`crate::obb::corner_signs`]): the
/// three corners that differ from it in one sign.
pub(crate) const BOX_NEIGHBOURS: [[u8; 3]; 8] = {
    let mut lists = [[0; 3]; 8];
    let mut i = 0;
    while i < 8 {
        lists[i] = [(i ^ 1) as u8, (i ^ 2) as u8, (i ^ 4) as u8];
        i += 1;
    }
    lists
};

/// Octant starts of the box corners: corner `i` is the extreme one along octant `i`'s diagonal.
pub(crate) const BOX_OCTANT_STARTS: [u8; 8] = [0, 1, 2, 3, 4, 5, 6, 7];

impl Hull<'_> {
    /// Index of a vertex with the largest dot product with `d`, by a scan of all vertices.
    fn scan(&self, d: DVec3) -> usize {
        let mut best = 0;
        let mut best_dot = d.dot(self.vertices[0]);
        for (i, &p) in self.vertices.iter().enumerate().skip(1) {
            let s = d.dot(p);
            if s > best_dot {
                best = i;
                best_dot = s;
            }
        }
        best
    }

    /// Index of a vertex with the largest dot product with `d`: from the higher of vertex
    /// `start` and the octant start of `d`, steps along [`Hull::neighbours`] to the best
    /// neighbour until none improves. On a convex hull whose edges are all listed, that
    /// local maximum is the global one; [`gjk_overlap`] rescans before it relies on that.
    fn climb(&self, d: DVec3, start: usize) -> usize {
        if self.neighbours.is_empty() {
            return self.scan(d);
        }
        let octant =
            usize::from(d.x > 0.0) | usize::from(d.y > 0.0) << 1 | usize::from(d.z > 0.0) << 2;
        let jump = usize::from(self.octant_starts[octant]);
        let (start_dot, jump_dot) = (d.dot(self.vertices[start]), d.dot(self.vertices[jump]));
        let mut best = if jump_dot > start_dot { jump } else { start };
        let mut best_dot = start_dot.max(jump_dot);
        loop {
            let from = best;
            for &j in &self.neighbours[from] {
                let s = d.dot(self.vertices[usize::from(j)]);
                let better = s > best_dot;
                best = if better { usize::from(j) } else { best };
                best_dot = if better { s } else { best_dot };
            }
            if best == from {
                return best;
            }
        }
    }
}

/// The vertex pairs (A's index, B's index) of a simplex of four points of hull(A - B) that held
/// the origin: kept by the caller of [`gjk_overlap`] for the next call on the same hulls. At
/// any pose its four points are points of hull(A - B), so where they still hold the origin
/// (within the slack) the hulls overlap, as GJK's own final simplex would show.
pub(crate) type OverlapWitness = [(u16, u16); 4];

/// GJK on hulls `a` and `b`, `a` given in the working frame and `b` in a frame mapped to it by
/// `q -> m q + t` (`m` a rotation). `slack` (mm) is the distance within which the hulls count
/// as overlapping; separation is reported only along an axis whose gap exceeds it.
///
/// `witness`: a simplex kept from an earlier call on the same hulls. When its four points
/// hold the origin at this pose the answer is `Overlapping` at once; otherwise GJK runs, and
/// the witness becomes its final simplex when that holds the origin (`None` for any other
/// outcome).
///
/// Cost per iteration: one support point on each side, by hill climbing from the previous
/// one (a few dot products), and the closest point on a simplex of at most four points. The
/// separation and stall verdicts are taken on support points from a full scan of both vertex
/// sets, so a missing edge in [`Hull::neighbours`] can only cost time.
pub(crate) fn gjk_overlap(
    a: &Hull<'_>,
    b: &Hull<'_>,
    m: DMat3,
    t: DVec3,
    slack: f64,
    witness: &mut Option<OverlapWitness>,
) -> GjkOutcome {
    if a.vertices.is_empty() || b.vertices.is_empty() {
        return GjkOutcome::Undecided;
    }
    let m_t = m.transpose();
    // The point of hull(A - B) minimising `v . x` (the support point in direction -v) from
    // the vertices of A and B maximising `-v . p` and `v . p`.
    let minkowski = |ia: usize, ib: usize| a.vertices[ia] - (m * b.vertices[ib] + t);
    let holds_origin = |pairs: &OverlapWitness| {
        let point = |k: usize| {
            let (ia, ib) = (usize::from(pairs[k].0), usize::from(pairs[k].1));
            (ia < a.vertices.len() && ib < b.vertices.len()).then(|| minkowski(ia, ib))
        };
        let (Some(p), Some(q), Some(r), Some(s)) = (point(0), point(1), point(2), point(3)) else {
            return false;
        };
        let (closest, face) = tetrahedron(p, q, r, s);
        face.len == 4 && closest.length_squared() <= slack * slack
    };
    if witness.as_ref().is_some_and(holds_origin) {
        return GjkOutcome::Overlapping;
    }
    *witness = None;
    let (mut ia, mut ib) = (0, 0);
    // Some point of hull(A - B) near its closest point to the origin to start with: the
    // difference of the frame origins (both frames are centred on their volumes).
    let mut v = if t == DVec3::ZERO { DVec3::X } else { -t };
    let mut simplex = Simplex::default();
    for iteration in 0..MAX_ITERATIONS {
        let vv = v.length_squared();
        if !vv.is_finite() {
            return GjkOutcome::Undecided;
        }
        // After the first iteration, `v` is a convex combination of support points.
        if iteration > 0 && vv <= slack * slack {
            return GjkOutcome::Overlapping;
        }
        let v_b = m_t * v;
        (ia, ib) = (a.climb(-v, ia), b.climb(v_b, ib));
        let mut w = minkowski(ia, ib);
        // When w is the true support point, every x in hull(A - B) has `v . x >= v . w`: along
        // v / |v|, hull(A) lies beyond hull(B) by `v . w / |v|` or more (the separation
        // test), and `|v|^2 - v . w` bounds how much nearer to the origin hull(A - B) comes
        // than v (the stall test). Both verdicts are taken on a scanned support point.
        let separated = |w: DVec3| v.dot(w) > slack * vv.sqrt();
        let stalled = |w: DVec3| iteration > 0 && vv - v.dot(w) <= MIN_PROGRESS * vv;
        if separated(w) || stalled(w) {
            (ia, ib) = (a.scan(-v), b.scan(v_b));
            w = minkowski(ia, ib);
            if separated(w) {
                return GjkOutcome::Separated(v.dot(w) / vv.sqrt() - slack);
            }
            if stalled(w) {
                return GjkOutcome::Undecided;
            }
        }
        #[allow(clippy::cast_possible_truncation)]
        simplex.push(w, (ia as u16, ib as u16));
        let closest = simplex.reduce();
        let closest_squared = closest.length_squared();
        // A full tetrahedron means the origin is inside it: `closest` is the origin as a
        // convex combination of its corners, up to rounding.
        if simplex.len == 4 {
            return if closest_squared <= slack * slack {
                let fits = a.vertices.len() <= usize::from(u16::MAX)
                    && b.vertices.len() <= usize::from(u16::MAX);
                *witness = fits.then_some(simplex.pairs);
                GjkOutcome::Overlapping
            } else {
                GjkOutcome::Undecided
            };
        }
        // The closest point of a hull containing the previous one and w is strictly nearer
        // in exact arithmetic; anything else is rounding.
        if iteration > 0 && closest_squared >= vv {
            return GjkOutcome::Undecided;
        }
        v = closest;
    }
    GjkOutcome::Undecided
}

/// Up to four points of the Minkowski difference, with the vertex pairs (A's, B's) that made
/// them.
#[derive(Clone, Copy, Debug, Default)]
struct Simplex {
    points: [DVec3; 4],
    pairs: [(u16, u16); 4],
    len: usize,
}

impl Simplex {
    /// A face of the simplex being reduced, from its points; their pairs are set by
    /// [`Simplex::reduce`].
    fn from_points(points: &[DVec3]) -> Self {
        let mut simplex = Simplex::default();
        for &p in points {
            simplex.push(p, (0, 0));
        }
        simplex
    }

    fn push(&mut self, p: DVec3, pair: (u16, u16)) {
        self.points[self.len] = p;
        self.pairs[self.len] = pair;
        self.len += 1;
    }

    /// Replaces the simplex by the face whose hull holds (up to rounding) its point closest
    /// to the origin, and returns that point, always a convex combination of the points. The
    /// face's points are copies of the simplex's, so each finds its pair by equality.
    fn reduce(&mut self) -> DVec3 {
        let (closest, mut face) = match self.points[..self.len] {
            [p] => (p, Simplex::from_points(&[p])),
            [p, q] => segment(p, q),
            [p, q, r] => triangle(p, q, r),
            [p, q, r, s] => tetrahedron(p, q, r, s),
            _ => unreachable!("a simplex has one to four points"),
        };
        for k in 0..face.len {
            if let Some(j) = (0..self.len).find(|&j| self.points[j] == face.points[k]) {
                face.pairs[k] = self.pairs[j];
            }
        }
        *self = face;
        closest
    }
}

/// `num / den` clamped to `[0, 1]`, 0 for a non-positive denominator.
fn fraction(num: f64, den: f64) -> f64 {
    if den > 0.0 {
        (num / den).clamp(0.0, 1.0)
    } else {
        0.0
    }
}

/// Closest point to the origin on the segment `pq`, and its face.
fn segment(p: DVec3, q: DVec3) -> (DVec3, Simplex) {
    let pq = q - p;
    let s = -p.dot(pq);
    let len2 = pq.length_squared();
    if s <= 0.0 {
        (p, Simplex::from_points(&[p]))
    } else if s >= len2 {
        (q, Simplex::from_points(&[q]))
    } else {
        (p + pq * fraction(s, len2), Simplex::from_points(&[p, q]))
    }
}

/// Closest point to the origin on the triangle `pqr` (Ericson 5.1.5), and its face.
fn triangle(p: DVec3, q: DVec3, r: DVec3) -> (DVec3, Simplex) {
    let (pq, pr) = (q - p, r - p);
    let (d1, d2) = (-pq.dot(p), -pr.dot(p));
    if d1 <= 0.0 && d2 <= 0.0 {
        return (p, Simplex::from_points(&[p]));
    }
    let (d3, d4) = (-pq.dot(q), -pr.dot(q));
    if d3 >= 0.0 && d4 <= d3 {
        return (q, Simplex::from_points(&[q]));
    }
    let vr = d1 * d4 - d3 * d2;
    if vr <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        let s = fraction(d1, d1 - d3);
        return (p + pq * s, Simplex::from_points(&[p, q]));
    }
    let (d5, d6) = (-pq.dot(r), -pr.dot(r));
    if d6 >= 0.0 && d5 <= d6 {
        return (r, Simplex::from_points(&[r]));
    }
    let vq = d5 * d2 - d1 * d6;
    if vq <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        let s = fraction(d2, d2 - d6);
        return (p + pr * s, Simplex::from_points(&[p, r]));
    }
    let vp = d3 * d6 - d5 * d4;
    if vp <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0 {
        let s = fraction(d4 - d3, (d4 - d3) + (d5 - d6));
        return (q + (r - q) * s, Simplex::from_points(&[q, r]));
    }
    let sum = vp + vq + vr;
    if vp >= 0.0 && vq >= 0.0 && vr >= 0.0 && sum > 0.0 {
        let (u, w) = (vq / sum, vr / sum);
        return (p + pq * u + pr * w, Simplex::from_points(&[p, q, r]));
    }
    // A (nearly) degenerate triangle that rounding sent to the face region: its closest
    // point lies on an edge.
    [segment(p, q), segment(q, r), segment(r, p)]
        .into_iter()
        .min_by(|x, y| x.0.length_squared().total_cmp(&y.0.length_squared()))
        .expect("three candidates")
}

/// Closest point to the origin on the tetrahedron `pqrs` (Ericson 5.1.6), and its face: the
/// origin itself (as the barycentric combination) when no face plane separates it from the
/// opposite vertex, else the nearest closest point among the faces that do (or are
/// degenerate).
fn tetrahedron(p: DVec3, q: DVec3, r: DVec3, s: DVec3) -> (DVec3, Simplex) {
    // Each face with its opposite vertex.
    let faces = [(p, q, r, s), (p, r, s, q), (p, s, q, r), (q, s, r, p)];
    // Barycentric coordinate of the origin for each opposite vertex: the ratio of the
    // origin's and the vertex's signed distances to the face plane (NaN when degenerate).
    let lambdas = faces.map(|(f0, f1, f2, o)| {
        let n = (f1 - f0).cross(f2 - f0);
        -f0.dot(n) / (o - f0).dot(n)
    });
    if lambdas.iter().all(|&l| l >= 0.0) {
        let sum: f64 = lambdas.iter().sum();
        let combination = lambdas
            .iter()
            .zip(&faces)
            .fold(DVec3::ZERO, |acc, (&l, face)| acc + face.3 * l)
            / sum;
        return (combination, Simplex::from_points(&[p, q, r, s]));
    }
    faces
        .iter()
        .zip(lambdas)
        // Outside the face, or a degenerate face (NaN).
        .filter(|(_, l)| *l < 0.0 || l.is_nan())
        .map(|(&(f0, f1, f2, _), _)| triangle(f0, f1, f2))
        .min_by(|x, y| x.0.length_squared().total_cmp(&y.0.length_squared()))
        .expect("some face separates the origin")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::obb::corner_signs;
    use glam::DQuat;

    /// A hull whose support points are full scans.
    fn hull(vertices: &[DVec3]) -> Hull<'_> {
        Hull {
            vertices,
            neighbours: &[],
            octant_starts: &[0; 8],
        }
    }

    fn cube(center: DVec3, half: f64) -> [DVec3; 8] {
        std::array::from_fn(|i| center + corner_signs(i) * half)
    }

    #[test]
    fn cubes_at_known_distances() {
        let a = cube(DVec3::ZERO, 1.0);
        let b = cube(DVec3::ZERO, 1.0);
        let climbing = |vertices| Hull {
            vertices,
            neighbours: &BOX_NEIGHBOURS,
            octant_starts: &BOX_OCTANT_STARTS,
        };
        let rot = DMat3::from_quat(DQuat::from_rotation_z(0.3));
        // Rotated about z by 0.3 rad, b's extent along x is cos 0.3 + sin 0.3.
        let reach = 1.0 + 0.3f64.cos() + 0.3f64.sin();
        let slack = 1e-10;
        // The cubes' distance at each offset along x: `None` where they overlap.
        for (offset, distance) in [
            (0.0, None),
            (reach - 1e-3, None),
            (reach + 1e-3, Some(1e-3)),
            (10.0, Some(10.0 - reach)),
        ] {
            let t = DVec3::new(offset, 0.2, -0.1);
            for (outcome, how) in [
                (
                    gjk_overlap(&hull(&a), &hull(&b), rot, t, slack, &mut None),
                    "scanning",
                ),
                (
                    gjk_overlap(&climbing(&a), &climbing(&b), rot, t, slack, &mut None),
                    "climbing",
                ),
            ] {
                match (outcome, distance) {
                    (GjkOutcome::Overlapping, None) => {}
                    // The gap is a lower bound on the distance, beyond the slack.
                    (GjkOutcome::Separated(gap), Some(d)) => {
                        assert!(
                            gap > 0.0 && gap <= d - slack + 1e-12,
                            "{offset}, {how}: {gap}"
                        );
                    }
                    other => panic!("{offset}, {how}: {other:?}"),
                }
            }
        }
    }

    /// A witness kept from an overlap answers the next overlap as GJK would, and never hides
    /// a separation: moved apart, the cubes are separated and the witness is dropped; a witness
    /// naming vertices the hulls do not have is ignored.
    #[test]
    fn a_kept_witness_never_hides_a_separation() {
        let (a, b) = (cube(DVec3::ZERO, 1.0), cube(DVec3::ZERO, 1.0));
        let rot = DMat3::from_quat(DQuat::from_rotation_z(0.3));
        let slack = 1e-10;
        let mut witness = None;
        let deep = DVec3::new(0.5, 0.2, -0.1);
        let outcome = gjk_overlap(&hull(&a), &hull(&b), rot, deep, slack, &mut witness);
        assert_eq!(outcome, GjkOutcome::Overlapping);
        let kept = witness.expect("GJK's final simplex held the origin");
        // Nudged: still overlapping, from the witness, which stays.
        let nudged = deep + DVec3::splat(1e-3);
        let outcome = gjk_overlap(&hull(&a), &hull(&b), rot, nudged, slack, &mut witness);
        assert_eq!((outcome, witness), (GjkOutcome::Overlapping, Some(kept)));
        // Apart: the witness fails, GJK separates them and drops it.
        let apart = DVec3::new(3.0, 0.2, -0.1);
        let outcome = gjk_overlap(&hull(&a), &hull(&b), rot, apart, slack, &mut witness);
        assert!(matches!(outcome, GjkOutcome::Separated(_)), "{outcome:?}");
        assert_eq!(witness, None);
        let mut bogus = Some([(40, 0), (0, 40), (1, 1), (2, 2)]);
        let outcome = gjk_overlap(&hull(&a), &hull(&b), rot, deep, slack, &mut bogus);
        assert_eq!(outcome, GjkOutcome::Overlapping);
        assert!(bogus.is_some_and(|w| w.iter().all(|&(i, j)| i < 8 && j < 8)));
    }

    #[test]
    fn degenerate_point_sets() {
        // A point inside a flat square, and just above it; a segment crossing it.
        let square = [
            DVec3::new(-1.0, -1.0, 0.0),
            DVec3::new(1.0, -1.0, 0.0),
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(-1.0, 1.0, 0.0),
        ];
        let point = [DVec3::ZERO];
        let id = DMat3::IDENTITY;
        let at = |z: f64| DVec3::new(0.3, -0.2, z);
        assert_eq!(
            gjk_overlap(&hull(&square), &hull(&point), id, at(0.0), 1e-12, &mut None),
            GjkOutcome::Overlapping
        );
        // Separated by 1e-6 mm (to the rounding of the inputs), less the slack.
        let gap = |outcome| match outcome {
            GjkOutcome::Separated(gap) => gap,
            other => panic!("{other:?}"),
        };
        let expected = 1e-6 - 1e-12;
        let found = gap(gjk_overlap(
            &hull(&square),
            &hull(&point),
            id,
            at(1e-6),
            1e-12,
            &mut None,
        ));
        assert!((found - expected).abs() <= 1e-15, "{found}");
        let stick = [DVec3::new(0.0, 0.0, -1.0), DVec3::new(0.0, 0.0, 1.0)];
        assert_eq!(
            gjk_overlap(&hull(&square), &hull(&stick), id, at(0.5), 1e-12, &mut None),
            GjkOutcome::Overlapping
        );
        let found = gap(gjk_overlap(
            &hull(&square),
            &hull(&stick),
            id,
            DVec3::new(1.0 + 1e-6, 0.0, 0.5),
            1e-12,
            &mut None,
        ));
        assert!((found - expected).abs() <= 1e-15, "{found}");
        assert_eq!(
            gjk_overlap(
                &hull(&square),
                &hull(&point),
                id,
                DVec3::NAN,
                1e-12,
                &mut None
            ),
            GjkOutcome::Undecided
        );
    }
}
