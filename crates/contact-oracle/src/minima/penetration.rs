//! Penetration witnesses: pairs where the surfaces overlap, locally deepest.
//!
//! The signed distance of A's surface to B, φ(u_a, v_a) = (S_a − S_b) · n_b at the foot S_b of
//! S_a on B (a point–surface Newton projection, [`crate::polishing::polish::minimise`] with A's
//! parameters frozen), is negative where A is inside B. A witness is a local minimum of φ with
//! φ < 0: there ∇φ = (n_b · S_a,u, n_b · S_a,v) = 0, so the connecting vector is anti-parallel
//! to both normals, and the pair is a saddle of f = ½|S_a − S_b|², finally polished by plain
//! Newton on ∇f = 0 ([`crate::polishing::polish::stationary`]).
//!
//! Starts: the deepest sample of each connected region of A's samples inside B, and every
//! crossing the minimum search ran into (a crossing too small to hold a sample is still found,
//! since φ descends from the crossing into the overlap).
//!
//! On a trimmed face of A the descent stays inside the trim (a step that leaves it is refused),
//! and a witness must lie inside it, away from its boundary; B's foot may be anywhere on B,
//! its faces, edges and vertices ([`crate::polishing::polish::minimise`]).

use crate::polishing::feature_moves::{self, MAX_SWITCHES, TrimStep};
use crate::polishing::linalg::{self, N};
use crate::polishing::pair::Pair;
use crate::polishing::polish::{self, Limits, Polished};
use crate::samples::kdtree::KdTree;
use crate::samples::sampling::Sample;
use crate::solids::held::Held;
use crate::solids::posed::PosedSolid;
use geom_param::{Boundary, ParamSide};

/// φ and its gradient at one point of A.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Phi {
    pair: Pair,
    value: f64,
    g: [f64; 2],
    /// |S_a,u|, |S_a,v|.
    speed: [f64; 2],
    /// B's unit outward normal at the foot.
    normal_b: Option<glam::DVec3>,
}

/// Projects A's point of `pair` onto B (from B's parameters in `pair`) and evaluates φ.
fn phi(a: &PosedSolid, b: &PosedSolid, pair: Pair, limits: &Limits) -> Option<Phi> {
    let p = polish::minimise(a, b, pair, [false, false, true, true], limits);
    if !p.converged {
        return None;
    }
    let e = &p.eval;
    let (value, nb) = if p.pair.held_b == Held::Face {
        let nb = b.normal(p.pair.fb, p.pair.b[0], p.pair.b[1])?;
        let value = if p.active[2] || p.active[3] {
            // The foot is on an edge of B's face: the signed distance is |r| with the side of
            // the face normal (exact for points beyond a ridge, whose foot is the ridge).
            e.r.length().copysign(e.r.dot(nb))
        } else {
            e.r.dot(nb)
        };
        (value, nb)
    } else {
        // The foot is held on an edge or at a vertex of B: φ = ±|r|, outside where r points
        // to the outer side of the adjacent faces; its gradient direction is r / φ.
        let outward = b.sign_normal(p.pair.fb, p.pair.b, p.pair.held_b)?;
        let value = e.r.length().copysign(e.r.dot(outward));
        let nb = (e.r / value).try_normalize().unwrap_or(outward);
        (value, nb)
    };
    Some(Phi {
        pair: p.pair,
        value,
        g: [nb.dot(e.pa.du), nb.dot(e.pa.dv)],
        speed: [e.pa.du.length(), e.pa.dv.length()],
        normal_b: Some(nb),
    })
}

/// The signed distance φ of A's point of `pair` (held where `pair` holds it) to B, and the pair
/// with B's foot, projected from B's parameters in `pair`; `None` when the projection does not
/// converge.
pub(crate) fn signed_distance(
    a: &PosedSolid,
    b: &PosedSolid,
    pair: Pair,
    limits: &Limits,
) -> Option<(f64, Pair)> {
    phi(a, b, pair, limits).map(|p| (p.value, p.pair))
}

