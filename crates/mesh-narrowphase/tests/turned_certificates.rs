//! A certificate for a turn ([`Certificate::ForTurn`]) against the test it stands for: every
//! node pair certified at a rotation for a turn by α is certified again by the plain test
//! ([`certificate`] with no turn) at rotations turned from it by up to α, the full angle
//! included, about random axes. The pairs are those where certificates matter: a ball's patches
//! against a spherical cavity's and a torus's, with B turned so that the nodes' cone axes face
//! each other and then tilted at random.

mod common;

use common::{Rng, socket, sphere, torus};
use geom_param::ObjectModel;
use glam::{DMat3, DQuat, DVec3};
use mesh_narrowphase::cones::cone_traversal::{Certificate, certificate};
use mesh_narrowphase::cones::patch_tree::{PatchNode, PatchTree};

fn tree(object: &ObjectModel, component: usize) -> PatchTree {
    PatchTree::build(&object.meshes[component], &object.solid)
}

/// Nodes small enough for a certificate (cones below 30° and smooth), at most `count` of them.
fn candidates(tree: &PatchTree, count: usize) -> Vec<&PatchNode> {
    let narrow = (std::f64::consts::PI / 6.0).cos();
    let mut nodes: Vec<&PatchNode> = tree
        .nodes
        .iter()
        .filter(|n| n.smooth && n.cone.cos >= narrow)
        .collect();
    let step = (nodes.len() / count).max(1);
    nodes = nodes.into_iter().step_by(step).collect();
    nodes
}

/// A rotation taking `from` to `to` (unit vectors).
fn turning(from: DVec3, to: DVec3) -> DQuat {
    DQuat::from_rotation_arc(from, to)
}

/// Checks every pair of `nodes_a` x `nodes_b` at `tilts` random rotations; returns how many
/// were certified for the turn (each checked at `probes` turned rotations).
fn check(nodes_a: &[&PatchNode], nodes_b: &[&PatchNode], turn: f64, rng: &mut Rng) -> usize {
    let (tilts, probes) = (3, 8);
    let mut for_turn = 0;
    for a in nodes_a {
        for b in nodes_b {
            for _ in 0..tilts {
                let facing = turning(b.cone.axis, -a.cone.axis);
                let tilt = DQuat::from_axis_angle(rng.axis(), rng.range(0.0, 0.4));
                let rotation = (tilt * facing).normalize();
                let r = DMat3::from_quat(rotation);
                let here = certificate(a, b, (r * b.cone.axis, &r), turn);
                if here != Some(Certificate::ForTurn) {
                    continue;
                }
                for_turn += 1;
                for k in 0..probes {
                    // The full turn for half the probes, a random fraction for the others.
                    let angle = if k % 2 == 0 {
                        turn
                    } else {
                        rng.range(0.0, turn)
                    };
                    let q = DQuat::from_axis_angle(rng.axis(), angle);
                    let turned = DMat3::from_quat((q * rotation).normalize());
                    let again = certificate(a, b, (turned * b.cone.axis, &turned), 0.0);
                    assert!(
                        again.is_some(),
                        "certified for a turn by {turn} rad, not after turning by {angle} rad"
                    );
                }
            }
        }
    }
    for_turn
}

#[test]
fn a_certificate_for_a_turn_holds_after_any_such_turn() {
    let ball = sphere(8.0, 0.05);
    let cavity = socket(20.0, 26.0, 0.0, 0.05);
    let ring = torus(20.0, 4.0, 0.05);
    let ball_tree = tree(&ball, 0);
    let ball_nodes = candidates(&ball_tree, 40);
    let mut rng = Rng(0x5eed_c0de_1234_5678);
    let mut for_turn = 0;
    for (other, turn) in [(&cavity, 0.02), (&cavity, 0.2), (&ring, 0.05)] {
        for component in 0..other.meshes.len() {
            let other_tree = tree(other, component);
            let other_nodes = candidates(&other_tree, 40);
            for_turn += check(&ball_nodes, &other_nodes, turn, &mut rng);
            for_turn += check(&other_nodes, &ball_nodes, turn, &mut rng);
        }
    }
    // The test means something only where certificates for a turn are common.
    assert!(for_turn > 500, "{for_turn} pairs certified for a turn");
}

/// The turn costs margin: a pair certified at its rotation only is still certified there, and
/// a turn so large that no certificate could survive it (a right angle) gives none.
#[test]
fn a_turn_too_large_leaves_the_certificate_at_its_rotation() {
    let ball = sphere(8.0, 0.05);
    let cavity = socket(20.0, 26.0, 0.0, 0.05);
    let (ball_tree, cavity_tree) = (tree(&ball, 0), tree(&cavity, 0));
    let (nodes_a, nodes_b) = (candidates(&ball_tree, 20), candidates(&cavity_tree, 20));
    let mut at_rotation = 0;
    for a in &nodes_a {
        for b in &nodes_b {
            let rotation = turning(b.cone.axis, -a.cone.axis);
            let r = DMat3::from_quat(rotation);
            let small = certificate(a, b, (r * b.cone.axis, &r), 0.0);
            let large = certificate(a, b, (r * b.cone.axis, &r), std::f64::consts::FRAC_PI_2);
            assert_eq!(small.is_some(), large.is_some());
            assert_ne!(large, Some(Certificate::ForTurn));
            at_rotation += usize::from(large == Some(Certificate::AtRotation));
        }
    }
    assert!(at_rotation > 50, "{at_rotation} pairs certified");
}
