//! Validation of a built [`HybridTree`] against its object: shape of the tree, one leaf per
//! component, and coverage (every node covers the leaf volumes below it and the inflated
//! surfaces of its components).

use geom_param::{ComponentId, ObjectModel};
use glam::DVec3;

use crate::bevelled_volume::{BevelledVolume, SLAB_DIRECTIONS};
use crate::hybrid_tree::{HybridTree, Node, NodeKind};
use crate::obb::Obb;

/// Relative rounding allowance of the coverage checks: a point counts as covered when it is
/// inside up to this fraction of the node's size plus its centre's distance from the origin.
const COVER_REL: f64 = 1e-9;

/// Why a tree does not fit its object.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum TreeError {
    /// The tree does not have `2n - 1` nodes for the object's `n` components.
    #[error("tree has {found} nodes, expected {expected} for the object's components")]
    NodeCount {
        /// `2n - 1` (0 for no component).
        expected: usize,
        /// Nodes in the tree.
        found: usize,
    },
    /// An internal node's child index is out of range or not after its parent, or a node is
    /// reached twice or never from the root.
    #[error("node {node} has a bad child link or is not reached exactly once from the root")]
    Shape {
        /// The offending node.
        node: usize,
    },
    /// A component is bounded by no leaf or by several, or a leaf names a component the
    /// object does not have.
    #[error("component {component:?} is in {leaves} leaves, expected exactly 1")]
    ComponentLeaves {
        /// The component.
        component: ComponentId,
        /// How many leaves name it.
        leaves: usize,
    },
    /// A node's box does not cover a leaf volume below it.
    #[error("node {node} does not cover the volume of leaf {leaf}")]
    UncoveredLeaf {
        /// The node.
        node: usize,
        /// The leaf below it.
        leaf: usize,
    },
    /// A node (box or leaf volume) does not cover a mesh vertex of one of its components
    /// inflated by `margin / 2 + chordal_error`.
    #[error("node {node} does not cover vertex {vertex} of component {component:?} inflated")]
    UncoveredSurface {
        /// The node.
        node: usize,
        /// The component.
        component: ComponentId,
        /// Index of the vertex in the component's mesh.
        vertex: usize,
    },
}

impl HybridTree {
    /// Checks that the tree fits `object`, which must be the object it was built from:
    /// `2n - 1` nodes forming one binary tree rooted at 0 with children after parents; every
    /// component in exactly one leaf; every leaf volume and every node box covering the mesh
    /// vertices of its components as balls of radius `margin / 2 + chordal_error` (hence, by
    /// the chordal bound, the exact surfaces inflated by `margin / 2`); and every node box
    /// covering every leaf volume below it (the bevelled volumes through their vertices,
    /// within their [`BevelledVolume::tolerance`]). Unbounded volumes cover everything.
    /// Coverage is checked up to a rounding allowance of 1e-9 of the coordinates involved.
    ///
    /// # Errors
    /// The first violation found, as a [`TreeError`].
    pub fn validate(&self, object: &ObjectModel) -> Result<(), TreeError> {
        let n = object.meshes.len();
        let nodes = self.nodes();
        let expected = (2 * n).saturating_sub(1);
        if nodes.len() != expected {
            return Err(TreeError::NodeCount {
                expected,
                found: nodes.len(),
            });
        }
        let below = self.leaves_below()?;
        let mut leaves_of = vec![0usize; n];
        for (i, node) in nodes.iter().enumerate() {
            if let NodeKind::Leaf { component, .. } = node.kind {
                match leaves_of.get_mut(component.0 as usize) {
                    Some(count) => *count += 1,
                    None => {
                        return Err(TreeError::ComponentLeaves {
                            component,
                            leaves: 0,
                        });
                    }
                }
                check_leaf_volume(i, node, object, self.margin())?;
            }
        }
        if let Some((k, &leaves)) = leaves_of.iter().enumerate().find(|(_, c)| **c != 1) {
            return Err(TreeError::ComponentLeaves {
                component: ComponentId(k as u32),
                leaves,
            });
        }
        for (i, node) in nodes.iter().enumerate() {
            let Some(bounds) = &node.bounds else {
                continue;
            };
            for &leaf in &below[i] {
                let leaf_node = &nodes[leaf];
                if !box_covers_leaf(bounds, leaf_node) {
                    return Err(TreeError::UncoveredLeaf { node: i, leaf });
                }
                if let NodeKind::Leaf { component, .. } = leaf_node.kind {
                    let inflate = surface_inflate(object, component, self.margin());
                    let covered = |p: DVec3, r: f64| box_covers_ball(bounds, p, r);
                    check_surface(i, component, object, inflate, covered)?;
                }
            }
        }
        Ok(())
    }

