//! A contact whose seed looked penetrating: tube-bracket 17360574881066406849 of
//! `cargo xtask soak 2000 --general --seed 8002`, built as a contact at 2.18e-2 mm between the
//! tube's top outer rim (edge 1) and a fillet edge of the bracket (edge 10).
//!
//! Stage 2 seeds the pair of convex components whose hulls overlap (the tube's hull fills its
//! hole) with a pair 20 mm apart that the pair solve's first test calls penetrating; the
//! nested penetration solver then crept towards the minimum and stopped at its iteration limit
//! 1e-4 mm short, and the pair was reported separated. A penetration solve that does not
//! converge is now polished as a distance minimisation from its end, taken when that converges
//! to a pair that is not penetrating.
//!
//! Truth: the oracle (dense sampling of both exact solids and its own polish), and the
//! invariant of an edge-edge minimum: the connecting vector normal to both edges' tangents.

use contact_pipeline::{ContactOptions, ContactPipeline, PairState, QueryScratch};
use geom_param::{DPose3, DQuat, DVec3, FeatureLocation};
use xtask::soak::oracle_check::oracle_report;
use xtask::soak::run::prepare_objects;

#[test]
fn a_rim_on_a_fillet_edge_seeded_as_penetrating_is_a_contact() {
    let pipeline = ContactPipeline::new(ContactOptions::default()).expect("default options");
    let objects = prepare_objects(&pipeline).expect("fixture objects build");
    let (tube, bracket) = (&objects["tube"], &objects["bracket"]);
    let pose_b = DPose3 {
        translation: DVec3::new(21.202025385061923, 38.14577432773079, 63.898102949178046),
        rotation: DQuat::from_xyzw(
            0.23827692450705035,
            -0.7364019000965644,
            0.5957798082373371,
            0.21443593187316565,
        ),
    };
    let report = pipeline
        .query(
            tube,
            &DPose3::IDENTITY,
            bracket,
            &pose_b,
            &mut QueryScratch::default(),
        )
        .expect("unit quaternion");
    let oracle = oracle_report(
        &tube.model.solid,
        &bracket.model.solid,
        &pose_b,
        pipeline.options(),
    )
    .expect("oracle runs");
    assert_eq!(report.state, PairState::Contact, "{report:?}");
    assert_eq!(oracle.contacts.len(), 1, "{oracle:?}");
    assert_eq!(report.contacts.len(), 1, "{report:?}");
    let (c, o) = (&report.contacts[0], &oracle.contacts[0]);
    assert!((c.distance - o.distance).abs() <= 1e-9, "{c:?} {o:?}");
    assert!(
        c.point_a.distance(o.point_a) <= 1e-6 && c.point_b.distance(o.point_b) <= 1e-6,
        "{c:?} {o:?}"
    );
    let (FeatureLocation::Edge { id: ea, t: ta }, FeatureLocation::Edge { id: eb, t: tb }) =
        (c.location_a, c.location_b)
    else {
        panic!("the rim against the fillet edge: {c:?}");
    };
    let gap = c.point_b - c.point_a;
    let tangent_a = tube.model.solid.eval_edge(ea, ta).d1.normalize();
    let tangent_b = pose_b.rotation * bracket.model.solid.eval_edge(eb, tb).d1.normalize();
    assert!(gap.dot(tangent_a).abs() <= 1e-9 * gap.length(), "{c:?}");
    assert!(gap.dot(tangent_b).abs() <= 1e-9 * gap.length(), "{c:?}");
}
