//! Moves of a polished point between the features of its solid, where the face's region is
//! not its parameter rectangle (a trim) or an edge has ends: out of a trimmed face onto the
//! edge a step crossed, off an edge into a face or onto its end vertex, and off a vertex along
//! an edge or into a face.
//!
//! These generalise the rectangle's bound constraints (an active parameter at a side) to "stay
//! in the face's region": a point held on an edge has the edge's t as its only parameter, and
//! it is a constrained stationary point when f does not descend into either face (the
//! connecting vector lies in the edge's normal cone); a vertex, when f descends along none of
//! its edges and into none of its faces.

use crate::polishing::linalg::N;
use crate::polishing::pair::Pair;
use crate::solids::held::Held;
use crate::solids::posed::PosedSolid;
use geom_param::{EdgeOn, FaceId, ParamSide};
use glam::{DVec2, DVec3};

/// Moves between features before a polish gives up (guards against cycling).
pub(crate) const MAX_SWITCHES: u32 = 64;
/// Length of the probe step into a face from a vertex, relative to the face's (u, v) extent.
const PROBE: f64 = 1e-7;

/// The point on the trim boundary of `face` nearest to (u, v), held on its edge.
fn onto_boundary(solid: &PosedSolid, face: FaceId, uv: [f64; 2]) -> Option<([f64; 2], Held)> {
    let trim = solid.trim(face)?;
    let near = trim.nearest(DVec2::from(uv))?;
    let edge = trim.loops[near.loop_index].entries[near.index].edge;
    let on = EdgeOn::Trim {
        loop_index: u32::try_from(near.loop_index).ok()?,
        index: u32::try_from(near.index).ok()?,
    };
    let uses = solid.solid.edge(edge).uses;
    let use_index = uses
        .iter()
        .position(|u| u.face == face && u.on == on)
        .unwrap_or_else(|| solid.use_on(edge, face));
    let held = Held::Edge {
        edge,
        t: near.t,
        use_index,
    };
    Some((solid.use_params(&uses[use_index], near.t), held))
}

/// `p` with every movable point that is free on a trimmed face outside its trim moved onto
/// the nearest point of the trim's boundary, held on that edge.
pub(crate) fn enter_trims(a: &PosedSolid, b: &PosedSolid, mut p: Pair, movable: [bool; N]) -> Pair {
    for (on_a, solid) in [(true, a), (false, b)] {
        let (face, uv, held) = p.side(on_a);
        let k = if on_a { 0 } else { 2 };
        if held != Held::Face || !(movable[k] || movable[k + 1]) || solid.inside(face, uv) {
            continue;
        }
        if let Some((uv, held)) = onto_boundary(solid, face, uv) {
            p.set_side(on_a, face, uv, held);
        }
    }
    p
}

/// What became of a step with respect to the trims of the faces it moves on.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum TrimStep {
    /// The step stays in every trim: the trial pair unchanged.
    Inside(Pair),
    /// The step leaves a trim part way: the trial pair with that point stopped on the crossed
    /// edge, held there.
    Cut(Pair),
    /// The step leaves a trim right where it starts (the point is on the boundary and the
    /// step points out): the start with that point (A's when the flag is true) held on the
    /// boundary's edge, a move to take without a step unless [`stays_in_face`].
    Hold(Pair, bool),
}

