//! A straight edge through a pencil's ridge, found by the swap property of the soaks
//! (pencil-bracket 15275829082547009235 of `cargo xtask soak 2000 --general --seed 13244`).
//!
//! The bracket's edge 5 (the line x = 60, y = 0 of its frame, along z) passes 7.04e-4 mm inside
//! the pencil's cylinder r = 3.6 (face 4), 0.027 mm above the ridge where that cylinder meets the
//! ring z = 6 facing down (face 3). With the pencil as A, the seed's solve ended on a crossing
//! of the edge with the ring, and the penetration solve from there stalled on the ridge against
//! the bracket's face beside the edge; its restarts moved one side at a time, never the ridge
//! onto the cylinder together with the bracket's end onto its edge, and the pair was answered
//! Separated (with the bracket as A, Contact at -7.04e-4, inside the band).
//!
//! Truth: inside the pencil near its ridge the depth of a point is its distance below the
//! cylinder (3.6 − ρ, ρ the distance from the pencil's axis) where that is less than its height
//! above the ring, so the deepest point of the line is its point nearest the axis, at depth
//! 3.6 − dist(line, axis) mm; and the pair's answer may not depend on which object is A.

use contact_pipeline::{ContactOptions, ContactPipeline, PairReport, PairState, QueryScratch};
use geom_param::{DPose3, DQuat, DVec3, EdgeId, FaceId, FeatureId};
use xtask::soak::run::prepare_objects;

#[test]
fn an_edge_just_inside_a_ridge_gives_one_contact_in_both_orders() {
    let pipeline = ContactPipeline::new(ContactOptions::default()).expect("default options");
    let objects = prepare_objects(&pipeline).expect("fixture objects build");
    let (pencil, bracket) = (&objects["pencil"], &objects["bracket"]);
    let bracket_pose = DPose3 {
        translation: DVec3::new(-7.055459701751108, -18.449487488020743, 69.19305241102481),
        rotation: DQuat::from_xyzw(
            0.8308300958297675,
            -0.06161442810832501,
            -0.5203084229465178,
            -0.18762771416635465,
        ),
    };
    let mut scratch = QueryScratch::default();
    let mut query = |a, pose_a: &DPose3, b, pose_b: &DPose3| -> PairReport {
        pipeline
            .query(a, pose_a, b, pose_b, &mut scratch)
            .expect("unit quaternions")
    };
    // Both in the world frame, which is the pencil's.
    let straight = query(pencil, &DPose3::IDENTITY, bracket, &bracket_pose);
    let swapped = query(bracket, &bracket_pose, pencil, &DPose3::IDENTITY);
    // The closed form: the edge's line in the pencil's frame and its distance from the axis.
    let origin = bracket_pose * DVec3::new(60.0, 0.0, 0.0);
    let along = bracket_pose.rotation * DVec3::Z;
    let across = along.cross(DVec3::Z);
    let to_axis = origin.dot(across).abs() / across.length();
    let depth = 3.6 - to_axis;
    assert!(depth > 7.0e-4 && depth < 7.1e-4, "depth {depth}");
    // The line's point nearest the axis: origin + s along, with (origin + s along) · (z × across)
    // = 0 in the plane through the axis normal to `across`.
    let normal_plane = DVec3::Z.cross(across);
    let s = -origin.dot(normal_plane) / along.dot(normal_plane);
    let deepest = origin + along * s;
    assert!(deepest.z > 6.0 + 1e-2, "{deepest}");
    for report in [&straight, &swapped] {
        assert_eq!(report.state, PairState::Contact, "{report:?}");
        assert_eq!(report.contacts.len(), 1, "{report:?}");
    }
    let (s, w) = (&straight.contacts[0], &swapped.contacts[0]);
    for c in [s, w] {
        assert!((c.distance + depth).abs() <= 1e-9, "{c:?} against {depth}");
    }
    assert!(s.point_a.distance(w.point_b) <= 1e-9, "{s:?} / {w:?}");
    assert!(s.point_b.distance(w.point_a) <= 1e-9, "{s:?} / {w:?}");
    assert!(s.point_b.distance(deepest) <= 1e-6, "{s:?} / {deepest}");
    assert!((s.point_a.truncate().length() - 3.6).abs() <= 1e-9, "{s:?}");
    assert_eq!(s.location_a.feature(), FeatureId::Face(FaceId(4)));
    assert_eq!(s.location_b.feature(), FeatureId::Edge(EdgeId(5)));
}