/// Signed distance of the samples of `own` (A) to B that are inside B or near its surface
/// (`None` for the others). `near` holds each sample's nearest sample of `other` within the
/// sampled reach; samples less than a spacing in front of it are projected, and the inside
/// ones are grown by flood fill over `radius` neighbourhoods (a region deep inside B is
/// reached from its rim, each new sample projected from its neighbour's foot).
#[allow(clippy::too_many_arguments)]
pub(crate) fn signed_distances(
    a: &PosedSolid,
    b: &PosedSolid,
    own: &[Sample],
    own_tree: &KdTree,
    other: &[Sample],
    near: &[Option<(usize, f64)>],
    spacing: f64,
    radius: f64,
    limits: &Limits,
) -> Vec<Option<Phi>> {
    let mut phis: Vec<Option<Phi>> = vec![None; own.len()];
    let mut seen = vec![false; own.len()];
    let mut queue = Vec::new();
    for (i, s) in own.iter().enumerate() {
        let Some((j, _)) = near[i] else { continue };
        let o = &other[j];
        if (s.point - o.point).dot(o.normal) >= spacing {
            continue;
        }
        seen[i] = true;
        let start = Pair::faces(s.face, s.uv, o.face, o.uv);
        phis[i] = phi(a, b, start, limits);
        if phis[i].is_some_and(|p| p.value < 0.0) {
            queue.push(i);
        }
    }
    while let Some(i) = queue.pop() {
        let Some(from) = phis[i] else { continue };
        let mut around = Vec::new();
        own_tree.within(own[i].point, radius, &mut |k| around.push(k));
        for k in around {
            if seen[k] {
                continue;
            }
            seen[k] = true;
            let mut start = from.pair;
            (start.fa, start.a, start.held_a) = (own[k].face, own[k].uv, Held::Face);
            phis[k] = phi(a, b, start, limits);
            if phis[k].is_some_and(|p| p.value < 0.0) {
                queue.push(k);
            }
        }
    }
    phis
}

/// Connected regions (neighbourhood `radius`) of the samples with φ < 0; returns each
/// region's deepest sample's φ.
pub(crate) fn deepest_per_region(
    own: &[Sample],
    own_tree: &KdTree,
    phis: &[Option<Phi>],
    radius: f64,
) -> Vec<(usize, Pair)> {
    let inside: Vec<bool> = phis
        .iter()
        .map(|p| p.is_some_and(|p| p.value < 0.0))
        .collect();
    let mut parent: Vec<usize> = (0..own.len()).collect();
    fn root(parent: &mut [usize], mut i: usize) -> usize {
        while parent[i] != i {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        i
    }
    for i in (0..own.len()).filter(|&i| inside[i]) {
        let mut near = Vec::new();
        own_tree.within(own[i].point, radius, &mut |k| near.push(k));
        for k in near.into_iter().filter(|&k| inside[k]) {
            let (ri, rk) = (root(&mut parent, i), root(&mut parent, k));
            if ri != rk {
                parent[ri] = rk;
            }
        }
    }
    let mut best: std::collections::BTreeMap<usize, (f64, usize)> = Default::default();
    for i in (0..own.len()).filter(|&i| inside[i]) {
        let r = root(&mut parent, i);
        let value = phis[i].map_or(f64::INFINITY, |p| p.value);
        let entry = best.entry(r).or_insert((value, i));
        if value < entry.0 {
            *entry = (value, i);
        }
    }
    best.values()
        .filter_map(|&(_, i)| phis[i].map(|p| (i, p.pair)))
        .collect()
}

/// The end of a descent of φ: the pair, φ, and whether it is an interior local minimum of φ
/// (stationary to 1e-11 in the angle between the normals, Hessian positive semi-definite).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Descent {
    pub pair: Pair,
    pub value: f64,
    pub minimum: bool,
}

