//! The convex-convex path: GJK between two hulls with hill-climbing support maps and warm start.

use crate::hill_climb_support::HillClimbSupport;
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
    /// The last query's final simplex: its first `simplex_len` points, each a vertex of A's
    /// hull in A's frame and a vertex of B's hull in B's frame.
    pub simplex: [[DVec3; 2]; 4],
    /// How many points of `simplex` hold (0: none yet).
    pub simplex_len: usize,
}

impl WarmStart {
    /// Puts the last query's final simplex, posed by `pose_ab`, into `simplex` (every point is
    /// a pair of hull vertices, so a point of the hulls' Minkowski difference at any pose);
    /// false when there is none.
    ///
    /// Why: GJK between two nearly parallel flat faces (two plates 0.05 mm apart, tilted by
    /// 0.01-0.03 rad) spends 30 iterations building its simplex from a support point in the
    /// last direction, which is any vertex of the face; each iteration walks both plates'
    /// flat hulls. From the last simplex it starts next to the answer.
    fn restore(&self, pose_ab: &DPose3, simplex: &mut VoronoiSimplex) -> bool {
        let posed = |[a, b]: [DVec3; 2]| CsoPoint::new(a, *pose_ab * b);
        let Some((&first, rest)) = self.simplex[..self.simplex_len.min(4)].split_first() else {
            return false;
        };
        simplex.reset(posed(first));
        for &point in rest {
            // A point degenerate with the others at this pose is left out.
            simplex.add_point(posed(point));
        }
        true
    }

    /// Keeps `simplex`'s points (B's posed by `pose_ab` in A's frame) for [`Self::restore`].
    fn keep(&mut self, pose_ab: &DPose3, simplex: &VoronoiSimplex) {
        let inverse = pose_ab.inverse();
        self.simplex_len = simplex.dimension() + 1;
        for i in 0..self.simplex_len {
            let point = simplex.point(i);
            self.simplex[i] = [point.orig1, inverse * point.orig2];
        }
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
    if !warm.restore(pose_ab, simplex) {
        simplex.reset(CsoPoint::from_shapes(pose_ab, &sa, &sb, dir));
    }
    let result = gjk::closest_points(pose_ab, &sa, &sb, max_distance, true, simplex);
    warm.keep(pose_ab, simplex);
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
