//! Feature switching: keeping parameters in their domains by wrapping periodic ones and moving
//! onto the bounding edge or vertex when a face parameter reaches its side, and back into an
//! adjacent face when the objective decreases into it.

use crate::features::feature_eval::{Body, Frame, Loc, LocalFacePoint, side_of, wrap};
use geom_param::{
    Boundary, DVec2, DVec3, EdgeId, EdgeUse, FaceId, FeatureId, FeatureLocation, ParamRange,
    ParamSide, PoleMeridians, Solid, SurfacePoint, meridian_tangent,
};

/// The parameter across a face side that collapses into a smooth pole, moved from
/// `x` (on the side) into the face by the pull's component along the meridian `tangent` (the
/// side's inward direction, ∂S/∂x turned inward, in the pull's frame), at most a quarter of the range: the first
/// Newton step along that meridian where f's Hessian there is about the identity (a dome's
/// pole under a plane: the point moves by the connecting vector's tangential component).
/// `x` where the pull does not enter the face.
///
/// Why not the side itself: there the other parameter runs around the vertex at zero speed, so
/// it is no coordinate, and the Newton system in it is singular to rounding (scaled Hessian
/// entries |d| |∂²S/∂u∂v| / speed floor ~ 1e6): the steps from the pole were 1e-10 mm long,
/// and the solve either crept around the pole (u jumping between meridians, 80 steps) or went
/// back onto the vertex and cycled to the feature-switch limit (a paperweight's dome pole
/// 0.0146 mm from a tilted flat bottom, where the witness lies 0.73 mm off the pole).
fn off_vertex(range: &ParamRange, side: ParamSide, x: f64, tangent: DVec3, pull: DVec3) -> f64 {
    let speed = tangent.length();
    let along = pull.dot(tangent.normalize_or_zero());
    if !(speed > 0.0 && along > 0.0) {
        return x;
    }
    let inward = match side {
        ParamSide::UMin | ParamSide::VMin => 1.0,
        ParamSide::UMax | ParamSide::VMax => -1.0,
    };
    let step = (along / speed).min(0.25 * range.span());
    if !step.is_finite() {
        return x;
    }
    x + inward * step
}

/// Wraps periodic parameters, clamps the others, and where a non-periodic face parameter is on
/// its side switches to what lies beyond it: the edge (with t = the parameter running along the
/// side) or the vertex the side collapses into.
pub(crate) fn settle(body: &Body, loc: Loc) -> Loc {
    let Body::Solid { solid, .. } = body else {
        return loc;
    };
    match loc {
        Some(FeatureLocation::Face { id, u, v }) => {
            let face = solid.face(id);
            let domain = face.surface.domain();
            let w = [wrap(&domain[0], u), wrap(&domain[1], v)];
            if let Some(trim) = &face.trim {
                return Some(settle_trimmed(solid, id, trim, [u, v]));
            }
            for i in 0..2 {
                let range = domain[i];
                if range.periodic || (w[i] > range.min && w[i] < range.max) {
                    continue;
                }
                match face.boundary(side_of(i, w[i] >= range.max)) {
                    Boundary::Edge(e) => {
                        let side = side_of(i, w[i] >= range.max);
                        let on = solid
                            .edge(e)
                            .uses
                            .iter()
                            .find(|u| u.face == id && u.on.side() == Some(side))
                            .map_or(geom_param::EdgeOn::Side(side), |u| u.on);
                        let t = wrap(&solid.edge(e).curve.domain(), on.edge_param(w[1 - i]));
                        return Some(FeatureLocation::Edge { id: e, t });
                    }
                    Boundary::Vertex(vertex) => {
                        return Some(FeatureLocation::Vertex { id: vertex });
                    }
                    Boundary::Periodic | Boundary::Trimmed => {}
                }
            }
            Some(FeatureLocation::Face {
                id,
                u: w[0],
                v: w[1],
            })
        }
        Some(FeatureLocation::Edge { id, t }) => {
            let edge = solid.edge(id);
            let range = edge.curve.domain();
            match edge.ends {
                Some([start, _]) if !range.periodic && t <= range.min => {
                    Some(FeatureLocation::Vertex { id: start })
                }
                Some([_, end]) if !range.periodic && t >= range.max => {
                    Some(FeatureLocation::Vertex { id: end })
                }
                _ => Some(FeatureLocation::Edge {
                    id,
                    t: wrap(&range, t),
                }),
            }
        }
        other => other,
    }
}

