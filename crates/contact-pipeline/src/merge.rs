//! Merging refined seeds that reached the same local minimum.

use crate::report::Contact;

/// Adds `candidate` to `contacts` unless one already there is the same minimum: both closest
/// points within `tolerance` (mm) of the candidate's. Of two duplicates the one with the
/// smaller final gradient is kept. Returns true when the candidate was merged away.
pub(crate) fn insert_or_merge(
    contacts: &mut Vec<Contact>,
    candidate: Contact,
    tolerance: f64,
) -> bool {
    let same = |c: &Contact| {
        c.point_a.distance(candidate.point_a) <= tolerance
            && c.point_b.distance(candidate.point_b) <= tolerance
    };
    match contacts.iter_mut().find(|c| same(c)) {
        Some(existing) => {
            if candidate.diagnostics.gradient_norm < existing.diagnostics.gradient_norm {
                *existing = candidate;
            }
            true
        }
        None => {
            contacts.push(candidate);
            false
        }
    }
}
