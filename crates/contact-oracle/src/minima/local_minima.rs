//! Local minima of distance between the two surfaces (distance >= 0): discrete minima of the
//! nearest-sample distance, polished by [`crate::polishing::polish::minimise`] and accepted
//! only where they are local minima of the distance on the union of faces, edges and vertices:
//! stationary over the parameters of the features the points are on, the reduced Hessian over
//! those parameters positive semi-definite, and (held on an edge or vertex) no descent into a
//! neighbouring feature, i.e. the connecting vector in the feature's normal cone.

use crate::minima::penetration;
use crate::polishing::feature_moves::in_normal_cone;
use crate::polishing::linalg::{self, N};
use crate::polishing::pair::Pair;
use crate::polishing::polish::{self, Limits, Polished};
use crate::samples::kdtree::KdTree;
use crate::samples::sampling::Sample;
use crate::solids::held::Held;
use crate::solids::posed::PosedSolid;
use geom_param::{Boundary, FaceId, FeatureLocation, ParamSide};
use glam::{DVec2, DVec3};

/// Neighbourhood radius for discrete minima, in spacings.
pub(crate) const NEIGHBOURHOOD: f64 = 1.5;

/// Nearest sample of `other` for every sample of `own`: (index, distance), or `None` beyond
/// `limit`.
pub(crate) fn nearest(own: &[Sample], other: &KdTree, limit: f64) -> Vec<Option<(usize, f64)>> {
    own.iter()
        .map(|s| other.nearest_within(s.point, limit))
        .collect()
}

/// Samples whose nearest distance is a discrete local minimum among the samples of their own
/// face within `radius` (ties broken by index so a plateau yields one candidate per
/// neighbourhood).
///
/// Per face, not over the whole solid: a local minimum of the distance over the union of the
/// faces is also one over each closed face it lies on (a minimum on an edge belongs to both of
/// its faces), so every face's own discrete minima are starts for it. Over the whole solid
/// the nearest-*sample* distance, whose error is of the order of the spacing (the other
/// solid's samples are that far apart), lets a neighbouring face's sample hide a minimum:
/// a pencil's ferrule corner 0.0856 mm from a goblet lost to a sample of the body face across
/// the 0.1 mm step, 0.8 mm away, whose nearest sample happened to be nearer (0.177 against
/// 0.214 mm) although its true distance is about 0.15 mm.
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
            if own[k].face != s.face {
                return;
            }
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
    let plain = p.pair.on_faces() && a.trim(p.pair.fa).is_none() && b.trim(p.pair.fb).is_none();
    if !plain {
        // Near touching, the points settle only loosely along the common tangent (see
        // `refine_touching`), too loosely to tell which feature they touch on (a face a hair
        // from its trim, an edge a hair from its end), and slowly (next to a pole the LM may
        // not settle at all): pin them first.
        if !p.converged && p.eval.r.length() >= spacing {
            return Outcome::Rejected;
        }
        let p = if p.converged {
            snap_to_vertex(a, b, p, limits)
        } else {
            p
        };
        let p = refine_touching(a, b, p, spacing, limits);
        if !p.converged {
            return Outcome::Rejected;
        }
        if p.eval.r.length() <= 10.0 * limits.tolerance && !touching(a, b, &p, limits.tolerance) {
            return Outcome::Crossing(p.pair);
        }
        if !second_order_ok(&p) {
            return Outcome::Rejected;
        }
        return Outcome::Minimum(Box::new(p));
    }
    if !p.converged {
        return Outcome::Rejected;
    }
    let distance = p.eval.r.length();
    if distance <= 10.0 * limits.tolerance && !touching(a, b, &p, limits.tolerance) {
        return Outcome::Crossing(p.pair);
    }
    if !second_order_ok(&p) {
        return Outcome::Rejected;
    }
    let refined = refine_touching(a, b, snap_to_vertex(a, b, p, limits), spacing, limits);
    Outcome::Minimum(Box::new(refined))
}

/// Whether two coinciding points are a touch rather than a crossing: some direction n lies in
/// A's outward normal cone with −n in B's, for the features the points are on or, where the
/// points settled a hair from a boundary, the features next to them (see [`nearby`]). Both on
/// faces: opposite normals (to 1e-6). One on a face: its normal (negated for B's) tested
/// against the other's cone. Both on edges: the common normal of the two tangents. Otherwise
/// (a vertex against an edge or vertex) a crossing, which the penetration search then
/// examines.
fn touching(a: &PosedSolid, b: &PosedSolid, p: &Polished, tolerance: f64) -> bool {
    let candidates_a = nearby(a, &p.pair, true, p.active, tolerance);
    let candidates_b = nearby(b, &p.pair, false, p.active, tolerance);
    candidates_a.iter().any(|&held_a| {
        candidates_b.iter().any(|&held_b| {
            let mut pair = p.pair;
            (pair.held_a, pair.held_b) = (held_a, held_b);
            cones_meet(a, b, &pair)
        })
    })
}