/// The step from `p` to `q` (same features, parameters not yet normalised) checked against
/// the trims of the movable points free on trimmed faces (see [`TrimStep`]). The crossing is
/// the first one of the step's segment with the trim's polylines (the start itself when none
/// is found: it lies within the polylines' flatness of the boundary), projected onto the exact
/// boundary.
pub(crate) fn cut_at_trims(
    a: &PosedSolid,
    b: &PosedSolid,
    p: &Pair,
    mut q: Pair,
    movable: [bool; N],
) -> TrimStep {
    let mut cut = false;
    for (on_a, solid) in [(true, a), (false, b)] {
        let (face, from, held) = p.side(on_a);
        let to = q.side(on_a).1;
        let k = if on_a { 0 } else { 2 };
        if held != Held::Face || !(movable[k] || movable[k + 1]) || solid.inside(face, to) {
            continue;
        }
        let Some(trim) = solid.trim(face) else {
            continue;
        };
        let start = trim.unwrap(DVec2::from(from));
        let step = DVec2::from(to) - DVec2::from(from);
        let mut first = f64::INFINITY;
        for l in &trim.loops {
            for (p, q) in l.segments() {
                // start + s step = p + w (q − p), s and w in [0, 1].
                let e = q - p;
                let den = step.perp_dot(e);
                if den == 0.0 {
                    continue;
                }
                let d = p - start;
                let (s, w) = (d.perp_dot(e) / den, d.perp_dot(step) / den);
                if (0.0..=1.0).contains(&s) && (0.0..=1.0).contains(&w) {
                    first = first.min(s);
                }
            }
        }
        // Within rounding of the start (or no crossing found): the point is on the boundary.
        let at_start = first.is_infinite() || first <= 1e-12;
        let first = if at_start { 0.0 } else { first };
        let crossing = (start + first * step).to_array();
        if let Some((uv, held)) = onto_boundary(solid, face, crossing) {
            if at_start {
                let mut hold = *p;
                hold.set_side(on_a, face, uv, held);
                return TrimStep::Hold(hold, on_a);
            }
            q.set_side(on_a, face, uv, held);
            cut = true;
        }
    }
    if cut {
        TrimStep::Cut(q)
    } else {
        TrimStep::Inside(q)
    }
}

/// For a face without trim and a step to `raw` (u, v) that leaves its rectangle across a side
/// bounded by an edge with a use on a trimmed face (an edge of a general solid, not one between
/// two rectangles): that edge at the running parameter, clamped into the rectangle.
pub(crate) fn side_edge_crossed(solid: &PosedSolid, face: FaceId, raw: [f64; 2]) -> Option<Held> {
    if solid.trim(face).is_some() {
        return None;
    }
    let clamped = solid.normalize(face, raw);
    for index in 0..2 {
        let range = solid.range(face, index);
        if range.periodic || (raw[index] >= range.min && raw[index] <= range.max) {
            continue;
        }
        let side = match (index, raw[index] < range.min) {
            (0, true) => ParamSide::UMin,
            (0, false) => ParamSide::UMax,
            (_, true) => ParamSide::VMin,
            (_, false) => ParamSide::VMax,
        };
        let Some(held @ Held::Edge { edge, .. }) = solid.edge_on_side(face, side, clamped) else {
            continue;
        };
        let uses = solid.solid.edge(edge).uses;
        if uses.iter().any(|u| matches!(u.on, EdgeOn::Trim { .. })) {
            return Some(held);
        }
    }
    None
}

/// Whether (u, v) a tiny step from a corner lies in `face`'s region: inside the trim, or for a
/// face without trim inside the rectangle of the domain.
fn in_region(solid: &PosedSolid, face: FaceId, uv: DVec2) -> bool {
    match solid.trim(face) {
        Some(_) => solid.contains(face, uv.to_array(), 0.0),
        None => (0..2).all(|i| {
            let r = solid.range(face, i);
            r.periodic || (uv[i] >= r.min && uv[i] <= r.max)
        }),
    }
}

/// A face's (u, v) extent: its trim's box or its domain.
fn extent(solid: &PosedSolid, face: FaceId) -> f64 {
    match solid.trim(face) {
        Some(_) => solid.trim_extent(face),
        None => solid.range(face, 0).span().max(solid.range(face, 1).span()),
    }
}

