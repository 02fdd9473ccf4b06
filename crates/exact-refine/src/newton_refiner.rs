//! [`NewtonRefiner`]: the default [`Refiner`] (safeguarded Newton from the seed's locations).

use crate::checks::diagnostics::{diagnose, gap_within_error};
use crate::features::feature_eval::{Body, Frame, Loc};
use crate::features::feature_switch::{into_faces, on_closure, onto_nearest_edge};
use crate::options::NewtonOptions;
use crate::refined_contact::{RefineDiagnostics, RefineStatus, RefinedContact};
use crate::refiner::Refiner;
use crate::solver::crossing_probe::overlap_near;
use crate::solver::newton::{Outcome, Solution, State};
use crate::solver::pair_solve::{retry_on_sides, solve};
use crate::solver::penetration::solve_penetration;
use crate::solver::projection::project;
use geom_param::{DPose3, DVec3, FeatureLocation, Seed, SeedPoint, Solid};

/// Tolerance (sine of the angle between the connecting vector and the normal) of the seed
/// projections.
const SEED_ANGLE_TOLERANCE: f64 = 1e-3;

/// The default [`Refiner`]: runs the safeguarded Newton iteration of `newton.rs` on the pair
/// from the seed's own feature locations (a seed point whose parameters are not finite is
/// first projected onto its feature).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct NewtonRefiner {
    /// Tolerances and caps.
    pub options: NewtonOptions,
}

impl Refiner for NewtonRefiner {
    /// Nothing: every solve works in fixed-size arrays on the stack.
    type Scratch = ();

    fn refine(
        &self,
        a: &Solid,
        b: &Solid,
        pose_ab: &DPose3,
        seed: &Seed,
        _scratch: &mut (),
    ) -> RefinedContact {
        let pose_ok = pose_ab.translation.is_finite()
            && pose_ab.rotation.is_finite()
            && (pose_ab.rotation.length() - 1.0).abs() <= 1e-6;
        let (Some(start_a), Some(start_b)) = (sanitize(a, &seed.a), sanitize(b, &seed.b)) else {
            return invalid(seed);
        };
        if !pose_ok {
            return invalid(seed);
        }
        let body_a = Body::Solid {
            solid: a,
            frame: Frame::new(&DPose3::IDENTITY),
            within: None,
        };
        let body_b = Body::Solid {
            solid: b,
            frame: Frame::new(pose_ab),
            within: None,
        };
        let base = pose_ab.translation.length();
        let options = &self.options;
        // The projections only place the start of the pair solve, which alone decides the
        // accuracy: a connecting vector within 1e-3 rad of the normal is start enough (it
        // saves the last, quadratically converging, steps of each).
        let seed_options = NewtonOptions {
            angle_tolerance: options.angle_tolerance.max(SEED_ANGLE_TOLERANCE),
            ..*options
        };
        // A seed's own parameters (Stage 2 interpolates them from the mesh vertices' exact
        // correspondences) place the exact start within about the mesh's chordal error of the
        // seed point, and the pair solve starts there: projecting the point first moved the
        // start by no more than that, and cost a third of a Stage 2 seed's evaluations without
        // saving the pair solve a step on the fixture scenes (session 21). Only a point whose
        // parameters were not finite (`sanitize` put them mid-domain) is placed by projection.
        // A vertex has no parameters to place: whether the answer lies on an adjacent face
        // instead is decided by the pair solve's own re-entry test.
        let placeable = |point: &SeedPoint, start: &FeatureLocation| {
            point.local_point.is_finite()
                && !matches!(start, FeatureLocation::Vertex { .. })
                && !location_is_finite(&point.location)
        };
        let mut la = Some(start_a);
        let mut lb = Some(start_b);
        if placeable(&seed.a, &start_a) {
            la = project(&body_a, la, seed.a.local_point, 0.0, &seed_options)
                .state
                .la;
        }
        if placeable(&seed.b, &start_b) {
            lb = project(
                &body_b,
                lb,
                *pose_ab * seed.b.local_point,
                base,
                &seed_options,
            )
            .state
            .la;
        }
        let solution = solve(&body_a, &body_b, la, lb, base, options);
        let solution = on_seed_faces(
            &body_a,
            &body_b,
            (start_a, start_b),
            (la, lb),
            solution,
            base,
            options,
        );
        let solution = from_seed_locations(
            &body_a,
            &body_b,
            (start_a, start_b),
            (la, lb),
            solution,
            base,
            options,
        );
        let (solution, distance, normal, diagnostics) =
            check_touch(&body_a, &body_b, solution, base, options);
        let state = &solution.state;
        RefinedContact {
            point_a: state.ea.point,
            point_b: state.eb.point,
            location_a: state.la.unwrap_or(start_a),
            location_b: state.lb.unwrap_or(start_b),
            distance,
            normal,
            diagnostics,
        }
    }
}

