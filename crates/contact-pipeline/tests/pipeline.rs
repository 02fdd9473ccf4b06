//! The whole pipeline against closed forms (sphere on sphere, ball in a spherical cavity),
//! its states and early stops, a swapped stage, and bad poses.

use bvh_hybrid::BroadPhase;
use contact_pipeline::{
    ContactOptions, ContactPipeline, PairState, QueryDepth, QueryError, QueryScratch,
};
use exact_refine::NewtonRefiner;
use geom_param::{
    ComponentId, DPose3, DQuat, DVec3, MeshOptions, ObjectModel, Profile, SegmentSpec,
};
use mesh_narrowphase::MeshNarrowphase;

fn model(name: &str, specs: &[SegmentSpec]) -> ObjectModel {
    let profile = Profile::new(specs).expect("valid profile");
    ObjectModel::from_profile(
        name,
        profile,
        &MeshOptions {
            chordal_tolerance: 0.02,
        },
    )
    .expect("model")
}

fn sphere(r: f64) -> ObjectModel {
    model(
        "sphere",
        &[SegmentSpec::Arc {
            center: [0.0, 0.0],
            from: [0.0, -r],
            to: [0.0, r],
            ccw: true,
        }],
    )
}

/// A cup 80 mm wide whose cavity is a hemisphere of radius 30 centred at (0, 0, 40): its lowest
/// point is (0, 0, 10).
fn cup() -> ObjectModel {
    model(
        "cup",
        &[
            SegmentSpec::Line {
                from: [0.0, 0.0],
                to: [40.0, 0.0],
            },
            SegmentSpec::Line {
                from: [40.0, 0.0],
                to: [40.0, 40.0],
            },
            SegmentSpec::Line {
                from: [40.0, 40.0],
                to: [30.0, 40.0],
            },
            SegmentSpec::Arc {
                center: [0.0, 40.0],
                from: [30.0, 40.0],
                to: [0.0, 10.0],
                ccw: false,
            },
        ],
    )
}

fn at(p: DVec3) -> DPose3 {
    DPose3 {
        rotation: DQuat::IDENTITY,
        translation: p,
    }
}

#[test]
fn sphere_on_sphere_matches_the_closed_form() {
    let pipeline = ContactPipeline::new(ContactOptions::default()).expect("options");
    let a = pipeline.prepare(sphere(10.0));
    let b = pipeline.prepare(sphere(5.0));
    let mut scratch = QueryScratch::default();
    let direction = DVec3::new(1.0, 2.0, -0.5).normalize();
    let base = DVec3::new(3.0, -7.0, 11.0);
    for (gap, state) in [
        (0.05, PairState::Contact),
        (0.0, PairState::Contact),
        (0.5, PairState::Separated),
        (-0.3, PairState::Penetration),
    ] {
        let pose_b = at(base + direction * (15.0 + gap));
        let report = pipeline
            .query(&a, &at(base), &b, &pose_b, &mut scratch)
            .expect("query");
        assert_eq!(report.state, state, "gap {gap}");
        if state == PairState::Contact {
            assert_eq!(report.contacts.len(), 1, "gap {gap}");
            let c = report.contacts[0];
            assert!((c.distance - gap).abs() < 1e-9, "gap {gap}: {}", c.distance);
            assert!(
                c.point_a.distance(base + direction * 10.0) < 1e-4,
                "gap {gap}"
            );
            assert!(c.normal.distance(direction) < 1e-6, "gap {gap}");
        }
        assert!(report.stats.broad_ran);
    }
}

#[test]
fn ball_resting_in_a_spherical_cavity() {
    let pipeline = ContactPipeline::new(ContactOptions::default()).expect("options");
    let cup = pipeline.prepare(cup());
    let ball = pipeline.prepare(sphere(10.0));
    let mut scratch = QueryScratch::default();
    for gap in [0.0, 0.03, 0.09] {
        let report = pipeline
            .query(
                &cup,
                &DPose3::IDENTITY,
                &ball,
                &at(DVec3::new(0.0, 0.0, 20.0 + gap)),
                &mut scratch,
            )
            .expect("query");
        assert_eq!(report.state, PairState::Contact, "gap {gap}");
        assert_eq!(
            report.contacts.len(),
            1,
            "gap {gap}: every seed merged into one contact"
        );
        let c = report.contacts[0];
        assert!((c.distance - gap).abs() < 1e-9, "gap {gap}: {}", c.distance);
        assert!(
            c.point_a.distance(DVec3::new(0.0, 0.0, 10.0)) < 1e-4,
            "gap {gap}: {}",
            c.point_a
        );
        assert!(c.normal.distance(DVec3::Z) < 1e-6);
    }
}

