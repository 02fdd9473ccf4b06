//! The penetration witness: for interpenetrating features, the pair whose connecting vector is
//! anti-parallel to the normals and which locally maximises the depth.
//!
//! That pair is a saddle of f = ½|P_a − P_b|², and f is zero with zero gradient all along the
//! intersection curve, so neither minimising f nor solving ∇f = 0 keeps away from that curve.
//! The problem is therefore nested (Haynsworth: the witness has exactly this inertia): the side
//! with more parameters (on a tie, B at the start and then whichever side already is) is the
//! *inner* side, whose point is the projection of the
//! outer point onto it, and the *outer* point maximises the signed depth
//! D = −(P_outer − P_inner) · n_inner (positive inside the inner solid, minus the distance
//! outside). D has a non-zero gradient −n_inner · ∂P_outer/∂x on the intersection curve, so
//! ascent leaves it; outside (a start on the wrong side) maximising D minimises the distance,
//! so the same iteration finds the separated closest pair. With S the Schur complement of the
//! inner block in the Hessian of f (the Hessian of ½D²), Hess D = (S − ∇D ∇Dᵀ) / D; the step
//! is Newton on D with that Hessian made negative definite (eigenvalues floored), or a gradient
//! step where |D| is at rounding level, inside a trust region on D.
//!
//! Close to the witness (a Stage 2 seed), [`saddle_newton`] first tries plain Newton on
//! ∇f = 0, which needs no projections and is accepted only if it converges quadratically to a
//! stationary pair with exactly the witness's inertia; otherwise the nested solver runs.

// Small dense matrices (at most 4 x 4): index arithmetic reads closer to the formulas.
#![allow(clippy::needless_range_loop)]

use crate::features::feature_eval::{Body, Loc};
use crate::features::feature_switch::{
    TakenEntries, reenter, reenter_untaken, settle, snap_to_sides,
};
use crate::linalg::dense_solve::{cholesky, cholesky_solve, lu_solve};
use crate::linalg::sym_eigen::{sym_eigen, sym_eigenvalues};
use crate::options::NewtonOptions;
use crate::solver::crossing_probe::overlap_near;
use crate::solver::newton::{
    EPS, Outcome, Reentry, Solution, State, minimize, minimize_projection, take_step,
};
use geom_param::{DVec3, FeatureLocation};

/// Solves for the penetration witness from (`la`, `lb`) as described in the module docs.
pub(crate) fn solve_penetration(
    a: &Body,
    b: &Body,
    la: Loc,
    lb: Loc,
    base_scale: f64,
    options: &NewtonOptions,
) -> Solution {
    solve_penetration_from(a, b, (la, lb), true, base_scale, options)
}

