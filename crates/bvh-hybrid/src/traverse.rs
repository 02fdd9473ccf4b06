//! Tree-vs-tree traversal: simultaneous descent of two [`HybridTree`]s under a relative pose.
//!
//! A pair of nodes is tested by the separating-axis test of their boxes (15 axes, exact);
//! two leaves whose boxes overlap are then tested with their exact leaf volumes. When the
//! boxes of two internal nodes overlap, the one with the larger box is split (the usual rule
//! that keeps the two sides' boxes of similar size). Every ancestor box covers the leaf
//! volumes below it, so no overlapping leaf pair is pruned.

use geom_param::{ComponentId, DPose3};
use glam::{DMat3, DQuat, DVec3};

use crate::bevelled_volume::BevelledVolume;
use crate::gjk::OverlapWitness;
use crate::hybrid_tree::{HybridTree, Node, NodeKind};
use crate::obb::Obb;
use crate::traversal_front::{MetPair, TraversalFront};

/// Caller-owned scratch of [`overlapping_pairs`]: the stack of node pairs still to test, and
/// the front of the last traversal ([`TraversalFront`]: where it stopped on which pair of
/// trees, and by how much the pairs it found apart were apart). Both only grow, so queries
/// allocate nothing once they have reached their sizes.
#[derive(Clone, Debug, Default)]
pub struct TraversalScratch {
    stack: Vec<(u32, u32)>,
    front: TraversalFront,
}

/// B's pose in A's frame in the forms the tests use, with its inverse computed on demand.
struct RelativePose {
    rot: DQuat,
    rot_matrix: DMat3,
    trans: DVec3,
}

impl RelativePose {
    fn new(pose_ab: &DPose3) -> Self {
        // A rotation that is not unit length would scale B; renormalising keeps the tests
        // those of a rigid motion (a zero or non-finite rotation becomes NaN, which separates
        // nothing, so every pair is reported).
        let rot = pose_ab.rotation.normalize();
        RelativePose {
            rot,
            rot_matrix: DMat3::from_quat(rot),
            trans: pose_ab.translation,
        }
    }

    /// B's box in A's frame.
    fn box_in_a(&self, b: &Obb) -> Obb {
        Obb {
            center: self.rot_matrix * b.center + self.trans,
            axes: self.rot_matrix * b.axes,
            half_extents: b.half_extents,
        }
    }

    /// A's pose in B's frame: `p_b = rot^-1 (p_a - trans)`.
    fn inverse(&self) -> (DQuat, DVec3) {
        let inv = self.rot.conjugate();
        (inv, -(inv * self.trans))
    }
}

