//! A static 3-d tree over sample points: nearest neighbour and fixed-radius queries.
//!
//! Implicit layout (no node allocations): the points of a subrange are split at their median
//! along the subrange's widest axis; the median element is the node, the two halves its
//! children. Build O(n log n), queries O(log n) on surface samples.

use glam::DVec3;

/// A kd-tree over points; results are indices into the slice it was built from.
#[derive(Debug)]
pub(crate) struct KdTree {
    /// Points in tree order.
    points: Vec<DVec3>,
    /// Original index of each point in tree order.
    index: Vec<usize>,
    /// Split axis of the node at each position.
    axis: Vec<u8>,
    /// Tight bounding box (lo, hi) of the subtree rooted at each position.
    boxes: Vec<(DVec3, DVec3)>,
}

impl KdTree {
    pub fn new(points: &[DVec3]) -> Self {
        let mut order: Vec<(DVec3, usize)> = points.iter().copied().zip(0..).collect();
        let mut axis = vec![0_u8; points.len()];
        let mut boxes = vec![(DVec3::ZERO, DVec3::ZERO); points.len()];
        build(&mut order, &mut axis, &mut boxes);
        Self {
            points: order.iter().map(|p| p.0).collect(),
            index: order.iter().map(|p| p.1).collect(),
            axis,
            boxes,
        }
    }

    /// The nearest point to `q` no farther than `limit`, as (original index, distance). A
    /// finite limit keeps queries from far away cheap (the search prunes at the limit).
    pub fn nearest_within(&self, q: DVec3, limit: f64) -> Option<(usize, f64)> {
        let mut best = (usize::MAX, limit * limit);
        self.nearest_in(0, self.points.len(), q, &mut best);
        (best.0 != usize::MAX).then(|| (self.index[best.0], best.1.sqrt()))
    }

    /// Descends near child first; a subtree is skipped when its tight bounding box is
    /// farther than the best so far. Tight boxes (not just the split planes) are what keep a
    /// query from a point hovering over a densely sampled surface cheap: the subtrees of a
    /// surface are thin across it.
    fn nearest_in(&self, lo: usize, hi: usize, q: DVec3, best: &mut (usize, f64)) {
        if lo >= hi {
            return;
        }
        let mid = lo + (hi - lo) / 2;
        let (bl, bh) = self.boxes[mid];
        if (bl - q).max(q - bh).max(DVec3::ZERO).length_squared() >= best.1 {
            return;
        }
        let p = self.points[mid];
        let d2 = p.distance_squared(q);
        if d2 < best.1 {
            *best = (mid, d2);
        }
        let a = usize::from(self.axis[mid]);
        if q[a] < p[a] {
            self.nearest_in(lo, mid, q, best);
            self.nearest_in(mid + 1, hi, q, best);
        } else {
            self.nearest_in(mid + 1, hi, q, best);
            self.nearest_in(lo, mid, q, best);
        }
    }

    /// Calls `visit(original index)` for every point within `radius` of `q`.
    pub fn within(&self, q: DVec3, radius: f64, visit: &mut impl FnMut(usize)) {
        self.within_in(0, self.points.len(), q, radius, visit);
    }

    fn within_in(
        &self,
        lo: usize,
        hi: usize,
        q: DVec3,
        radius: f64,
        visit: &mut impl FnMut(usize),
    ) {
        if lo >= hi {
            return;
        }
        let mid = lo + (hi - lo) / 2;
        let p = self.points[mid];
        if p.distance_squared(q) <= radius * radius {
            visit(self.index[mid]);
        }
        let a = usize::from(self.axis[mid]);
        let delta = q[a] - p[a];
        if delta - radius <= 0.0 {
            self.within_in(lo, mid, q, radius, visit);
        }
        if delta + radius >= 0.0 {
            self.within_in(mid + 1, hi, q, radius, visit);
        }
    }
}

/// Builds the subtree over `points` (in place) and returns its bounding box.
fn build(
    points: &mut [(DVec3, usize)],
    axis: &mut [u8],
    boxes: &mut [(DVec3, DVec3)],
) -> (DVec3, DVec3) {
    let (lo, hi) = points.iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), p| (lo.min(p.0), hi.max(p.0)),
    );
    if points.is_empty() {
        return (lo, hi);
    }
    let extent = hi - lo;
    let a = if extent.x >= extent.y && extent.x >= extent.z {
        0
    } else if extent.y >= extent.z {
        1
    } else {
        2
    };
    let mid = points.len() / 2;
    points.select_nth_unstable_by(mid, |p, q| p.0[a].total_cmp(&q.0[a]));
    axis[mid] = a as u8;
    boxes[mid] = (lo, hi);
    let (left, right) = points.split_at_mut(mid);
    let (left_axis, right_axis) = axis.split_at_mut(mid);
    let (left_boxes, right_boxes) = boxes.split_at_mut(mid);
    build(left, left_axis, left_boxes);
    build(&mut right[1..], &mut right_axis[1..], &mut right_boxes[1..]);
    (lo, hi)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A deterministic cloud (a scrambled lattice) compared with brute force.
    #[test]
    fn agrees_with_brute_force() {
        let mut state = 12345_u64;
        let mut next = || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let points: Vec<DVec3> = (0..500)
            .map(|_| DVec3::new(next(), next(), next()) * 10.0)
            .collect();
        let tree = KdTree::new(&points);
        for _ in 0..200 {
            let q = DVec3::new(next(), next(), next()) * 12.0 - 1.0;
            let (i, d) = tree.nearest_within(q, f64::INFINITY).unwrap();
            let brute = points
                .iter()
                .map(|p| p.distance(q))
                .fold(f64::INFINITY, f64::min);
            assert_eq!(d, brute);
            assert_eq!(points[i].distance(q), brute);
            let bounded = tree.nearest_within(q, 0.5);
            assert_eq!(bounded.map(|b| b.1), (brute <= 0.5).then_some(brute));
            let mut found = Vec::new();
            tree.within(q, 1.5, &mut |j| found.push(j));
            found.sort_unstable();
            let want: Vec<usize> = (0..points.len())
                .filter(|&j| points[j].distance(q) <= 1.5)
                .collect();
            assert_eq!(found, want);
        }
        assert!(KdTree::new(&[]).nearest_within(DVec3::ZERO, 1.0).is_none());
    }
}