/// [`solve_penetration`] with the roles of a tie at the start chosen: A outer when
/// `a_outer_on_tie`, else B.
pub(crate) fn solve_penetration_from(
    a: &Body,
    b: &Body,
    (la, lb): (Loc, Loc),
    a_outer_on_tie: bool,
    base_scale: f64,
    options: &NewtonOptions,
) -> Solution {
    let mut steps = 0u32;
    // The outer gradient is only as good as the inner projection (its error divided by the
    // inner Hessian, which is below 1 inside a convex solid): project a thousand times tighter.
    let inner_options = NewtonOptions {
        angle_tolerance: 1e-3 * options.angle_tolerance,
        ..*options
    };
    // The pair with the inner point projected onto the inner feature, warm-started where it is.
    // Roles follow the current parameter counts (a switch can change them).
    let pair = |la: Loc, lb: Loc, outer_is_a: bool, steps: &mut u32| {
        let (outer, inner, lo, li) = if outer_is_a {
            (a, b, la, lb)
        } else {
            (b, a, lb, la)
        };
        let projection = minimize_projection(
            inner,
            outer.eval(&lo).point,
            li,
            base_scale,
            &inner_options,
            Reentry::Allowed,
        );
        *steps += projection.iterations;
        // A projection tending to a face's side (the closest point is on the edge, v = 1 − 2e-15
        // after many steps) is the edge: on the face the depth's curvature jumps there and the
        // outer iteration stalls. Within √ε x |P| it is put on the side.
        let li = snap_to_sides(inner, projection.state.la, EPS.sqrt());
        if outer_is_a {
            State::new(a, b, lo, li, base_scale)
        } else {
            State::new(a, b, li, lo, base_scale)
        }
    };
    // Whether A is the outer side: the side with fewer parameters; on a tie the side that
    // already is (A at the start). Why sticky: an outer point leaving an apex vertex re-enters
    // its cone at the apex, where the cone has no normal; were the roles to follow the tie
    // rule there, the cone would become the inner side and the projection onto it would stay
    // at the apex (a pencil's tip 1.2e-3 mm into a vase, `soak 10000 --seed 5002`, stalled
    // there and the pair was reported separated), while as the outer side it ascends the
    // depth down the cone.
    let roles = |s: &State, current: bool| {
        let (na, nb) = (s.na, s.n - s.na);
        if na == nb { current } else { na < nb }
    };
    let start = State::new(a, b, settle(a, la), settle(b, lb), base_scale);
    let mut built_as = roles(&start, a_outer_on_tie);
    let mut cur = pair(start.la, start.lb, built_as, &mut steps);
    let (max_radius, mut radius) = cur.trust_radii();
    let mut switches = 0;
    let mut taken = [TakenEntries::default(); 2];
    let end = |state, iterations, outcome| Solution {
        state,
        iterations,
        outcome,
    };
    for iteration in 0..options.max_iterations {
        let outer_is_a = roles(&cur, built_as);
        if outer_is_a != built_as {
            // The inner side lost a parameter (moved onto an edge or vertex): swap roles and
            // project the new inner side.
            built_as = outer_is_a;
            cur = pair(cur.la, cur.lb, outer_is_a, &mut steps);
            switches += 1;
            if switches > options.max_feature_switches {
                return end(cur, steps + iteration, Outcome::SwitchLimit);
            }
            continue;
        }
        let inner = if outer_is_a { b } else { a };
        let Some((merit, gradient)) = depth(inner, &cur, outer_is_a) else {
            return end(cur, steps + iteration, Outcome::Stalled);
        };
        let (step, escaping) = outer_step(&cur, outer_is_a, merit, &gradient, radius);
        let settled = depth_settled(&cur, (merit, &gradient), options) && !escaping;
        // A step below what the coordinates resolve ends the solve as well, and what follows
        // applies to that end too: on a smooth edge (a fillet meeting a cone, where the depth's
        // curvature jumps), the outer point stopped on the edge with the depth still rising
        // into the fillet face (two bowls' fillets 1e-3 mm deep, bowl-bowl
        // 7960296049327045656 of `soak 10000 --seed 13102`: ended 3.6e-4 mm deep on the edge).
        let stuck = !escaping && step.iter().all(|s| s.abs() <= 4.0 * EPS * cur.scale);
        if settled || stuck {
            // From an edge or vertex, continue into an adjacent face if the depth rises into it
            // (against the inner normal).
            let (outer, outer_loc, pull) = depth_pull((a, b), &cur, outer_is_a);
            let taken_here = &mut taken[usize::from(!outer_is_a)];
            let Some(entry) =
                reenter_untaken(outer, &outer_loc, pull, 64.0 * EPS, taken_here, None)
            else {
                return end(cur, steps + iteration, Outcome::Converged);
            };
            taken_here.record(&outer_loc, &Some(entry));
            switches += 1;
            if switches > options.max_feature_switches {
                return end(cur, steps + iteration, Outcome::SwitchLimit);
            }
            cur = if outer_is_a {
                pair(Some(entry), cur.lb, true, &mut steps)
            } else {
                pair(cur.la, Some(entry), false, &mut steps)
            };
            built_as = roles(&cur, outer_is_a);
            continue;
        }
        let length = step.iter().map(|s| s * s).sum::<f64>().sqrt();
        // The inner projection starts where the outer step moves it to first order, when the
        // step is short enough for that (turning the features by at most a quarter radian).
        let (ta, tb) = take_step(a, b, &cur, &step);
        let (pa, pb) = if length * cur.curvature <= 0.25 {
            take_step(a, b, &cur, &inner_prediction(&cur, outer_is_a, &step))
        } else {
            (cur.la, cur.lb)
        };
        let trial = if outer_is_a {
            pair(ta, pb, true, &mut steps)
        } else {
            pair(pa, tb, false, &mut steps)
        };
        if roles(&trial, outer_is_a) != outer_is_a {
            cur = trial; // re-paired with swapped roles at the top of the loop
            continue;
        }
        let trial_merit = depth(inner, &trial, outer_is_a).map_or(f64::NEG_INFINITY, |(m, _)| m);
        let slack = 8.0 * EPS * cur.scale;
        if trial_merit.is_finite() && trial_merit >= merit - slack {
            if trial.la.map(|l| l.feature()) != cur.la.map(|l| l.feature())
                || trial.lb.map(|l| l.feature()) != cur.lb.map(|l| l.feature())
            {
                switches += 1;
                if switches > options.max_feature_switches {
                    return end(trial, steps + iteration + 1, Outcome::SwitchLimit);
                }
            }
            if length >= 0.9 * radius {
                radius = (2.0 * radius).min(max_radius);
            }
            cur = trial;
        } else {
            radius = 0.25 * length;
            if radius < 4.0 * EPS * cur.scale {
                return end(cur, steps + iteration + 1, Outcome::Stalled);
            }
        }
    }
    // Out of iterations, the end is a witness only where a settled pair would be one (above):
    // the depth stationary along the outer features and rising into no face next to an edge
    // or vertex. Stationarity of f alone let an end on the intersection curve, or on a smooth
    // edge with the depth still rising into the fillet beyond it, pass as converged (a pencil
    // 1.7e-3 mm into a jar's bottom across the fillet's edge, where the end on the edge lay
    // 2.3e-8 mm above the fillet's witness 7.7e-4 mm away: pencil-jar 18264175689669441403
    // of `soak 10000 --seed 13158`, a contact found one way round only).
    let outer_is_a = roles(&cur, built_as);
    let inner = if outer_is_a { b } else { a };
    let settled = depth(inner, &cur, outer_is_a).is_some_and(|(merit, gradient)| {
        depth_settled(&cur, (merit, &gradient), options) && {
            let (outer, outer_loc, pull) = depth_pull((a, b), &cur, outer_is_a);
            reenter(outer, &outer_loc, pull, 64.0 * EPS).is_none()
        }
    });
    let outcome = if settled {
        Outcome::Converged
    } else {
        Outcome::IterationLimit
    };
    end(cur, steps + options.max_iterations, outcome)
}

