//! The soak's printed table: one row per ordered pair, then the totals and every failure with
//! the seed that reproduces it.

use crate::soak::run::{PairStats, SoakSummary, Worst};
use std::fmt::Write;

/// The tallies of all pairs added up (worst errors: the worst of all, with its pair's seed).
#[must_use]
pub fn totals(summary: &SoakSummary) -> PairStats {
    let mut total = PairStats::default();
    for (_, s) in &summary.pairs {
        total.poses += s.poses;
        for i in 0..3 {
            total.states[i] += s.states[i];
        }
        for (k, n) in &s.kinds {
            *total.kinds.entry(*k).or_default() += n;
        }
        total.missed += s.missed;
        total.false_contacts += s.false_contacts;
        total.state_mismatches += s.state_mismatches;
        total.depth_mismatches += s.depth_mismatches;
        total.worst_depth.update_from(s.worst_depth);
        total.borderline += s.borderline;
        for (p, n) in &s.property_failures {
            *total.property_failures.entry(*p).or_default() += n;
        }
        total.worst_distance.update_from(s.worst_distance);
        total.worst_point.update_from(s.worst_point);
        total.cross_check += s.cross_check;
        total.generator_failures += s.generator_failures;
        total.oracle_limits += s.oracle_limits;
    }
    total
}

impl Worst {
    fn update_from(&mut self, other: Worst) {
        if other.value > self.value {
            *self = other;
        }
    }
}

fn worst_pair(
    summary: &SoakSummary,
    pick: impl Fn(&PairStats) -> Worst,
) -> Option<&(String, String)> {
    summary
        .pairs
        .iter()
        .max_by(|x, y| pick(&x.1).value.total_cmp(&pick(&y.1).value))
        .map(|(p, _)| p)
}

fn row(out: &mut String, name: &str, s: &PairStats) {
    let props: usize = s.property_failures.values().sum();
    let _ = writeln!(
        out,
        "{name:<22} {:>6} {:>5} {:>5} {:>5} {:>6} {:>6} {:>6} {:>6} {:>6} {:>6} {:>9.2e} {:>9.2e} {:>9.2e} {:>6} {:>6} {:>4}",
        s.poses,
        s.states[0],
        s.states[1],
        s.states[2],
        s.missed,
        s.false_contacts,
        s.state_mismatches,
        s.depth_mismatches,
        s.borderline,
        props,
        s.worst_distance.value,
        s.worst_point.value,
        s.worst_depth.value,
        s.cross_check,
        s.oracle_limits,
        s.generator_failures,
    );
}

/// The table as text.
#[must_use]
pub fn render(summary: &SoakSummary) -> String {
    let mut out = String::new();
    let _ = writeln!(
        out,
        "{:<22} {:>6} {:>5} {:>5} {:>5} {:>6} {:>6} {:>6} {:>6} {:>6} {:>6} {:>9} {:>9} {:>9} {:>6} {:>6} {:>4}",
        "pair (A-B)",
        "poses",
        "sep",
        "cont",
        "pen",
        "missed",
        "false",
        "state",
        "depth",
        "border",
        "props",
        "worst d",
        "worst p",
        "worst dep",
        "xcheck",
        "olimit",
        "gen"
    );
    for ((a, b), s) in &summary.pairs {
        row(&mut out, &format!("{a}-{b}"), s);
    }
    let total = totals(summary);
    row(&mut out, "TOTAL", &total);
    let kinds: Vec<String> = total
        .kinds
        .iter()
        .map(|(k, n)| format!("{} {n}", k.name()))
        .collect();
    let _ = writeln!(out, "poses by aimed gap: {}", kinds.join(", "));
    let props: Vec<String> = total
        .property_failures
        .iter()
        .map(|(p, n)| format!("{} {n}", p.name()))
        .collect();
    if !props.is_empty() {
        let _ = writeln!(out, "property failures: {}", props.join(", "));
    }
    for (label, pick) in [
        (
            "distance",
            (|s: &PairStats| s.worst_distance) as fn(&PairStats) -> Worst,
        ),
        ("point", |s: &PairStats| s.worst_point),
        ("depth", |s: &PairStats| s.worst_depth),
    ] {
        if let Some((a, b)) = worst_pair(summary, pick) {
            let w = pick(&total);
            let _ = writeln!(
                out,
                "worst {label} error {:.3e} mm: replay with `cargo xtask soak --replay {a}-{b}:{}`",
                w.value, w.seed
            );
        }
    }
    for ((a, b), s) in &summary.pairs {
        for f in &s.failures {
            let tag = if f.what == "oracle-limit" {
                "NOTE"
            } else {
                "FAIL"
            };
            let _ = writeln!(
                out,
                "{tag} {a}-{b}:{} {}: {}{}",
                f.seed,
                f.what,
                f.detail,
                f.pose
                    .map(|p| format!(
                        " [aimed {} {:.3e}; pose_b t {:?} q {:?}]",
                        p.kind.name(),
                        p.target_gap,
                        p.pose_b.translation.to_array(),
                        p.pose_b.rotation.to_array()
                    ))
                    .unwrap_or_default()
            );
        }
    }
    out
}