/// [`settle`] on a trimmed face: the face location where (u, v) lies in the trimmed region
/// (within rounding of the model tolerance), otherwise the nearest point of the trim's
/// boundary, on the edge it belongs to (or, at the edge's end, its vertex).
fn settle_trimmed(
    solid: &geom_param::Solid,
    id: geom_param::FaceId,
    trim: &geom_param::Trim,
    uv: [f64; 2],
) -> FeatureLocation {
    match outside_trim(trim, uv) {
        (_, Some(near)) => boundary_location(solid, trim, near),
        // Keep the unwrapped parameters: the trim's loops live there, and evaluation wraps.
        (p, None) => FeatureLocation::Face { id, u: p.x, v: p.y },
    }
}

/// `uv` unwrapped ([`geom_param::Trim::unwrap`]), with its nearest boundary point when it lies
/// outside the trimmed region (beyond rounding of the model tolerance); `None` inside it and
/// for a trim without loops.
fn outside_trim(trim: &geom_param::Trim, uv: [f64; 2]) -> (DVec2, Option<geom_param::TrimNearest>) {
    let p = trim.unwrap(DVec2::new(uv[0], uv[1]));
    let (lo, hi) = trim.bounds();
    let rounding = 16.0 * f64::EPSILON * (hi - lo).max_element().max(1.0);
    if trim.contains(p, rounding) {
        return (p, None);
    }
    (p, trim.nearest(p))
}

/// [`settle`] for the end `to` of a step from `from`, with where the step left its face's
/// trimmed region when it did (both on the same face): the fraction β in [0, 1) of the step at
/// which it crosses the trim's boundary, taken as the line through the boundary point nearest
/// to `to`, normal to the offset of `to` from it (exact for a straight trim, to second order in
/// the step for a curved one), and the edge location of the boundary point nearest to the cut
/// point `from + β (to − from)`. No crossing for a step that does not approach that line.
///
/// Why: a parameter rectangle's side cuts the step where it is reached
/// ([`crate::solver::newton::take_step`]), so that both features move by the same fraction
/// of their Newton step; a trim's boundary did not, and the point beyond it was put on its
/// nearest boundary point while the other feature took its whole step. A tube's top face
/// (trimmed by its rims) under a loft: the face-face step ran 0.8 mm past the rim, the loft's
/// point went 0.8 mm the wrong way, and the solve spent four rejected or shrunken steps
/// reaching the rim edge, where the minimum was.
///
/// Inlined, so that the steps on features other than trimmed faces (every step of a solid of
/// revolution) pay only for the test that sends them to [`settle`].
#[inline]
pub(crate) fn settle_step(
    body: &Body,
    from: &Loc,
    to: Loc,
) -> (Loc, Option<(f64, FeatureLocation)>) {
    if let (Body::Solid { solid, .. }, Some(FeatureLocation::Face { id, u, v })) = (body, to)
        && let Some(trim) = &solid.face(id).trim
    {
        settle_trimmed_step(solid, trim, from, (id, [u, v]))
    } else {
        (settle(body, to), None)
    }
}

