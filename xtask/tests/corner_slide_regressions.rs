//! A rounded box's corner into a jar: rounded-box-jar 11629375279842791555 of
//! `cargo xtask soak 2000 --general --seed 8001`, where the pose generator's touch bisection
//! ended in "Separated" on both sides (the state jumped over the band).
//!
//! The seed is the box's corner vertex (where the corner's sphere patch, face 21, closes into
//! a point and the edge fillet face 7 ends). Re-entry from the vertex into face 7 starts at its
//! parameter rectangle's corner; every Newton step there pushed out of one side while moving
//! along the other, was cut to nothing at the side, and settled on the side's edge at its end,
//! which is the vertex again: the solve cycled vertex -> face -> edge end -> vertex to the
//! feature-switch limit 8.6e-3 mm from the jar, and the pair was dropped. Now a coordinate on
//! its bound that the step pushes outward is held and the others move (`newton::take_step`).
//!
//! Truth: the oracle (dense sampling of both exact solids, its own penetration descent and
//! polish) for the deepest witness, and the witness invariant: the connecting vector along
//! both surface normals.

use contact_pipeline::{ContactOptions, ContactPipeline, PairState, QueryScratch};
use geom_param::{DPose3, DQuat, DVec3};
use xtask::soak::oracle_check::oracle_report;
use xtask::soak::run::prepare_objects;

#[test]
fn a_box_corner_into_a_jar_slides_off_its_vertex() {
    let pipeline = ContactPipeline::new(ContactOptions::default()).expect("default options");
    let objects = prepare_objects(&pipeline).expect("fixture objects build");
    let (bx, jar) = (&objects["rounded-box"], &objects["jar"]);
    let pose_b = DPose3 {
        translation: DVec3::new(54.81445104103664, -39.704530090392765, -7.292177555040325),
        rotation: DQuat::from_xyzw(
            -0.7414583326856444,
            0.14303497268325627,
            -0.31770959902191803,
            0.5734467265316425,
        ),
    };
    let report = pipeline
        .query(
            bx,
            &DPose3::IDENTITY,
            jar,
            &pose_b,
            &mut QueryScratch::default(),
        )
        .expect("unit quaternion");
    let oracle = oracle_report(
        &bx.model.solid,
        &jar.model.solid,
        &pose_b,
        pipeline.options(),
    )
    .expect("oracle runs");
    assert_eq!(report.state, PairState::Penetration, "{report:?}");
    let ours = report
        .contacts
        .iter()
        .min_by(|x, y| x.distance.total_cmp(&y.distance))
        .expect("a penetration depth");
    let truth = oracle
        .contacts
        .iter()
        .min_by(|x, y| x.distance.total_cmp(&y.distance))
        .expect("the oracle's witness");
    assert!(
        (ours.distance - truth.distance).abs() <= 1e-9,
        "{ours:?} {truth:?}"
    );
    assert!(
        ours.point_a.distance(truth.point_a) <= 1e-6
            && ours.point_b.distance(truth.point_b) <= 1e-6,
        "{ours:?} {truth:?}"
    );
    // The witness invariant on the exact geometry: P_b - P_a along both outward normals.
    let gap = (ours.point_b - ours.point_a).normalize();
    let normal_a = bx
        .model
        .solid
        .face_normal_at(&ours.location_a)
        .expect("a face point of the box");
    let normal_b = pose_b.rotation
        * jar
            .model
            .solid
            .face_normal_at(&ours.location_b)
            .expect("a face point of the jar");
    assert!(gap.cross(normal_a).length() <= 1e-9, "{ours:?}");
    assert!(gap.cross(normal_b).length() <= 1e-9, "{ours:?}");
}
