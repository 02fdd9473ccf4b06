//! Tree construction on the paper objects and closed-form objects: shape (2n - 1 nodes, the
//! paper's depths), validation, coverage of the exact surfaces checked by dense sampling of the
//! exact faces and edges (independent of the meshes the volumes were fitted on), and bad input.

mod support;

use bvh_hybrid::bevelled_volume::SLAB_DIRECTIONS;
use bvh_hybrid::{
    BroadPhase, HybridBvh, HybridTree, LeafShape, Node, NodeKind, Obb, TreeError, TreeOptions,
};
use geom_param::{Boundary, ObjectModel};
use glam::DVec3;
use support::{NAMES, bumpy_column, paper, sphere};

const MARGIN: f64 = 0.5;
const SHAPES: [LeafShape; 2] = [LeafShape::Bevelled, LeafShape::Box];

fn options(leaf_shape: LeafShape) -> TreeOptions {
    TreeOptions { leaf_shape }
}

#[test]
fn paper_trees_have_the_papers_size_and_validate() {
    for name in NAMES {
        for tolerance in [0.2, 0.02] {
            let object = paper(name, tolerance);
            let n = object.components.len();
            for shape in SHAPES {
                let tree = HybridTree::build(&object, MARGIN, &options(shape));
                assert_eq!(tree.len(), 2 * n - 1, "{name}");
                let levels = (n as f64).log2().ceil() as usize + 1;
                assert_eq!(tree.depth(), levels, "{name}");
                tree.validate(&object)
                    .unwrap_or_else(|e| panic!("{name} {shape:?}: {e}"));
                assert!(
                    tree.nodes().iter().all(|node| node.bounds.is_some()),
                    "{name}"
                );
            }
        }
    }
    // Section V: the paperweight's tree has 3 levels and 5 nodes, the goblet's 4 and 15.
    let paperweight = HybridBvh::default().build(&paper("paperweight", 0.1), MARGIN);
    assert_eq!((paperweight.depth(), paperweight.len()), (3, 5));
    let goblet = HybridBvh::default().build(&paper("goblet", 0.1), MARGIN);
    assert_eq!((goblet.depth(), goblet.len()), (4, 15));
}

#[test]
fn many_component_trees_are_balanced_and_validate() {
    for n in [1, 2, 7, 64, 100] {
        let object = bumpy_column(n, 0.1);
        assert_eq!(object.components.len(), n);
        let tree = HybridTree::build(&object, MARGIN, &TreeOptions::default());
        assert_eq!(tree.len(), 2 * n - 1);
        assert_eq!(tree.depth(), (n as f64).log2().ceil() as usize + 1);
        tree.validate(&object).expect("valid");
    }
}

/// Whether the ball (`p`, `r`) is inside the node's volume (bevelled slabs for a bevelled
/// leaf, the box otherwise), allowing `slack` (mm) for rounding.
fn node_covers_ball(node: &Node, p: DVec3, r: f64, slack: f64) -> bool {
    if let NodeKind::Leaf {
        bevelled: Some(v), ..
    } = &node.kind
    {
        let q = v.axes().transpose() * (p - v.center());
        return SLAB_DIRECTIONS.iter().enumerate().all(|(k, d)| {
            let s = d.dot(q);
            s - r >= v.slab_min()[k] - slack && s + r <= v.slab_max()[k] + slack
        });
    }
    let b: &Obb = node.bounds.as_ref().expect("bounded");
    let q = (b.axes.transpose() * (p - b.center)).abs() + DVec3::splat(r);
    q.cmple(b.half_extents + DVec3::splat(slack)).all()
}

/// Dense samples of the exact surface of every component: a grid of (u, v) over each face's
/// domain (including its sides) and points along each of its edges.
fn exact_samples(object: &ObjectModel, per_side: usize) -> Vec<Vec<DVec3>> {
    object
        .components
        .iter()
        .map(|c| {
            let mut points = Vec::new();
            for &f in &c.faces {
                let face = object.solid.face(f);
                let [du, dv] = face.surface.domain();
                for i in 0..=per_side {
                    for j in 0..=per_side {
                        let u = du.min + (du.max - du.min) * i as f64 / per_side as f64;
                        let v = dv.min + (dv.max - dv.min) * j as f64 / per_side as f64;
                        points.push(object.solid.eval_face(f, u, v).point);
                    }
                }
                for side in face.boundary {
                    if let Boundary::Edge(e) = side {
                        let curve = &object.solid.edge(e).curve;
                        let dt = curve.domain();
                        for i in 0..=4 * per_side {
                            let t = dt.min + (dt.max - dt.min) * i as f64 / (4 * per_side) as f64;
                            points.push(object.solid.eval_edge(e, t).point);
                        }
                    }
                }
            }
            points
        })
        .collect()
}

