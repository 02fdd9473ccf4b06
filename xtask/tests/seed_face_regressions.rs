//! A minimum Newton walks past: loft-goblet 5159088000359678616 of the CI's general soak
//! (`cargo xtask soak 600 --general --seed 2026`), built as a contact at 1.645e-2 mm between
//! the loft's top rim (edge 1) and the goblet's wall (face 4).
//!
//! The rim has a second local minimum of distance 0.9 mm along it, at 5.42e-2 mm, against the
//! goblet's lip (face 5, at v = 0.003 from its smooth joint with face 4). Stage 2 seeds the
//! lip's component, at the joint, and Newton from that seed crossed the joint into face 4 and
//! reached the first minimum, so the second was missed. Now a solve that leaves its seed's
//! faces is solved again kept on them, and polished without that restriction.
//!
//! Truth: the oracle (dense sampling of both exact solids and its own polish), and the
//! invariant of an edge-face minimum: the connecting vector normal to the edge's tangent and
//! along the face's normal.

use contact_pipeline::{ContactOptions, ContactPipeline, PairState, QueryScratch};
use geom_param::{DPose3, DQuat, DVec3, FeatureLocation};
use xtask::soak::oracle_check::oracle_report;
use xtask::soak::run::prepare_objects;

#[test]
fn a_minimum_beside_a_smooth_joint_is_found_from_its_own_seed() {
    let pipeline = ContactPipeline::new(ContactOptions::default()).expect("default options");
    let objects = prepare_objects(&pipeline).expect("fixture objects build");
    let (loft, goblet) = (&objects["loft"], &objects["goblet"]);
    let pose_b = DPose3 {
        translation: DVec3::new(12.967085400280743, 87.82556170239336, 42.51667316969232),
        rotation: DQuat::from_xyzw(
            0.1951765601686254,
            0.6524124264010629,
            -0.7293013205184067,
            0.06620966793700832,
        ),
    };
    let report = pipeline
        .query(
            loft,
            &DPose3::IDENTITY,
            goblet,
            &pose_b,
            &mut QueryScratch::default(),
        )
        .expect("unit quaternion");
    let oracle = oracle_report(
        &loft.model.solid,
        &goblet.model.solid,
        &pose_b,
        pipeline.options(),
    )
    .expect("oracle runs");
    assert_eq!(report.state, PairState::Contact);
    assert_eq!(oracle.contacts.len(), 2, "{oracle:?}");
    assert_eq!(report.contacts.len(), 2, "{report:?}");
    for o in &oracle.contacts {
        let c = report
            .contacts
            .iter()
            .min_by(|x, y| {
                let dx = x.point_a.distance(o.point_a);
                dx.total_cmp(&y.point_a.distance(o.point_a))
            })
            .expect("two contacts");
        assert!((c.distance - o.distance).abs() <= 1e-9, "{c:?} {o:?}");
        assert!(
            c.point_a.distance(o.point_a) <= 1e-6 && c.point_b.distance(o.point_b) <= 1e-6,
            "{c:?} {o:?}"
        );
        // The edge-face invariant, on the exact geometry.
        let FeatureLocation::Edge { id, t } = c.location_a else {
            panic!("the loft's rim: {c:?}");
        };
        let tangent = loft.model.solid.eval_edge(id, t).d1.normalize();
        let gap = c.point_b - c.point_a;
        assert!(gap.dot(tangent).abs() <= 1e-9 * gap.length(), "{c:?}");
        let face_normal = pose_b.rotation
            * goblet
                .model
                .solid
                .face_normal_at(&c.location_b)
                .expect("a face point of the goblet");
        assert!(
            gap.normalize().cross(face_normal).length() <= 1e-9,
            "{c:?} {face_normal:?}"
        );
    }
    let lip = report
        .contacts
        .iter()
        .find(|c| matches!(c.location_b, FeatureLocation::Face { id, .. } if id.0 == 5))
        .expect("the minimum against the lip, face 5");
    assert!((lip.distance - 5.4167658592e-2).abs() <= 1e-9, "{lip:?}");
}