/// Clears `out` and pushes every (component of A, component of B) whose leaf volumes overlap,
/// B being posed in A's frame by `pose_ab` (`point_in_a = pose_ab * point_in_b`). Each pair
/// is pushed once; the pairs are sorted. See [`crate::BroadPhase::overlapping_components`].
///
/// A query on the trees of the scratch's last query starts from that traversal's front
/// ([`TraversalFront`]): the node pairs it found apart by more than B's motion since are
/// not tested again (their volumes are still apart: a fresh traversal could only report them
/// where rounding makes it err towards reporting).
pub fn overlapping_pairs(
    a: &HybridTree,
    b: &HybridTree,
    pose_ab: &DPose3,
    scratch: &mut TraversalScratch,
    out: &mut Vec<(ComponentId, ComponentId)>,
) {
    out.clear();
    let TraversalScratch { stack, front } = scratch;
    stack.clear();
    let (nodes_a, nodes_b) = (a.nodes(), b.nodes());
    if nodes_a.is_empty() || nodes_b.is_empty() {
        return;
    }
    let pose = RelativePose::new(pose_ab);
    front.start((a, b), (pose.rot, pose.trans), stack);
    front.met_again(
        |pair| match (leaf(pair.a, nodes_a), leaf(pair.b, nodes_b)) {
            // Two box leaves (or unbounded ones): their boxes are their volumes.
            (Some((node_a, _, None)), Some((node_b, _, None))) => boxes_gap(node_a, node_b, &pose),
            (Some((node_a, _, va)), Some((node_b, _, vb))) => {
                leaves_gap((node_a, va), (node_b, vb), &pose, &mut pair.witness)
            }
            _ => None,
        },
        |pair| {
            if let (Some((_, ca, _)), Some((_, cb, _))) =
                (leaf(pair.a, nodes_a), leaf(pair.b, nodes_b))
            {
                out.push((ca, cb));
            }
        },
    );
    while let Some((ia, ib)) = stack.pop() {
        let (node_a, node_b) = (&nodes_a[ia as usize], &nodes_b[ib as usize]);
        if let Some(gap) = boxes_gap(node_a, node_b, &pose) {
            front.apart(ia, ib, gap);
            continue;
        }
        match (&node_a.kind, &node_b.kind) {
            (
                NodeKind::Leaf {
                    component: ca,
                    bevelled: va,
                },
                NodeKind::Leaf {
                    component: cb,
                    bevelled: vb,
                },
            ) => {
                let mut witness = None;
                let (va, vb) = (va.as_deref(), vb.as_deref());
                match leaves_gap((node_a, va), (node_b, vb), &pose, &mut witness) {
                    Some(gap) => front.apart(ia, ib, gap),
                    None => {
                        front.met(MetPair {
                            a: ia,
                            b: ib,
                            witness,
                        });
                        out.push((*ca, *cb));
                    }
                }
            }
            (NodeKind::Internal { children }, NodeKind::Leaf { .. }) => {
                stack.extend(children.iter().map(|&c| (c, ib)));
            }
            (NodeKind::Leaf { .. }, NodeKind::Internal { children }) => {
                stack.extend(children.iter().map(|&c| (ia, c)));
            }
            (NodeKind::Internal { children: ka }, NodeKind::Internal { children: kb }) => {
                if box_size(node_a) >= box_size(node_b) {
                    stack.extend(ka.iter().map(|&c| (c, ib)));
                } else {
                    stack.extend(kb.iter().map(|&c| (ia, c)));
                }
            }
        }
    }
    out.sort_unstable();
}

/// Leaf `i` of `nodes`, with its component and bevelled volume; `None` for an internal node.
fn leaf(i: u32, nodes: &[Node]) -> Option<(&Node, ComponentId, Option<&BevelledVolume>)> {
    match nodes.get(i as usize) {
        Some(
            node @ Node {
                kind:
                    NodeKind::Leaf {
                        component,
                        bevelled,
                    },
                ..
            },
        ) => Some((node, *component, bevelled.as_deref())),
        _ => None,
    }
}

/// `None` when the two nodes' boxes overlap (an unbounded box overlaps everything), else the
/// gap the separating-axis test found between them (mm, a lower bound on their distance).
fn boxes_gap(a: &Node, b: &Node, pose: &RelativePose) -> Option<f64> {
    match (&a.bounds, &b.bounds) {
        (Some(box_a), Some(box_b)) => box_a.separation(&pose.box_in_a(box_b)),
        _ => None,
    }
}

/// The exact test of two leaves whose boxes overlap: bevelled against bevelled (from and to
/// an overlap `witness`, see [`crate::gjk::OverlapWitness`]), bevelled against a box leaf,
/// or (two box leaves, or an unbounded leaf) the box test already done. `None` when they
/// overlap, else the gap found (mm, a lower bound on their distance).
fn leaves_gap(
    (a, va): (&Node, Option<&BevelledVolume>),
    (b, vb): (&Node, Option<&BevelledVolume>),
    pose: &RelativePose,
    witness: &mut Option<OverlapWitness>,
) -> Option<f64> {
    match (va, vb, &a.bounds, &b.bounds) {
        (Some(va), Some(vb), _, _) => va.separation_witnessed(vb, pose.rot, pose.trans, witness),
        (Some(va), None, _, Some(box_b)) => va.separation_obb(box_b, pose.rot, pose.trans),
        (None, Some(vb), Some(box_a), _) => {
            let (rot_ba, trans_ba) = pose.inverse();
            vb.separation_obb(box_a, rot_ba, trans_ba)
        }
        _ => None,
    }
}

/// Size used to choose which internal node to split: the sum of the box's half extents (mm),
/// infinite when unbounded.
fn box_size(node: &Node) -> f64 {
    node.bounds
        .map_or(f64::INFINITY, |b| b.half_extents.element_sum())
}
