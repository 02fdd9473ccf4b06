//! The pair solve: the critical point of ½|P_a − P_b|² near a start, by the safeguarded Newton
//! minimisation of [`crate::solver::newton`], handing penetrating pairs to the witness solvers
//! of [`crate::solver::penetration`].
//!
//! A solve that stalls on two faces, or that penetrates without converging, is retried from
//! the nearest edges (an edge's witness) and as a plain minimisation from its end ([`solve`]).

use crate::features::feature_eval::{Body, FeatureEval, Loc};
use crate::features::feature_switch::{
    into_faces, onto_nearest_edge, settle, settle_start, snap_to_sides, snap_within_distance,
};
use crate::options::NewtonOptions;
use crate::solver::newton::{
    EPS, FaceView, Outcome, Reentry, Solution, State, TOUCH_ANGLE, cones_opposed, face_views,
    minimize, minimize_known, slide_on_face,
};
use crate::solver::penetration::{
    edge_face_witness, edge_pair_minimum, edge_pair_witness, saddle_newton, solve_penetration,
    solve_penetration_from,
};
use geom_param::{DVec3, FeatureLocation};

/// Solves for the critical point of ½|P_a − P_b|² near (`la`, `lb`) as described in the module
/// docs. `base_scale` (mm) enters the rounding floors (B's translation, for instance).
pub(crate) fn solve(
    a: &Body,
    b: &Body,
    la: Loc,
    lb: Loc,
    base_scale: f64,
    options: &NewtonOptions,
) -> Solution {
    // The start's snap evaluates each face there; the first state reuses those evaluations.
    let mut known = [None, None];
    let la = settle_start(a, la, &mut known[0]);
    let lb = settle_start(b, lb, &mut known[1]);
    let mut first = minimize_known(
        a,
        b,
        (la, lb),
        base_scale,
        options,
        Reentry::Allowed,
        [known[0].as_ref(), known[1].as_ref()],
    );
    if first.outcome == Outcome::IterationLimit {
        // Slow, not lost: at an exact touch the gap is quartic in the offset along the flattest
        // direction and Newton converges only linearly (a goblet on a bowl at 2.7e-10 mm took 62
        // iterations one way round and stopped at 64 the other). Continue once from the end.
        let again = minimize(
            a,
            b,
            first.state.la,
            first.state.lb,
            base_scale,
            options,
            Reentry::Allowed,
        );
        first = Solution {
            iterations: first.iterations + again.iterations,
            ..again
        };
    }
    if matches!(first.outcome, Outcome::Stalled | Outcome::SwitchLimit) {
        if let Some(mut fast) = stalled_edge_witness(a, b, &first.state, base_scale, options) {
            fast.iterations += first.iterations;
            return fast;
        }
    }
    if first.outcome == Outcome::Penetrating {
        let (la, lb) = (first.state.la, first.state.lb);
        if let Some(mut fast) = saddle_newton(a, b, &first.state, base_scale, options)
            .or_else(|| edge_pair_witness(a, b, la, lb, base_scale, options))
            .or_else(|| edge_pair_touch(a, b, la, lb, base_scale, options))
            .or_else(|| nearest_edges_witness(a, b, &first.state, base_scale, options))
        {
            fast.iterations += first.iterations;
            return fast;
        }
        let mut deep = solve_penetration(a, b, first.state.la, first.state.lb, base_scale, options);
        deep.iterations += first.iterations;
        let deep = retry_on_sides(a, b, deep, base_scale, options);
        return separated_end(a, b, deep, base_scale, options);
    }
    // Minimising f can end on the intersection curve of two faces (f = 0 with the normals not
    // opposed) without ever seeing a penetrating pair: restart once inside the lens.
    match crossing_restart(a, b, &first.state) {
        Some((ra, rb)) if first.outcome == Outcome::Converged => {
            // An edge already crossing a face is the ridge witness's own start (a bracket's
            // edge 1e-3 mm into a vase, where the restart moved onto the edge's other face and
            // the nested solver wandered 13.5 mm along it).
            let (la, lb) = (first.state.la, first.state.lb);
            let fast = nearest_edges_witness(a, b, &first.state, base_scale, options)
                .or_else(|| edge_face_witness(a, b, la, lb, base_scale, options))
                .or_else(|| ridge_witness(a, b, &first.state, (ra, rb), base_scale, options));
            if let Some(mut fast) = fast {
                fast.iterations += first.iterations;
                return fast;
            }
            let mut deep = solve_penetration(a, b, ra, rb, base_scale, options);
            deep.iterations += first.iterations;
            retry_on_sides(a, b, deep, base_scale, options)
        }
        _ => first,
    }
}