/// [`settle_step`] for the end `uv` of a step on trimmed face `id`.
fn settle_trimmed_step(
    solid: &Solid,
    trim: &geom_param::Trim,
    from: &Loc,
    (id, [u, v]): (FaceId, [f64; 2]),
) -> (Loc, Option<(f64, FeatureLocation)>) {
    let (end, near) = outside_trim(trim, [u, v]);
    let Some(near) = near else {
        let inside = FeatureLocation::Face {
            id,
            u: end.x,
            v: end.y,
        };
        return (Some(inside), None);
    };
    let settled = boundary_location(solid, trim, near);
    let Some(FeatureLocation::Face {
        id: from_id,
        u: u0,
        v: v0,
    }) = *from
    else {
        return (Some(settled), None);
    };
    if from_id != id {
        return (Some(settled), None);
    }
    // The start shifted by the same whole periods as the end.
    let start = DVec2::new(u0, v0) + (end - DVec2::new(u, v));
    let outward = end - near.point;
    let (approach, room) = (outward.dot(end - start), outward.dot(near.point - start));
    if !(approach > 0.0 && room.is_finite()) {
        return (Some(settled), None);
    }
    let beta = (room / approach).clamp(0.0, 1.0);
    let on = onto_trim_boundary(solid, id, trim, start + beta * (end - start));
    let crossing =
        (beta < 1.0 && !matches!(on, FeatureLocation::Face { .. })).then_some((beta, on));
    (Some(settled), crossing)
}

/// The nearest point of `trim`'s boundary to `p` (unwrapped, see [`geom_param::Trim::unwrap`])
/// on face `id`, as the edge location there (or, at the edge's end, its vertex); the face
/// location `p` for a trim without loops.
fn onto_trim_boundary(
    solid: &geom_param::Solid,
    id: geom_param::FaceId,
    trim: &geom_param::Trim,
    p: DVec2,
) -> FeatureLocation {
    let Some(near) = trim.nearest(p) else {
        return FeatureLocation::Face { id, u: p.x, v: p.y };
    };
    boundary_location(solid, trim, near)
}

/// The edge location of the trim's boundary point `near` (or, at the edge's end, its vertex).
fn boundary_location(
    solid: &geom_param::Solid,
    trim: &geom_param::Trim,
    near: geom_param::TrimNearest,
) -> FeatureLocation {
    let entry = &trim.loops[near.loop_index].entries[near.index];
    let edge_loc = Some(FeatureLocation::Edge {
        id: entry.edge,
        t: near.t,
    });
    settle(
        &Body::Solid {
            solid,
            frame: crate::features::feature_eval::Frame::identity(),
            within: None,
        },
        edge_loc,
    )
    .unwrap_or(FeatureLocation::Edge {
        id: entry.edge,
        t: near.t,
    })
}

/// [`settle`] for the start of a solve: a face parameter whose point lies within coordinate
/// rounding (16 ε x max(1, |S(u, v)|) mm along the face) of a non-periodic side is put on
/// that side first, so that the start is the edge or vertex there ([`snap_to_sides`]).
///
/// Why: a seed on an edge that went through a change of frame arrives a few ulps inside the
/// face (v = 1 − 6e-16 at the goblet's rim); started there, the pair solve treats the edge's
/// point as an interior face point, and the face-face penetration solve that follows has no
/// witness to converge to (the witness is on the edge) and wanders off.
///
/// `known` receives the face's evaluation at the start, for the solve's first state
/// ([`Body::eval_reusing`]).
pub(crate) fn settle_start(body: &Body, loc: Loc, known: &mut Option<LocalFacePoint>) -> Loc {
    snap_within(
        body,
        loc,
        |at| 16.0 * f64::EPSILON * at.point.length().max(1.0),
        known,
    )
}

/// [`settle`] after putting each non-periodic face parameter whose point lies within
/// `relative` x max(1, |S(u, v)|) mm (along the face, to first order) of its side onto that
/// side; on a trimmed face, the point onto the nearest boundary edge when that edge's point is
/// within the same distance.
pub(crate) fn snap_to_sides(body: &Body, loc: Loc, relative: f64) -> Loc {
    snap_within(
        body,
        loc,
        |at| relative * at.point.length().max(1.0),
        &mut None,
    )
}

/// [`settle`] after putting each non-periodic face parameter whose point lies within `reach`
/// mm (along the face, to first order) of its side onto that side.
pub(crate) fn snap_within_distance(body: &Body, loc: Loc, reach: f64) -> Loc {
    snap_within(body, loc, |_| reach, &mut None)
}

