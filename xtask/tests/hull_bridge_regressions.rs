//! A closest point of a convex component's hull that lies on no face, found as a generator
//! failure of `soak 2000 --general --seed 11205` (goblet-bracket 17017317051815854570): while
//! the generator brought the bracket onto the goblet, the state jumped from contact to
//! separated over 1e-9 mm.
//!
//! The bracket's outer faces (its flat sides, ends and backs) form one convex component: no
//! concave face or edge inside it. But it is an L, and its hull bridges the inner corner with
//! facets that lie on no face. The goblet's cup sat beside that corner: GJK's closest point on
//! the bracket's hull was on a bridging facet, Stage 2 snapped it to the nearest hull vertex
//! (the bracket's far corner), and Stage 3 from there converged to a minimum at 0.266 mm,
//! outside the band; the minimum at 0.035 mm, on the face beside the bridge, had no seed. A
//! hull point off the surface now sends the pair to the general path.
//!
//! Truth, independent of the stages: the oracle's minimum, and the exact surfaces' normals at
//! the reported points, both along the connecting vector.

use contact_pipeline::{ContactOptions, ContactPipeline, PairState, QueryScratch};
use geom_param::{DPose3, DQuat, DVec3};
use xtask::soak::oracle_check::oracle_report;
use xtask::soak::run::prepare_objects;

#[test]
fn a_goblet_beside_an_l_brackets_inner_corner_is_in_contact() {
    let pipeline = ContactPipeline::new(ContactOptions::default()).expect("default options");
    let objects = prepare_objects(&pipeline).expect("fixture objects build");
    let (goblet, bracket) = (&objects["goblet"], &objects["bracket"]);
    let pose_b = DPose3 {
        translation: DVec3::new(-57.03604187323735, 24.870052305873003, 98.63538248204969),
        rotation: DQuat::from_xyzw(
            0.16356030549239542,
            0.5062601988967003,
            -0.234960185958935,
            0.8134754750417805,
        ),
    };
    let oracle = oracle_report(
        &goblet.model.solid,
        &bracket.model.solid,
        &pose_b,
        pipeline.options(),
    )
    .expect("oracle runs");
    assert_eq!(oracle.contacts.len(), 1, "{oracle:?}");
    let truth = &oracle.contacts[0];
    assert!((truth.distance - 0.034_663).abs() < 1e-6, "{truth:?}");

    let mut scratch = QueryScratch::default();
    let ab = pipeline
        .query(goblet, &DPose3::IDENTITY, bracket, &pose_b, &mut scratch)
        .expect("valid poses");
    let ba = pipeline
        .query(bracket, &pose_b, goblet, &DPose3::IDENTITY, &mut scratch)
        .expect("valid poses");
    assert_eq!(ab.state, PairState::Contact, "{ab:?}");
    assert_eq!(ba.state, PairState::Contact, "{ba:?}");
    let found = ab
        .contacts
        .iter()
        .find(|c| (c.distance - truth.distance).abs() < 1e-9)
        .unwrap_or_else(|| panic!("the oracle's minimum: {ab:?}"));
    assert!(found.point_a.distance(truth.point_a) < 1e-5, "{found:?}");
    assert!(found.point_b.distance(truth.point_b) < 1e-5, "{found:?}");
    assert!(
        ba.contacts
            .iter()
            .any(|c| (c.distance - truth.distance).abs() < 1e-9),
        "{ba:?}"
    );

    // The connecting vector is normal to both exact faces there.
    let along = (found.point_b - found.point_a).normalize();
    let normal_a = goblet
        .model
        .solid
        .face_normal_at(&found.location_a)
        .expect("a face point of the goblet");
    let normal_b = pose_b.rotation
        * bracket
            .model
            .solid
            .face_normal_at(&found.location_b)
            .expect("a face point of the bracket");
    assert!(along.dot(normal_a) > 1.0 - 1e-12, "{along} {normal_a}");
    assert!(along.dot(normal_b) < -1.0 + 1e-12, "{along} {normal_b}");
}
