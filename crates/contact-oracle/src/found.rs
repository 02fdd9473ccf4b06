//! A polished pair turned into a contact: signed distance, normal, and merging of duplicates.

use crate::polish::{Eval, Pair};
use crate::posed::PosedSolid;
use crate::report::OracleContact;

/// Builds the contact for a polished pair. The distance is |S_b − S_a| signed by A's outward
/// normal; the normal is the unit connecting vector oriented so that
/// point_b = point_a + distance · normal (A's face normal when the points coincide, which is
/// also A's outward normal wherever the connecting vector is normal to A).
pub(crate) fn contact(
    a: &PosedSolid,
    pair: &Pair,
    eval: &Eval,
    residual: f64,
    iterations: u32,
    negative: bool,
) -> OracleContact {
    let (pa, pb) = (eval.pa.point, eval.pb.point);
    let gap = pb - pa;
    let face_normal = a.normal(pair.fa, pair.a[0], pair.a[1]);
    let length = gap.length();
    let sign = if negative { -1.0 } else { 1.0 };
    let distance = sign * length;
    // A's face normal where the connecting vector is normal to A (interior points, to the
    // residual); the connecting vector itself at an edge, where A has a cone of normals.
    let along =
        |n: glam::DVec3| (gap - n * gap.dot(n)).length() <= 1e3 * residual.max(1e-15 * length);
    let normal = match face_normal {
        Some(n) if length == 0.0 || along(n) => n,
        _ => (gap / distance)
            .try_normalize()
            .or(face_normal)
            .unwrap_or(glam::DVec3::Z),
    };
    OracleContact {
        point_a: pa,
        point_b: pb,
        distance,
        normal,
        face_a: pair.fa,
        params_a: pair.a,
        face_b: pair.fb,
        params_b: pair.b,
        residual,
        iterations,
    }
}

/// Adds `c` unless a contact with both points within `radius` is already there (keeping the
/// one with the smaller residual).
pub(crate) fn merge(into: &mut Vec<OracleContact>, c: OracleContact, radius: f64) {
    if let Some(old) = into.iter_mut().find(|o| {
        o.point_a.distance(c.point_a) <= radius && o.point_b.distance(c.point_b) <= radius
    }) {
        if c.residual < old.residual {
            *old = c;
        }
    } else {
        into.push(c);
    }
}
