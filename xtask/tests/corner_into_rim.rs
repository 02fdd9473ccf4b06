//! A bracket's corner pushed into a tube's rim, found as a flip failure of
//! `soak 2000 --general --seed 13253` (tube-bracket 4510831738877038708; the same on main before
//! session 30). At the generated pose the closest pair is the tube's outer top rim (edge 1)
//! against the bracket's corner (vertex 1), 0.0422 mm apart. Moved along the contact normal by
//! the gap plus δ, the corner lies inside the tube, under its top cap and inside its outer wall.
//! The normal is nearly radial, so the corner goes δ into the outer wall but only 0.14 δ under
//! the cap, and the bracket's edge 2, which descends from the corner, is deepest (about
//! 0.58 δ) where it is as far under the cap as inside the wall. The pipeline's witness is the
//! rim against that point of edge 2, √2 times as far: δ = 1 µm (the flip's pose, just past
//! delta1 = −1 µm, whose expected −1 µm is the corner-rim pair's own distance) is reported as a
//! contact at −0.815 µm where the depth is about 0.58 µm, and at δ = 2 µm (depth 1.15 µm, a
//! penetration) that pair fails the witness check. Until session 32 the pair was then reported
//! separated; the check now finds the edge's point inside the tube, 1.12 µm deep.
//!
//! Truth the code does not produce: the bracket's edge against the tube's closed-form walls
//! (outer radius 9 mm, inner 5 mm, top cap at z = 60 mm), sampled densely.

use contact_pipeline::{ContactOptions, ContactPipeline, PairState, QueryScratch};
use geom_param::{DPose3, DQuat, DVec3, EdgeId, FeatureLocation};
use xtask::soak::run::prepare_objects;

#[test]
fn a_bracket_corner_two_microns_into_a_tube_rim() {
    let pipeline = ContactPipeline::new(ContactOptions::default()).expect("default options");
    let objects = prepare_objects(&pipeline).expect("fixture objects build");
    let (tube, bracket) = (&objects["tube"], &objects["bracket"]);
    let pose_b = DPose3 {
        translation: DVec3::new(6.372464805311892, 29.787691484684967, 40.24496351987444),
        rotation: DQuat::from_array([
            -0.1910860331164557,
            0.3662491402201933,
            -0.5939613451918344,
            -0.6903315259016443,
        ]),
    };
    let query = |pose: &DPose3| {
        pipeline
            .query(
                tube,
                &DPose3::IDENTITY,
                bracket,
                pose,
                &mut QueryScratch::default(),
            )
            .expect("unit quaternion")
    };
    let report = query(&pose_b);
    assert_eq!(report.state, PairState::Contact, "{report:?}");
    let contact = &report.contacts[0];
    assert!((contact.distance - 0.042243).abs() < 1e-6, "{contact:?}");
    assert!(
        matches!(contact.location_b, FeatureLocation::Vertex { .. }),
        "{contact:?}"
    );
    let depth = 2e-3;
    let moved = DPose3 {
        rotation: pose_b.rotation,
        translation: pose_b.translation - contact.normal * (contact.distance + depth),
    };
    // The bracket's edge 2 ends at the corner (t = 30); its points near the corner against the
    // tube's closed-form walls: a point inside lies min(60 - z, 9 - r) from the tube's boundary.
    let inside = |t: f64| {
        let p = moved
            * bracket
                .model
                .solid
                .point_at(&FeatureLocation::Edge { id: EdgeId(2), t });
        let r = p.truncate().length();
        let depth = (60.0 - p.z).min(9.0 - r);
        if r > 5.0 { depth } else { f64::NEG_INFINITY }
    };
    let deepest = (0..=20_000)
        .map(|k| inside(30.0 - 0.01 * f64::from(k) / 20_000.0))
        .fold(f64::NEG_INFINITY, f64::max);
    // About 1.15 µm: the solids overlap by more than -delta1 (1 µm), a penetration.
    assert!(deepest > 1.1e-3 && deepest < 1.2e-3, "deepest {deepest}");
    let report = query(&moved);
    // The one seed's pair (the rim against the bracket's edge 2, √2 times the depth: the point
    // where the edge is as far under the cap as inside the wall, measured to the rim between
    // them) is measured through the material, but its point on the edge lies inside the tube
    // deeper than -delta1 (the witness check's `Overlapping`, session 32): a penetration, with
    // that point as its witness.
    assert_eq!(report.state, PairState::Penetration, "{report:?}");
    assert_eq!(report.stats.through_material, 1, "{report:?}");
    assert_eq!(report.penetration_witnesses.len(), 1, "{report:?}");
    let witness = report.penetration_witnesses[0];
    let r = witness.truncate().length();
    let witness_depth = (60.0 - witness.z).min(9.0 - r);
    assert!(
        r > 5.0 && witness_depth > 1e-3 && witness_depth <= deepest,
        "witness {witness} at depth {witness_depth} (deepest {deepest})"
    );
    // FIXME: no contact measures the depth. The deepest point is a kink of the depth,
    // equidistant from the cap and the outer wall, and no smooth critical pair of the solvers:
    // restarting the solve from each face near the nearer boundary point was tried (session
    // 31), and two restarts ended at the same edge-edge pair, the third at the corner against
    // the outer wall (-1.98 µm, with the cap 0.28 µm away). A witness for a kink (a point
    // against two faces at once) would be needed.
    assert!(report.contacts.is_empty(), "{report:?}");
}