/// Descends φ from `start` by Levenberg–Marquardt on a finite-difference Hessian of the exact
/// gradient. A step is taken when φ decreases, or when φ stays within rounding (64 ulp of the
/// coordinates) and the gradient shrinks: near a touching contact (φ ≈ 0) φ is flat
/// to rounding over a region where its gradient is still well resolved, so the gradient is
/// what pins the point.
///
/// A's point descends over the features of A as [`polish::minimise`] moves over them: a step
/// that leaves a trimmed face stops on the crossed edge (and must lower φ), the point then
/// descends along the edge (t), onto its end vertex, and back into a face or along another
/// edge wherever φ descends there (slope below −1e-11 per unit length). An edge or vertex is
/// a minimum of φ when φ descends into none of its neighbours. (On a face without trim the
/// descent stops at the rectangle's sides, as it always did.)
pub(crate) fn descend(
    a: &PosedSolid,
    b: &PosedSolid,
    start: Pair,
    spacing: f64,
    limits: &Limits,
) -> Option<Descent> {
    const ANGLE: f64 = 1e-11;
    let mut x = phi(a, b, start, limits)?;
    let angle = |x: &Phi| {
        (0..2)
            .filter(|&k| x.speed[k] > 0.0)
            .map(|k| x.g[k].abs() / x.speed[k])
            .fold(0.0, f64::max)
    };
    // φ is known to rounding: 64 ulp of the coordinates.
    let coordinates = a
        .eval_held(x.pair.fa, x.pair.a, x.pair.held_a)
        .point
        .length();
    let flat = 64.0 * f64::EPSILON * (coordinates + spacing + x.value.abs());
    let mut mu = 1e-3;
    let mut hessian = [[0.0; N]; N];
    let mut stationary = false;
    let mut switches = 0;
    for _ in 0..100 {
        if switches < MAX_SWITCHES {
            let moved = feature_moves::leave(a, b, &x.pair, [x.normal_b, None], ANGLE)
                .and_then(|q| phi(a, b, q, limits));
            if let Some(t) = moved {
                x = t;
                switches += 1;
                continue;
            }
        }
        hessian = fd_hessian(a, b, &x, spacing, limits)?;
        if angle(&x) <= ANGLE {
            stationary = true;
            break;
        }
        let mut accepted = false;
        while mu < 1e16 {
            let mut m = hessian;
            for k in 0..2 {
                m[k][k] += mu * x.speed[k].powi(2).max(1e-12);
            }
            let Some(delta) = linalg::solve(&m, &[-x.g[0], -x.g[1], 0.0, 0.0], 2) else {
                mu *= 10.0;
                continue;
            };
            let reach = (delta[0] * x.speed[0])
                .abs()
                .max((delta[1] * x.speed[1]).abs());
            let scale = if reach > spacing {
                spacing / reach
            } else {
                1.0
            };
            let mut trial = x.pair;
            let mut cut = false;
            if x.pair.held_a == Held::Face {
                let raw = [trial.a[0] + scale * delta[0], trial.a[1] + scale * delta[1]];
                trial.a = a.normalize(trial.fa, raw);
                if !a.inside(trial.fa, trial.a) {
                    // Out of A's trimmed face: the step stops on the edge it crosses; on the
                    // boundary already, the point is held on its edge (a move, φ unchanged).
                    let mut q = x.pair;
                    q.a = raw;
                    match feature_moves::cut_at_trims(a, b, &x.pair, q, [true, true, false, false])
                    {
                        TrimStep::Inside(q) | TrimStep::Cut(q) => {
                            trial = polish::normalize(a, b, q);
                            cut = true;
                        }
                        TrimStep::Hold(q, _) => {
                            // Held on the edge unless φ descends into the face (then the
                            // step is refused and damped towards the gradient).
                            let stay = x.normal_b.is_some_and(|nb| {
                                feature_moves::stays_in_face(a, q.held_a, nb, ANGLE)
                            });
                            let hold = switches < MAX_SWITCHES && !stay;
                            let held = hold
                                .then(|| phi(a, b, polish::normalize(a, b, q), limits))
                                .flatten();
                            if let Some(t) = held {
                                x = t;
                                switches += 1;
                                accepted = true;
                                break;
                            }
                            mu *= 8.0;
                            continue;
                        }
                    }
                } else if let Some(held) = feature_moves::side_edge_crossed(a, trial.fa, raw) {
                    // Across a rectangle's side onto an edge of a general solid.
                    trial.held_a = held;
                    trial = polish::normalize(a, b, trial);
                    cut = true;
                }
            } else {
                polish::set(&mut trial, 0, polish::params(&x.pair, 0) + scale * delta[0]);
                trial = polish::normalize(a, b, trial);
            }
            match phi(a, b, trial, limits) {
                Some(t)
                    if t.value < x.value
                        || (!cut && t.value <= x.value + flat && angle(&t) < angle(&x)) =>
                {
                    x = t;
                    mu = (mu * 0.3).max(1e-15);
                    accepted = true;
                    break;
                }
                _ => mu *= 8.0,
            }
        }
        if !accepted {
            break;
        }
    }
    // Next to a pole the parametrisation is polar and the descent crawls: try the pole itself.
    let range = a.range(x.pair.fa, 1);
    for (bound, side) in [(range.min, ParamSide::VMin), (range.max, ParamSide::VMax)] {
        let near =
            (x.pair.a[1] - bound).abs() <= 1e-3 * range.span() && x.pair.held_a == Held::Face;
        if near && matches!(a.boundary(x.pair.fa, side), Boundary::Vertex(_)) {
            let mut pole = x.pair;
            pole.a[1] = bound;
            if let Some(t) = phi(a, b, pole, limits) {
                if t.value <= x.value + flat {
                    x = t;
                    // At the pole only one meridian is seen: stationary when no direction
                    // into the face descends (the pole is a smooth point or an apex).
                    stationary = pole_is_stationary(a, &x);
                }
            }
        }
    }
    let (interior, convex) = if x.pair.held_a == Held::Face {
        // A pole is a smooth interior point of the surface; edges (and trim boundaries) are
        // not.
        let interior = a.interior(x.pair.fa, x.pair.a);
        let mut m = [[0.0; N]; N];
        for i in 0..2 {
            for j in 0..2 {
                m[i][j] = hessian[i][j] / (x.speed[i] * x.speed[j]);
            }
        }
        // At a pole (|S_u| -> 0) the normalised Hessian is meaningless; the pole test above
        // already required no descent in any direction.
        let usable = x.speed[0] > 1e-9 * x.speed[1] && x.speed[1] > 1e-9 * x.speed[0];
        (interior, !usable || linalg::min_eigenvalue(&m, 2) >= -1e-6)
    } else {
        // On an edge or at a vertex: no descent into a neighbouring feature (the normal cone
        // condition), and on an edge φ'' >= 0 along it.
        let settled = feature_moves::leave(a, b, &x.pair, [x.normal_b, None], ANGLE).is_none();
        let curved = x.speed[0] == 0.0 || hessian[0][0] / (x.speed[0] * x.speed[0]) >= -1e-6;
        (settled, curved)
    };
    Some(Descent {
        pair: x.pair,
        value: x.value,
        minimum: stationary && interior && convex,
    })
}