/// Whether the nested solve's pair `state` is stationary in the depth D (`merit`, and its
/// scaled `gradient` over the outer variables, from [`depth`]): f stationary, and not on the
/// intersection curve, where f is stationary too but D still rises (its gradient is the sine
/// of the crossing angle there): D's slope at most 1e-6 plus its rounding noise 2·floor/|D|
/// (none below 1e3 ε x scale, where D itself is rounding).
fn depth_settled(
    state: &State,
    (merit, gradient): (f64, &[f64; 4]),
    options: &NewtonOptions,
) -> bool {
    let slope = gradient.iter().fold(0.0_f64, |m, g| m.max(g.abs()));
    let noise = if merit.abs() > 1e3 * EPS * state.scale {
        2.0 * state.gradient_floor() / merit.abs()
    } else {
        0.0
    };
    state.stationary(options) && slope <= 1e-6 + noise
}

/// The nested solve's outer side at `state` (body and location) and the direction in which
/// moving its point raises the depth: against the inner side's outward normal (zero where
/// that has none).
fn depth_pull<'a, 'b>(
    (a, b): (&'b Body<'a>, &'b Body<'a>),
    state: &State,
    outer_is_a: bool,
) -> (&'b Body<'a>, Loc, DVec3) {
    let (outer, outer_loc, inner_normal) = if outer_is_a {
        (a, state.la, state.outward_b(b))
    } else {
        (b, state.lb, state.outward_a(a))
    };
    (outer, outer_loc, inner_normal.map_or(DVec3::ZERO, |n| -n))
}

