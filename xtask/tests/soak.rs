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

/// Every failure of the run over every object, which is exactly today's one known failure.
///
/// FIXME(issue 18): loft-goblet 5159088000359678616 misses a second minimum, 5.4e-2 mm, of the
/// loft's rim edge against the goblet's inner wall next to its smooth joint with the rim's top
/// (face 5 at v = 0.003), 1.1 mm from the first (1.6e-2 mm, against face 4): Stage 2 gives one
/// seed between the two, at the joint, and Newton from it reaches the first. When it is fixed,
/// this becomes `assert_eq!(total.failure_count(), 0)` as for the paper objects.
#[test]
fn general_soak_fails_only_where_known() {
    let summary = general_summary();
    let total = totals(summary);
    assert_eq!(total.poses, GENERAL_POSES);
    assert_eq!(summary.pairs.len(), 100);
    let failures: Vec<(String, u64, String)> = summary
        .pairs
        .iter()
        .flat_map(|((a, b), stats)| {
            stats
                .failures
                .iter()
                .filter(|f| f.what != "oracle-limit")
                .map(move |f| (format!("{a}-{b}"), f.seed, f.what.clone()))
        })
        .collect();
    assert_eq!(
        failures,
        vec![(
            "loft-goblet".to_string(),
            5_159_088_000_359_678_616,
            "missed".to_string()
        )],
        "\n{}",
        render(summary)
    );
    assert_eq!(total.failure_count(), 1, "\n{}", render(summary));
}
