//! The component-based hybrid tree of one object (paper section III-A): its nodes and its
//! top-down construction.

use geom_param::{ComponentId, ObjectModel};
use glam::DVec3;
use std::sync::atomic::{AtomicU64, Ordering};

use crate::bevelled_volume::BevelledVolume;
use crate::obb::Obb;
use crate::split::split_balanced;

/// Which volume the leaves use.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum LeafShape {
    /// An OBB with its edges bevelled by cut planes tight to the component (the paper's
    /// octagonal volume; here the 18-DOP of [`BevelledVolume`]). The default.
    #[default]
    Bevelled,
    /// A plain OBB, as in the internal nodes: looser, cheaper to test. For comparisons.
    Box,
}

/// How to build a [`HybridTree`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct TreeOptions {
    /// The leaf volume.
    pub leaf_shape: LeafShape,
}

/// What a node holds besides its box.
#[derive(Clone, Debug, PartialEq)]
pub enum NodeKind {
    /// An internal node and the indices of its two children in [`HybridTree::nodes`] (both
    /// greater than its own index).
    Internal {
        /// The two children.
        children: [u32; 2],
    },
    /// A leaf: one whole surface component.
    Leaf {
        /// The component it bounds.
        component: ComponentId,
        /// The bevelled volume, for [`LeafShape::Bevelled`] leaves with a finite volume;
        /// `None` when the node's box is the leaf volume itself ([`LeafShape::Box`]) or the
        /// leaf is unbounded.
        bevelled: Option<Box<BevelledVolume>>,
    },
}

/// One node of a [`HybridTree`], in the object's frame (mm).
#[derive(Clone, Debug, PartialEq)]
pub struct Node {
    /// A box covering everything below the node: for an internal node, every leaf volume
    /// below it; for a leaf, its volume (the bevelled volume's axis slabs, or the leaf box
    /// itself). `None` means unbounded (all of space): a margin or mesh that could not be
    /// bounded, see [`crate::BroadPhase::build`].
    pub bounds: Option<Obb>,
    /// Internal node or leaf.
    pub kind: NodeKind,
}

/// The component-based tree of one object: `2n - 1` nodes for `n` components, the root at
/// index 0, each internal node before its children. Leaves are whole surface components.
///
/// Every leaf volume covers its component's exact surface inflated by `margin / 2` (it is
/// fitted over the component's mesh vertices, widened by `margin / 2` plus the mesh's chordal
/// error), and every node's box covers every leaf volume below it.
#[derive(Clone, Debug)]
pub struct HybridTree {
    nodes: Vec<Node>,
    margin: f64,
    options: TreeOptions,
    /// Unique per build (a clone keeps it: same nodes), so that a traversal front recorded
    /// on a pair of trees is never taken for another pair's ([`crate::TraversalScratch`]).
    id: u64,
}

/// Trees compare by their nodes, margin and options (not by which build made them).
impl PartialEq for HybridTree {
    fn eq(&self, other: &Self) -> bool {
        self.nodes == other.nodes && self.margin == other.margin && self.options == other.options
    }
}

impl HybridTree {
    /// Builds the tree of `object` for the margin `margin` (mm).
    ///
    /// Leaves: [`BevelledVolume::fit`] (or [`Obb::fit`] for [`LeafShape::Box`]) over the
    /// component's mesh vertices with inflate `margin / 2 + chordal_error`; a component with no
    /// finite mesh vertex, a non-finite chordal error, or a margin that is negative or not
    /// finite gets an unbounded leaf. Splitting: top-down, balanced halves by the median of the
    /// leaf centres along one axis of the node's box, the axis whose halves have the smallest
    /// summed box volume (see [`crate::split`]). Internal boxes: [`Obb::fit`] over the vertices
    /// of every leaf volume below, widened by those volumes' vertex tolerance; unbounded if
    /// any leaf below is.
    #[must_use]
    pub fn build(object: &ObjectModel, margin: f64, options: &TreeOptions) -> Self {
        let leaves: Vec<Leaf> = object
            .meshes
            .iter()
            .enumerate()
            .map(|(k, mesh)| {
                let component = ComponentId(u32::try_from(k).unwrap_or(u32::MAX));
                let inflate = 0.5 * margin + mesh.chordal_error;
                Leaf::fit(component, &mesh.positions, inflate, options.leaf_shape)
            })
            .collect();
        static BUILDS: AtomicU64 = AtomicU64::new(0);
        let mut tree = HybridTree {
            nodes: Vec::with_capacity((2 * leaves.len()).saturating_sub(1)),
            margin,
            options: *options,
            id: BUILDS.fetch_add(1, Ordering::Relaxed),
        };
        if !leaves.is_empty() {
            let mut order: Vec<usize> = (0..leaves.len()).collect();
            let mut points = Vec::new();
            tree.build_node(&leaves, &mut order, &mut points);
        }
        tree
    }