/// Plain Newton on ∇f = 0 from a penetrating pair near its witness, without the nested
/// projections: the witness is the nearby critical point of f with exactly
/// [`State::witness_index`] negative Hessian eigenvalues, and Newton converges to it
/// quadratically from close enough. Accepted only when it behaves so: the pair stays
/// penetrating on the same features, every step turns the features by less than 0.1 rad, the
/// residual at least halves per step, and the end is stationary with exactly that inertia
/// (which rules out the intersection curve of two faces, where the Hessian is positive
/// semi-definite; two edges meet in a point, where the pair does not penetrate) and no depth
/// rising into a face ([`deepens_into_face`]). `None` otherwise: the nested solver then
/// starts from `start` (Stage 2 seeds of a penetrating pair take 2-4 steps here instead of a
/// projection per step there).
///
/// This is also the only solver of a witness between two edges (two crossing rims): the nested
/// solver projects the outer point onto the inner side, and the closest boundary point to a
/// point inside a convex wedge is on one of its faces, never on its edge, so it cannot
/// represent that pair (it climbs towards the wedge's bisector, where the projection jumps
/// between the faces, and stalls).
pub(crate) fn saddle_newton(
    a: &Body,
    b: &Body,
    start: &State,
    base_scale: f64,
    options: &NewtonOptions,
) -> Option<Solution> {
    /// Quadratic convergence from a good start needs 2-5 steps; more means it is not in that
    /// regime.
    const MAX_STEPS: u32 = 8;
    let mut cur = *start;
    let n = cur.n;
    if cur.na == 0 || cur.na == n {
        return None;
    }
    let target = cur.witness_index();
    for iteration in 0..MAX_STEPS {
        if !cur.penetrating(a, b) {
            return None;
        }
        let step = lu_solve(&cur.hs, n, &cur.gs)?.map(|x| -x);
        let negligible = step[..n].iter().all(|s| s.abs() <= 4.0 * EPS * cur.scale);
        if cur.stationary(options) || negligible {
            // The end (stationary, or the step below what the coordinates can represent) is
            // the witness only with its inertia.
            let spectrum = sym_eigenvalues(&cur.hs, n);
            let floor = cur.eigen_floor(&spectrum);
            let values = &spectrum[..n];
            // Also rejects NaN: every comparison with NaN is false.
            let inertia = values.iter().all(|l| l.abs() > floor)
                && values.iter().filter(|&&l| l < 0.0).count() == target;
            return (inertia && !deepens_into_face(a, b, &cur)).then_some(Solution {
                state: cur,
                iterations: iteration,
                outcome: Outcome::Converged,
            });
        }
        let length = step[..n].iter().map(|s| s * s).sum::<f64>().sqrt();
        // (False for NaN as well.)
        let short = length * cur.curvature < 0.1;
        if !short {
            return None;
        }
        let (ta, tb) = take_step(a, b, &cur, &step);
        if ta.map(|l| l.feature()) != cur.la.map(|l| l.feature())
            || tb.map(|l| l.feature()) != cur.lb.map(|l| l.feature())
        {
            return None;
        }
        let trial = State::new(a, b, ta, tb, base_scale);
        let halved = trial.gradient_norm() <= 0.5 * cur.gradient_norm();
        if !halved {
            return None;
        }
        cur = trial;
    }
    None
}

/// The penetration witness between two edges near (`la`, `lb`), both edges (`None`
/// otherwise): f minimised over the two edge parameters without leaving them (the witness of
/// two crossing edges is a minimum of f there, [`State::witness_index`] 0), then accepted by
/// [`saddle_newton`]'s tests (penetrating, no negative eigenvalue, no depth rising into a face
/// of either edge). `None` when the minimisation does not converge or the end fails them.
///
/// Why: the nested solver cannot represent this pair (see [`saddle_newton`]), and plain Newton
/// on the edges converges only from close by (from the rims next to where the nested solver
/// stalled, 0.09 mm deep against a 0.05 mm witness in `closed_form.rs`, it did not).
pub(crate) fn edge_pair_witness(
    a: &Body,
    b: &Body,
    la: Loc,
    lb: Loc,
    base_scale: f64,
    options: &NewtonOptions,
) -> Option<Solution> {
    let closest = edge_pair_minimum(a, b, la, lb, base_scale, options)?;
    let mut witness = saddle_newton(a, b, &closest.state, base_scale, options)?;
    witness.iterations += closest.iterations;
    Some(witness)
}

/// f minimised over the parameters of two edges from (`la`, `lb`) without leaving them, when
/// both are edges and the minimisation converges; `None` otherwise.
pub(crate) fn edge_pair_minimum(
    a: &Body,
    b: &Body,
    la: Loc,
    lb: Loc,
    base_scale: f64,
    options: &NewtonOptions,
) -> Option<Solution> {
    let on_edge = |l: &Loc| matches!(l, Some(FeatureLocation::Edge { .. }));
    if !(on_edge(&la) && on_edge(&lb)) {
        return None;
    }
    let closest = minimize(a, b, la, lb, base_scale, options, Reentry::Never);
    (closest.outcome == Outcome::Converged).then_some(closest)
}