/// The features a point of `pair` may be taken on when testing a touch: its own; on a face
/// without trim, the edge of a side its parameter is held at (`active`); on a trimmed face,
/// the boundary edge within 10 x `tolerance` (mm) of it; on such an edge, the end vertex within
/// 10 x `tolerance`.
fn nearby(
    solid: &PosedSolid,
    pair: &Pair,
    on_a: bool,
    active: [bool; N],
    tolerance: f64,
) -> Vec<Held> {
    let (face, uv, held) = pair.side(on_a);
    let point = solid.eval_held(face, uv, held).point;
    let near = |q: DVec3| q.distance(point) <= 10.0 * tolerance;
    let mut out = vec![held];
    if held == Held::Face {
        let k = if on_a { 0 } else { 2 };
        let side_edge = (k..k + 2)
            .filter(|&k| active[k])
            .find_map(|k| on_side_edge(solid, face, uv, k % 2));
        let trim_edge = solid.trim(face).and_then(|trim| {
            let n = trim.nearest(DVec2::from(uv))?;
            let edge = trim.loops[n.loop_index].entries[n.index].edge;
            near(solid.eval_edge(edge, n.t).point).then(|| Held::Edge {
                edge,
                t: n.t,
                use_index: solid.use_on(edge, face),
            })
        });
        out.extend(side_edge.into_iter().chain(trim_edge));
    }
    let edges: Vec<Held> = out[1..].to_vec();
    for held in edges.into_iter().chain([held]) {
        if let Held::Edge { edge, .. } = held {
            if let Some(ends) = solid.solid.edge(edge).ends {
                for v in ends {
                    if near(solid.vertex_point(v)) && !out.contains(&Held::Vertex(v)) {
                        out.push(Held::Vertex(v));
                    }
                }
            }
        }
    }
    out
}

/// Whether some direction lies in A's normal cone with its opposite in B's, for the features
/// `pair` holds its points on (see [`touching`]).
fn cones_meet(a: &PosedSolid, b: &PosedSolid, pair: &Pair) -> bool {
    if pair.on_faces() {
        let na = a.normal(pair.fa, pair.a[0], pair.a[1]);
        let nb = b.normal(pair.fb, pair.b[0], pair.b[1]);
        return matches!((na, nb), (Some(na), Some(nb)) if (na + nb).length() <= 1e-6);
    }
    let n = match (pair.held_a, pair.held_b) {
        (Held::Face, _) => a.normal(pair.fa, pair.a[0], pair.a[1]),
        (_, Held::Face) => b.normal(pair.fb, pair.b[0], pair.b[1]).map(|n| -n),
        (
            Held::Edge {
                edge: ea, t: ta, ..
            },
            Held::Edge {
                edge: eb, t: tb, ..
            },
        ) => a
            .eval_edge(ea, ta)
            .d1
            .cross(b.eval_edge(eb, tb).d1)
            .try_normalize()
            .and_then(|n| {
                let outward = a.sign_normal(pair.fa, pair.a, pair.held_a)?;
                Some(if n.dot(outward) < 0.0 { -n } else { n })
            }),
        _ => None,
    };
    n.is_some_and(|n| {
        in_normal_cone(a, pair.fa, pair.a, pair.held_a, n)
            && in_normal_cone(b, pair.fb, pair.b, pair.held_b, -n)
    })
}

/// The edge along the rectangle side of `face` where parameter `index` is held at its bound,
/// as a held point (t = the running parameter), if a side there is bounded by an edge.
fn on_side_edge(solid: &PosedSolid, face: FaceId, uv: [f64; 2], index: usize) -> Option<Held> {
    let side = solid
        .sides_at(face, uv, 0.0)
        .into_iter()
        .find(|&side| solid.side_param(face, side).index == index)?;
    solid.edge_on_side(face, side, uv)
}

