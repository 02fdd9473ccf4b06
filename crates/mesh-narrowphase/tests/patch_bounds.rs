//! The patch tree's normal bounds against the exact surfaces: every outward normal sampled
//! densely inside each leaf's piece (the face's `Surface::normal` at the piece's interpolated
//! parameters, not the samples the tree was built from) lies in the leaf's cap and band and in
//! every ancestor's, on solids of every surface kind the fixtures hold (planes, cylinders,
//! cones, tori and revolved arcs, a NURBS loft); and the bands of pieces on a cylinder are thin,
//! which is what lets a pair of crossed or tilted cylinders be pruned.

mod common;

use common::fixture_object;
use geom_param::{ComponentMesh, Solid};
use glam::{DVec2, DVec3};
use mesh_narrowphase::cones::normal_cone::{NormalBand, NormalCone};
use mesh_narrowphase::cones::patch_tree::{PatchLeaf, PatchTree};

/// The angle (rad) by which `n` lies outside the cap (0 inside).
fn outside_cap(cap: &NormalCone, n: DVec3) -> f64 {
    if cap.is_all() {
        return 0.0;
    }
    (cap.axis.angle_between(n) - cap.half_angle()).max(0.0)
}

/// The angle (rad) by which `n` lies outside the band (0 inside).
fn outside_band(band: &NormalBand, n: DVec3) -> f64 {
    if band.is_all() {
        return 0.0;
    }
    let a = band.axis.angle_between(n);
    (band.lo - a).max(a - band.hi).max(0.0)
}

/// Exact normals at a grid of barycentric points (`steps` per edge) of every piece of `tree`,
/// each checked against its leaf and all the leaf's ancestors; returns the number checked.
fn check_tree(tree: &PatchTree, mesh: &ComponentMesh, solid: &Solid, steps: usize) -> usize {
    // Depth-first with the ancestors' indices.
    let mut stack = vec![(0_u32, Vec::<u32>::new())];
    let mut checked = 0;
    while let Some((i, mut path)) = stack.pop() {
        let node = &tree.nodes[i as usize];
        path.push(i);
        let PatchLeaf::Piece(k) = node.leaf else {
            stack.push((i + 1, path.clone()));
            stack.push((node.right, path));
            continue;
        };
        let piece = &tree.pieces[k as usize];
        let t = piece.triangle as usize;
        let face = mesh.triangle_faces[t];
        let params = mesh.triangle_params[t];
        let surface = &solid.faces[face.0 as usize].surface;
        let [du, dv] = surface.domain();
        for a in 0..=steps {
            for b in 0..=steps - a {
                let w = [a as f64, b as f64, (steps - a - b) as f64].map(|x| x / steps as f64);
                let bary = piece.to_triangle(w);
                let uv = DVec2::from(params[0]) * bary[0]
                    + DVec2::from(params[1]) * bary[1]
                    + DVec2::from(params[2]) * bary[2];
                let Some(n) = surface.normal(du.normalize(uv.x), dv.normalize(uv.y)) else {
                    continue;
                };
                for &j in &path {
                    let at = &tree.nodes[j as usize];
                    let (cap, band) = (outside_cap(&at.cone, n), outside_band(&at.band, n));
                    assert!(
                        cap <= 1e-9 && band <= 1e-9,
                        "node {j} (leaf {i}): normal {n} outside its cap by {cap:e} rad, its \
                         band by {band:e} rad ({:?}, {:?})",
                        at.cone,
                        at.band
                    );
                }
                checked += 1;
            }
        }
    }
    checked
}

#[test]
fn every_exact_normal_lies_in_its_leaf_and_ancestors_bounds() {
    for (name, tolerance) in [
        ("tube", 0.05),
        ("loft", 0.05),
        ("pencil", 0.05),
        ("vase", 0.05),
        ("bowl", 0.2),
        ("rounded-box", 0.05),
        ("bracket", 0.05),
    ] {
        let model = fixture_object(name, tolerance);
        for mesh in &model.meshes {
            let tree = PatchTree::build(mesh, &model.solid);
            if tree.nodes.is_empty() {
                continue;
            }
            let checked = check_tree(&tree, mesh, &model.solid, 6);
            assert!(checked > 0, "{name}: nothing sampled");
        }
    }
}

/// A tube's inner and outer cylinders: every piece lying inside a cylinder face (no corner on
/// an edge) gets a band about the tube's axis (±z) at most a tenth as wide as its cap, which is
/// as wide as the piece's turn about the axis (the band's width is the third-order allowance
/// and the floor only). A piece with a corner on one of the rims (circles about z, where the
/// cylinder meets an annulus) gets a band about the rim's tangent instead, which holds every
/// direction normal to the rim's tangent at the piece's corners (the normals of the rim: the
/// arc from the cylinder's radial normal to the annulus's ±z, whichever quadrant).
#[test]
fn pieces_of_a_cylinder_have_thin_bands_about_its_axis() {
    let model = fixture_object("tube", 0.05);
    let (mut thin, mut rims) = (0, 0);
    for mesh in &model.meshes {
        let tree = PatchTree::build(mesh, &model.solid);
        let (bottom, top) = mesh
            .positions
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
                (lo.min(p.z), hi.max(p.z))
            });
        for node in &tree.nodes {
            let PatchLeaf::Piece(k) = node.leaf else {
                continue;
            };
            // Pieces of the cylinders have radial normals: caps about a horizontal axis.
            if node.cone.axis.z.abs() > 0.3 || node.band.is_all() {
                continue;
            }
            if node.band.axis.z.abs() <= 1e-9 {
                // About a rim's tangent: every direction normal to the tangent at a corner on
                // a rim (the tube's top or bottom plane).
                let rim = |z: f64| (z - bottom).abs().min((z - top).abs()) <= 1e-9 * top.abs();
                for corner in tree.pieces[k as usize].corners {
                    if !rim(corner.z) {
                        continue;
                    }
                    let radial = DVec3::new(corner.x, corner.y, 0.0).normalize();
                    for step in 0..24 {
                        let phi = f64::from(step) * std::f64::consts::TAU / 24.0;
                        let n = radial * phi.cos() + DVec3::Z * phi.sin();
                        let out = outside_band(&node.band, n);
                        assert!(
                            out <= 1e-9,
                            "rim normal {n} outside {:?} by {out:e}",
                            node.band
                        );
                    }
                }
                rims += 1;
                continue;
            }
            assert!(
                node.band.axis.cross(DVec3::Z).length() <= 1e-9,
                "band axis {}",
                node.band.axis
            );
            let cap = 2.0 * node.cone.half_angle();
            assert!(cap > 0.05, "cap {:?}", node.cone);
            assert!(
                node.band.hi - node.band.lo <= 0.1 * cap,
                "band [{}, {}] on a cylinder, cap {cap}",
                node.band.lo,
                node.band.hi
            );
            thin += 1;
        }
    }
    assert!(thin > 50, "{thin} cylinder pieces with a band");
    assert!(rims > 50, "{rims} rim pieces with a band");
}