/// The witness between an edge and the other side's face, from `la`, `lb` (one an edge, the
/// other a face): f minimised on those two features (no re-entry), then [`saddle_newton`] from
/// the penetrating pair that reaches, or, where the minimisation ends on the crossing of the
/// edge with the face (f = 0), from the deepest probe of [`overlap_near`] along the edge,
/// falling back to the nested solver from that probe. `None` unless one converges to a
/// witness: saddle Newton's own acceptance tests, or for the nested solver a stationary pair
/// on the same edge and face (from a ridge's probe it can otherwise end on other features
/// with a converged outer loop but a gradient of 0.25: a goblet's rim against a paperweight).
///
/// Why: where a ridge cuts a face (a goblet's rim edge 1e-3 mm into a pencil's cone), a solve
/// that starts on the ridge's face next to it reaches the crossing of the two faces, and the
/// nested solver from the lens of that crossing can wander to a far critical pair (the pencil's
/// apex 100 mm through the goblet); from the ridge itself the witness is 2-4 steps away.
pub(crate) fn edge_face_witness(
    a: &Body,
    b: &Body,
    la: Loc,
    lb: Loc,
    base_scale: f64,
    options: &NewtonOptions,
) -> Option<Solution> {
    let kind = |l: &Loc| match l {
        Some(FeatureLocation::Edge { .. }) => 1,
        Some(FeatureLocation::Face { .. }) => 2,
        _ => 0,
    };
    if kind(&la) * kind(&lb) != 2 {
        return None;
    }
    let closest = minimize(a, b, la, lb, base_scale, options, Reentry::Never);
    let start = match closest.outcome {
        Outcome::Penetrating => closest.state,
        Outcome::Converged => {
            let (pa, pb, _) = overlap_near(a, b, &closest.state, base_scale, options)?;
            State::new(a, b, pa, pb, base_scale)
        }
        _ => return None,
    };
    let feature = |l: &Loc| l.map(|l| l.feature());
    let mut witness = saddle_newton(a, b, &start, base_scale, options).or_else(|| {
        let deep = solve_penetration(a, b, start.la, start.lb, base_scale, options);
        let kept = feature(&deep.state.la) == feature(&start.la)
            && feature(&deep.state.lb) == feature(&start.lb);
        (deep.outcome == Outcome::Converged && kept && deep.state.stationary(options))
            .then_some(deep)
    })?;
    witness.iterations += closest.iterations;
    Some(witness)
}

/// Whether the witness candidate `state` has its outer point (the side with fewer parameters,
/// A on a tie as in [`solve_penetration`]) on an edge or vertex from which the depth rises into
/// an adjacent face (against the inner side's outward normal, the nested solver's re-entry
/// test): then the deepest pair is on that face, not on the edge (the bowl's rim fillet edge
/// against the pencil, where the edge's witness is 1.04e-4 mm deep and the face's 1e-3 mm).
///
/// Two edges have no inner side: each point is then tested with the connecting direction
/// itself, the depth |d| rising into a face of A whose inward tangent has a positive component
/// along d = P_a − P_b, into one of B along −d. (At a convex edge this holds exactly when d
/// leaves the edge's normal cone, the arc between its faces' normals, on that face's side.)
fn deepens_into_face(a: &Body, b: &Body, state: &State) -> bool {
    if state.na == 1 && state.n == 2 {
        let direction = state.d.normalize_or_zero();
        return reenter(a, &state.la, direction, 64.0 * EPS).is_some()
            || reenter(b, &state.lb, -direction, 64.0 * EPS).is_some();
    }
    let outer_is_a = state.na <= state.n - state.na;
    let (outer, outer_loc, pull) = depth_pull((a, b), state, outer_is_a);
    reenter(outer, &outer_loc, pull, 64.0 * EPS).is_some()
}

/// The signed depth D of the outer point below the inner feature (mm) and its scaled gradient
/// over the outer variables, or `None` where the inner feature has no outward direction.
fn depth(inner: &Body, state: &State, outer_is_a: bool) -> Option<(f64, [f64; 4])> {
    let (n, outer_minus_inner) = if outer_is_a {
        (state.outward_b(inner)?, state.d)
    } else {
        (state.outward_a(inner)?, -state.d)
    };
    let (first, o0, p) = if outer_is_a {
        (&state.ea.d, 0, state.na)
    } else {
        (&state.eb.d, state.na, state.n - state.na)
    };
    let mut gradient = [0.0; 4];
    for i in 0..p {
        gradient[o0 + i] = -n.dot(first[i]) / state.speed[o0 + i];
    }
    Some((-outer_minus_inner.dot(n), gradient))
}