/// The snap of [`snap_to_sides`] with the reach (mm) a function of the face's point; `known`
/// receives the face's evaluation it took (at the wrapped start parameters), which is the first
/// evaluation of the result when that is the same face point ([`Body::eval_reusing`] checks).
fn snap_within(
    body: &Body,
    loc: Loc,
    reach: impl Fn(&SurfacePoint) -> f64,
    known: &mut Option<LocalFacePoint>,
) -> Loc {
    let (Body::Solid { solid, .. }, Some(FeatureLocation::Face { id, u, v })) = (body, loc) else {
        return settle(body, loc);
    };
    let face = solid.face(id);
    let surface = &face.surface;
    let domain = surface.domain();
    let mut w = [wrap(&domain[0], u), wrap(&domain[1], v)];
    let known = known.insert(LocalFacePoint {
        face: id,
        uv: w,
        at: surface.eval(w[0], w[1]),
    });
    let at = &known.at;
    let reach = reach(at);
    if let Some(trim) = &face.trim {
        // A trimmed face's sides are its trim's edges: the nearest boundary point, if its
        // point is within reach of the face's.
        if let Some(near) = trim.nearest(DVec2::new(u, v)) {
            let edge = trim.loops[near.loop_index].entries[near.index].edge;
            if solid.eval_edge(edge, near.t).point.distance(at.point) <= reach {
                let on_edge = Some(FeatureLocation::Edge {
                    id: edge,
                    t: near.t,
                });
                return settle(body, on_edge);
            }
        }
        return settle(body, loc);
    }
    for (i, speed) in [at.du.length(), at.dv.length()].into_iter().enumerate() {
        let range = domain[i];
        if range.periodic {
            continue;
        }
        for bound in [range.min, range.max] {
            if (w[i] - bound).abs() * speed <= reach {
                w[i] = bound;
            }
        }
    }
    let snapped = Some(FeatureLocation::Face {
        id,
        u: w[0],
        v: w[1],
    });
    settle(body, snapped)
}

/// A face location moved onto the nearest edge bounding its face: the nearest point of a
/// trim's boundary, or of the rectangle's non-periodic sides that are edges (nearest in space,
/// at the same running parameter); settled, so an edge's end becomes its vertex. Edge and
/// vertex locations, and faces with no bounding edge, are returned unchanged.
pub(crate) fn onto_nearest_edge(body: &Body, loc: Loc) -> Loc {
    let (Body::Solid { solid, .. }, Some(FeatureLocation::Face { id, u, v })) = (body, loc) else {
        return loc;
    };
    let face = solid.face(id);
    if let Some(trim) = &face.trim {
        let Some(near) = trim.nearest(DVec2::new(u, v)) else {
            return loc;
        };
        let edge = trim.loops[near.loop_index].entries[near.index].edge;
        return settle(
            body,
            Some(FeatureLocation::Edge {
                id: edge,
                t: near.t,
            }),
        );
    }
    let domain = face.surface.domain();
    let w = [wrap(&domain[0], u), wrap(&domain[1], v)];
    let at = face.surface.eval(w[0], w[1]).point;
    let mut best: Option<(f64, [f64; 2])> = None;
    for i in 0..2 {
        let range = domain[i];
        if range.periodic {
            continue;
        }
        for (bound, at_max) in [(range.min, false), (range.max, true)] {
            if !matches!(face.boundary(side_of(i, at_max)), Boundary::Edge(_)) {
                continue;
            }
            let mut on_side = w;
            on_side[i] = bound;
            let gap = face.surface.eval(on_side[0], on_side[1]).point.distance(at);
            if best.is_none_or(|(g, _)| gap < g) {
                best = Some((gap, on_side));
            }
        }
    }
    match best {
        Some((_, [u, v])) => settle(body, Some(FeatureLocation::Face { id, u, v })),
        None => loc,
    }
}

