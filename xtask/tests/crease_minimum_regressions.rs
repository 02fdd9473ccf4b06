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
/// ridge where the taper (face 7) meets the tip cone (face 8) at z = 174, 0.0692 mm away.
/// The tip is a cone of radius 1 mm meshed with 8 segments (chordal error 0.077 mm), so the
/// three lie within one leaf's ball: the ridge's candidate (mesh distance 0.124 mm) was merged
/// into one on the tip cone 0.9 mm away (0.075 mm, not certainly lower), which went to the
/// apex. A candidate on a ridge is now kept apart from a neighbour off that ridge unless the
/// neighbour is certainly lower.
///
/// Truth, independent of the stages: the oracle's three minima, and at the ridge's minimum the
/// invariants of a curve-surface minimum: the connecting vector is normal to the goblet's face
/// and to the crease circle (r = 1 about A's z axis at z = 174), and lies between the two
/// faces' outward normals there (the edge's normal cone).
#[test]
fn a_pencil_tip_on_a_goblet_has_a_minimum_on_the_tips_crease() {
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
    assert_eq!(report.contacts.len(), 3, "{report:?}");
    for o in &oracle.contacts {
        assert!(
            report
                .contacts
                .iter()
                .any(|c| (c.distance - o.distance).abs() < 1e-9
                    && c.point_a.distance(o.point_a) < 1e-5),
            "{o:?} not in {report:?}"
        );
    }
    let crease = report
        .contacts
        .iter()
        .find(|c| matches!(c.location_a, FeatureLocation::Edge { .. }))
        .expect("the ridge's minimum");
    assert!((crease.distance - 0.069_182).abs() < 1e-5, "{crease:?}");
    let p = crease.point_a;
    assert!((p.z - 174.0).abs() < 1e-9, "{crease:?}");
    assert!((p.truncate().length() - 1.0).abs() < 1e-9, "{crease:?}");
    let w = (crease.point_b - p).normalize();
    let tangent = DVec3::new(-p.y, p.x, 0.0).normalize();
    assert!(w.dot(tangent).abs() < 1e-7, "{w:?} {tangent:?}");
    let FeatureLocation::Face { id, u, v } = crease.location_b else {
        panic!("on the goblet's face: {crease:?}");
    };
    let nb = pose_b.rotation
        * goblet
            .model
            .solid
            .eval_face(id, u, v)
            .cross_normal()
            .expect("a regular point");
    assert!(w.dot(-nb) > 1.0 - 1e-12, "{w:?} {nb:?}");
    // The faces' outward normals at the crease point, and w between them (in their plane,
    // the radial-axial plane, inside the arc they span).
    let angle = p.y.atan2(p.x);
    let solid = &pencil.model.solid;
    let [n7, n8] = [(FaceId(7), 1), (FaceId(8), 0)].map(|(face, end)| {
        let range = solid.face(face).surface.domain()[1];
        let v = if end == 1 { range.max } else { range.min };
        let s = solid.eval_face(face, angle.rem_euclid(std::f64::consts::TAU), v);
        assert!(s.point.distance(p) < 1e-9, "{face:?} {:?} {p:?}", s.point);
        s.cross_normal().expect("a regular point")
    });
    let span = n7.angle_between(n8);
    assert!(
        w.angle_between(n7) <= span + 1e-9 && w.angle_between(n8) <= span + 1e-9,
        "{w:?} {n7:?} {n8:?}"
    );
}
