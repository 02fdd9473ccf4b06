//! The certificate ([`certificate`]) against the closed-form graphs of spheres: a node pair it
//! certifies must have a gap whose height Hessian over the certificate's plane Π is positive
//! definite at every pair of points of the two patches, as the certificate's proof claims
//! (whatever the translation, since the certificate does not depend on it).
//!
//! Truth, independent of the certificate's bounds: at a point of a sphere of radius r with
//! normal n, the patch seen as a graph over Π (normal w, the direction it faces) has height
//! Hessian H(ξ, ξ) = c⁻¹ κ |Jξ|² for ξ in Π, with c = n · w, κ = ±1/r (positive convex, seen
//! from the other patch) and Jξ = ξ − (n·ξ)/c w the lift of ξ into the tangent plane. The gap's
//! Hessian is the sum of the two patches' (both facing each other). It is evaluated at the
//! normals of the corners of every piece of each node, projected radially onto the sphere.

mod common;

use common::{Rng, socket, sphere};
use glam::{DMat3, DQuat, DVec3};
use mesh_narrowphase::cones::cone_traversal::certificate;
use mesh_narrowphase::cones::patch_tree::{PatchLeaf, PatchNode, PatchTree};

/// The unit normals (pointing out of the solid) at the corners of node `i`'s pieces, for a
/// sphere centred at the origin whose solid lies inside (`ball`) or outside (a cavity).
fn corner_normals(tree: &PatchTree, i: u32, ball: bool, out: &mut Vec<DVec3>) {
    let node = &tree.nodes[i as usize];
    match node.leaf {
        PatchLeaf::Piece(k) => {
            for p in tree.pieces[k as usize].corners {
                let n = p.normalize();
                out.push(if ball { n } else { -n });
            }
        }
        PatchLeaf::Inner => {
            corner_normals(tree, i + 1, ball, out);
            corner_normals(tree, node.right, ball, out);
        }
    }
}

/// The height Hessian's quadratic form at unit ξ in Π of a sphere patch with normal `n`
/// facing `facing` (unit, normal to Π), curvature `kappa` (1/mm, library sign).
fn height_form(n: DVec3, facing: DVec3, kappa: f64, xi: DVec3) -> f64 {
    let c = n.dot(facing);
    let lifted = xi - facing * (n.dot(xi) / c);
    kappa * lifted.length_squared() / c
}

/// The smallest eigenvalue of the gap's Hessian over all pairs of `normals_a` x `normals_b`
/// (B's in A's frame), A facing `w`, B facing `-w`.
fn least_gap_curvature(
    (normals_a, kappa_a): (&[DVec3], f64),
    (normals_b, kappa_b): (&[DVec3], f64),
    w: DVec3,
) -> f64 {
    let (e1, e2) = w.any_orthonormal_pair();
    let mut least = f64::INFINITY;
    for &na in normals_a {
        for &nb in normals_b {
            let form = |x: DVec3, y: DVec3| {
                0.25 * (height_form(na, w, kappa_a, x + y) - height_form(na, w, kappa_a, x - y)
                    + height_form(nb, -w, kappa_b, x + y)
                    - height_form(nb, -w, kappa_b, x - y))
            };
            let (m11, m22, m12) = (form(e1, e1), form(e2, e2), form(e1, e2));
            let half = 0.5 * (m11 + m22);
            let lambda = half - (0.25 * (m11 - m22) * (m11 - m22) + m12 * m12).sqrt();
            least = least.min(lambda);
        }
    }
    least
}

/// Checks every certified pair of a ball's nodes against a spherical cavity's at random
/// rotations near facing; returns (certified pairs, pairs whose gap is not convex).
fn check(ball_radius: f64, cavity_radius: f64, rng: &mut Rng) -> (usize, usize) {
    let ball = sphere(ball_radius, 0.05);
    let cavity = socket(cavity_radius, cavity_radius + 6.0, 0.0, 0.05);
    let ball_tree = PatchTree::build(&ball.meshes[0], &ball.solid);
    let narrow = (std::f64::consts::PI / 6.0).cos();
    let smooth = |tree: &PatchTree| -> Vec<u32> {
        (0..tree.nodes.len() as u32)
            .filter(|&i| {
                let n: &PatchNode = &tree.nodes[i as usize];
                n.smooth && n.cone.cos >= narrow && !n.is_leaf()
            })
            .collect()
    };
    let ball_nodes = smooth(&ball_tree);
    let (mut certified, mut wrong) = (0, 0);
    for component in 0..cavity.meshes.len() {
        let cavity_tree = PatchTree::build(&cavity.meshes[component], &cavity.solid);
        // The cavity's inner sphere: nodes whose corners all lie on it.
        let inner: Vec<u32> = smooth(&cavity_tree)
            .into_iter()
            .filter(|&i| {
                let mut normals = Vec::new();
                corner_normals(&cavity_tree, i, false, &mut normals);
                let n = &cavity_tree.nodes[i as usize];
                (n.centre.length() - cavity_radius).abs() < 0.5 * n.radius + 1.0
                    && normals.iter().all(|m| m.dot(n.cone.axis) > 0.5)
            })
            .collect();
        for &i in ball_nodes.iter().step_by((ball_nodes.len() / 40).max(1)) {
            for &j in inner.iter().step_by((inner.len() / 40).max(1)) {
                let (a, b) = (&ball_tree.nodes[i as usize], &cavity_tree.nodes[j as usize]);
                let (mut normals_a, mut normals_b) = (Vec::new(), Vec::new());
                corner_normals(&ball_tree, i, true, &mut normals_a);
                corner_normals(&cavity_tree, j, false, &mut normals_b);
                for _ in 0..4 {
                    let facing = DQuat::from_rotation_arc(b.cone.axis, -a.cone.axis);
                    let tilt = DQuat::from_axis_angle(rng.axis(), rng.range(0.0, 0.4));
                    let r = DMat3::from_quat((tilt * facing).normalize());
                    let axis_b = r * b.cone.axis;
                    if certificate(a, b, (axis_b, &r), 0.0).is_none() {
                        continue;
                    }
                    certified += 1;
                    let Some(w) = (a.cone.axis - axis_b).try_normalize() else {
                        continue;
                    };
                    let turned: Vec<DVec3> = normals_b.iter().map(|&n| r * n).collect();
                    let least = least_gap_curvature(
                        (&normals_a, 1.0 / ball_radius),
                        (&turned, -1.0 / cavity_radius),
                        w,
                    );
                    if least.is_nan() || least <= 0.0 {
                        wrong += 1;
                    }
                }
            }
        }
    }
    (certified, wrong)
}

#[test]
fn a_certified_pair_of_sphere_patches_has_a_convex_gap() {
    let mut rng = Rng(0xc0ff_ee15_2026_1202);
    let mut total = 0;
    for (ball, cavity) in [(8.0, 20.0), (8.0, 10.0), (8.0, 9.0), (8.0, 8.6)] {
        let (certified, wrong) = check(ball, cavity, &mut rng);
        assert_eq!(
            wrong, 0,
            "ball {ball} in cavity {cavity}: {wrong} of {certified} certified pairs have a non-convex gap"
        );
        total += certified;
    }
    // The test means something only where certificates are common.
    assert!(total > 200, "{total} pairs certified");
}
