//! Agreement of two runs of the oracle at different sample spacings.

use crate::report::{CrossCheck, OracleContact};

/// Pairs each contact of `first` with one of `second` whose points both lie within `radius`;
/// counts the contacts of either list left without a partner and the largest differences over
/// the matched pairs.
pub(crate) fn compare(
    first: &[OracleContact],
    second: &[OracleContact],
    radius: f64,
) -> CrossCheck {
    let mut used = vec![false; second.len()];
    let mut out = CrossCheck {
        unmatched: 0,
        max_distance_difference: 0.0,
        max_point_difference: 0.0,
    };
    for c in first {
        let partner = second.iter().enumerate().position(|(j, d)| {
            !used[j]
                && c.point_a.distance(d.point_a) <= radius
                && c.point_b.distance(d.point_b) <= radius
        });
        match partner {
            Some(j) => {
                used[j] = true;
                let d = &second[j];
                out.max_distance_difference = out
                    .max_distance_difference
                    .max((c.distance - d.distance).abs());
                out.max_point_difference = out
                    .max_point_difference
                    .max(c.point_a.distance(d.point_a))
                    .max(c.point_b.distance(d.point_b));
            }
            None => out.unmatched += 1,
        }
    }
    out.unmatched += used.iter().filter(|u| !**u).count();
    out
}
