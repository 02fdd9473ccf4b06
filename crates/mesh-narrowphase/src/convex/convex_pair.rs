//! The convex-convex path: GJK between two hulls with hill-climbing support maps and warm start.

use crate::convex::hill_climb_support::HillClimbSupport;
use geom_param::{ConvexHull, DPose3};
use glam::DVec3;
use parry3d_f64::query::gjk::{self, CsoPoint, GJKResult, VoronoiSimplex};

/// Warm-start state of one component pair: the last GJK direction, support vertices and final
/// simplex.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct WarmStart {
    /// Last search direction in A's frame (zero: none yet).
    pub dir: DVec3,
    /// Last support vertex on A's hull.
    pub vertex_a: u32,
    /// Last support vertex on B's hull.
    pub vertex_b: u32,
    /// The last query's final simplex: its first `simplex_len` points, each a pair of hull
    /// vertices (A's index, B's index).
    pub simplex: [[u32; 2]; 4],
    /// How many points of `simplex` hold (0: none).
    pub simplex_len: usize,
}

impl WarmStart {
    /// Puts the last query's final simplex into `simplex`, its vertices taken from the hulls
    /// (B's posed by `pose_ab`); false when there is none. Any pair of hull vertices is a point
    /// of the hulls' Minkowski difference, at any pose and whatever hulls the indices came
    /// from (a start left by other hulls only starts GJK elsewhere): an index out of range
    /// leaves the start to the last direction.
    ///
    /// Why: GJK between two nearly parallel flat faces (two plates 0.05 mm apart, tilted by
    /// 0.01-0.03 rad) spent 30 iterations building its simplex from a support point in the
    /// last direction, which is any vertex of the face; each iteration walks both plates'
    /// flat hulls. From the last simplex it starts next to the answer.
    fn restore(
        &self,
        (hull_a, hull_b): (&ConvexHull, &ConvexHull),
        pose_ab: &DPose3,
        simplex: &mut VoronoiSimplex,
    ) -> bool {
        let posed = |[a, b]: [u32; 2]| {
            let a = hull_a.points.get(a as usize)?;
            let b = hull_b.points.get(b as usize)?;
            Some(CsoPoint::new(*a, *pose_ab * *b))
        };
        let points = &self.simplex[..self.simplex_len.min(4)];
        let Some(first) = points.first().and_then(|&p| posed(p)) else {
            return false;
        };
        simplex.reset(first);
        for &point in &points[1..] {
            // A point degenerate with the others at this pose is left out.
            if let Some(point) = posed(point) {
                simplex.add_point(point);
            }
        }
        true
    }

    /// Keeps `simplex`'s points as hull vertex indices for [`Self::restore`], found among the
    /// support maps' recent answers and the restored start (`self`): A's point is a hull
    /// vertex to the bit, B's one posed by `pose_ab` (brought back to B's frame, within
    /// rounding of the vertex). Where a point is not found, no simplex is kept.
    fn keep(
        &mut self,
        (sa, sb): (&HillClimbSupport<'_>, &HillClimbSupport<'_>),
        (hull_a, hull_b): (&ConvexHull, &ConvexHull),
        pose_ab: &DPose3,
        simplex: &VoronoiSimplex,
    ) {
        let restored = self.simplex;
        let restored = &restored[..self.simplex_len.min(4)];
        let candidates_a = restored.iter().map(|p| p[0]).chain(sa.recent());
        let candidates_b = restored.iter().map(|p| p[1]).chain(sb.recent());
        let inverse = pose_ab.inverse();
        let mut kept = [[0; 2]; 4];
        let len = simplex.dimension() + 1;
        for (i, slot) in kept.iter_mut().enumerate().take(len) {
            let point = simplex.point(i);
            let a = candidates_a
                .clone()
                .find(|&k| hull_a.points.get(k as usize) == Some(&point.orig1));
            let on_b = inverse * point.orig2;
            let rounding = 1e-12 * (1.0 + point.orig2.length() + pose_ab.translation.length());
            let b = candidates_b.clone().find(|&k| {
                hull_b
                    .points
                    .get(k as usize)
                    .is_some_and(|p| p.distance(on_b) <= rounding)
            });
            let (Some(a), Some(b)) = (a, b) else {
                self.simplex_len = 0;
                return;
            };
            *slot = [a, b];
        }
        self.simplex = kept;
        self.simplex_len = len;
    }
}

/// What GJK says about two hulls.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum HullProximity {
    /// Farther apart than the query distance (certified by a separating direction).
    Separated,
    /// Closest points on A's hull and on B's hull (both in A's frame), apart by more than the
    /// touching tolerance and at most the query distance.
    Close {
        /// On A's hull.
        p1: DVec3,
        /// On B's hull, in A's frame.
        p2: DVec3,
    },
    /// The hulls overlap or touch (within the touching tolerance).
    Overlapping,
    /// GJK hit its iteration cap without an answer.
    NotConverged,
}

/// GJK's simplex, reused across queries.
#[derive(Clone, Debug, Default)]
pub struct GjkScratch {
    /// Parry's simplex.
    pub simplex: VoronoiSimplex,
}

/// Runs GJK between `hull_a` and `hull_b` (B posed by `pose_ab` in A's frame), up to distance
/// `max_distance` (mm). Distances at or below `touching` (mm) count as overlap. Parry's GJK stops
/// when its bounds agree to about 4e-8 relative, or after 100 iterations (reported here as
/// [`HullProximity::NotConverged`] unless the returned direction certifies separation).
/// Returns the verdict and the number of support evaluations.
pub fn hull_proximity(
    hull_a: &ConvexHull,
    hull_b: &ConvexHull,
    pose_ab: &DPose3,
    max_distance: f64,
    touching: f64,
    warm: &mut WarmStart,
    gjk_scratch: &mut GjkScratch,
) -> (HullProximity, u32) {
    let GjkScratch { simplex } = gjk_scratch;
    let sa = HillClimbSupport::new(hull_a, warm.vertex_a);
    let sb = HillClimbSupport::new(hull_b, warm.vertex_b);
    let dir = warm
        .dir
        .try_normalize()
        .or_else(|| (-pose_ab.translation).try_normalize())
        .unwrap_or(DVec3::X);
    if !warm.restore((hull_a, hull_b), pose_ab, simplex) {
        simplex.reset(CsoPoint::from_shapes(pose_ab, &sa, &sb, dir));
    }
    let result = gjk::closest_points(pose_ab, &sa, &sb, max_distance, true, simplex);
    warm.keep((&sa, &sb), (hull_a, hull_b), pose_ab, simplex);
    let verdict = match result {
        GJKResult::ClosestPoints(p1, p2, n) => {
            warm.dir = n;
            if p1.distance(p2) <= touching {
                HullProximity::Overlapping
            } else {
                HullProximity::Close { p1, p2 }
            }
        }
        GJKResult::NoIntersection(n) | GJKResult::Proximity(n) => {
            // Parry also returns NoIntersection at its iteration cap; trust only a direction
            // that really separates the hulls by more than max_distance.
            let w = CsoPoint::from_shapes(pose_ab, &sa, &sb, n);
            if -n.dot(w.point) > max_distance {
                warm.dir = n;
                HullProximity::Separated
            } else {
                HullProximity::NotConverged
            }
        }
        GJKResult::Intersection => HullProximity::Overlapping,
    };
    warm.vertex_a = sa.current();
    warm.vertex_b = sb.current();
    (verdict, sa.evaluations().max(sb.evaluations()))
}