/// The first move off an edge or vertex with descent, for A's point then B's: from an edge at
/// an end where descent runs past it, onto the end vertex; from an edge, into the face with
/// the steepest descent across it (slope below −`tolerance`); from a vertex, along the edge or
/// into the face with the steepest descent below −`tolerance`. `rates[0]` (A) and `rates[1]`
/// (B) are the gradients of the objective with respect to the point's position (the objective
/// changes by rate · w when the point moves by w), `None` for a point that does not move.
pub(crate) fn leave(
    a: &PosedSolid,
    b: &PosedSolid,
    p: &Pair,
    rates: [Option<DVec3>; 2],
    tolerance: f64,
) -> Option<Pair> {
    for (on_a, solid, rate) in [(true, a, rates[0]), (false, b, rates[1])] {
        let Some(rate) = rate else {
            continue;
        };
        let found = match p.side(on_a).2 {
            Held::Face => None,
            Held::Edge { edge, t, .. } => leave_edge(solid, p, on_a, rate, edge, t, tolerance),
            Held::Vertex(vertex) => leave_vertex(solid, p, on_a, rate, vertex, tolerance),
        };
        if found.is_some() {
            return found;
        }
    }
    None
}

/// The moves off an edge (see [`leave`]).
fn leave_edge(
    solid: &PosedSolid,
    p: &Pair,
    on_a: bool,
    rate: DVec3,
    edge: geom_param::EdgeId,
    t: f64,
    tolerance: f64,
) -> Option<Pair> {
    let mut q = *p;
    let curve = &solid.solid.edge(edge).curve;
    let range = curve.domain();
    let at_end = !range.periodic && (t <= range.min || t >= range.max);
    if at_end {
        let at_start = t <= range.min;
        let inward = if at_start { 1.0 } else { -1.0 };
        let d1 = solid.eval_edge(edge, t).d1;
        let slope = inward * rate.dot(d1) / d1.length().max(f64::MIN_POSITIVE);
        if slope >= 0.0 {
            if let Some(ends) = solid.solid.edge(edge).ends {
                let (face, uv, _) = p.side(on_a);
                let vertex = ends[usize::from(!at_start)];
                q.set_side(on_a, face, uv, Held::Vertex(vertex));
                return Some(q);
            }
        }
    }
    let uses = solid.solid.edge(edge).uses;
    let mut best: Option<(f64, usize)> = None;
    for (i, use_) in uses.iter().enumerate() {
        let Some(w) = solid.inward(use_, t) else {
            continue;
        };
        let slope = rate.dot(w);
        if best.is_none_or(|(s, _)| slope < s) {
            best = Some((slope, i));
        }
    }
    let (slope, i) = best?;
    if slope >= -tolerance {
        return None;
    }
    q.set_side(
        on_a,
        uses[i].face,
        solid.use_params(&uses[i], t),
        Held::Face,
    );
    Some(q)
}

/// The steepest descent of an objective with gradient `rate` (world frame) at (u, v) of
/// `face`, if it enters the face's region: its slope (per unit length) and the point a probe
/// step (1e-7 of the face's (u, v) extent) along it.
fn descent_into_face(
    solid: &PosedSolid,
    face: FaceId,
    uv: [f64; 2],
    rate: DVec3,
) -> Option<(f64, [f64; 2])> {
    let s = solid.eval(face, uv[0], uv[1]);
    let g = DVec2::new(rate.dot(s.du), rate.dot(s.dv));
    let (guu, guv, gvv) = (s.du.dot(s.du), s.du.dot(s.dv), s.dv.dot(s.dv));
    let det = guu * gvv - guv * guv;
    // Also refuses a NaN determinant.
    if det.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
        return None;
    }
    let d = -DVec2::new(gvv * g.x - guv * g.y, guu * g.y - guv * g.x) / det;
    let unit = d.try_normalize()?;
    let probe = DVec2::from(uv) + unit * PROBE * extent(solid, face);
    if !in_region(solid, face, probe) {
        return None;
    }
    let w = (s.du * d.x + s.dv * d.y).try_normalize()?;
    Some((rate.dot(w), probe.to_array()))
}