/// Whether φ has no descent into the face from the pole where `x` sits: the slope of φ along
/// S_v is n_b · S_v, probed over 32 meridians.
fn pole_is_stationary(a: &PosedSolid, x: &Phi) -> bool {
    let Some(nb) = x.normal_b else { return false };
    let range = a.range(x.pair.fa, 0);
    let vr = a.range(x.pair.fa, 1);
    let inward = if x.pair.a[1] <= vr.min { 1.0 } else { -1.0 };
    (0..32).all(|k| {
        let u = range.min + range.span() * f64::from(k) / 32.0;
        let s = a.eval(x.pair.fa, u, x.pair.a[1]);
        let w = s.dv * inward;
        nb.dot(w) >= -1e-11 * w.length()
    })
}

/// A penetration witness from `start`: the descent must end at an interior local minimum of φ
/// with φ < 0; the pair is then polished by plain Newton on ∇f = 0, kept when it converges
/// nearby and at the descent's depth (| |r| − |φ| | <= 10 x tolerance), else the descent's own
/// pair is returned with its residual.
///
/// The depth condition matters where φ's minimum is not a smooth stationary pair, e.g. at an
/// apex of A inside B: ∇f also vanishes wherever f = 0, on the curve where the surfaces cross,
/// and Newton from the apex can land there (|r| ~ 0, normals not opposite). Such a point is a
/// crossing, not a witness of the depth the descent found.
pub(crate) fn witness(
    a: &PosedSolid,
    b: &PosedSolid,
    start: Pair,
    spacing: f64,
    limits: &Limits,
) -> Option<Polished> {
    let d = descend(a, b, start, spacing, limits)?;
    if !(d.minimum && d.value < 0.0) {
        return None;
    }
    let polished = polish::stationary(a, b, d.pair, limits);
    let near = a.eval(d.pair.fa, d.pair.a[0], d.pair.a[1]).point;
    let same_depth = (polished.eval.r.length() - d.value.abs()).abs() <= 10.0 * limits.tolerance;
    // Newton is unconstrained: a free point must still lie in its face's region.
    let q = &polished.pair;
    let in_regions = (q.held_a != Held::Face || a.inside(q.fa, q.a))
        && (q.held_b != Held::Face || b.inside(q.fb, q.b));
    if polished.converged
        && same_depth
        && in_regions
        && polished.eval.pa.point.distance(near) <= spacing
    {
        return Some(polished);
    }
    Some(settled(a, b, d.pair, polished.iterations, limits))
}