/// For a location on an edge, the two adjacent faces' locations a relative 1e-9 of the
/// parameter span inside the side the edge runs along (at the edge's parameter); empty
/// otherwise. Starts for a solve that failed on the edge itself.
pub(crate) fn into_faces(body: &Body, loc: Loc) -> Vec<Loc> {
    let (Body::Solid { solid, within, .. }, Some(FeatureLocation::Edge { id, t })) = (body, loc)
    else {
        return Vec::new();
    };
    solid
        .edge(id)
        .uses
        .iter()
        .filter(|use_| within.is_none_or(|f| use_.face == f))
        .map(|use_| {
            let domain = solid.face(use_.face).surface.domain();
            let [u0, v0] = solid.use_params(use_, t);
            let inward = solid.use_inward(use_, t).normalize_or_zero();
            let u = u0 + 1e-9 * domain[0].span() * inward.x;
            let v = v0 + 1e-9 * domain[1].span() * inward.y;
            settle(
                body,
                Some(FeatureLocation::Face {
                    id: use_.face,
                    u,
                    v,
                }),
            )
        })
        .collect()
}

/// Re-entries one solve has taken on one side, as (from, into) feature pairs, so that a solve
/// that comes back to the edge or vertex it left tries another way in first.
///
/// Why: at a rounded box's corner vertex, where three faces meet with one tangent plane, the
/// best first-order direction pointed into a flat face whose descent led straight back out
/// over its edge to the same vertex; the solve took that entry every time and ended at its
/// switch limit, while the entry into the fillet led to the minimum (0.049 mm, bowl against
/// rounded box in `soak 2000 --general --seed 9202`).
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct TakenEntries {
    pairs: [Option<(FeatureId, FeatureId)>; TAKEN_ENTRIES],
}

/// Re-entries remembered per side and solve (more than the default switch limit).
const TAKEN_ENTRIES: usize = 16;

impl TakenEntries {
    /// Remembers the re-entry from `from` into `into` (the oldest is forgotten when full).
    pub(crate) fn record(&mut self, from: &Loc, into: &Loc) {
        let (Some(from), Some(into)) = (from, into) else {
            return;
        };
        self.pairs.rotate_right(1);
        self.pairs[0] = Some((from.feature(), into.feature()));
    }

    /// Whether the re-entry from `from` into `into` was taken before.
    fn taken(&self, from: FeatureId, into: FeatureId) -> bool {
        self.pairs.contains(&Some((from, into)))
    }
}

/// From an edge or vertex, the adjacent face location (on the shared side) whose inward
/// direction makes the largest angle-cosine with `pull` (the direction, in A's frame, in which
/// moving the point decreases the objective), if that component exceeds `threshold` (mm).
/// From a vertex a face collapses into, its directions are its [`geom_param::PoleMeridians`]:
/// the best one is only a start, Newton then turns the running parameter to the optimum.
pub(crate) fn reenter(body: &Body, loc: &Loc, pull: DVec3, threshold: f64) -> Loc {
    reenter_untaken(body, loc, pull, threshold, &TakenEntries::default(), None)
}

/// Whether a meridian (`tangent`) and the one half a turn round (`opposite`) leave their
/// vertex in opposite directions: a smooth pole, with a tangent plane, rather than an apex.
fn smooth_pole(tangent: DVec3, opposite: DVec3) -> bool {
    (tangent.normalize_or_zero() + opposite.normalize_or_zero()).length() <= 1e-6
}