/// A penetration solve that did not converge, polished as a distance minimisation from its
/// end when that converges to a pair that is not penetrating (the minimisation's own test):
/// the pair was never penetrating, only its start looked so. `deep` otherwise.
///
/// Why: Stage 2 hands the seed of two convex components whose hulls overlap (a tube's hull
/// fills its hole) as a penetrating pair 20 mm apart; the first minimisation stops there as
/// penetrating, and the nested solver crept towards the true minimum (a tube's rim against a
/// bracket's fillet edge, 0.0218 mm) and stopped at its iteration limit 1e-4 mm short.
fn separated_end(
    a: &Body,
    b: &Body,
    deep: Solution,
    base_scale: f64,
    options: &NewtonOptions,
) -> Solution {
    if deep.outcome == Outcome::Converged {
        return deep;
    }
    let polished = minimize(
        a,
        b,
        deep.state.la,
        deep.state.lb,
        base_scale,
        options,
        Reentry::Allowed,
    );
    if polished.outcome == Outcome::Converged {
        Solution {
            iterations: deep.iterations + polished.iterations,
            ..polished
        }
    } else {
        deep
    }
}

/// The touch of two edges near (`la`, `lb`): their pair minimum ([`edge_pair_minimum`]) when
/// its gap is within rounding (|d| ≤ 1e3 ε x scale, where [`State::sign`] calls a pair
/// touching); `None` otherwise. (Not re-entered into the faces: there f can fall by rounding
/// into a face that the other edge crosses within rounding of its boundary, an end that is no
/// local minimum.)
///
/// Why: two edges crossing within rounding of each other (a goblet rim's inner circle under a
/// vase's bottom circle at 1.3e-11 mm, goblet-vase 2504669063869504659 of
/// `soak 10000 --seed 13122`) look penetrating from points a little apart along them, where
/// the part of d across both edges is still above rounding and negative, and touching at their
/// minimum, where it is not: the penetration witness solvers reject the minimum (not
/// penetrating), and every seed ran the nested solver to its limits (about 1400 steps) without
/// an answer. The minimum of f over the two edges is the pair's critical point: a touch.
fn edge_pair_touch(
    a: &Body,
    b: &Body,
    la: Loc,
    lb: Loc,
    base_scale: f64,
    options: &NewtonOptions,
) -> Option<Solution> {
    edge_pair_minimum(a, b, la, lb, base_scale, options)
        .filter(|closest| closest.state.d.length() <= 1e3 * EPS * closest.state.scale)
}

/// The witness between two edges ([`edge_pair_witness`]) started from each point of `state`
/// moved onto its face's nearest boundary edge ([`onto_nearest_edge`]), when that leaves both
/// on edges and moves at least one; `None` otherwise or when it does not converge to a witness.
///
/// Why: two ridges crossing (a rim on a rim, a plate's edge across another's) penetrate in a
/// lens whose witness is the pair of edges, not a point of either face; the face-face solve
/// reaches the lens's crossing curve (the goblet's rim on the tube's bottom cap, 1e-3 mm deep:
/// the crossing 0.01 mm from the tube's edge, 3e-4 of the annulus from the goblet's) and the
/// nested solver from there cannot represent the edge pair. `edge_pair_witness` accepts only a
/// converged pair that passes the witness tests, so a start whose edges hold no witness costs
/// one short solve.
fn nearest_edges_witness(
    a: &Body,
    b: &Body,
    state: &State,
    base_scale: f64,
    options: &NewtonOptions,
) -> Option<Solution> {
    let (ea, eb) = (
        onto_nearest_edge(a, state.la),
        onto_nearest_edge(b, state.lb),
    );
    if ea == state.la && eb == state.lb {
        return None;
    }
    edge_pair_witness(a, b, ea, eb, base_scale, options)
}