/// The minimum of the seed's own pair of faces, when the pair solve from it (`solution`)
/// left a seed face and another minimum lies on it: Stage 2 seeds every close pair of
/// components, so a minimum of the seed's pair that Newton walked past, across a smooth
/// joint into a neighbouring face with a lower minimum, has no other seed (a loft's rim over
/// a goblet's lip: two minima 0.9 mm apart on either side of the lip's joint, one seed each,
/// both solves ended in the lower one).
///
/// When either side of `solution` ended off the closure of its seed face (`seeds`: the seed
/// locations; the face itself, its edges and vertices), the pair is solved again from its
/// `starts` with re-entry kept on the seed faces (`Body::Solid::within`), and that
/// answer is polished without the restriction: if it stays on the seed faces' closures and
/// converges, it is a local minimum of the distance over both whole solids (an end on a seed
/// face's boundary that is no minimum of the union slides off in the polish), and it is the
/// answer; so is a converged polish that left the seed faces when `solution` did not converge.
/// Otherwise `solution` is.
fn on_seed_faces(
    a: &Body,
    b: &Body,
    seeds: (FeatureLocation, FeatureLocation),
    starts: (Loc, Loc),
    solution: Solution,
    base: f64,
    options: &NewtonOptions,
) -> Solution {
    let (
        (
            Body::Solid {
                solid: sa,
                frame: fa,
                ..
            },
            FeatureLocation::Face { id: face_a, .. },
        ),
        (
            Body::Solid {
                solid: sb,
                frame: fb,
                ..
            },
            FeatureLocation::Face { id: face_b, .. },
        ),
    ) = ((a, seeds.0), (b, seeds.1))
    else {
        return solution;
    };
    let on_seed = |state: &State| {
        state.la.is_some_and(|l| on_closure(sa, &l, face_a))
            && state.lb.is_some_and(|l| on_closure(sb, &l, face_b))
    };
    if on_seed(&solution.state) {
        return solution;
    }
    let kept_a = Body::Solid {
        solid: sa,
        frame: *fa,
        within: Some(face_a),
    };
    let kept_b = Body::Solid {
        solid: sb,
        frame: *fb,
        within: Some(face_b),
    };
    let kept = solve(&kept_a, &kept_b, starts.0, starts.1, base, options);
    if kept.outcome != Outcome::Converged || !on_seed(&kept.state) {
        return solution;
    }
    let polished = solve(a, b, kept.state.la, kept.state.lb, base, options);
    // A converged polish that left the seed faces is still a local minimum over both solids:
    // better than an answer that did not converge.
    let replaces_unconverged =
        polished.outcome == Outcome::Converged && solution.outcome != Outcome::Converged;
    if !replaces_unconverged
        && (polished.outcome != Outcome::Converged || !on_seed(&polished.state))
    {
        return solution;
    }
    let iterations = solution.iterations + kept.iterations + polished.iterations;
    Solution {
        iterations,
        ..polished
    }
}