    /// Appends the subtree over `leaves[order[..]]` (pre-order) and returns its root index.
    fn build_node(&mut self, leaves: &[Leaf], order: &mut [usize], points: &mut Vec<DVec3>) -> u32 {
        let index = self.nodes.len();
        if let [only] = *order {
            let leaf = &leaves[only];
            self.nodes.push(Node {
                bounds: leaf.bounds,
                kind: NodeKind::Leaf {
                    component: leaf.component,
                    bevelled: leaf.bevelled.clone(),
                },
            });
            return index as u32;
        }
        let bounds = enclose_leaves(leaves, order, points);
        // Placeholder children, set once the subtrees are built.
        self.nodes.push(Node {
            bounds,
            kind: NodeKind::Internal { children: [0, 0] },
        });
        let items: Vec<Option<Obb>> = order.iter().map(|&k| leaves[k].bounds).collect();
        let half = split_balanced(order, &items, bounds.as_ref());
        let (left, right) = order.split_at_mut(half);
        let first = self.build_node(leaves, left, points);
        let second = self.build_node(leaves, right, points);
        self.nodes[index].kind = NodeKind::Internal {
            children: [first, second],
        };
        index as u32
    }

    /// The nodes, root first (empty for an object with no components).
    pub fn nodes(&self) -> &[Node] {
        &self.nodes
    }

    /// Number of nodes: `2n - 1` for `n` components (0 for none).
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// Whether the tree has no node (an object with no components).
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// Number of levels: 1 for a single leaf, 0 when empty. The split is balanced, so this is
    /// `ceil(log2 n) + 1` for `n` components.
    pub fn depth(&self) -> usize {
        let mut depth = 0;
        let mut stack: Vec<(u32, usize)> = Vec::new();
        if !self.nodes.is_empty() {
            stack.push((0, 1));
        }
        while let Some((i, level)) = stack.pop() {
            depth = depth.max(level);
            if let Some(Node {
                kind: NodeKind::Internal { children },
                ..
            }) = self.nodes.get(i as usize)
            {
                stack.extend(children.iter().map(|&c| (c, level + 1)));
            }
        }
        depth
    }

    /// Which build made the tree (unique per build within the process).
    pub(crate) fn id(&self) -> u64 {
        self.id
    }

    /// The margin (mm) the tree was built for.
    pub fn margin(&self) -> f64 {
        self.margin
    }

    /// The options the tree was built with.
    pub fn options(&self) -> &TreeOptions {
        &self.options
    }
}

/// A fitted leaf before it is placed in the tree.
struct Leaf {
    component: ComponentId,
    bounds: Option<Obb>,
    bevelled: Option<Box<BevelledVolume>>,
}

impl Leaf {
    fn fit(component: ComponentId, points: &[DVec3], inflate: f64, shape: LeafShape) -> Self {
        let (bounds, bevelled) = match shape {
            LeafShape::Bevelled => match BevelledVolume::fit(points, inflate) {
                Some(v) => (Some(v.bounding_obb()), Some(Box::new(v))),
                None => (None, None),
            },
            LeafShape::Box => (Obb::fit(points, inflate), None),
        };
        Leaf {
            component,
            bounds,
            bevelled,
        }
    }

    /// Points whose hull, widened by the returned distance (mm), covers the leaf volume.
    fn cover_points(&self, points: &mut Vec<DVec3>) -> f64 {
        match (&self.bevelled, &self.bounds) {
            (Some(v), _) => {
                points.extend(v.world_vertices());
                v.tolerance()
            }
            (None, Some(b)) => {
                points.extend(b.corners());
                0.0
            }
            (None, None) => 0.0,
        }
    }
}

/// The box of an internal node over `leaves[order[..]]`, or `None` (unbounded) when a leaf
/// below is unbounded. `points` is reused scratch.
fn enclose_leaves(leaves: &[Leaf], order: &[usize], points: &mut Vec<DVec3>) -> Option<Obb> {
    points.clear();
    let mut widen = 0.0_f64;
    for &k in order {
        leaves[k].bounds.as_ref()?;
        widen = widen.max(leaves[k].cover_points(points));
    }
    Obb::fit(points, widen)
}