/// At an apex, the meridian between the samples of `meridians` that best follows `pull` (a
/// golden-section search over the two sample spacings around the best sample), with its
/// running parameter, when a meridian between the samples could descend where the best sample
/// does not (its score within |pull| Δ² / 4 of zero, Δ the samples' angular spacing); `None`
/// at a smooth pole (its samples are only a start: the re-entry moves
/// off the pole and Newton turns the running parameter) and where the pull points well away
/// from every meridian (no meridian between two samples can descend then).
///
/// Why: an apex's meridians sweep a cone, and a pull just inside the cone's rim is felt by a
/// narrow band of meridians only. A pencil's tip 1.6e-3 mm into a vase had its depth rising
/// into the tip cone along meridians within about a degree of one direction, 0.008 mm from
/// the apex to a witness 1.8e-6 mm deeper; no sample (22.5 degrees apart) saw it, and the
/// apex was reported as the witness with the connecting vector 4.6e-4 rad outside its cone
/// (pencil-vase 11822164592621655215 of `soak 10000 --seed 13115`).
fn apex_meridian_between(
    solid: &Solid,
    meridians: &PoleMeridians,
    frame: &Frame,
    pull: DVec3,
) -> Option<(DVec3, f64)> {
    let face = solid.face(meridians.face);
    if smooth_pole(meridians.tangents[0], meridians.opposite[0]) {
        return None;
    }
    let score = |tangent: DVec3| pull.dot(frame.vector(tangent).normalize_or_zero());
    let (best, best_score) = meridians
        .tangents
        .iter()
        .map(|&t| score(t))
        .enumerate()
        .max_by(|x, y| x.1.total_cmp(&y.1))?;
    let n = meridians.at.len();
    let (before, after) = (
        meridians.tangents[(best + n - 1) % n],
        meridians.tangents[(best + 1) % n],
    );
    let here = frame.vector(meridians.tangents[best]).normalize_or_zero();
    let spacing = here
        .angle_between(frame.vector(before).normalize_or_zero())
        .max(here.angle_between(frame.vector(after).normalize_or_zero()));
    // Between two samples Δ apart the score (|pull| times the cosine of a unit direction that
    // turns at most at unit rate) rises above the better sample by at most |pull| Δ² / 8:
    // twice that is the margin.
    let margin = -0.25 * pull.length() * spacing * spacing;
    // NaN (a degenerate pull or tangent) searches nothing.
    if best_score.is_nan() || margin.is_nan() || best_score <= margin {
        return None;
    }
    let step = meridians.at.get(1).map_or(0.0, |t1| t1 - meridians.at[0]);
    let at = |t: f64| score(meridian_tangent(face, meridians.side, t));
    // Golden-section search for the maximum, one evaluation per step.
    const GOLDEN: f64 = 0.618_033_988_749_894_9;
    let (mut lo, mut hi) = (meridians.at[best] - step, meridians.at[best] + step);
    let (mut x1, mut x2) = (hi - GOLDEN * (hi - lo), lo + GOLDEN * (hi - lo));
    let (mut f1, mut f2) = (at(x1), at(x2));
    for _ in 0..24 {
        if f1 < f2 {
            lo = x1;
            (x1, f1) = (x2, f2);
            x2 = lo + GOLDEN * (hi - lo);
            f2 = at(x2);
        } else {
            hi = x2;
            (x2, f2) = (x1, f1);
            x1 = hi - GOLDEN * (hi - lo);
            f1 = at(x1);
        }
    }
    let t = 0.5 * (lo + hi);
    let domain = face.surface.domain();
    let range = domain[usize::from(!matches!(meridians.side, ParamSide::VMin | ParamSide::VMax))];
    let t = range.normalize(t);
    Some((meridian_tangent(face, meridians.side, t), t))
}