/// The penetration witness of an edge, where minimising f stalled on two faces (`state`):
/// between the two faces' nearest boundary edges ([`nearest_edges_witness`]), or between
/// either face's nearest boundary edge and the other face ([`edge_face_witness`]). Only a
/// validated witness is taken; `None` otherwise (also when `state` is not on two faces).
///
/// Why: a rim 1e-3 mm into a face, with the seed on the rim's cap 4e-3 mm in from the rim (a
/// loft's bottom cap on a paperweight's dome), minimises f on the cap and the dome towards
/// their crossing, which runs out of the cap's trim beside the rim: the solve stalls at
/// |d| = 1.8e-4 mm (57 iterations) without seeing a penetrating pair, and the pair was
/// reported separated. The witness is the rim against the dome.
fn stalled_edge_witness(
    a: &Body,
    b: &Body,
    state: &State,
    base_scale: f64,
    options: &NewtonOptions,
) -> Option<Solution> {
    let on_face = |l: &Loc| matches!(l, Some(FeatureLocation::Face { .. }));
    if !(on_face(&state.la) && on_face(&state.lb)) {
        return None;
    }
    if let Some(both) = nearest_edges_witness(a, b, state, base_scale, options) {
        return Some(both);
    }
    [
        (onto_nearest_edge(a, state.la), state.lb),
        (state.la, onto_nearest_edge(b, state.lb)),
    ]
    .into_iter()
    .filter(|&starts| starts != (state.la, state.lb))
    .find_map(|(sa, sb)| edge_face_witness(a, b, sa, sb, base_scale, options))
}

/// The witness of a ridge cutting the other side's face ([`edge_face_witness`]), from a
/// crossing `state` with one point moved onto its face's nearest boundary edge
/// ([`onto_nearest_edge`]) and the other left on its face; each side tried where the edge is
/// within the lens that the crossing restart (`restart`) would search, the move of either of
/// its points. `None` when neither start converges to a witness.
fn ridge_witness(
    a: &Body,
    b: &Body,
    state: &State,
    restart: (Loc, Loc),
    base_scale: f64,
    options: &NewtonOptions,
) -> Option<Solution> {
    let lens = a
        .eval(&restart.0)
        .point
        .distance(state.ea.point)
        .max(b.eval(&restart.1).point.distance(state.eb.point));
    let within = |body: &Body, moved: Loc, from: DVec3| {
        moved.is_some() && body.eval(&moved).point.distance(from) <= lens
    };
    let ea = onto_nearest_edge(a, state.la);
    let eb = onto_nearest_edge(b, state.lb);
    let mut starts = Vec::with_capacity(2);
    if ea != state.la && within(a, ea, state.ea.point) {
        starts.push((ea, state.lb));
    }
    if eb != state.lb && within(b, eb, state.eb.point) {
        starts.push((state.la, eb));
    }
    starts
        .into_iter()
        .find_map(|(sa, sb)| edge_face_witness(a, b, sa, sb, base_scale, options))
}

