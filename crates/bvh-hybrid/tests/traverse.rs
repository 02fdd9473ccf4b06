//! Tree-vs-tree queries against closed forms (two spheres, a sphere along a column of bumps),
//! the symmetry of swapping A and B, scratch reuse, and bad poses.

mod support;

use bvh_hybrid::{BroadPhase, HybridBvh, LeafShape, TraversalScratch, TreeOptions};
use geom_param::{ComponentId, DPose3, DQuat, DVec3};
use support::{NAMES, Rng, bump_tip, bumpy_column, near_contact_pose, paper, sphere};

const MARGIN: f64 = 0.5;

fn query(
    phase: &HybridBvh,
    a: &bvh_hybrid::HybridTree,
    b: &bvh_hybrid::HybridTree,
    pose: &DPose3,
) -> Vec<(ComponentId, ComponentId)> {
    let mut out = vec![(ComponentId(99), ComponentId(99))]; // must be cleared
    phase.overlapping_components(a, b, pose, &mut TraversalScratch::default(), &mut out);
    out
}

/// Two spheres of radius R whose centres are D apart: surface distance D - 2R. Reported
/// whenever D - 2R < margin; never reported once D exceeds twice the circumradius of the
/// bevelled leaf (sqrt(3/2) (R + inflate), plus the mesh's slack).
#[test]
fn two_spheres_against_the_closed_form() {
    let (r, tolerance) = (10.0, 0.05);
    let object = sphere(r, tolerance);
    let inflate = 0.5 * MARGIN + object.meshes[0].chordal_error;
    let far = 2.0 * 1.5f64.sqrt() * (r + inflate + 2.0 * tolerance);
    let phase = HybridBvh::default();
    let tree = phase.build(&object, MARGIN);
    let mut rng = Rng(7);
    let (mut reported_between, mut tried_between) = (0, 0);
    for _ in 0..2000 {
        let gap = rng.range(-1.0, far - 2.0 * r + 1.0);
        let pose = DPose3::from_parts(rng.unit_vector() * (2.0 * r + gap), rng.rotation());
        let reported = !query(&phase, &tree, &tree, &pose).is_empty();
        if gap < MARGIN {
            assert!(reported, "gap {gap} below the margin must be reported");
        } else if 2.0 * r + gap > far {
            assert!(
                !reported,
                "gap {gap} beyond the leaves' reach must not be reported"
            );
        } else {
            tried_between += 1;
            reported_between += usize::from(reported);
        }
    }
    // In between the answer depends on the orientations; both answers must occur.
    assert!(0 < reported_between && reported_between < tried_between);
}

/// A small sphere (radius 1) against a column of 100 bumps (pitch 1 mm, each a band of
/// half-height 0.5 whose leaf is widened by 0.25 + chordal error): a sphere touching bump k at
/// its tip is reported with bump k and, since its own leaf reaches at most
/// sqrt(3/2) (1 + 0.25 + chordal) < 1.6 mm from its centre, with bumps at most 2 away;
/// one moved 2 mm out meets nothing.
#[test]
fn sphere_finds_its_bump_among_many() {
    let column = bumpy_column(100, 0.05);
    let ball = sphere(1.0, 0.05);
    let phase = HybridBvh::default();
    let (tree_a, tree_b) = (phase.build(&column, MARGIN), phase.build(&ball, MARGIN));
    let mut rng = Rng(11);
    for k in [0, 1, 37, 50, 98, 99] {
        let (z, tip) = bump_tip(k);
        let angle = rng.range(0.0, std::f64::consts::TAU);
        let out = DVec3::new(angle.cos(), angle.sin(), 0.0);
        let touching = DPose3::from_parts(out * (tip + 1.0 + 0.2) + DVec3::Z * z, rng.rotation());
        let found = query(&phase, &tree_a, &tree_b, &touching);
        assert!(
            found.contains(&(ComponentId(k as u32), ComponentId(0))),
            "bump {k}: {found:?}"
        );
        assert!(
            found.iter().all(|(c, _)| c.0.abs_diff(k as u32) <= 2),
            "bump {k}: {found:?}"
        );
        let away = DPose3::from_parts(out * (tip + 1.0 + 2.0) + DVec3::Z * z, rng.rotation());
        assert!(
            query(&phase, &tree_a, &tree_b, &away).is_empty(),
            "bump {k}"
        );
    }
}

/// Swapping the objects (and inverting the pose) swaps the pairs; reusing scratch across
/// queries changes nothing; each pair is reported once.
#[test]
fn swapping_objects_and_reusing_scratch_agree() {
    let objects: Vec<_> = NAMES.iter().map(|n| paper(n, 0.1)).collect();
    for leaf_shape in [LeafShape::Bevelled, LeafShape::Box] {
        let phase = HybridBvh {
            options: TreeOptions { leaf_shape },
        };
        let trees: Vec<_> = objects.iter().map(|o| phase.build(o, MARGIN)).collect();
        let mut rng = Rng(3);
        let mut scratch = TraversalScratch::default();
        let (mut ab, mut ba) = (Vec::new(), Vec::new());
        let mut nonempty = 0;
        for _ in 0..300 {
            let (a, b) = (rng.index(6), rng.index(6));
            let pose = near_contact_pose(&mut rng, &objects[a], &objects[b], MARGIN);
            phase.overlapping_components(&trees[a], &trees[b], &pose, &mut scratch, &mut ab);
            phase.overlapping_components(
                &trees[b],
                &trees[a],
                &pose.inverse(),
                &mut scratch,
                &mut ba,
            );
            let mut swapped: Vec<_> = ba.iter().map(|&(x, y)| (y, x)).collect();
            let mut sorted = ab.clone();
            sorted.sort();
            swapped.sort();
            assert_eq!(sorted, swapped, "{} vs {}", NAMES[a], NAMES[b]);
            let mut unique = sorted.clone();
            unique.dedup();
            assert_eq!(unique.len(), sorted.len());
            let mut fresh = query(&phase, &trees[a], &trees[b], &pose);
            fresh.sort();
            assert_eq!(fresh, sorted);
            nonempty += usize::from(!ab.is_empty());
        }
        assert!(nonempty > 100, "poses should mostly be near contact");
    }
}

