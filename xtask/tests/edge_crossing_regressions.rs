//! Crossing sharp edges, found by `cargo xtask soak 1000 --general --seed 3102` (flip
//! property): a pair built as an edge-edge contact, moved along its normal to delta1 ± eps.
//! The minimum distance is 1-Lipschitz in the translation and the moved pair stays a critical
//! pair at exactly the moved distance, so at delta1 + eps the pair is a contact at that
//! distance and at delta1 - eps a penetration. Each test checks the moved answer against an
//! independent fact: the closed-form distance of two straight edges (the common perpendicular
//! of their lines, from their end vertices), or the common-perpendicular invariant of two
//! curved edges (the connecting vector normal to both tangents).

use contact_pipeline::{
    Contact, ContactOptions, ContactPipeline, PairReport, PairState, PreparedObject, QueryScratch,
};
use geom_param::{DPose3, DQuat, DVec3, FeatureLocation};
use std::collections::BTreeMap;
use xtask::soak::run::prepare_objects;

fn setup() -> (ContactPipeline, BTreeMap<String, PreparedObject>) {
    let pipeline = ContactPipeline::new(ContactOptions::default()).expect("default options");
    let objects = prepare_objects(&pipeline).expect("fixture objects build");
    (pipeline, objects)
}

fn pose(t: [f64; 3], q: [f64; 4]) -> DPose3 {
    DPose3 {
        translation: DVec3::from_array(t),
        rotation: DQuat::from_array(q),
    }
}

fn query(
    pipeline: &ContactPipeline,
    a: &PreparedObject,
    b: &PreparedObject,
    pose_b: &DPose3,
) -> PairReport {
    pipeline
        .query(
            a,
            &DPose3::IDENTITY,
            b,
            pose_b,
            &mut QueryScratch::default(),
        )
        .expect("unit quaternions")
}

/// The pair at `pose_b` (an edge-edge contact), and the pair moved along that contact's normal
/// to delta1 + eps and to delta1 - eps, each queried fresh. Returns the base contact and the
/// two moved reports.
fn flipped(
    pipeline: &ContactPipeline,
    a: &PreparedObject,
    b: &PreparedObject,
    pose_b: &DPose3,
    eps: f64,
) -> (Contact, DPose3, PairReport, PairReport) {
    let base = query(pipeline, a, b, pose_b);
    let c = *base
        .contacts
        .iter()
        .min_by(|x, y| x.distance.total_cmp(&y.distance))
        .expect("the built contact");
    assert!(
        matches!(c.location_a, FeatureLocation::Edge { .. })
            && matches!(c.location_b, FeatureLocation::Edge { .. }),
        "an edge-edge contact: {c:?}"
    );
    let shift = |s: f64| DPose3 {
        rotation: pose_b.rotation,
        translation: pose_b.translation + c.normal * s,
    };
    let to_delta1 = -(c.distance - pipeline.options().delta1);
    let kept = shift(to_delta1 + eps);
    let inside = query(pipeline, a, b, &kept);
    let beyond = query(pipeline, a, b, &shift(to_delta1 - eps));
    (c, kept, inside, beyond)
}

