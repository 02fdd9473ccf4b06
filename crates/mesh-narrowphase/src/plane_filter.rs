//! A floating-point filter in front of the exact triangle test: most BVH candidates lie clearly
//! on one side of the other triangle's plane.

use glam::DVec3;

/// True when one triangle lies strictly on one side of the other's plane by far more than the
/// rounding error of evaluating the plane in f64, so the exact test would say disjoint.
///
/// The signed distances are computed as `n · (p - a)` with `n = (b - a) × (c - a)`; each carries
/// a rounding error below a few units of 2^-52 times `|n| |p - a|`. The threshold, 1e-12 of that
/// product (about 4500 units), leaves a wide safety factor, so a `true` is never wrong; a `false`
/// only means "ask the exact test". Non-finite input gives `false`.
#[must_use]
pub fn clearly_apart(t1: &[DVec3; 3], t2: &[DVec3; 3]) -> bool {
    one_side(t1, t2) || one_side(t2, t1)
}

/// Whether all of `t`'s corners are clearly on the same side of `plane`'s plane.
fn one_side(plane: &[DVec3; 3], t: &[DVec3; 3]) -> bool {
    let [a, b, c] = *plane;
    let n = (b - a).cross(c - a);
    let norm = n.length();
    let mut above = 0;
    let mut below = 0;
    for p in t {
        let d = *p - a;
        let side = n.dot(d);
        let margin = 1e-12 * norm * d.length();
        if side > margin {
            above += 1;
        } else if side < -margin {
            below += 1;
        }
    }
    above == 3 || below == 3
}