/// Every exact surface sample, as a ball of radius margin / 2, is inside its leaf volume and
/// inside every ancestor's box. The meshes are coarse (0.5 mm chordal tolerance), so this
/// fails if the chordal error were not accounted for.
#[test]
fn volumes_cover_the_exact_surface_inflated_by_half_the_margin() {
    let mut objects: Vec<ObjectModel> = NAMES.iter().map(|n| paper(n, 0.5)).collect();
    objects.push(sphere(10.0, 0.5));
    objects.push(bumpy_column(5, 0.2));
    for object in &objects {
        let samples = exact_samples(object, 96);
        for shape in SHAPES {
            let tree = HybridTree::build(object, MARGIN, &options(shape));
            let nodes = tree.nodes();
            let mut path: Vec<usize> = Vec::new();
            visit(nodes, 0, &mut path, &mut |leaf, ancestors| {
                let NodeKind::Leaf { component, .. } = nodes[leaf].kind else {
                    unreachable!()
                };
                for &p in &samples[component.0 as usize] {
                    for &k in ancestors.iter().chain([&leaf]) {
                        assert!(
                            node_covers_ball(&nodes[k], p, 0.5 * MARGIN, 1e-9),
                            "{} {shape:?}: node {k} misses an exact point of {component:?}",
                            object.name
                        );
                    }
                }
            });
        }
    }
}

fn visit(nodes: &[Node], i: usize, path: &mut Vec<usize>, f: &mut impl FnMut(usize, &[usize])) {
    match nodes[i].kind {
        NodeKind::Leaf { .. } => f(i, path),
        NodeKind::Internal { children } => {
            path.push(i);
            for c in children {
                visit(nodes, c as usize, path, f);
            }
            path.pop();
        }
    }
}

/// The leaf volumes are not gratuitously loose: a sphere's bevelled leaf has every vertex
/// within the 18-DOP circumradius sqrt(3/2) (R + inflate) of the centre (a box corner
/// would be at sqrt(3)), and its slabs are within 1e-9 of R + inflate.
#[test]
fn sphere_leaf_is_the_18_dop_of_the_inflated_ball() {
    let (r, tolerance) = (10.0, 0.05);
    let object = sphere(r, tolerance);
    let tree = HybridTree::build(&object, MARGIN, &TreeOptions::default());
    let [node] = tree.nodes() else {
        panic!("one component, one node")
    };
    let NodeKind::Leaf {
        bevelled: Some(v), ..
    } = &node.kind
    else {
        panic!("bevelled leaf")
    };
    let inflate = 0.5 * MARGIN + object.meshes[0].chordal_error;
    // The mesh vertices lie on the sphere, so each slab's offset is within the chordal
    // error of R about the (near-origin) centre.
    for k in 0..9 {
        assert!(
            (v.slab_max()[k] - (r + inflate)).abs() < 2.0 * tolerance,
            "slab {k}"
        );
        assert!(
            (v.slab_min()[k] + (r + inflate)).abs() < 2.0 * tolerance,
            "slab {k}"
        );
    }
    let bound = 1.5f64.sqrt() * (r + inflate + 2.0 * tolerance);
    assert!(v.world_vertices().all(|p| p.length() <= bound));
}

#[test]
fn validation_rejects_the_wrong_object() {
    let paperweight = paper("paperweight", 0.1);
    let goblet = paper("goblet", 0.1);
    let tree = HybridTree::build(&paperweight, MARGIN, &TreeOptions::default());
    assert_eq!(
        tree.validate(&goblet),
        Err(TreeError::NodeCount {
            expected: 15,
            found: 5
        })
    );
    // Same topology, larger surface: its vertices are not covered.
    let small = HybridTree::build(&sphere(10.0, 0.1), MARGIN, &TreeOptions::default());
    assert!(matches!(
        small.validate(&sphere(11.0, 0.1)),
        Err(TreeError::UncoveredSurface { node: 0, .. })
    ));
}

/// A margin that cannot be bounded gives unbounded volumes (every pair reported), not a panic.
#[test]
fn bad_margins_give_unbounded_trees() {
    let object = paper("goblet", 0.1);
    for margin in [f64::NAN, f64::INFINITY, -1.0] {
        let tree = HybridTree::build(&object, margin, &TreeOptions::default());
        assert_eq!(tree.len(), 15);
        assert!(tree.nodes().iter().all(|n| n.bounds.is_none()));
        tree.validate(&object)
            .expect("unbounded volumes cover everything");
    }
}