/// bracket-bracket 5138639870048740581: A's edge 2 (the line x = y = 0) and B's edge 7 (a
/// straight edge of the L-bracket's top plate) cross. Before: the seeds near the crossing
/// ended on a trimmed face's boundary without moving onto its edge (the trimmed face's point
/// within 1.7e-13 mm of edge 7 stayed a face point), stopped unconverged 1.07e-3 mm deep, and
/// that unconverged depth made the pair penetrating at delta1 + 6e-8.
#[test]
fn crossing_bracket_edges_at_delta1_flip_the_state() {
    let (pipeline, objects) = setup();
    let bracket = &objects["bracket"];
    let pose_b = pose(
        [-10.202560926793424, -46.72211374301438, 44.17337856932757],
        [
            -0.286250612865282,
            -0.7576442781398441,
            -0.37447563543808354,
            -0.45144626800921556,
        ],
    );
    let eps = 6e-8;
    let (c, kept, inside, beyond) = flipped(&pipeline, bracket, bracket, &pose_b, eps);
    let target = pipeline.options().delta1 + eps;
    assert_eq!(inside.state, PairState::Contact, "{inside:?}");
    let moved = inside
        .contacts
        .iter()
        .find(|k| (k.distance - target).abs() < 1e-9)
        .unwrap_or_else(|| panic!("a contact at {target}: {inside:?}"));
    assert_eq!(beyond.state, PairState::Penetration, "{beyond:?}");
    // Closed form: the distance of the two edges' lines, from their end vertices.
    let line = |solid: &geom_param::Solid, location: &FeatureLocation, posed: &DPose3| {
        let FeatureLocation::Edge { id, .. } = *location else {
            panic!("an edge")
        };
        let ends = solid
            .edge(id)
            .ends
            .expect("a straight edge has end vertices");
        (
            *posed * solid.vertex(ends[0]).point,
            *posed * solid.vertex(ends[1]).point,
        )
    };
    let (p0, p1) = line(&bracket.model.solid, &c.location_a, &DPose3::IDENTITY);
    let (q0, q1) = line(&bracket.model.solid, &c.location_b, &kept);
    let n = (p1 - p0).cross(q1 - q0).normalize();
    let closed_form = (q0 - p0).dot(n).abs();
    assert!(
        (moved.distance.abs() - closed_form).abs() < 1e-9,
        "{} against the lines' {closed_form}",
        moved.distance
    );
}

/// goblet-tube 11598950496498070928: the goblet's rim circle (edge 7, z = 150) and the tube's
/// outer bottom circle (edge 0) cross. Before: the face-face solve from the seed reached the
/// crossing of the goblet's top annulus with the tube's bottom cap, and the nested penetration
/// solver from there, which cannot represent an edge pair, wandered 0.9 mm off to the inner
/// rim and stopped at its iteration limit: both moved poses were reported separated. Now the
/// crossing's points are moved onto their faces' nearest edges and the edge pair's witness is
/// solved there.
#[test]
fn crossing_rims_of_a_goblet_and_a_tube_flip_the_state() {
    let (pipeline, objects) = setup();
    let (goblet, tube) = (&objects["goblet"], &objects["tube"]);
    let pose_b = pose(
        [-26.005210800497082, -34.40708424775921, 149.93186269531066],
        [
            0.05660003863491108,
            -0.13623207559663658,
            0.12319771314221578,
            0.9813559908013438,
        ],
    );
    let eps = 1.5e-7;
    let (_, kept, inside, beyond) = flipped(&pipeline, goblet, tube, &pose_b, eps);
    let target = pipeline.options().delta1 + eps;
    assert_eq!(inside.state, PairState::Contact, "{inside:?}");
    let moved = inside
        .contacts
        .iter()
        .find(|k| (k.distance - target).abs() < 1e-9)
        .unwrap_or_else(|| panic!("a contact at {target}: {inside:?}"));
    assert_eq!(beyond.state, PairState::Penetration, "{beyond:?}");
    // The common perpendicular: the connecting vector normal to both rims' tangents.
    let tangent = |solid: &geom_param::Solid, location: &FeatureLocation, posed: &DPose3| {
        let FeatureLocation::Edge { id, t } = *location else {
            panic!("an edge: {location:?}")
        };
        posed.rotation * solid.edge(id).curve.eval(t).d1.normalize()
    };
    let gap = moved.point_b - moved.point_a;
    for t in [
        tangent(&goblet.model.solid, &moved.location_a, &DPose3::IDENTITY),
        tangent(&tube.model.solid, &moved.location_b, &kept),
    ] {
        assert!(gap.normalize().dot(t).abs() < 1e-6, "{moved:?}");
    }
}