/// The first-order move of the inner point when the outer one takes the scaled `step`: with
/// the inner point a closest point (∇_inner f = 0), H_ii δ_inner = −H_io δ_outer (implicit
/// function theorem). Zero where the inner block is not positive definite.
fn inner_prediction(state: &State, outer_is_a: bool, step: &[f64; 4]) -> [f64; 4] {
    let (n, na) = (state.n, state.na);
    let (i0, q) = if outer_is_a { (na, n - na) } else { (0, na) };
    let mut block = [[0.0; 4]; 4];
    let mut rhs = [0.0; 4];
    for i in 0..q {
        for j in 0..q {
            block[i][j] = state.hs[i0 + i][i0 + j];
        }
        rhs[i] = -(0..n)
            .filter(|j| !(i0..i0 + q).contains(j))
            .map(|j| state.hs[i0 + i][j] * step[j])
            .sum::<f64>();
    }
    let mut out = [0.0; 4];
    if let Some(l) = cholesky(&block, q) {
        let x = cholesky_solve(&l, q, &rhs);
        for i in 0..q {
            if x[i].is_finite() {
                out[i0 + i] = x[i];
            }
        }
    }
    out
}

/// The scaled outer step (zero on the inner variables) maximising D, clipped to `radius`, and
/// whether it is an escape from a stationary minimum or saddle of D.
fn outer_step(
    state: &State,
    outer_is_a: bool,
    depth: f64,
    gradient: &[f64; 4],
    radius: f64,
) -> ([f64; 4], bool) {
    let (n, na) = (state.n, state.na);
    let (o0, p, i0, q) = if outer_is_a {
        (0, na, na, n - na)
    } else {
        (na, n - na, 0, na)
    };
    let floor = 64.0 * EPS * (1.0 + state.scale * state.curvature);
    let mut step = [0.0; 4];
    let mut escape = false;
    if depth.abs() <= 1e3 * EPS * state.scale {
        // On (or at rounding distance from) the intersection curve: steepest ascent.
        step = *gradient;
    } else {
        // Inner block inverse (positive definite: the inner point is a closest point).
        let mut inner_block = [[0.0; 4]; 4];
        for i in 0..q {
            for j in 0..q {
                inner_block[i][j] = state.hs[i0 + i][i0 + j];
            }
        }
        let inner_eigen = sym_eigen(&inner_block, q);
        let mut inner_inv = [[0.0; 4]; 4];
        for k in 0..q {
            let lambda = inner_eigen.values[k].abs().max(floor);
            for i in 0..q {
                for j in 0..q {
                    inner_inv[i][j] +=
                        inner_eigen.vectors[i][k] * inner_eigen.vectors[j][k] / lambda;
                }
            }
        }
        // Hess D = (S − ∇D ∇Dᵀ) / D with S the Schur complement of the inner block.
        let mut hess = [[0.0; 4]; 4];
        for i in 0..p {
            for j in 0..p {
                let mut v = state.hs[o0 + i][o0 + j];
                for k in 0..q {
                    for l in 0..q {
                        v -= state.hs[o0 + i][i0 + k] * inner_inv[k][l] * state.hs[i0 + l][o0 + j];
                    }
                }
                hess[i][j] = (v - gradient[o0 + i] * gradient[o0 + j]) / depth;
            }
        }
        let eigen = sym_eigen(&hess, p);
        let floor = floor / depth.abs();
        for k in 0..p {
            let lambda = -eigen.values[k].abs().max(floor);
            let c: f64 = (0..p).map(|i| eigen.vectors[i][k] * gradient[o0 + i]).sum();
            for i in 0..p {
                step[o0 + i] -= eigen.vectors[i][k] * c / lambda;
            }
        }
        // At a stationary minimum or saddle of D (the outer point on the far side, say) the
        // Newton step vanishes: leave along the direction of positive curvature.
        let top = p.saturating_sub(1);
        if p > 0
            && step.iter().all(|s| s.abs() <= 4.0 * EPS * state.scale)
            && eigen.values[top] > floor
        {
            for i in 0..p {
                step[o0 + i] = eigen.vectors[i][top] * radius;
            }
            escape = true;
        }
    }
    let length = step.iter().map(|s| s * s).sum::<f64>().sqrt();
    if length > radius {
        for s in &mut step {
            *s *= radius / length;
        }
    }
    (step, escape)
}
