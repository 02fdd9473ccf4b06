//! [`TraversalFront`]: where the last traversal of a pair of trees stopped (its front, as in
//! FCL's front lists), so that the next query on the same trees starts there instead of at
//! the roots, and skips the node pairs that the motion since cannot have brought together.
//!
//! Every node pair the traversal ends at is either apart (their volumes separated by a gap
//! found by the overlap test, a lower bound on their distance) or a leaf pair whose volumes
//! met (reported). Between two queries every point of B's node moves in A's frame by at most
//! |Δt| + θ ρ, with Δt the change of B's translation, θ the angle of the rotation between the
//! two poses and ρ the largest distance from B's origin of a point of the node's box
//! (|R1 x − R0 x| ≤ 2 sin(θ/2) |x| ≤ θ |x|). A pair apart by more than that is still apart; it
//! is kept with its gap less the motion, the others are tested again from where they stopped.
//! A met pair is tested again from the simplex that proved its overlap (four vertex pairs of
//! the two volumes, [`crate::gjk::OverlapWitness`]): where those still hold the origin at the
//! new pose, the volumes still meet, without a GJK run.

use glam::{DQuat, DVec3};

use crate::gjk::OverlapWitness;
use crate::hybrid_tree::{HybridTree, Node};

/// A node pair found apart, and a lower bound on their volumes' distance (mm) at the front's
/// pose.
#[derive(Clone, Copy, Debug)]
struct ApartPair {
    a: u32,
    b: u32,
    gap: f64,
}

/// A leaf pair whose volumes met, with the simplex that proved it (see
/// [`crate::gjk::OverlapWitness`]) when GJK found one.
#[derive(Clone, Copy, Debug)]
pub(crate) struct MetPair {
    pub(crate) a: u32,
    pub(crate) b: u32,
    pub(crate) witness: Option<OverlapWitness>,
}

/// The front of the last traversal (see the module documentation).
#[derive(Clone, Debug, Default)]
pub(crate) struct TraversalFront {
    /// The ids of the trees it was recorded on (A's, B's); `None`: no front.
    trees: Option<(u64, u64)>,
    /// B's pose in A's frame at which the gaps hold: unit rotation and translation (mm).
    rotation: DQuat,
    translation: DVec3,
    apart: Vec<ApartPair>,
    /// Leaf pairs whose volumes met: reported, and tested again by every query (from their
    /// witnesses, [`TraversalFront::met_again`]).
    met: Vec<MetPair>,
}

impl TraversalFront {
    /// Starts a query on `trees` at B's pose (`rotation`, unit, and `translation`, mm, in
    /// A's frame): pushes onto `stack` the node pairs to test, the roots when the front was
    /// not recorded on these trees (or the pose is not finite), otherwise every apart pair
    /// that the motion since the front's pose may have closed. The apart pairs it cannot have
    /// closed stay in the front with their gaps less the motion, and the met pairs stay for
    /// [`TraversalFront::met_again`]; the traversal then records the pairs it ends at
    /// ([`TraversalFront::apart`], [`TraversalFront::met`]).
    pub(crate) fn start(
        &mut self,
        (a, b): (&HybridTree, &HybridTree),
        (rotation, translation): (DQuat, DVec3),
        stack: &mut Vec<(u32, u32)>,
    ) {
        let ids = Some((a.id(), b.id()));
        let finite = rotation.is_finite() && translation.is_finite();
        if self.trees != ids || !finite {
            self.apart.clear();
            self.met.clear();
            self.trees = if finite { ids } else { None };
            (self.rotation, self.translation) = (rotation, translation);
            stack.push((0, 0));
            return;
        }
        let shift = translation.distance(self.translation);
        let turn = {
            let q = if rotation.dot(self.rotation) >= 0.0 {
                rotation - self.rotation
            } else {
                rotation + self.rotation
            };
            4.0 * (0.5 * q.length()).min(1.0).asin()
        };
        (self.rotation, self.translation) = (rotation, translation);
        let nodes_b = b.nodes();
        self.apart.retain_mut(|pair| {
            let motion = nodes_b
                .get(pair.b as usize)
                .map_or(f64::INFINITY, |n| shift + turn * reach(n));
            // Far more than the rounding of the motion bound.
            let motion = motion * (1.0 + 1e-9);
            let kept = pair.gap > motion;
            if kept {
                pair.gap -= motion;
            } else {
                stack.push((pair.a, pair.b));
            }
            kept
        });
    }

    /// Tests the met pairs again at this query's pose with `test` (the leaves' overlap test,
    /// from the pair's witness; `None` for volumes that meet, else their gap): those that
    /// still meet stay, reported by `report`; the others become apart pairs.
    pub(crate) fn met_again(
        &mut self,
        mut test: impl FnMut(&mut MetPair) -> Option<f64>,
        mut report: impl FnMut(&MetPair),
    ) {
        let Self { met, apart, .. } = self;
        met.retain_mut(|pair| match test(pair) {
            None => {
                report(pair);
                true
            }
            Some(gap) => {
                apart.push(ApartPair {
                    a: pair.a,
                    b: pair.b,
                    gap,
                });
                false
            }
        });
    }

    /// Records a node pair the traversal found apart by `gap` (mm).
    pub(crate) fn apart(&mut self, a: u32, b: u32, gap: f64) {
        self.apart.push(ApartPair { a, b, gap });
    }

    /// Records a leaf pair whose volumes met, with the witness of their overlap test.
    pub(crate) fn met(&mut self, pair: MetPair) {
        self.met.push(pair);
    }
}

/// The largest distance (mm) from its object's origin of a point of the node's box (∞ when
/// unbounded).
fn reach(node: &Node) -> f64 {
    node.bounds.map_or(f64::INFINITY, |b| {
        b.center.length() + b.half_extents.length()
    })
}