    /// The leaves below each node (itself for a leaf), checking the tree's shape on the way.
    fn leaves_below(&self) -> Result<Vec<Vec<usize>>, TreeError> {
        let nodes = self.nodes();
        let mut reached = vec![false; nodes.len()];
        if let Some(r) = reached.first_mut() {
            *r = true;
        }
        for (i, node) in nodes.iter().enumerate() {
            if let NodeKind::Internal { children } = node.kind {
                for c in children.map(|c| c as usize) {
                    if c <= i || c >= nodes.len() || reached[c] {
                        return Err(TreeError::Shape { node: i });
                    }
                    reached[c] = true;
                }
            }
        }
        if let Some(node) = reached.iter().position(|r| !r) {
            return Err(TreeError::Shape { node });
        }
        // Children come after parents: fill from the back.
        let mut below: Vec<Vec<usize>> = vec![Vec::new(); nodes.len()];
        for i in (0..nodes.len()).rev() {
            below[i] = match nodes[i].kind {
                NodeKind::Leaf { .. } => vec![i],
                NodeKind::Internal { children } => {
                    let [c0, c1] = children.map(|c| c as usize);
                    [below[c0].as_slice(), below[c1].as_slice()].concat()
                }
            };
        }
        Ok(below)
    }
}

/// The radius each mesh vertex must be covered with: `margin / 2 + chordal_error` (mm).
fn surface_inflate(object: &ObjectModel, component: ComponentId, margin: f64) -> f64 {
    0.5 * margin + object.meshes[component.0 as usize].chordal_error
}

/// A leaf's own volume covers its component's inflated mesh vertices.
fn check_leaf_volume(
    i: usize,
    node: &Node,
    object: &ObjectModel,
    margin: f64,
) -> Result<(), TreeError> {
    let NodeKind::Leaf {
        component,
        bevelled,
    } = &node.kind
    else {
        return Ok(());
    };
    let inflate = surface_inflate(object, *component, margin);
    match (bevelled, &node.bounds) {
        (Some(v), _) => check_surface(i, *component, object, inflate, |p, r| {
            bevelled_covers_ball(v, p, r)
        }),
        (None, Some(b)) => check_surface(i, *component, object, inflate, |p, r| {
            box_covers_ball(b, p, r)
        }),
        (None, None) => Ok(()),
    }
}

/// Every mesh vertex of `component`, as a ball of radius `inflate`, passes `covered`.
fn check_surface(
    node: usize,
    component: ComponentId,
    object: &ObjectModel,
    inflate: f64,
    covered: impl Fn(DVec3, f64) -> bool,
) -> Result<(), TreeError> {
    let positions = &object.meshes[component.0 as usize].positions;
    match positions.iter().position(|&p| !covered(p, inflate)) {
        Some(vertex) => Err(TreeError::UncoveredSurface {
            node,
            component,
            vertex,
        }),
        None => Ok(()),
    }
}

/// Whether the ball (`p`, `r`) lies in the box, up to the rounding allowance.
fn box_covers_ball(b: &Obb, p: DVec3, r: f64) -> bool {
    let allowance = COVER_REL * (b.center.length() + b.half_extents.element_sum() + r);
    let q = b.axes.mul_transpose_vec3(p - b.center).abs() + DVec3::splat(r);
    q.cmple(b.half_extents + DVec3::splat(allowance)).all()
}

/// Whether the ball (`p`, `r`) lies in the bevelled volume, up to the rounding allowance: the
/// ball is inside the intersection of slabs iff its centre is at least `r` inside each slab.
fn bevelled_covers_ball(v: &BevelledVolume, p: DVec3, r: f64) -> bool {
    let size = v.bounding_obb().half_extents.element_sum();
    let allowance = COVER_REL * (v.center().length() + size + r);
    let q = v.axes().mul_transpose_vec3(p - v.center());
    SLAB_DIRECTIONS.iter().enumerate().all(|(k, d)| {
        let s = d.dot(q);
        s - r >= v.slab_min()[k] - allowance && s + r <= v.slab_max()[k] + allowance
    })
}

/// Whether a node box covers a leaf's volume: its bevelled vertices within their tolerance,
/// or its box corners. An unbounded leaf is covered only by nothing bounded.
fn box_covers_leaf(bounds: &Obb, leaf: &Node) -> bool {
    match (&leaf.kind, &leaf.bounds) {
        (
            NodeKind::Leaf {
                bevelled: Some(v), ..
            },
            _,
        ) => v
            .world_vertices()
            .all(|p| box_covers_ball(bounds, p, v.tolerance())),
        (_, Some(b)) => b.corners().iter().all(|&p| box_covers_ball(bounds, p, 0.0)),
        (_, None) => false,
    }
}
