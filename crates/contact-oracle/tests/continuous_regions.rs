//! Continuous contacts (the paper's section IV: flat faces on flat faces) in closed form: the
//! distance is the same over a whole region, there is no isolated minimum, and the oracle must
//! report the region once (one contact at its distance), with every other point it accepted in
//! the region listed as a member of it.

use contact_oracle::closed_form::{BrepScene, SceneObject};
use contact_oracle::{OracleOptions, find_contacts};
use geom_param::{DPose3, DQuat, DVec3};

/// A block 10 x 10 x 10 (B) resting with its bottom face parallel to the top face (z = 5) of a
/// block 60 x 60 x 10 (A) at `gap`, turned by 0.3 rad about z and shifted, the whole scene
/// moved by a rigid motion. The distance is `gap` over B's whole bottom face (a square of
/// side 10 inside A's top face).
fn block_on_block(gap: f64) -> BrepScene {
    let motion = DPose3 {
        rotation: DQuat::from_axis_angle(DVec3::new(1.0, 2.0, -0.5).normalize(), 0.7),
        translation: DVec3::new(12.0, -40.0, 7.5),
    };
    BrepScene {
        name: format!("block_on_block(gap {gap})"),
        a: SceneObject::Block {
            size: DVec3::new(60.0, 60.0, 10.0),
        },
        pose_a: DPose3::IDENTITY,
        b: SceneObject::Block {
            size: DVec3::splat(10.0),
        },
        pose_b: DPose3 {
            rotation: DQuat::from_rotation_z(0.3),
            translation: DVec3::new(4.0, -3.0, 10.0 + gap),
        },
        expected: Vec::new(),
    }
    .moved(&motion)
}

#[test]
fn a_block_resting_flat_on_a_block_is_one_region() {
    for gap in [0.05, 1e-3, 1e-6] {
        let scene = block_on_block(gap);
        let (a, b) = scene.solids().expect("blocks build");
        let options = OracleOptions::for_solids(&a, &b, 0.2);
        let report =
            find_contacts(&a, &scene.pose_a, &b, &scene.pose_b, &options).expect("oracle runs");
        assert_eq!(report.contacts.len(), 1, "{}: {report:?}", scene.name);
        let resolution = 5.0 * options.tolerance;
        let normal = scene.pose_a.rotation * DVec3::Z;
        let top = scene.pose_a * DVec3::new(0.0, 0.0, 5.0);
        for c in report.region(0) {
            assert!(
                (c.distance - gap).abs() <= resolution,
                "{}: {c:?}",
                scene.name
            );
            // On A's top face, and B's point straight above it.
            assert!((c.point_a - top).dot(normal).abs() < 1e-9, "{c:?}");
            assert!(
                (c.point_b - c.point_a - normal * gap).length() <= resolution,
                "{c:?}"
            );
        }
    }
}
