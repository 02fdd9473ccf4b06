//! A minimum on the outer rim of a flat annulus, missed by `soak 10000 --seed 13154`
//! (goblet-vase 1604628255842907462; session 20's code misses it too). A vase's concave body
//! hangs over the goblet's top, a flat annulus between radii 37 and 40 mm at z = 150 that forms
//! one convex component with the goblet's outer wall. The distance has two minima in the band:
//! on the inner rim (0.0270 mm) and on the outer rim (0.0828 mm), 3 mm apart across the
//! annulus, with a ridge of the distance between them.
//!
//! Only the inner rim's minimum was reported. The normal-cone path's candidates are the
//! triangle pairs' closest points: the annulus is meshed with triangles spanning its width,
//! and the vase's mesh lies up to 0.068 mm off its surface, so the candidate near the outer rim
//! was at radius 39.84 mm inside a triangle (mesh distance 0.0886), not on the rim's ridge, and
//! the radius rule took it for the mid-annulus candidate 1.5 mm away (0.0879, whose seed
//! descends to the inner rim). A candidate dropped so now hands over its pieces' sides along
//! a convex edge inside the component that neither it nor the kept candidate lies on: the
//! closest points of that side, a ridge's own candidate, which the ridge rule keeps apart.
//!
//! Truth, independent of the stages: the oracle's minima (dense sampling, polished).

use contact_pipeline::{ContactOptions, ContactPipeline, PairState, QueryScratch};
use geom_param::{DPose3, DQuat, DVec3};
use xtask::soak::oracle_check::oracle_report;
use xtask::soak::run::prepare_objects;

#[test]
fn a_vase_over_a_goblet_top_touches_both_rims() {
    let pipeline = ContactPipeline::new(ContactOptions::default()).expect("default options");
    let objects = prepare_objects(&pipeline).expect("fixture objects build");
    let (goblet, vase) = (&objects["goblet"], &objects["vase"]);
    let pose_b = DPose3 {
        translation: DVec3::new(27.861359425790447, -16.789425872771382, 187.27216217894832),
        rotation: DQuat::from_xyzw(
            -0.31509609448613063,
            0.7469449350198903,
            0.48849676266073155,
            -0.32273615873915357,
        ),
    };
    let oracle = oracle_report(
        &goblet.model.solid,
        &vase.model.solid,
        &pose_b,
        pipeline.options(),
    )
    .expect("oracle runs");
    let mut truth: Vec<_> = oracle.contacts.iter().map(|c| c.distance).collect();
    truth.sort_by(f64::total_cmp);
    assert_eq!(truth.len(), 2, "{:?}", oracle.contacts);
    assert!((truth[0] - 0.0270).abs() < 1e-4 && (truth[1] - 0.0828).abs() < 1e-4);
    let outer = oracle
        .contacts
        .iter()
        .find(|c| c.distance == truth[1])
        .expect("the outer minimum");
    let radius = outer.point_a.truncate().length();
    assert!(
        (radius - 40.0).abs() < 1e-6 && (outer.point_a.z - 150.0).abs() < 1e-6,
        "on the outer rim: {outer:?}"
    );
    let report = pipeline
        .query(
            goblet,
            &DPose3::IDENTITY,
            vase,
            &pose_b,
            &mut QueryScratch::default(),
        )
        .expect("unit quaternion");
    assert_eq!(report.state, PairState::Contact);
    let mut found: Vec<_> = report.contacts.iter().collect();
    found.sort_by(|x, y| x.distance.total_cmp(&y.distance));
    assert_eq!(found.len(), 2, "{:?}", report.contacts);
    for (c, d) in found.iter().zip(&truth) {
        assert!((c.distance - d).abs() <= 1e-9, "{found:?} vs {truth:?}");
    }
    assert!(
        found[1].point_a.distance(outer.point_a) <= 1e-6,
        "{:?} vs {outer:?}",
        found[1]
    );
}