/// As [`reenter`], preferring a way in that `taken` does not hold from this location: the
/// best of those when one exceeds `threshold`, else the best of all (a solve that has only
/// taken ways in left keeps cycling to its switch limit rather than stopping at a point that
/// is not stationary). Among the untaken ways in, the face `came_from` (the face the solve
/// stepped off onto this edge or vertex) goes first whenever f decreases into it at all.
///
/// Why the face it came from: where f decreases into both faces of an edge, each leads to a
/// critical pair of its own, and the seed stands for the one on its face (Stage 2 seeds the
/// other face's separately). A pencil's taper 0.098 mm from a bowl's rim beside its ridge
/// 1.8e-3 mm into the rim: the taper's seed stepped onto the ridge and went on into the other
/// face, the steeper way, to the penetration, which the other seed found too; queried the
/// other way round, its first step stayed on the taper, so the contact was found one way only
/// (pencil-bowl 17590256838382410736 of `soak 4000 --general --seed 13222`).
pub(crate) fn reenter_untaken(
    body: &Body,
    loc: &Loc,
    pull: DVec3,
    threshold: f64,
    taken: &TakenEntries,
    came_from: Option<FaceId>,
) -> Loc {
    let (
        Body::Solid {
            solid,
            frame,
            within,
        },
        Some(location),
    ) = (body, loc)
    else {
        return None;
    };
    let from = location.feature();
    let mut best: Option<(f64, FeatureLocation)> = None;
    let mut best_untaken: Option<(f64, FeatureLocation)> = None;
    let mut back: Option<(f64, FeatureLocation)> = None;
    let mut offer = |tangent: DVec3, loc: FeatureLocation| {
        if within.is_some_and(|f| !on_closure(solid, &loc, f)) {
            return;
        }
        let score = pull.dot(frame.vector(tangent).normalize_or_zero());
        if score <= threshold {
            return;
        }
        if best.is_none_or(|(s, _)| score > s) {
            best = Some((score, loc));
        }
        if taken.taken(from, loc.feature()) {
            return;
        }
        if best_untaken.is_none_or(|(s, _)| score > s) {
            best_untaken = Some((score, loc));
        }
        let into_origin = matches!(loc, FeatureLocation::Face { id, .. } if Some(id) == came_from);
        if into_origin && back.is_none_or(|(s, _)| score > s) {
            back = Some((score, loc));
        }
    };
    // The direction into a face from an edge use at t (in the solid's frame) and the face
    // location there.
    let into_face = |use_: &EdgeUse, t: f64| {
        let surface = &solid.face(use_.face).surface;
        let [u, v] = solid.use_params(use_, t);
        let inward = solid.use_inward(use_, t);
        let s = surface.eval(u, v);
        (
            s.du * inward.x + s.dv * inward.y,
            FeatureLocation::Face {
                id: use_.face,
                u,
                v,
            },
        )
    };
    match *location {
        FeatureLocation::Edge { id, t } => {
            for use_ in &solid.edge(id).uses {
                let (tangent, face) = into_face(use_, t);
                offer(tangent, face);
            }
        }
        FeatureLocation::Vertex { id } => {
            // Edges ending here: along the edge away from the vertex, and into its faces.
            for &e in &solid.vertex(id).edges {
                let edge = solid.edge(e);
                let Some(ends) = edge.ends else { continue };
                let range = edge.curve.domain();
                for (end, t, away) in [(ends[0], range.min, 1.0), (ends[1], range.max, -1.0)] {
                    if end != id {
                        continue;
                    }
                    offer(
                        away * edge.curve.eval(t).d1,
                        FeatureLocation::Edge { id: e, t },
                    );
                    for use_ in &edge.uses {
                        let (tangent, face) = into_face(use_, t);
                        offer(tangent, face);
                    }
                }
            }
            for meridians in solid.pole_meridians(id) {
                let domain = solid.face(meridians.face).surface.domain();
                let across =
                    usize::from(matches!(meridians.side, ParamSide::VMin | ParamSide::VMax));
                for ((&t, &tangent), &opposite) in meridians
                    .at
                    .iter()
                    .zip(&meridians.tangents)
                    .zip(&meridians.opposite)
                {
                    let mut uv = meridians.side.params_at(&domain, t);
                    // Off a smooth pole only, where the meridian half a turn round leaves in the
                    // opposite direction (a tangent plane); an apex (a cone's tip) is a vertex
                    // of the solid, and its re-entry starts on it as before.
                    if smooth_pole(tangent, opposite) {
                        uv[across] = off_vertex(
                            &domain[across],
                            meridians.side,
                            uv[across],
                            frame.vector(tangent),
                            pull,
                        );
                    }
                    offer(
                        tangent,
                        FeatureLocation::Face {
                            id: meridians.face,
                            u: uv[0],
                            v: uv[1],
                        },
                    );
                }
                if let Some((tangent, t)) = apex_meridian_between(solid, meridians, frame, pull) {
                    let [u, v] = meridians.side.params_at(&domain, t);
                    let id = meridians.face;
                    offer(tangent, FeatureLocation::Face { id, u, v });
                }
            }
        }
        FeatureLocation::Face { .. } => {}
    }
    back.or(best_untaken).or(best).map(|(_, l)| l)
}

