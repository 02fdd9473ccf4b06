//! The CI-sized soaks: 14 random near-contact poses for each of the 36 ordered pairs of the paper
//! objects (504 poses), and 6 for each of the 100 ordered pairs of every fixture object, the
//! general ones (rounded box, tube, L-bracket, NURBS loft) included (600 poses), with every
//! oracle-free property and the comparison with `contact-oracle` of `cargo xtask soak`. The
//! full runs are `cargo xtask soak 10000` and `cargo xtask soak 10000 --general`.

use std::sync::OnceLock;
use xtask::soak::properties::Property;
use xtask::soak::run::{SoakConfig, SoakSummary, run_soak};
use xtask::soak::table::{render, totals};

const POSES: usize = 14 * 36;
const SEED: u64 = 2026;

/// The run, shared by the tests of this file (run once).
fn summary() -> &'static SoakSummary {
    static SUMMARY: OnceLock<SoakSummary> = OnceLock::new();
    SUMMARY.get_or_init(|| {
        run_soak(
            &SoakConfig {
                poses: POSES,
                seed: SEED,
                pairs: Vec::new(),
                // The general fixture objects have their own run below.
                general: false,
            },
            |_, _| {},
        )
        .expect("soak runs")
    })
}

/// Every failure of the run (missed, false, state, property) is a failure of the test.
#[test]
fn soak_has_no_failures() {
    let summary = summary();
    let total = totals(summary);
    assert_eq!(total.poses, POSES);
    assert_eq!(total.failure_count(), 0, "\n{}", render(summary));
}

/// The properties that hold on every pose so far stay that way: no NaN, and each contact
/// self-consistent (unit normal, point_b = point_a + d n, points on their features).
#[test]
fn soak_contacts_are_finite_and_consistent() {
    let summary = summary();
    let total = totals(summary);
    assert_eq!(total.poses, POSES);
    assert_eq!(summary.pairs.len(), 36);
    for property in [Property::Finite, Property::Consistency] {
        assert_eq!(
            total.property_failures.get(&property).copied().unwrap_or(0),
            0,
            "{}\n{}",
            property.name(),
            render(summary)
        );
    }
}

const GENERAL_POSES: usize = 6 * 100;

/// The run over every fixture object (`cargo xtask soak 600 --general --seed 2026`).
fn general_summary() -> &'static SoakSummary {
    static SUMMARY: OnceLock<SoakSummary> = OnceLock::new();
    SUMMARY.get_or_init(|| {
        run_soak(
            &SoakConfig {
                poses: GENERAL_POSES,
                seed: SEED,
                pairs: Vec::new(),
                general: true,
            },
            |_, _| {},
        )
        .expect("soak runs")
    })
}

/// The run over every object has no failure: no missed, false, state, property or generator
/// failure (oracle limits are listed, not failures). Its last one (issue 18), loft-goblet
/// 5159088000359678616, a second minimum on the goblet's lip next to a smooth joint that
/// Newton from its own seed walked past, is kept with its literal pose in
/// `seed_face_regressions.rs`.
#[test]
fn general_soak_has_no_failures() {
    let summary = general_summary();
    let total = totals(summary);
    assert_eq!(total.poses, GENERAL_POSES);
    assert_eq!(summary.pairs.len(), 100);
    assert_eq!(total.failure_count(), 0, "\n{}", render(summary));
}

/// Two pencils crossed at random miss each other on most lines of approach: with 8 attempts
/// `soak 10000 --seed 13114` had no pose for pencil-pencil 8657644817059814099 (a generator
/// failure). The generator now finds one, built at the gap it aims for.
#[test]
fn two_thin_objects_get_a_pose() {
    let pipeline =
        contact_pipeline::ContactPipeline::new(contact_pipeline::ContactOptions::default())
            .expect("default options");
    let objects = xtask::soak::run::prepare_objects(&pipeline).expect("fixture objects build");
    let pencil = &objects["pencil"];
    let mut generator = xtask::soak::pose_generator::PoseGenerator::new(&pipeline, pencil, pencil);
    let pose = generator
        .generate(8_657_644_817_059_814_099)
        .expect("a line of approach meets the pencil");
    let report = pipeline
        .query(
            pencil,
            &geom_param::DPose3::IDENTITY,
            pencil,
            &pose.pose_b,
            &mut contact_pipeline::QueryScratch::default(),
        )
        .expect("unit quaternion");
    // The seed draws a touch: the pencils at the aimed gap (|gap| < 1e-9 mm) along the
    // contact the generator moved B by.
    assert!(pose.target_gap.abs() < 1e-9, "{pose:?}");
    assert_eq!(
        report.state,
        contact_pipeline::PairState::Contact,
        "{report:?}"
    );
    let nearest = report
        .contacts
        .iter()
        .map(|c| c.distance)
        .fold(f64::INFINITY, f64::min);
    assert!(
        (nearest - pose.target_gap).abs() < 1e-8,
        "{nearest} against the aimed {}: {report:?}",
        pose.target_gap
    );
}
