//! The CI-sized soak: 14 random near-contact poses for each of the 36 ordered pairs of the paper
//! objects (504 poses), with every oracle-free property and the comparison with
//! `contact-oracle` of `cargo xtask soak`. The full run is `cargo xtask soak 10000`.

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
                // FIXME(issue 18): the CI soak covers the six paper objects; the general fixture
                // objects are not at zero failures yet (`cargo xtask soak 600 --general --seed
                // 2026`: 6 missed, 1 false, 2 state, 16 property failures; docs/ROBUSTNESS.md).
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