/// Other starts for a pair solve that did not converge from its `starts` (the seed's
/// locations, or a point's projection where they had no finite parameters), tried in turn
/// until one converges: the seed's own locations (`seeds`), when they differ, which the
/// solve's start puts on an edge or vertex when they lie on one to rounding
/// ([`crate::features::feature_switch::settle_start`]); both moved onto their nearest edges;
/// and on each side the faces across that edge, the other side at its seed. The answer is the
/// first that converged, else `solution`.
///
/// Why: a start from points of the mesh may lie on the wrong side of an edge (these cases
/// were met when every seed point was projected first). A seed on two crossing rims (a vase's bottom edge pressed
/// 1.0004e-3 mm into a paperweight along its edge 2, both seed locations at v = 1 to rounding)
/// was projected 1.5e-8 in parameter into the vase's face, and the solve from there crept
/// along the rim for 158 steps without converging, while the one from the rims converges in
/// 43 to the edge-face witness. A goblet's rim 0.012 mm inside a tube's outer cylinder, 0.19
/// mm below its end, was seeded on the tube's end face; from there, and from the end's outer
/// edge, the penetration solve went down the rim to a stall 1.1 mm "deep", while from the
/// cylinder across that edge it converges in 4 steps to the witness.
fn from_seed_locations(
    a: &Body,
    b: &Body,
    seeds: (FeatureLocation, FeatureLocation),
    starts: (Loc, Loc),
    solution: Solution,
    base: f64,
    options: &NewtonOptions,
) -> Solution {
    if solution.outcome == Outcome::Converged {
        return solution;
    }
    let seeds = (Some(seeds.0), Some(seeds.1));
    let edges = (onto_nearest_edge(a, seeds.0), onto_nearest_edge(b, seeds.1));
    let mut others = vec![seeds, edges];
    others.extend(into_faces(a, edges.0).into_iter().map(|fa| (fa, seeds.1)));
    others.extend(into_faces(b, edges.1).into_iter().map(|fb| (seeds.0, fb)));
    let mut iterations = solution.iterations;
    for (k, &start) in others.iter().enumerate() {
        if start == starts || others[..k].contains(&start) {
            continue;
        }
        let again = solve(a, b, start.0, start.1, base, options);
        iterations += again.iterations;
        if again.outcome == Outcome::Converged {
            return Solution {
                iterations,
                ..again
            };
        }
    }
    Solution {
        iterations,
        ..solution
    }
}

/// The final answer from a pair solve's `solution`: its signed distance, normal and
/// diagnostics; but a converged pair whose gap is within its own error estimate is a touch
/// only if its normals are opposed (the diagnostics' test) and the surfaces do not cross next
/// to it ([`overlap_near`]). Where they do,
/// the answer is the penetration witness solved from the overlapping probe when that
/// converges deeper to a witness that passes the second-order test, and otherwise the pair
/// itself. (A lens so shallow that its witness does not converge is within the distance's
/// error of d = 0 anyway: `soak 10000 --seed 14` had 35 touches built at |g| < 1e-9 mm lost
/// when such pairs were dropped instead.)
fn check_touch(
    a: &Body,
    b: &Body,
    solution: Solution,
    base: f64,
    options: &NewtonOptions,
) -> (Solution, f64, DVec3, RefineDiagnostics) {
    let (distance, normal) = signed_distance(a, b, &solution.state);
    let diagnostics = diagnose(a, b, &solution, normal);
    let state = &solution.state;
    if !diagnostics.converged
        || !gap_within_error(
            state,
            diagnostics.error_estimate,
            diagnostics.point_error_estimate,
        )
    {
        return (solution, distance, normal, diagnostics);
    }
    let Some((la, lb, _)) = overlap_near(a, b, state, base, options) else {
        return (solution, distance, normal, diagnostics);
    };
    let deep = retry_on_sides(
        a,
        b,
        solve_penetration(a, b, la, lb, base, options),
        base,
        options,
    );
    let (deep_distance, deep_normal) = signed_distance(a, b, &deep.state);
    if deep.outcome == Outcome::Converged && deep_distance < distance {
        let iterations = solution.iterations + deep.iterations;
        let deep = Solution { iterations, ..deep };
        let deep_diagnostics = diagnose(a, b, &deep, deep_normal);
        if deep_diagnostics.is_local_minimum {
            return (deep, deep_distance, deep_normal, deep_diagnostics);
        }
    }
    (solution, distance, normal, diagnostics)
}

/// The signed distance and unit normal (A to B) at a final state: along A's outward normal
/// when A's point is on a face, else along B's outward normal negated when B's is, else along
/// the connecting vector (reversed when penetrating).
///
/// Why a face's normal first: at a critical pair the connecting vector is parallel to it, and
/// at a touch (|d| ~ 1e-11 mm) the connecting vector's direction is rounding (a pencil's apex
/// touching a face gave a normal 4e-5 rad off), while the face's normal is exact.
fn signed_distance(a: &Body, b: &Body, state: &State) -> (f64, DVec3) {
    let gap = -state.d; // P_b − P_a
    if let Some(FeatureLocation::Face { .. }) = state.la {
        if let Some(n) = state.outward_a(a) {
            return (gap.dot(n), n);
        }
    }
    if let Some(FeatureLocation::Face { .. }) = state.lb {
        if let Some(n) = state.outward_b(b) {
            return (-gap.dot(n), -n);
        }
    }
    if let Some(n) = edge_pair_normal(a, b, state) {
        return (gap.dot(n), n);
    }
    let sign = state.sign(a, b);
    let normal = (gap * sign)
        .try_normalize()
        .or_else(|| state.outward_b(b).map(|n| -n))
        .or_else(|| state.outward_a(a))
        .unwrap_or(DVec3::Z);
    (sign * gap.length(), normal)
}