/// Whether a point held on an edge (by [`TrimStep::Hold`]) should stay free on the face
/// instead, under an objective with gradient `rate`: at an interior point of the edge, when
/// the objective descends across it into the face (slope below −`tolerance`, as [`leave`]
/// releases it); at an end of the edge (a corner of the face, where the direction across the
/// edge need not enter the face), when its steepest descent enters the face.
pub(crate) fn stays_in_face(solid: &PosedSolid, held: Held, rate: DVec3, tolerance: f64) -> bool {
    let Held::Edge {
        edge, t, use_index, ..
    } = held
    else {
        return false;
    };
    let range = solid.solid.edge(edge).curve.domain();
    let use_ = solid.solid.edge(edge).uses[use_index];
    let at_end = !range.periodic && (t <= range.min || t >= range.max);
    if at_end {
        let uv = solid.use_params(&use_, t);
        descent_into_face(solid, use_.face, uv, rate).is_some_and(|(s, _)| s < -tolerance)
    } else {
        solid
            .inward(&use_, t)
            .is_some_and(|w| rate.dot(w) < -tolerance)
    }
}

/// The moves off a vertex (see [`leave`]).
fn leave_vertex(
    solid: &PosedSolid,
    p: &Pair,
    on_a: bool,
    rate: DVec3,
    vertex: geom_param::VertexId,
    tolerance: f64,
) -> Option<Pair> {
    // (slope, face, uv, feature)
    let mut best: Option<(f64, FaceId, [f64; 2], Held)> = None;
    let mut consider = |slope: f64, face: FaceId, uv: [f64; 2], held: Held| {
        if best.is_none_or(|(s, ..)| slope < s) {
            best = Some((slope, face, uv, held));
        }
    };
    for (edge, t, direction) in solid.edges_leaving(vertex) {
        let uses = solid.solid.edge(edge).uses;
        consider(
            rate.dot(direction),
            uses[0].face,
            solid.use_params(&uses[0], t),
            Held::Edge {
                edge,
                t,
                use_index: 0,
            },
        );
        // Into a face: its steepest descent direction at the corner, if it points into the
        // face's region (otherwise the best direction into the face runs along one of the
        // edges that bound it there, already considered). The point enters the face a probe
        // step along it, so that the next step starts off the boundary.
        for use_ in &uses {
            let uv = solid.use_params(use_, t);
            if let Some((slope, probe)) = descent_into_face(solid, use_.face, uv, rate) {
                consider(slope, use_.face, probe, Held::Face);
            }
        }
    }
    let (slope, face, uv, held) = best?;
    if slope >= -tolerance {
        return None;
    }
    let mut q = *p;
    q.set_side(on_a, face, uv, held);
    Some(q)
}

/// Whether `n` (unit, world frame) lies in the outward normal cone of the held point
/// (`face`, `uv`, `held`), to 1e-6 in angle: n · w <= 1e-6 for every direction w leading off
/// the point into the solid's surface (into either face of an edge, ±along the edge, along
/// every edge of a vertex), and n on the outer side of [`PosedSolid::sign_normal`]. On a face,
/// n must be the face's normal.
pub(crate) fn in_normal_cone(
    solid: &PosedSolid,
    face: FaceId,
    uv: [f64; 2],
    held: Held,
    n: DVec3,
) -> bool {
    const ANGLE: f64 = 1e-6;
    let outer = solid
        .sign_normal(face, uv, held)
        .is_some_and(|s| n.dot(s) > 0.0);
    match held {
        Held::Face => solid
            .normal(face, uv[0], uv[1])
            .is_some_and(|m| (m - n).length() <= ANGLE),
        Held::Edge { edge, t, .. } => {
            let along = solid.eval_edge(edge, t).d1.normalize_or_zero();
            outer
                && n.dot(along).abs() <= ANGLE
                && solid
                    .solid
                    .edge(edge)
                    .uses
                    .iter()
                    .filter_map(|u| solid.inward(u, t))
                    .all(|w| n.dot(w) <= ANGLE)
        }
        Held::Vertex(vertex) => {
            outer
                && solid
                    .edges_leaving(vertex)
                    .into_iter()
                    .all(|(_, _, w)| n.dot(w) <= ANGLE)
        }
    }
}
