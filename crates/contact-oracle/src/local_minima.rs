//! Local minima of distance between the two surfaces (distance >= 0): discrete minima of the
//! nearest-sample distance, polished by [`crate::polish::minimise`] and accepted only where
//! they are local minima of the distance on the union of faces.

use crate::kdtree::KdTree;
use crate::linalg::{self, N};
use crate::penetration;
use crate::polish::{self, Limits, Pair, Polished};
use crate::posed::PosedSolid;
use crate::sampling::Sample;
use geom_param::{Boundary, ParamSide};

/// Neighbourhood radius for discrete minima, in spacings.
pub(crate) const NEIGHBOURHOOD: f64 = 1.5;

/// Nearest sample of `other` for every sample of `own`: (index, distance), or `None` beyond
/// `limit`.
pub(crate) fn nearest(own: &[Sample], other: &KdTree, limit: f64) -> Vec<Option<(usize, f64)>> {
    own.iter()
        .map(|s| other.nearest_within(s.point, limit))
        .collect()
}

/// Samples whose nearest distance is a discrete local minimum among their own solid's samples
/// within `radius` (ties broken by index so a plateau yields one candidate per neighbourhood).
pub(crate) fn candidates(
    own: &[Sample],
    own_tree: &KdTree,
    nearest: &[Option<(usize, f64)>],
    radius: f64,
) -> Vec<usize> {
    let mut out = Vec::new();
    for (i, s) in own.iter().enumerate() {
        let Some((_, d)) = nearest[i] else { continue };
        let mut minimum = true;
        own_tree.within(s.point, radius, &mut |k| {
            if let Some((_, dk)) = nearest[k] {
                if dk < d || (dk == d && k < i) {
                    minimum = false;
                }
            }
        });
        if minimum {
            out.push(i);
        }
    }
    out
}

/// What a polished candidate turned out to be.
pub(crate) enum Outcome {
    /// A local minimum of distance on the union of both solids' faces.
    Minimum(Box<Polished>),
    /// The surfaces cross here (distance ~ 0, normals not opposite): a start for the
    /// penetration search.
    Crossing(Pair),
    /// Not converged or not a minimum.
    Rejected,
}

/// Polishes one candidate pair and classifies it.
pub(crate) fn polish(
    a: &PosedSolid,
    b: &PosedSolid,
    start: Pair,
    spacing: f64,
    limits: &Limits,
) -> Outcome {
    let p = polish::minimise(a, b, start, [true; N], limits);
    if !p.converged {
        return Outcome::Rejected;
    }
    let distance = p.eval.r.length();
    if distance <= 10.0 * limits.tolerance {
        let na = a.normal(p.pair.fa, p.pair.a[0], p.pair.a[1]);
        let nb = b.normal(p.pair.fb, p.pair.b[0], p.pair.b[1]);
        let opposite = matches!((na, nb), (Some(na), Some(nb)) if (na + nb).length() <= 1e-6);
        if !opposite {
            return Outcome::Crossing(p.pair);
        }
    }
    if !second_order_ok(&p) {
        return Outcome::Rejected;
    }
    let refined = refine_touching(a, b, snap_to_vertex(a, b, p, limits), spacing, limits);
    Outcome::Minimum(Box::new(refined))
}

/// A minimum that settled next to a pole or apex (where the parametrisation is polar and LM
/// crawls) is compared with the vertex itself: if the vertex is at least as close, the polish
/// restarts there (turning towards any descent into the face).
fn snap_to_vertex(a: &PosedSolid, b: &PosedSolid, p: Polished, limits: &Limits) -> Polished {
    let mut start = p.pair;
    let mut snapped = false;
    for k in [1, 3] {
        let (solid, face) = if k == 1 {
            (a, p.pair.fa)
        } else {
            (b, p.pair.fb)
        };
        let range = solid.range(face, 1);
        let v = if k == 1 {
            &mut start.a[1]
        } else {
            &mut start.b[1]
        };
        for (bound, side) in [(range.min, ParamSide::VMin), (range.max, ParamSide::VMax)] {
            let near = (*v - bound).abs() <= 1e-3 * range.span() && *v != bound;
            if near && matches!(solid.boundary(face, side), Boundary::Vertex(_)) {
                *v = bound;
                snapped = true;
            }
        }
    }
    if !snapped {
        return p;
    }
    let q = polish::minimise(a, b, start, [true; N], limits);
    let coordinates = p.eval.pa.point.length().max(p.eval.pb.point.length());
    let rounding = 64.0 * f64::EPSILON * coordinates * p.eval.r.length();
    if q.converged && q.eval.f() <= p.eval.f() + rounding && second_order_ok(&q) {
        q
    } else {
        p
    }
}

/// Near touching (distance below a spacing) f is quartic along the common tangent and the LM
/// points settle only to ~sqrt(rounding / curvature); the descent of A's signed distance to B
/// is regular there, so an interior minimum is re-polished by it when it ends nearby.
fn refine_touching(
    a: &PosedSolid,
    b: &PosedSolid,
    p: Polished,
    spacing: f64,
    limits: &Limits,
) -> Polished {
    if p.eval.r.length() >= spacing || p.active.iter().any(|&x| x) {
        return p;
    }
    let Some(d) = penetration::descend(a, b, p.pair, spacing, limits) else {
        return p;
    };
    let moved = a
        .eval(d.pair.fa, d.pair.a[0], d.pair.a[1])
        .point
        .distance(p.eval.pa.point);
    if !d.minimum || moved > spacing {
        return p;
    }
    let q = penetration::settled(a, b, d.pair, p.iterations, limits);
    if q.converged { q } else { p }
}

/// The reduced Hessian over the free parameters, normalised by the parametric speeds
/// (H_ij / (|c_i| |c_j|), dimensionless), is positive semi-definite up to 1e-7. Parameters
/// whose direction vanishes (u at a pole) carry no information and are left out.
fn second_order_ok(p: &Polished) -> bool {
    let e = &p.eval;
    let scale = e.cols.iter().map(|c| c.length()).fold(0.0, f64::max);
    let free: Vec<usize> = (0..N)
        .filter(|&k| !p.active[k] && e.cols[k].length() > 1e-9 * scale)
        .collect();
    let mut m = [[0.0; N]; N];
    for (i, &ki) in free.iter().enumerate() {
        for (j, &kj) in free.iter().enumerate() {
            m[i][j] = e.h[ki][kj] / (e.cols[ki].length() * e.cols[kj].length());
        }
    }
    free.is_empty() || linalg::min_eigenvalue(&m, free.len()) >= -1e-7
}