/// For two edges with tangents apart, their common normal t_a × t_b (unit), turned away from
/// A (along A's outward direction there, or against B's): exact at a touch, where the
/// connecting vector's direction is rounding. `None` otherwise, or when neither outward
/// direction orients it.
fn edge_pair_normal(a: &Body, b: &Body, state: &State) -> Option<DVec3> {
    let (Some(FeatureLocation::Edge { .. }), Some(FeatureLocation::Edge { .. })) =
        (state.la, state.lb)
    else {
        return None;
    };
    let common = state.ea.d[0]
        .normalize_or_zero()
        .cross(state.eb.d[0].normalize_or_zero());
    // Below 1e-6 (tangents within 1e-6 rad) the cross product loses its direction.
    if common.length() <= 1e-6 {
        return None;
    }
    let common = common.normalize();
    let away = state
        .outward_a(a)
        .map(|n| n.dot(common))
        .filter(|c| c.abs() > 1e-6)
        .or_else(|| {
            state
                .outward_b(b)
                .map(|n| -n.dot(common))
                .filter(|c| c.abs() > 1e-6)
        })?;
    Some(common * away.signum())
}

/// The seed's location with finite parameters (non-finite ones reset to the middle of their
/// domain), or `None` when its feature is not on `solid`.
fn sanitize(solid: &Solid, point: &SeedPoint) -> Option<FeatureLocation> {
    let mid = |p: f64, range: geom_param::ParamRange| {
        if p.is_finite() {
            p
        } else {
            0.5 * (range.min + range.max)
        }
    };
    match point.location {
        FeatureLocation::Face { id, u, v } => {
            let [du, dv] = solid.faces.get(id.0 as usize)?.surface.domain();
            Some(FeatureLocation::Face {
                id,
                u: mid(u, du),
                v: mid(v, dv),
            })
        }
        FeatureLocation::Edge { id, t } => {
            let range = solid.edges.get(id.0 as usize)?.curve.domain();
            Some(FeatureLocation::Edge {
                id,
                t: mid(t, range),
            })
        }
        FeatureLocation::Vertex { id } => solid.vertices.get(id.0 as usize).map(|_| point.location),
    }
}

/// Whether every parameter of `location` is finite (a vertex has none).
fn location_is_finite(location: &FeatureLocation) -> bool {
    match *location {
        FeatureLocation::Face { u, v, .. } => u.is_finite() && v.is_finite(),
        FeatureLocation::Edge { t, .. } => t.is_finite(),
        FeatureLocation::Vertex { .. } => true,
    }
}

/// The result for input that cannot be refined.
fn invalid(seed: &Seed) -> RefinedContact {
    let clean = |l: FeatureLocation| match l {
        FeatureLocation::Face { id, u, v } => FeatureLocation::Face {
            id,
            u: if u.is_finite() { u } else { 0.0 },
            v: if v.is_finite() { v } else { 0.0 },
        },
        FeatureLocation::Edge { id, t } => FeatureLocation::Edge {
            id,
            t: if t.is_finite() { t } else { 0.0 },
        },
        vertex => vertex,
    };
    RefinedContact {
        point_a: DVec3::ZERO,
        point_b: DVec3::ZERO,
        location_a: clean(seed.a.location),
        location_b: clean(seed.b.location),
        distance: f64::INFINITY,
        normal: DVec3::Z,
        diagnostics: RefineDiagnostics {
            iterations: 0,
            gradient_norm: f64::INFINITY,
            condition: f64::INFINITY,
            converged: false,
            is_local_minimum: false,
            error_estimate: f64::INFINITY,
            point_error_estimate: f64::INFINITY,
            gap_curvature: f64::INFINITY,
            status: RefineStatus::InvalidInput,
        },
    }
}