#[test]
fn state_only_stops_early_with_the_same_state() {
    let full = ContactPipeline::new(ContactOptions::default()).expect("options");
    let quick = ContactPipeline::new(ContactOptions {
        depth: QueryDepth::StateOnly,
        ..Default::default()
    })
    .expect("options");
    let (a, b) = (full.prepare(sphere(10.0)), full.prepare(sphere(5.0)));
    let (qa, qb) = (quick.prepare(sphere(10.0)), quick.prepare(sphere(5.0)));
    let mut scratch = QueryScratch::default();
    for gap in [0.05, 3.0, -0.3] {
        let pose_b = at(DVec3::new(15.0 + gap, 0.0, 0.0));
        let x = full
            .query(&a, &DPose3::IDENTITY, &b, &pose_b, &mut scratch)
            .expect("query");
        let y = quick
            .query(&qa, &DPose3::IDENTITY, &qb, &pose_b, &mut scratch)
            .expect("query");
        assert_eq!(x.state, y.state, "gap {gap}");
        assert!(y.stats.refined <= x.stats.refined);
    }
    // Far apart: only Stage 1 runs.
    let far = quick
        .query(
            &qa,
            &DPose3::IDENTITY,
            &qb,
            &at(DVec3::new(100.0, 0.0, 0.0)),
            &mut scratch,
        )
        .expect("query");
    assert_eq!(far.state, PairState::Separated);
    assert!(!far.stats.mesh_ran && !far.stats.refine_ran);
}

/// A broad phase that reports every component pair: swapping it in must not change the answer.
struct AllPairs;

impl BroadPhase for AllPairs {
    type Tree = u32;
    type Scratch = ();
    fn build(&self, object: &ObjectModel, _margin: f64) -> u32 {
        object.components.len() as u32
    }
    fn overlapping_components(
        &self,
        a: &u32,
        b: &u32,
        _pose_ab: &DPose3,
        _scratch: &mut (),
        out: &mut Vec<(ComponentId, ComponentId)>,
    ) {
        out.clear();
        out.extend((0..*a).flat_map(|i| (0..*b).map(move |j| (ComponentId(i), ComponentId(j)))));
    }
}

#[test]
fn a_swapped_broad_phase_gives_the_same_contacts() {
    let options = ContactOptions::default();
    let default = ContactPipeline::new(options).expect("options");
    let swapped = ContactPipeline::with_stages(
        AllPairs,
        MeshNarrowphase::default(),
        NewtonRefiner::default(),
        options,
    )
    .expect("options");
    let (a, b) = (default.prepare(cup()), default.prepare(sphere(10.0)));
    let (sa, sb) = (swapped.prepare(cup()), swapped.prepare(sphere(10.0)));
    let pose_b = at(DVec3::new(0.0, 0.0, 20.04));
    let x = default
        .query(
            &a,
            &DPose3::IDENTITY,
            &b,
            &pose_b,
            &mut QueryScratch::default(),
        )
        .expect("query");
    let y = swapped
        .query(
            &sa,
            &DPose3::IDENTITY,
            &sb,
            &pose_b,
            &mut QueryScratch::default(),
        )
        .expect("query");
    assert_eq!(x.state, y.state);
    assert_eq!(x.contacts.len(), y.contacts.len());
    for (c, d) in x.contacts.iter().zip(&y.contacts) {
        assert!((c.distance - d.distance).abs() < 1e-12);
        assert!(c.point_a.distance(d.point_a) < 1e-9);
    }
    assert!(y.stats.component_pairs >= x.stats.component_pairs);
}

#[test]
fn bad_poses_and_options_are_errors() {
    let pipeline = ContactPipeline::new(ContactOptions::default()).expect("options");
    let (a, b) = (
        pipeline.prepare(sphere(10.0)),
        pipeline.prepare(sphere(5.0)),
    );
    let mut scratch = QueryScratch::default();
    let nan = at(DVec3::new(f64::NAN, 0.0, 0.0));
    let skew = DPose3 {
        rotation: DQuat::from_xyzw(0.0, 0.0, 0.0, 2.0),
        translation: DVec3::ZERO,
    };
    for pose in [nan, skew] {
        let result = pipeline.query(&a, &DPose3::IDENTITY, &b, &pose, &mut scratch);
        assert!(
            matches!(result, Err(QueryError::BadPose { object: "b", .. })),
            "{result:?}"
        );
    }
    for options in [
        ContactOptions {
            margin: -1.0,
            ..Default::default()
        },
        ContactOptions {
            delta1: 0.2,
            delta2: 0.1,
            ..Default::default()
        },
        ContactOptions {
            delta2: 2.0,
            margin: 1.0,
            ..Default::default()
        },
        ContactOptions {
            chordal_tolerance: f64::NAN,
            ..Default::default()
        },
    ] {
        assert!(ContactPipeline::new(options).is_err(), "{options:?}");
    }
}