/// A penetration solve that did not converge, restarted from other features of its end: first
/// Newton on two edges (each face point within the gap |d| of a side put on it, when that
/// gives an edge on both sides); then the nested solver from each face point within
/// √ε x max(1, |P|) mm of a side put on that side ([`snap_to_sides`]), when that moves one;
/// failing that, from each edge point moved just inside each adjacent face ([`into_faces`]),
/// the other side as it is and then, where its point lies within the gap |d| of a side, on that
/// side. The first restart that converges is the answer; `deep` when none does.
///
/// Why: where the witness is on a smooth edge (equal normals on both sides, the goblet's
/// z = 150 rim joint), the face-face solve approaches the side without reaching it (v = 1 −
/// 4e-14) while the depth's curvature jumps there, and its trust region stalls 1.7e-7 mm short
/// of the depth; from the edge the same witness is an interior point and converges. Conversely,
/// a seed exactly on a face's side (the bowl's v = 0.6) starts edge against edge, where the
/// nested solver (outer and inner both edges) can stall while the witness is the other edge
/// against that face.
pub(crate) fn retry_on_sides(
    a: &Body,
    b: &Body,
    deep: Solution,
    base_scale: f64,
    options: &NewtonOptions,
) -> Solution {
    if deep.outcome == Outcome::Converged {
        return deep;
    }
    let (la, lb) = (deep.state.la, deep.state.lb);
    // First the witness between two edges, which the nested solver cannot represent and
    // approaches by stalling next to the inner side's edge (2.3e-6 mm from the goblet's rim):
    // each face point within the gap |d| of a side put on it, and f minimised on the two
    // edges from there ([`edge_pair_witness`], which accepts only a converged witness).
    let reach = deep.state.d.length();
    if let Some(witness) = edge_pair_witness(
        a,
        b,
        snap_within_distance(a, la, reach),
        snap_within_distance(b, lb, reach),
        base_scale,
        options,
    ) {
        return Solution {
            iterations: deep.iterations + witness.iterations,
            ..witness
        };
    }
    let feature = |l: &Loc| l.map(|l| l.feature());
    let (sa, sb) = (
        snap_to_sides(a, la, EPS.sqrt()),
        snap_to_sides(b, lb, EPS.sqrt()),
    );
    let mut starts = Vec::new();
    if feature(&sa) != feature(&la) || feature(&sb) != feature(&lb) {
        starts.push((sa, sb));
    }
    let (faces_a, faces_b) = (into_faces(a, la), into_faces(b, lb));
    starts.extend(faces_a.iter().map(|&fa| (fa, lb)));
    starts.extend(faces_b.iter().map(|&fb| (la, fb)));
    // Both sides moved at once: one side's edge into its faces, the other's face point onto
    // its edge. A straight edge 7.0e-4 mm inside a pencil's cylinder just above its ridge
    // stalled ridge against the face beside the edge, and each restart moving one side
    // stalled too; the witness is the edge against the cylinder (pencil-bracket
    // 15275829082547009235 of `soak 2000 --general --seed 13244`).
    let (ea, eb) = (
        snap_within_distance(a, la, reach),
        snap_within_distance(b, lb, reach),
    );
    if feature(&eb) != feature(&lb) {
        starts.extend(faces_a.iter().map(|&fa| (fa, eb)));
    }
    if feature(&ea) != feature(&la) {
        starts.extend(faces_b.iter().map(|&fb| (ea, fb)));
    }
    let mut iterations = deep.iterations;
    for (ra, rb) in starts {
        let again = solve_penetration(a, b, ra, rb, base_scale, options);
        iterations += again.iterations;
        if again.outcome == Outcome::Converged {
            return Solution {
                iterations,
                ..again
            };
        }
    }
    // Last, two faces with the roles swapped (B outer): where the deepest point is one side's
    // apex (a pencil's tip 0.2 mm into a bowl), A's points have no nearest point at the apex
    // to project to, and only the apex's side as the outer one reaches it.
    if deep.state.na == 2 && deep.state.n == 4 {
        let again = solve_penetration_from(a, b, (la, lb), false, base_scale, options);
        iterations += again.iterations;
        if again.outcome == Outcome::Converged {
            return Solution {
                iterations,
                ..again
            };
        }
    }
    deep
}

/// Where to restart when `state` sits on a crossing of the two surfaces (f = 0 with no common
/// normal): each point moved along its face, away from the other face's outward normal, by the
/// lens size angle / curvature.
///
/// A point on a face has its normal; a point on an edge has the arc of normals between its two
/// faces'. The pair is a touch when the two cones hold opposite directions (to 1e-9 in the
/// cosine for two faces, the same angle for an edge): a face's normal negated inside the edge's
/// arc. Otherwise the surfaces cross, and an edge's point restarts on the adjacent face that
/// cuts the other surface most steeply (its normal least opposed to the other's). Edge against
/// edge and vertices are left alone.
fn crossing_restart(a: &Body, b: &Body, state: &State) -> Option<(Loc, Loc)> {
    if state.d.length() > 1e3 * EPS * state.scale {
        return None;
    }
    let va = face_views(a, &state.la, &state.ea)?;
    let vb = face_views(b, &state.lb, &state.eb)?;
    if va.len() > 1 && vb.len() > 1 {
        return None;
    }
    if cones_opposed(&va, &vb, TOUCH_ANGLE) {
        return None; // a touch, not a crossing
    }
    // The view of one side that cuts the other side's single face most steeply.
    let steepest = |views: &[FaceView], other: DVec3| {
        views
            .iter()
            .copied()
            .max_by(|x, y| x.normal.dot(other).total_cmp(&y.normal.dot(other)))
    };
    let (fa, fb) = if va.len() == 1 {
        (va[0], steepest(&vb, va[0].normal)?)
    } else {
        (steepest(&va, vb[0].normal)?, vb[0])
    };
    let (na, nb) = (fa.normal, fb.normal);
    let opposed = -na.dot(nb);
    let angle = opposed.clamp(-1.0, 1.0).acos();
    let length = angle / state.curvature.max(f64::MIN_POSITIVE);
    let shift = |body: &Body, e: &FeatureEval, loc: &Loc, own: DVec3, other: DVec3| {
        let w = (other - own * other.dot(own)).normalize_or_zero() * -length;
        slide_on_face(body, loc, e, w)
    };
    let ra = settle(a, shift(a, &fa.eval, &fa.loc, na, nb));
    let rb = settle(b, shift(b, &fb.eval, &fb.loc, nb, na));
    Some((ra, rb))
}