/// Whether `location` is on face `face` or on its boundary (an edge with a use on it, a vertex
/// that such an edge ends at or that the face collapses into).
pub(crate) fn on_closure(solid: &Solid, location: &FeatureLocation, face: FaceId) -> bool {
    let edge_on = |e: EdgeId| solid.edge(e).uses.iter().any(|u| u.face == face);
    match *location {
        FeatureLocation::Face { id, .. } => id == face,
        FeatureLocation::Edge { id, .. } => edge_on(id),
        FeatureLocation::Vertex { id } => {
            let vertex = solid.vertex(id);
            vertex.faces.contains(&face) || vertex.edges.iter().any(|&e| edge_on(e))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use geom_param::DPose3;

    fn cap(u: f64, v: f64) -> Loc {
        Some(FeatureLocation::Face {
            id: FaceId(3),
            u,
            v,
        })
    }

    /// A step across a tube's top cap (a plane trimmed by circles of radius 10 and 8 mm) is cut
    /// where it leaves the trim: a radial step from radius 9.9 to 10.9 mm at a tenth, onto the
    /// outer rim (edge 1) at the point it crosses; a slanted one within second order of where
    /// the segment meets the circle; a step that stays on the cap is not cut.
    #[test]
    fn a_step_across_a_trim_is_cut_where_it_crosses() {
        let tube = geom_param::tube(10.0, 8.0, 20.0).expect("tube");
        let body = Body::Solid {
            solid: &tube,
            frame: Frame::new(&DPose3::IDENTITY),
            within: None,
        };
        for k in 0..12 {
            let phi = 0.5 * f64::from(k);
            let radial = DVec2::new(phi.cos(), phi.sin());
            let (from, to) = (9.9 * radial, 10.9 * radial);
            let (settled, crossing) = settle_step(&body, &cap(from.x, from.y), cap(to.x, to.y));
            let (beta, on) = crossing.expect("the radial step crosses the rim");
            assert!((beta - 0.1).abs() < 1e-12, "phi {phi}: beta {beta}");
            assert!(
                matches!(on, FeatureLocation::Edge { id, .. } if id == EdgeId(1)),
                "phi {phi}: {on:?}"
            );
            let rim = DVec3::new(10.0 * radial.x, 10.0 * radial.y, 20.0);
            assert!(tube.point_at(&on).distance(rim) < 1e-9, "phi {phi}");
            assert!(matches!(settled, Some(FeatureLocation::Edge { .. })));

            // Slanted by 45 degrees: the segment meets the circle at s solving
            // |from + s (to - from)| = 10.
            let tangent = radial.perp();
            let to = from + 0.5 * (radial + tangent);
            let d = to - from;
            let (qa, qb, qc) = (d.dot(d), 2.0 * from.dot(d), from.dot(from) - 100.0);
            let exact = (-qb + (qb * qb - 4.0 * qa * qc).sqrt()) / (2.0 * qa);
            let (_, crossing) = settle_step(&body, &cap(from.x, from.y), cap(to.x, to.y));
            let (beta, _) = crossing.expect("the slanted step crosses the rim");
            // The step is 0.71 mm on a circle of curvature 0.1 /mm.
            assert!(
                (beta - exact).abs() < 0.05,
                "phi {phi}: {beta} against {exact}"
            );

            let inside = 9.0 * radial + 0.5 * tangent;
            let (settled, crossing) =
                settle_step(&body, &cap(from.x, from.y), cap(inside.x, inside.y));
            assert_eq!(crossing, None, "phi {phi}");
            assert!(matches!(settled, Some(FeatureLocation::Face { .. })));
        }
    }
}