/// A touch (|r| within 10 x `limits.tolerance`) on an edge (held there, or free on a trimmed
/// face within that distance of it) within that distance of one of its end vertices: the pair with that point at the vertex (the other point projected
/// afresh) when its signed distance is lower. Where a corner pokes a hair into the other
/// solid, f = ½|r|² vanishes on the curve where the corner's edges cross the other surface,
/// and the polish can stop on that curve beside the corner, a touch by the cone test; the
/// deepest point, the witness, is the corner itself (bracket-paperweight 4792506523713132914
/// of `soak 300 --general --seed 2026`: the crossing 1.6e-9 mm along the edge at +1.3e-10 mm,
/// the corner at −1.03e-9 mm). `signed` gives a pair's signed distance.
pub(crate) fn deeper_corner(
    a: &PosedSolid,
    b: &PosedSolid,
    p: Polished,
    limits: &Limits,
    signed: impl Fn(&Polished) -> f64,
) -> Polished {
    let near = 10.0 * limits.tolerance;
    if p.eval.r.length() > near {
        return p;
    }
    let mut best = (signed(&p), p);
    for on_a in [true, false] {
        let solid = if on_a { a } else { b };
        let (face, uv, held) = p.pair.side(on_a);
        // Held on the edge, or free on a trimmed face within `near` of it.
        let FeatureLocation::Edge { id: edge, .. } = solid.location(face, uv, held, near) else {
            continue;
        };
        let Some(ends) = solid.solid.edge(edge).ends else {
            continue;
        };
        let point = if on_a {
            p.eval.pa.point
        } else {
            p.eval.pb.point
        };
        for vertex in ends {
            if solid.vertex_point(vertex).distance(point) > near {
                continue;
            }
            let (face, uv, _) = p.pair.side(on_a);
            let mut start = p.pair;
            start.set_side(on_a, face, uv, Held::Vertex(vertex));
            let movable = if on_a {
                [false, false, true, true]
            } else {
                [true, true, false, false]
            };
            let q = polish::minimise(a, b, start, movable, limits);
            if !q.converged {
                continue;
            }
            let value = signed(&q);
            if value < best.0 {
                best = (value, q);
            }
        }
    }
    best.1
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
        if p.pair.side(k == 1).2 != Held::Face {
            continue;
        }
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
/// is regular there, so an interior minimum is re-polished by it when it ends nearby. Between
/// two faces without trims, from A's face only (as it always was); otherwise from A's point,
/// else from B's (the descent of B's signed distance to A: where A's point touches B's edge or
/// vertex, A's signed distance to B has a kink at its minimum, B's along the edge does not),
/// and only to a descent that stays outside (a crossing must stay one for the penetration
/// search).
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
    let plain = p.pair.on_faces() && a.trim(p.pair.fa).is_none() && b.trim(p.pair.fb).is_none();
    for from_b in [false, true] {
        if plain && from_b {
            break;
        }
        let (x, y, pair) = if from_b {
            (b, a, p.pair.swapped())
        } else {
            (a, b, p.pair)
        };
        let Some(d) = penetration::descend(x, y, pair, spacing, limits) else {
            continue;
        };
        let moved = x
            .eval(d.pair.fa, d.pair.a[0], d.pair.a[1])
            .point
            .distance(x.eval_held(pair.fa, pair.a, pair.held_a).point);
        let outside = plain || d.value >= -10.0 * limits.tolerance;
        if !d.minimum || moved > spacing || !outside {
            continue;
        }
        let found = if from_b { d.pair.swapped() } else { d.pair };
        let q = penetration::settled(a, b, found, p.iterations, limits);
        if q.converged {
            return q;
        }
    }
    p
}

/// The reduced Hessian over the free parameters (those of the features the points are on, not
/// held at a bound), normalised by the parametric speeds (H_ij / (|c_i| |c_j|),
/// dimensionless), is positive semi-definite up to 1e-7. Parameters whose direction vanishes
/// (u at a pole) carry no information and are left out.
fn second_order_ok(p: &Polished) -> bool {
    let e = &p.eval;
    let scale = e.cols.iter().map(|c| c.length()).fold(0.0, f64::max);
    let dims = p.pair.dims();
    let free: Vec<usize> = (0..N)
        .filter(|&k| dims[k] && !p.active[k] && e.cols[k].length() > 1e-9 * scale)
        .collect();
    let mut m = [[0.0; N]; N];
    for (i, &ki) in free.iter().enumerate() {
        for (j, &kj) in free.iter().enumerate() {
            m[i][j] = e.h[ki][kj] / (e.cols[ki].length() * e.cols[kj].length());
        }
    }
    free.is_empty() || linalg::min_eigenvalue(&m, free.len()) >= -1e-7
}
