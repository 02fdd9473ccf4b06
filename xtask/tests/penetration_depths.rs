//! The pipeline's penetration depths against the oracle crate: its closed-form scenes with
//! negative gaps (sphere into sphere, a ball into a spherical cavity's wall, crossed cylinders,
//! a tilted torus into a plane, a rod across a torus: two regions), moved by random rigid
//! motions; and, on two of them, the oracle's own penetration witnesses (dense sampling and
//! Newton, sharing no code with the stages).

use contact_oracle::closed_form::{
    crossed_cylinders, rod_across_torus, sphere_in_bowl, sphere_on_sphere, torus_on_plane,
};
use contact_oracle::{ClosedFormScene, OracleOptions, find_contacts};
use contact_pipeline::{Contact, ContactOptions, ContactPipeline, PairState, QueryScratch};
use geom_param::{DPose3, DQuat, DVec3};

/// The penetration contacts (distance < delta1) of the pipeline for `scene`.
fn depths(pipeline: &ContactPipeline, scene: &ClosedFormScene) -> (PairState, Vec<Contact>) {
    let a = pipeline
        .prepare_description(&scene.a)
        .expect("scene object builds");
    let b = pipeline
        .prepare_description(&scene.b)
        .expect("scene object builds");
    let report = pipeline
        .query(
            &a,
            &scene.pose_a,
            &b,
            &scene.pose_b,
            &mut QueryScratch::default(),
        )
        .expect("query");
    let delta1 = pipeline.options().delta1;
    let deep = report
        .contacts
        .iter()
        .copied()
        .filter(|c| c.distance < delta1)
        .collect();
    (report.state, deep)
}

/// Every expected contact of `scene` below delta1 is one pipeline depth and vice versa:
/// distance within 1e-9 mm, points within 1e-6 mm, the normal A's outward normal.
fn check_scene(pipeline: &ContactPipeline, scene: &ClosedFormScene) {
    let (state, deep) = depths(pipeline, scene);
    let delta1 = pipeline.options().delta1;
    let expected: Vec<_> = scene
        .expected
        .iter()
        .filter(|e| e.distance < delta1)
        .collect();
    assert!(!expected.is_empty(), "{}", scene.name);
    assert_eq!(state, PairState::Penetration, "{}", scene.name);
    assert_eq!(deep.len(), expected.len(), "{}: {deep:?}", scene.name);
    for e in expected {
        let found = deep.iter().any(|c| {
            (c.distance - e.distance).abs() < 1e-9
                && c.point_a.distance(e.point_a) < 1e-6
                && c.point_b.distance(e.point_b) < 1e-6
                && c.normal.distance(e.normal) < 1e-6
        });
        assert!(found, "{}: expected {e:?}, got {deep:?}", scene.name);
    }
}

fn motion(k: u32) -> DPose3 {
    let f = f64::from(k);
    DPose3 {
        rotation: DQuat::from_rotation_x(0.3 + f)
            * DQuat::from_rotation_y(-0.7 * f)
            * DQuat::from_rotation_z(1.1 + 0.5 * f),
        translation: DVec3::new(10.0 * f - 7.0, 3.0 - f, 25.0 * f),
    }
}

#[test]
fn closed_form_depths_of_the_oracle_scenes() {
    let pipeline = ContactPipeline::new(ContactOptions::default()).expect("options");
    for (k, gap) in [-0.01, -0.3, -1.5].into_iter().enumerate() {
        let m = motion(u32::try_from(k).expect("small"));
        let direction = DVec3::new(0.3, -0.5, 0.8);
        for scene in [
            sphere_on_sphere(10.0, 7.0, gap, direction, [DQuat::IDENTITY; 2]),
            sphere_in_bowl(5.0, 20.0, gap, 0.3, 1.0, DQuat::from_rotation_z(0.2)),
            crossed_cylinders(4.0, 3.0, gap, 30.0),
            torus_on_plane(10.0, 3.0, 0.3, gap),
            rod_across_torus(10.0, 3.0, 2.0, gap),
        ] {
            check_scene(&pipeline, &scene.moved(&m));
        }
    }
}

/// The oracle's witnesses, found by its own search (not from the closed form), against the
/// pipeline's depths on two scenes.
#[test]
fn depths_match_the_oracles_witnesses() {
    let pipeline = ContactPipeline::new(ContactOptions::default()).expect("options");
    for scene in [
        crossed_cylinders(4.0, 3.0, -0.2, 30.0).moved(&motion(1)),
        rod_across_torus(10.0, 3.0, 2.0, -0.05).moved(&motion(2)),
    ] {
        let (_, deep) = depths(&pipeline, &scene);
        let (a, b) = scene.solids().expect("scene solids");
        let options = OracleOptions::for_solids(&a, &b, 1.0);
        let oracle = find_contacts(&a, &scene.pose_a, &b, &scene.pose_b, &options).expect("oracle");
        let witnesses: Vec<_> = oracle
            .contacts
            .iter()
            .filter(|o| o.distance < 0.0)
            .collect();
        assert!(!deep.is_empty(), "{}", scene.name);
        assert_eq!(
            deep.len(),
            witnesses.len(),
            "{}: {witnesses:?} vs {deep:?}",
            scene.name
        );
        for c in &deep {
            let partner = witnesses.iter().any(|o| {
                (o.distance - c.distance).abs() < 1e-7
                    && o.point_a.distance(c.point_a) < 1e-6
                    && o.point_b.distance(c.point_b) < 1e-6
            });
            assert!(partner, "{}: {c:?} vs {witnesses:?}", scene.name);
        }
    }
}