/// A scratch carried along a motion (the last traversal's front, whose pairs found apart are
/// skipped while the motion since cannot have closed their gaps) gives a fresh query's pairs
/// at every step: a ball rolling down a column of 100 bumps in steps of 0 to 1.5 mm and up to
/// 0.2 rad, meeting and leaving bumps as it goes (bevelled and box leaves), and the paper
/// objects in random walks through near-contact poses.
#[test]
fn a_carried_front_gives_the_fresh_pairs() {
    let mut rng = Rng(19);
    let mut warm = Vec::new();
    for leaf_shape in [LeafShape::Bevelled, LeafShape::Box] {
        let phase = HybridBvh {
            options: TreeOptions { leaf_shape },
        };
        let column = phase.build(&bumpy_column(100, 0.05), MARGIN);
        let ball = phase.build(&sphere(1.0, 0.05), MARGIN);
        let mut scratch = TraversalScratch::default();
        let (_, tip) = bump_tip(0);
        let mut pose = DPose3::from_parts(DVec3::new(tip + 1.1, 0.0, 0.0), rng.rotation());
        let mut met = 0;
        for step in 0..600 {
            let size = [0.0, 1e-3, 0.05, 0.4, 1.5][step % 5];
            let drift = DVec3::new(rng.range(-0.2, 0.2) * size, 0.0, rng.range(0.0, size));
            let angle = rng.range(0.0, 0.2) * size.min(1.0);
            let turn = DQuat::from_axis_angle(rng.unit_vector(), angle);
            pose = DPose3::from_parts(pose.translation + drift, (turn * pose.rotation).normalize());
            phase.overlapping_components(&column, &ball, &pose, &mut scratch, &mut warm);
            let fresh = query(&phase, &column, &ball, &pose);
            assert_eq!(warm, fresh, "{leaf_shape:?} leaves, step {step}");
            met += warm.len();
        }
        assert!(met > 600, "the ball should mostly touch bumps: {met}");
    }

    let phase = HybridBvh::default();

    let objects: Vec<_> = NAMES.iter().map(|n| paper(n, 0.1)).collect();
    let trees: Vec<_> = objects.iter().map(|o| phase.build(o, MARGIN)).collect();
    for (a, b) in [(0, 1), (2, 3), (4, 5), (1, 4)] {
        let mut scratch = TraversalScratch::default();
        let mut pose = near_contact_pose(&mut rng, &objects[a], &objects[b], MARGIN);
        for step in 0..200 {
            if step % 50 == 0 {
                pose = near_contact_pose(&mut rng, &objects[a], &objects[b], MARGIN);
            }
            let size = [0.0, 1e-2, 0.3][step % 3];
            let turn = DQuat::from_axis_angle(rng.unit_vector(), 0.02 * size);
            pose = DPose3::from_parts(
                pose.translation + rng.unit_vector() * size,
                (turn * pose.rotation).normalize(),
            );
            phase.overlapping_components(&trees[a], &trees[b], &pose, &mut scratch, &mut warm);
            let fresh = query(&phase, &trees[a], &trees[b], &pose);
            assert_eq!(warm, fresh, "{} {}, step {step}", NAMES[a], NAMES[b]);
        }
    }
}

/// A pose that cannot be evaluated reports every pair instead of panicking or missing.
#[test]
fn bad_poses_report_every_pair() {
    let phase = HybridBvh::default();
    let a = phase.build(&paper("paperweight", 0.1), MARGIN);
    let b = phase.build(&paper("goblet", 0.1), MARGIN);
    let far = DVec3::splat(1e4);
    let bad = [
        DPose3::from_parts(DVec3::new(f64::NAN, 0.0, 0.0), DQuat::IDENTITY),
        DPose3::from_parts(far, DQuat::from_xyzw(0.0, 0.0, 0.0, 0.0)),
        DPose3::from_parts(far, DQuat::from_xyzw(f64::INFINITY, 0.0, 0.0, 1.0)),
    ];
    for pose in bad {
        assert_eq!(query(&phase, &a, &b, &pose).len(), 3 * 8, "{pose:?}");
    }
    // A non-unit but finite rotation is renormalised: far apart is still far apart.
    let scaled = DPose3::from_parts(far, DQuat::from_xyzw(0.0, 0.0, 0.0, 3.0));
    assert!(query(&phase, &a, &b, &scaled).is_empty());
}