/// A pair taken as it is, with its stationarity residual.
pub(crate) fn settled(
    a: &PosedSolid,
    b: &PosedSolid,
    pair: Pair,
    iterations: u32,
    limits: &Limits,
) -> Polished {
    let e = polish::evaluate(a, b, &pair);
    let residual = polish::residual(&e, pair.dims(), [false; N]);
    Polished {
        pair,
        eval: e,
        residual,
        active: [false; N],
        iterations,
        converged: residual <= limits.tolerance,
    }
}

/// Central-difference Hessian of φ from its exact gradient (steps of about 1e-4 spacing in 3-d)
/// over the parameters of A's feature (u, v on a face, t on an edge, none at a vertex).
fn fd_hessian(
    a: &PosedSolid,
    b: &PosedSolid,
    x: &Phi,
    spacing: f64,
    limits: &Limits,
) -> Option<[[f64; N]; N]> {
    let mut h = [[0.0; N]; N];
    let dims = x.pair.held_a.dims();
    for k in (0..2).filter(|&k| dims[k]) {
        let step = if x.speed[k] > 1e-9 * spacing {
            1e-4 * spacing / x.speed[k]
        } else {
            1e-6
        };
        let range = match x.pair.held_a {
            Held::Edge { edge, .. } => a.solid.edge(edge).curve.domain(),
            _ => a.range(x.pair.fa, k),
        };
        let at = polish::params(&x.pair, k);
        let (mut up, mut down) = (at + step, at - step);
        if !range.periodic {
            up = up.min(range.max);
            down = down.max(range.min);
        }
        let width = up - down;
        if width <= 0.0 {
            return None;
        }
        let mut lo = x.pair;
        let mut hi = x.pair;
        polish::set(&mut hi, k, up);
        polish::set(&mut lo, k, down);
        let (gp, gm) = (phi(a, b, hi, limits)?, phi(a, b, lo, limits)?);
        for j in 0..2 {
            h[j][k] = (gp.g[j] - gm.g[j]) / width;
        }
    }
    let off = 0.5 * (h[0][1] + h[1][0]);
    h[0][1] = off;
    h[1][0] = off;
    Some(h)
}
