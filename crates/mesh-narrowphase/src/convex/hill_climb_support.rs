//! A GJK support map over a convex hull that hill-climbs along the hull's vertex adjacency,
//! starting from its last answer.

use geom_param::ConvexHull;
use glam::DVec3;
use parry3d_f64::shape::SupportMap;
use std::cell::Cell;

/// Support map of a [`ConvexHull`] in its own frame.
///
/// On a convex polytope a vertex whose neighbours are no further along `dir` is a global maximum
/// of `dir · x`, so a greedy walk over the hull's edges finds the support point. Each step
/// strictly increases `dir · x`, so the walk visits each vertex at most once: it is capped at the
/// vertex count (reaching the cap would mean broken adjacency; the best vertex seen is returned).
/// Between consecutive GJK directions the walk is a few steps long; warm-starting from the last
/// query's vertex keeps it short across frames.
#[derive(Debug)]
pub struct HillClimbSupport<'a> {
    hull: &'a ConvexHull,
    current: Cell<u32>,
    evaluations: Cell<u32>,
    /// The vertices of the last [`SUPPORT_LOG`] answers, in a ring indexed by `evaluations`.
    log: Cell<[u32; SUPPORT_LOG]>,
}

/// How many recent answers [`HillClimbSupport::recent`] lists: more than the points of a GJK
/// simplex, so that a final simplex built from the last answers is found among them.
pub const SUPPORT_LOG: usize = 16;

impl<'a> HillClimbSupport<'a> {
    /// A support map over `hull` whose first walk starts at hull vertex `start` (taken modulo
    /// the vertex count, so any value is safe).
    #[must_use]
    pub fn new(hull: &'a ConvexHull, start: u32) -> Self {
        let n = hull.points.len().max(1) as u32;
        Self {
            hull,
            current: Cell::new(start % n),
            evaluations: Cell::new(0),
            log: Cell::new([start % n; SUPPORT_LOG]),
        }
    }

    /// The hull vertices of the last answers (up to [`SUPPORT_LOG`] of them, in no particular
    /// order; the start vertex where fewer were asked for).
    #[must_use]
    pub fn recent(&self) -> [u32; SUPPORT_LOG] {
        self.log.get()
    }

    /// The hull vertex the last walk ended at (the warm start of the next one).
    #[must_use]
    pub fn current(&self) -> u32 {
        self.current.get()
    }

    /// How many support points have been asked for.
    #[must_use]
    pub fn evaluations(&self) -> u32 {
        self.evaluations.get()
    }

    /// The hull vertex index furthest along `dir`.
    #[must_use]
    pub fn support_vertex(&self, dir: DVec3) -> u32 {
        self.evaluations
            .set(self.evaluations.get().saturating_add(1));
        let points = &self.hull.points;
        if points.is_empty() {
            return 0;
        }
        let mut best = self.current.get();
        let mut best_dot = dir.dot(points[best as usize]);
        for _ in 0..points.len() {
            let mut moved = false;
            for &n in self.hull.neighbors(best) {
                let d = dir.dot(points[n as usize]);
                if d > best_dot {
                    best = n;
                    best_dot = d;
                    moved = true;
                }
            }
            if !moved {
                break;
            }
        }
        self.current.set(best);
        let mut log = self.log.get();
        log[self.evaluations.get() as usize % SUPPORT_LOG] = best;
        self.log.set(log);
        best
    }
}

impl SupportMap for HillClimbSupport<'_> {
    fn local_support_point(&self, dir: DVec3) -> DVec3 {
        let v = self.support_vertex(dir) as usize;
        self.hull.points.get(v).copied().unwrap_or(DVec3::ZERO)
    }
}
