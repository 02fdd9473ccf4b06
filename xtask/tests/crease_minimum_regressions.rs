//! A minimum on the crease between a convex component and a concave one, found as a missed
//! contact of `soak 10000 --seed 9103` (pencil-goblet 12563377134518064866): a pencil leaning
//! on a goblet's cup touches it at the lip (4.7e-4 mm) and, 70 mm lower, at the crease where
//! the cup (convex, with the lip one component) meets the stem (concave), at 0.080 mm.
//!
//! Stage 2 answers a pair of convex components with GJK between their hulls: one seed, the
//! hulls' closest points (the lip). The crease's minimum lies on the convex component's open
//! boundary, where its connecting vector leans to the cup's side of the crease, and the stem's
//! patch pieces along the crease held only their own half of the crease's arc of normals, so
//! the normal-cone traversal of (pencil, stem) pruned it. A concave face's pieces on a convex
//! edge now hold the normals of the convex or flat faces across it too.
//!
//! Truth, independent of the stages: the oracle's two minima, and dense sampling of the
//! goblet's exact faces on both sides of the crease, none of which comes nearer the pencil's
//! cylinder (radius 3.5 mm about A's z axis) than the crease's point.

use contact_pipeline::{ContactOptions, ContactPipeline, PairState, QueryScratch};
use geom_param::{DPose3, DQuat, DVec3, FaceId, FeatureLocation};
use xtask::soak::oracle_check::oracle_report;
use xtask::soak::run::prepare_objects;

#[test]
fn a_pencil_on_a_goblet_touches_at_the_lip_and_at_the_cup_crease() {
    let pipeline = ContactPipeline::new(ContactOptions::default()).expect("default options");
    let objects = prepare_objects(&pipeline).expect("fixture objects build");
    let (pencil, goblet) = (&objects["pencil"], &objects["goblet"]);
    let pose_b = DPose3 {
        translation: DVec3::new(-27.51376187534058, 151.86736138775694, 69.29253320662471),
        rotation: DQuat::from_xyzw(
            -0.5059755716254317,
            -0.4945239547875215,
            0.3344756812983595,
            -0.6225438118555395,
        ),
    };
    let oracle = oracle_report(
        &pencil.model.solid,
        &goblet.model.solid,
        &pose_b,
        pipeline.options(),
    )
    .expect("oracle runs");
    assert_eq!(oracle.contacts.len(), 2, "{oracle:?}");
    let crease = oracle
        .contacts
        .iter()
        .max_by(|x, y| x.distance.total_cmp(&y.distance))
        .expect("two contacts");
    assert!((crease.distance - 0.0800).abs() < 1e-3, "{crease:?}");

    // Independent: the pencil's body is the cylinder of radius 3.5 about A's z axis there, and
    // no point of the goblet's faces beside the crease (the cup's face 8, the stem's face 9)
    // within 5 mm of the crease's point is nearer to it.
    let gap = |y: DVec3| (y.x * y.x + y.y * y.y).sqrt() - 3.5;
    assert!((gap(crease.point_b) - crease.distance).abs() < 1e-9);
    let solid = &goblet.model.solid;
    for face in [FaceId(8), FaceId(9)] {
        let surface = &solid.face(face).surface;
        let [du, dv] = surface.domain();
        for i in 0..=1000 {
            for j in 0..=40 {
                let u = du.min + du.span() * f64::from(i) / 1000.0;
                let v = dv.min + dv.span() * f64::from(j) / 40.0;
                let y = pose_b * surface.eval(u, v).point;
                if y.distance(crease.point_b) <= 5.0 {
                    assert!(
                        gap(y) >= crease.distance - 1e-9,
                        "{face:?} ({u}, {v}): {} < {}",
                        gap(y),
                        crease.distance
                    );
                }
            }
        }
    }

    let report = pipeline
        .query(
            pencil,
            &DPose3::IDENTITY,
            goblet,
            &pose_b,
            &mut QueryScratch::default(),
        )
        .expect("unit quaternion");
    assert_eq!(report.state, PairState::Contact, "{report:?}");
    assert_eq!(report.contacts.len(), 2, "{report:?}");
    for truth in &oracle.contacts {
        let found = report.contacts.iter().any(|c| {
            (c.distance - truth.distance).abs() <= 1e-9
                && c.point_a.distance(truth.point_a) <= 1e-6
                && c.point_b.distance(truth.point_b) <= 1e-6
        });
        assert!(found, "{truth:?} not in {report:?}");
    }
    assert!(
        report
            .contacts
            .iter()
            .any(|c| matches!(c.location_b, FeatureLocation::Edge { .. }))
    );
}

/// Found as a missed contact of `soak 10000 --seed 12103` (pencil-goblet
/// 11860975389841438187): a pencil's tip against the goblet's concave face 6 has three
/// minima, the tip's apex at 0.0415 mm, the taper's face at 0.0661 mm and, between them, the
/// crease where the taper (face 7) meets the tip cone (face 8) at z = 174, 0.0692 mm away.
/// The normal-cone path seeded two pairs on the tip cone beside the crease (0.9 and 2.2 mm
/// from it); both converged to the apex, and the crease's minimum had no seed of its own.
/// FIXME: today two contacts are reported; the oracle's three are the truth.
#[test]
fn a_pencil_tip_on_a_goblet_has_a_minimum_on_the_tips_crease_fixme() {
    let pipeline = ContactPipeline::new(ContactOptions::default()).expect("default options");
    let objects = prepare_objects(&pipeline).expect("fixture objects build");
    let (pencil, goblet) = (&objects["pencil"], &objects["goblet"]);
    let pose_b = DPose3 {
        translation: DVec3::new(32.73219097952951, 107.31177880888518, 182.66017484318527),
        rotation: DQuat::from_xyzw(
            0.6197730296708874,
            0.2862860335383167,
            -0.5650431843749363,
            0.46330108837007794,
        ),
    };
    let oracle = oracle_report(
        &pencil.model.solid,
        &goblet.model.solid,
        &pose_b,
        pipeline.options(),
    )
    .expect("oracle runs");
    let crease = oracle
        .contacts
        .iter()
        .find(|c| matches!(c.location_a, FeatureLocation::Edge { .. }))
        .expect("the oracle's minimum on the crease");
    assert!((crease.distance - 0.069_182).abs() < 1e-5, "{crease:?}");
    assert!((crease.point_a.z - 174.0).abs() < 1e-9, "{crease:?}");
    assert_eq!(oracle.contacts.len(), 3, "{oracle:?}");
    let report = pipeline
        .query(
            pencil,
            &DPose3::IDENTITY,
            goblet,
            &pose_b,
            &mut QueryScratch::default(),
        )
        .expect("valid poses");
    assert_eq!(report.state, PairState::Contact);
    assert_eq!(report.contacts.len(), 2, "{report:?}");
    assert!(
        report
            .contacts
            .iter()
            .all(|c| (c.distance - crease.distance).abs() > 1e-3),
        "{report:?}"
    );
}
