//! The safeguarded Newton solver for the closest pair of two features (0, 1 or 2 parameters
//! each): f = ½|P_a − P_b|² minimised with a trust region; a penetrating pair ends the
//! minimisation ([`Outcome::Penetrating`]), and the pair solve ([`crate::solver::pair_solve`])
//! hands it to [`crate::solver::penetration`].
//!
//! Every step lies inside a trust region on the step length (in mm: variables are scaled by
//! their speeds |∂P/∂x_i|) and is accepted only if f does not increase (up to rounding, and,
//! for a step onto another feature, up to |d| x the model tolerance by which a face and its
//! edge may disagree); a coordinate already on its bound that the step pushes outward is held
//! there while the others move. Where the connecting
//! vector is within 30 degrees of the normals it is the Newton step for the distance |d| itself
//! ([`distance_newton_step`]), which is exact along the rolling directions where f is quartic
//! (near touch); otherwise, or straight after such a step was rejected, the Newton step on f,
//! by Cholesky where the Hessian is safely positive definite and otherwise with each
//! eigenvalue replaced by its floored magnitude, which makes it a descent direction of f also
//! where the Hessian is indefinite or nearly singular (a "saddle-free" Newton step). A distance
//! step is taken with a second-order correction that cancels the parametrisation's own turn
//! along the face ([`tangential_correction`]; a disk in polar parameters). Both are
//! plain Newton at an isolated minimum, so convergence there is quadratic; at an exact touch,
//! where the minimum is degenerate, the distance step still converges in a few steps to the
//! accuracy that rounding allows.

// Small dense matrices (at most 4 x 4): index arithmetic reads closer to the formulas.
#![allow(clippy::needless_range_loop)]
use crate::features::feature_eval::{Body, FeatureEval, Loc, LocalFacePoint, params, with_params};
use crate::features::feature_switch::{
    TakenEntries, reenter, reenter_untaken, settle, settle_step,
};
use crate::linalg::dense_solve::{
    by_size, cholesky, cholesky_n, cholesky_solve, cholesky_solve_n, smallest_eigenvalue_bound,
};
use crate::linalg::sym_eigen::{SymEigen, sym_eigen};
use crate::options::NewtonOptions;
use geom_param::{DVec3, FaceId, FeatureLocation, ParamRange};
use std::f64::consts::PI;

/// Calls `f::<NA, NB>(args)` for the pair kind (`na`, `nb`) parameters on A and B (each 0, 1
/// or 2; larger counts are taken as 2): one monomorphised copy per kind, whose loops over
/// constant sizes the compiler unrolls.
macro_rules! by_pair_kind {
    ($na:expr, $nb:expr, $f:ident($($arg:expr),*)) => {
        match ($na, $nb) {
            (0, 0) => $f::<0, 0>($($arg),*),
            (0, 1) => $f::<0, 1>($($arg),*),
            (0, _) => $f::<0, 2>($($arg),*),
            (1, 0) => $f::<1, 0>($($arg),*),
            (1, 1) => $f::<1, 1>($($arg),*),
            (1, _) => $f::<1, 2>($($arg),*),
            (_, 0) => $f::<2, 0>($($arg),*),
            (_, 1) => $f::<2, 1>($($arg),*),
            (_, _) => $f::<2, 2>($($arg),*),
        }
    };
}
pub(crate) use by_pair_kind;

/// Rounding unit.
pub(crate) const EPS: f64 = f64::EPSILON;

/// Speed ratio below which a face parameter counts as running round a pole or apex
/// ([`State::pole_frozen`]).
const POLE_SPEED_RATIO: f64 = 1e-6;

/// The assembled problem at one pair of locations.
#[derive(Clone, Copy, Debug)]
pub(crate) struct State {
    /// Location on A.
    pub la: Loc,
    /// Location on B.
    pub lb: Loc,
    /// Evaluation on A.
    pub ea: FeatureEval,
    /// Evaluation on B.
    pub eb: FeatureEval,
    /// Number of A's parameters; B's follow them.
    pub na: usize,
    /// Number of variables.
    pub n: usize,
    /// P_a − P_b (mm).
    pub d: DVec3,
    /// Speeds |∂P/∂x_i| (floored), the variable scaling.
    pub speed: [f64; 4],
    /// Scaled gradient g_i / speed_i (mm): the connecting vector's tangential components.
    pub gs: [f64; 4],
    /// Scaled Hessian H_ij / (speed_i speed_j) (dimensionless).
    pub hs: [[f64; 4]; 4],
    /// Coordinate scale (mm) for rounding floors: max(|P_a|, |P_b|, |B's translation|).
    pub scale: f64,
    /// Largest |∂²P/∂x_i∂x_j| / (speed_i speed_j) (1/mm): curvature scale of the Hessian.
    pub curvature: f64,
    /// A's and B's outward directions at the points, each once a penetration test of the
    /// solve took it ([`Self::penetrating_remembered`]), for the later questions about this
    /// state (`None`: not taken).
    outward: [Option<Option<DVec3>>; 2],
}

impl State {
    /// The largest trust radius and the starting one (mm of arc length): twice, and half, the
    /// larger of the current gap and the parameter speeds.
    pub(crate) fn trust_radii(&self) -> (f64, f64) {
        let max_radius = 2.0
            * self.speed[..self.n]
                .iter()
                .fold(self.d.length(), |m, s| m.max(*s));
        (max_radius, 0.25 * max_radius)
    }

    pub(crate) fn new(a: &Body, b: &Body, la: Loc, lb: Loc, base_scale: f64) -> Self {
        Self::evaluated(a, b, la, lb, base_scale, [None, None])
    }

    /// [`Self::new`], taking each face's surface evaluation from `known` (A's, B's) where it
    /// is of that face point ([`Body::eval_reusing`]).
    pub(crate) fn evaluated(
        a: &Body,
        b: &Body,
        la: Loc,
        lb: Loc,
        base_scale: f64,
        known: [Option<&LocalFacePoint>; 2],
    ) -> Self {
        let (ea, eb) = (a.eval_reusing(&la, known[0]), b.eval_reusing(&lb, known[1]));
        let d = ea.point - eb.point;
        let (na, n) = (ea.n, ea.n + eb.n);
        let scale = base_scale
            .max(ea.point.length())
            .max(eb.point.length())
            .max(f64::MIN_POSITIVE);
        let Assembled {
            speed,
            gs,
            hs,
            curvature,
        } = by_pair_kind!(ea.n, eb.n, assemble(&ea, &eb, d));
        Self {
            la,
            lb,
            ea,
            eb,
            na,
            n,
            d,
            speed,
            gs,
            hs,
            scale,
            curvature,
            outward: [None, None],
        }
    }

    /// Rounding floor of the tangential residual (mm).
    pub(crate) fn gradient_floor(&self) -> f64 {
        16.0 * EPS * self.scale
    }

    /// Largest scaled gradient component (mm).
    pub(crate) fn gradient_norm(&self) -> f64 {
        self.gs[..self.n].iter().fold(0.0, |m, g| m.max(g.abs()))
    }

    /// The step's model with the running parameter of a face point next to a pole or apex
    /// frozen: a face parameter whose speed is below [`POLE_SPEED_RATIO`] times the other's
    /// on the same face runs round the vertex, is no coordinate there, and its row and column
    /// become the identity with a zero gradient. The step then moves along the meridian, and
    /// the parameter is free again once the point is off the vertex.
    ///
    /// Why: within 1e-9 mm of a pencil's apex the scaled Hessian's running entry is
    /// |d| / r ~ 1e7 (the circle of radius r about the apex), the running parameter jumped
    /// across the optimal meridian every step (±0.11 rad) and held the step along the meridian
    /// to doubling from 1e-13: 128 iterations reached v = 1 − 6e-9 of a minimum at v = 0.984
    /// (jar-pencil 6447751408969511474 of `soak 10000 --seed 13102`, a missed contact).
    fn pole_frozen(&self) -> Self {
        let mut model = *self;
        for (first, count) in [(0, self.na), (self.na, self.n - self.na)] {
            if count != 2 {
                continue;
            }
            for (i, j) in [(first, first + 1), (first + 1, first)] {
                if self.speed[i] > POLE_SPEED_RATIO * self.speed[j] {
                    continue;
                }
                model.gs[i] = 0.0;
                for k in 0..self.n {
                    model.hs[i][k] = 0.0;
                    model.hs[k][i] = 0.0;
                }
                model.hs[i][i] = 1.0;
            }
        }
        model
    }

    pub(crate) fn stationary(&self, options: &NewtonOptions) -> bool {
        self.gradient_norm() <= options.angle_tolerance * self.d.length() + self.gradient_floor()
    }

    /// Rounding floor of the scaled Hessian's eigenvalues: below it an eigenvalue is zero.
    pub(crate) fn eigen_floor(&self, values: &[f64; 4]) -> f64 {
        let largest = values[..self.n].iter().fold(0.0_f64, |m, l| m.max(l.abs()));
        64.0 * EPS * (largest + self.scale * self.curvature)
    }

    /// Whether the two points lie on different sides: one in front of the other's outward
    /// direction and the other behind it, each by more than half the gap (so that neither
    /// test is a direction grazing a normal cone's edge), with both directions known and the
    /// points farther apart than rounding. Such a pair is neither a contact (both in front)
    /// nor a penetration witness (both behind): P_a inside B, say, while P_b is outside A, as
    /// a pole of A inside a rod B against the rod's far side, both normals pointing the same
    /// way. It can still be a critical pair, even a local minimum of |d|.
    pub(crate) fn sides_disagree(&self, a: &Body, b: &Body) -> bool {
        let gap = -self.d; // P_b − P_a
        let length = gap.length();
        if length <= 1e3 * EPS * self.scale {
            return false;
        }
        let (Some(na), Some(nb)) = (self.outward_a(a), self.outward_b(b)) else {
            return false;
        };
        // > 0: P_b in front of A; > 0: P_a in front of B.
        let (front_a, front_b) = (gap.dot(na), -gap.dot(nb));
        front_a * front_b < 0.0 && front_a.abs() > 0.5 * length && front_b.abs() > 0.5 * length
    }

    /// +1 when separated (or touching), −1 when penetrating: P_b lies behind A's outward
    /// direction at P_a and P_a behind B's at P_b (both tests where both directions exist; far
    /// from the answer one of them alone is not a reliable witness of penetration). Points
    /// within rounding of each other (1e3 ε x scale, as at an exact touch) are touching: the
    /// direction of d is noise there. Two edges are tested with d's part across both
    /// ([`Self::edge_pair_gap`]), and are not penetrating while that part is within the
    /// curvature scale x the squared gradient (the edges' turn over the run between the points).
    pub(crate) fn sign(&self, a: &Body, b: &Body) -> f64 {
        self.sign_with(|side| {
            if side == 0 {
                self.outward_a(a)
            } else {
                self.outward_b(b)
            }
        })
    }

    /// [`Self::sign`] with the outward directions from `outward` (0: A's, 1: B's), asked only
    /// as far as the answer needs them: first the side whose direction is cheap (a face's,
    /// from its derivatives; an edge's sums its faces' normals, evaluating each face again),
    /// and the other only when the first does not already say "not behind", which rules
    /// penetration out whatever the other says.
    fn sign_with(&self, mut outward: impl FnMut(usize) -> Option<DVec3>) -> f64 {
        if self.d.length() <= 1e3 * EPS * self.scale {
            return 1.0;
        }
        let d = match self.edge_pair_gap() {
            // The two edges' points are still far apart along them: over that run the edges
            // turn off their tangent lines by up to curvature x run², which can exceed the
            // gap across, and the gap's sign says nothing yet.
            Some(across) if across.length() <= self.curvature * self.gradient_norm().powi(2) => {
                return 1.0;
            }
            Some(across) => across,
            None => self.d,
        };
        // P_b behind A's direction at P_a, P_a behind B's at P_b.
        let behind = |side: usize, n: DVec3| {
            if side == 0 {
                (-d).dot(n) < 0.0
            } else {
                d.dot(n) < 0.0
            }
        };
        let face_on_a = matches!(self.la, Some(FeatureLocation::Face { .. })) && self.ea.n == 2;
        let first = usize::from(!face_on_a);
        let second = 1 - first;
        let penetrating = match outward(first).map(|n| behind(first, n)) {
            Some(false) => false,
            Some(true) => outward(second).is_none_or(|n| behind(second, n)),
            None => outward(second).is_some_and(|n| behind(second, n)),
        };
        if penetrating { -1.0 } else { 1.0 }
    }

    /// For two edges with tangents t_a, t_b apart (sin of the angle above 1e-6), the part of
    /// the connecting vector along their common normal m = t_a × t_b: (d · m) m / |m|². `None`
    /// for any other pair.
    ///
    /// Why: an edge's outward direction (its faces' normals summed) is normal to its own
    /// tangent but not to the other edge's, so away from the common perpendicular the part
    /// of d along the other edge decides the sign. Two rims of goblets touching at 5.2e-10 mm
    /// were taken as penetrating at their first iterate (|d| = 1.2e-6 mm, nearly all along
    /// the rims), and the penetration solvers never converged. At the common perpendicular d
    /// is along m and the test is unchanged.
    fn edge_pair_gap(&self) -> Option<DVec3> {
        if self.na != 1 || self.n != 2 {
            return None;
        }
        let (Some(FeatureLocation::Edge { .. }), Some(FeatureLocation::Edge { .. })) =
            (self.la, self.lb)
        else {
            return None;
        };
        let m = self.ea.d[0]
            .normalize_or_zero()
            .cross(self.eb.d[0].normalize_or_zero());
        let m2 = m.length_squared();
        (m2 > 1e-12).then(|| m * (self.d.dot(m) / m2))
    }

    /// A's outward direction at its point ([`Body::outward_at`]; `a` is the body the state
    /// was assembled with).
    pub(crate) fn outward_a(&self, a: &Body) -> Option<DVec3> {
        match self.outward[0] {
            Some(n) => n,
            None => a.outward_at(&self.la, &self.ea),
        }
    }

    /// B's outward direction at its point.
    pub(crate) fn outward_b(&self, b: &Body) -> Option<DVec3> {
        match self.outward[1] {
            Some(n) => n,
            None => b.outward_at(&self.lb, &self.eb),
        }
    }

    /// [`Self::penetrating`], keeping the outward directions it takes in the state: a solve
    /// that ends here asks for them again (diagnostics, signed distance). The same numbers
    /// either way: both are [`Body::outward_at`] of the state's own locations and evaluations.
    pub(crate) fn penetrating_remembered(&mut self, a: &Body, b: &Body) -> bool {
        if !(self.na > 0 && self.na < self.n) {
            return false;
        }
        let mut taken = self.outward;
        let sign = self.sign_with(|side| {
            *taken[side].get_or_insert_with(|| {
                if side == 0 {
                    a.outward_at(&self.la, &self.ea)
                } else {
                    b.outward_at(&self.lb, &self.eb)
                }
            })
        });
        self.outward = taken;
        sign < 0.0
    }

    /// Whether the pair penetrates ([`Self::sign`] negative) with parameters on both sides:
    /// only such a pair can be a penetration witness (with no parameters on one side the
    /// witness test does not apply), so the outward directions are evaluated only then.
    pub(crate) fn penetrating(&self, a: &Body, b: &Body) -> bool {
        self.na > 0 && self.na < self.n && self.sign(a, b) < 0.0
    }

    /// The number of negative eigenvalues of f's Hessian at a penetration witness on these
    /// features: the dimension of the tangent directions the two points share (both normal
    /// to the connecting vector), along which moving both together rolls the pair shallower.
    /// With a face on either side that is min(n_a, n_b): the face's tangent plane holds every
    /// tangent of the other feature normal to d (face-face 2, face-edge 1). Two edges share
    /// none unless they are parallel: their witness (the common perpendicular of two crossing
    /// rims, d inside both edges' normal cones) is a minimum of f over the two edge
    /// parameters, like the common perpendicular of two skew lines, so 0 (parallel edges
    /// are degenerate, and the inertia test then rejects them).
    pub(crate) fn witness_index(&self) -> usize {
        let nb = self.n - self.na;
        if self.na == 1 && nb == 1 {
            0
        } else {
            self.na.min(nb)
        }
    }

    /// The scaled Hessian with the tangential part of the features' second derivatives left
    /// out: H_ij − s_i d_t · ∂²P/∂x_i∂x_j on each side's block, d_t the part of the connecting
    /// vector in that side's tangent space (s_i = +1 on A, −1 on B). It is the model of f along
    /// a step whose tangential second-order displacement is cancelled
    /// ([`tangential_correction`]): the point then moves along the linear prediction plus the
    /// normal part of ½ Σ ∂²P Δx Δx, so only d's normal part meets the second derivatives. At a
    /// stationary pair d_t is the residual and the two Hessians agree.
    fn normal_hessian(&self) -> [[f64; 4]; 4] {
        let mut out = self.hs;
        for (offset, e, sign) in [(0, &self.ea, 1.0), (self.na, &self.eb, -1.0)] {
            let Some(d_t) = tangential_part(e, self.d) else {
                continue;
            };
            for i in 0..e.n {
                for j in 0..e.n {
                    let (gi, gj) = (offset + i, offset + j);
                    out[gi][gj] -= sign * d_t.dot(e.dd[i][j]) / (self.speed[gi] * self.speed[gj]);
                }
            }
        }
        out
    }

    fn merit(&self) -> f64 {
        0.5 * self.d.length_squared()
    }
}

/// The variable scaling, scaled gradient and Hessian and curvature scale of a [`State`].
struct Assembled {
    speed: [f64; 4],
    gs: [f64; 4],
    hs: [[f64; 4]; 4],
    curvature: f64,
}

/// [`State`]'s scaled gradient g_i / speed_i and Hessian H_ij / (speed_i speed_j) of
/// f = ½|d|², d = P_a − P_b, for `NA` parameters on A (`ea`) and `NB` on B (`eb`): with s_i = +1
/// on A and −1 on B, g_i = s_i d · ∂P/∂x_i and H_ij = s_i s_j ∂P/∂x_i · ∂P/∂x_j + s_i d · ∂²P/∂x_i∂x_j
/// (the second term only within one side). Constant sizes let the compiler unroll the loops
/// for each of the nine feature pair kinds; the arithmetic and its order are the same for all.
fn assemble<const NA: usize, const NB: usize>(
    ea: &FeatureEval,
    eb: &FeatureEval,
    d: DVec3,
) -> Assembled {
    let n = NA + NB;
    let mut first = [DVec3::ZERO; 4];
    first[..NA].copy_from_slice(&ea.d[..NA]);
    first[NA..n].copy_from_slice(&eb.d[..NB]);
    let mut length = [0.0; 4];
    for i in 0..n {
        length[i] = first[i].length();
    }
    let max_speed = length[..n].iter().fold(0.0_f64, |m, l| m.max(*l));
    let floor = (1e-12 * max_speed).max(f64::MIN_POSITIVE.sqrt());
    let mut speed = [1.0; 4];
    for i in 0..n {
        speed[i] = length[i].max(floor);
    }
    let mut gs = [0.0; 4];
    let mut hs = [[0.0; 4]; 4];
    // Squared, so that the loop takes no square roots.
    let mut curvature2 = 0.0_f64;
    for i in 0..n {
        let (si, ai) = if i < NA { (1.0, true) } else { (-1.0, false) };
        gs[i] = si * d.dot(first[i]) / speed[i];
        // The Hessian is symmetric: fill the upper triangle and mirror it.
        for j in i..n {
            let sj = if j < NA { 1.0 } else { -1.0 };
            let same_side = (j < NA) == ai;
            let speeds = speed[i] * speed[j];
            let second = if same_side {
                let dd = if ai {
                    ea.dd[i][j]
                } else {
                    eb.dd[i - NA][j - NA]
                };
                curvature2 = curvature2.max(dd.length_squared() / (speeds * speeds));
                si * d.dot(dd)
            } else {
                0.0
            };
            hs[i][j] = (si * sj * first[i].dot(first[j]) + second) / speeds;
            hs[j][i] = hs[i][j];
        }
    }
    Assembled {
        speed,
        gs,
        hs,
        curvature: curvature2.sqrt(),
    }
}

/// How a solve ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Outcome {
    /// Stationary to tolerance, or the Newton step fell below rounding.
    Converged,
    /// `max_iterations` steps without convergence.
    IterationLimit,
    /// The trust region shrank below rounding without convergence.
    Stalled,
    /// `max_feature_switches` exceeded.
    SwitchLimit,
    /// (Internal hand-over) the minimisation reached a penetrating pair.
    Penetrating,
}

/// The end state of a solve.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Solution {
    pub state: State,
    pub iterations: u32,
    pub outcome: Outcome,
}

/// The edge location (`loc`, evaluated as `eval`) moved by `w` (mm, A's frame) to first order:
/// the parameter step (w · C') / |C'|², cut by [`inside_fraction`] so that the point stays on
/// its edge. `loc` unchanged where the edge's speed is zero or the location is not an edge.
pub(crate) fn slide_on_edge(body: &Body, loc: &Loc, eval: &FeatureEval, w: DVec3) -> Loc {
    let speed2 = eval.d[0].length_squared();
    if eval.n != 1 || speed2.is_nan() || speed2 <= 0.0 {
        return *loc;
    }
    let (x, _) = params(loc);
    let step = [eval.d[0].dot(w) / speed2, 0.0];
    let fraction = inside_fraction(&body.domains(loc), x, step);
    with_params(loc, [x[0] + fraction * step[0], x[1]])
}

/// The face location (`loc`, evaluated as `eval`) moved by the tangent displacement `w` (mm,
/// A's frame) to first order: the least-squares parameter step, cut by [`inside_fraction`] so
/// that the point stays on its face. `loc` unchanged where the face's first fundamental form
/// is singular (a pole) or the location is not a face.
pub(crate) fn slide_on_face(body: &Body, loc: &Loc, eval: &FeatureEval, w: DVec3) -> Loc {
    if eval.n != 2 {
        return *loc;
    }
    let e = eval;
    let (e11, e12, e22) = (e.d[0].dot(e.d[0]), e.d[0].dot(e.d[1]), e.d[1].dot(e.d[1]));
    let (r1, r2) = (e.d[0].dot(w), e.d[1].dot(w));
    let det = e11 * e22 - e12 * e12;
    let (x, _) = params(loc);
    if det.is_nan() || det <= 0.0 {
        return *loc;
    }
    let step = [(e22 * r1 - e12 * r2) / det, (e11 * r2 - e12 * r1) / det];
    let fraction = inside_fraction(&body.domains(loc), x, step);
    with_params(loc, [x[0] + fraction * step[0], x[1] + fraction * step[1]])
}

/// The fraction of the parameter `step` from `x` to take so that the point stays on its face:
/// 1 when the whole step stays inside the non-periodic ranges of `domains`, otherwise half the
/// fraction that reaches the first side crossed.
///
/// Why: the crossing restart's step (the lens size angle / curvature) is a local estimate; a step
/// that leaves the face is clamped onto its side (an edge) far outside the lens, where the
/// penetration solve can converge to a deep critical pair that is no witness (two goblets' rims
/// crossing: -6.07 mm between two edges instead of the -1.95e-3 mm witness).
fn inside_fraction(domains: &[ParamRange; 2], x: [f64; 2], step: [f64; 2]) -> f64 {
    let mut reach = 1.0_f64;
    for ((range, xi), si) in domains.iter().zip(x).zip(step) {
        if range.periodic || si == 0.0 || range.max <= range.min {
            continue;
        }
        let bound = if si > 0.0 { range.max } else { range.min };
        let to_side = (bound - xi) / si;
        if to_side < 1.0 {
            reach = reach.min(0.5 * to_side.max(0.0));
        }
    }
    reach
}

/// Largest angle (rad) between opposed normals that still counts as a touch: cos = 1 − 1e-9.
pub(crate) const TOUCH_ANGLE: f64 = 4.47213595499958e-5; // √(2e-9)

/// Whether the outward-normal cones of two points hold opposite directions to `tolerance`
/// (rad): a face's cone is its normal, an edge's the arc between its two faces' normals. With
/// one face, its normal negated must lie in the other's cone (for two faces, the angle between
/// the normals is at least π − `tolerance`); two edges are never judged opposed here.
///
/// The distance of a direction n from an arc [n1, n2] is measured to first order: its angle out
/// of the arc's plane (asin |n · m̂|, m̂ = n1 × n2 normalised, the edge's tangent line) plus its
/// excess inside the plane. The in-plane excess alone, ∠(n, n1) + ∠(n, n2) − ∠(n1, n2), grows
/// only with the square of the out-of-plane angle, so an edge crossing a face at 8e-3 rad
/// (a goblet's rim 1e-3 mm into a jar, `soak 10000 --seed 4002`) passed as a touch.
pub(crate) fn cones_opposed(va: &[FaceView], vb: &[FaceView], tolerance: f64) -> bool {
    let arc_excess = |n: DVec3, arc: &[FaceView]| match arc {
        [one] => angle_between(n, one.normal),
        [n1, n2, ..] => {
            let in_plane = angle_between(n, n1.normal) + angle_between(n, n2.normal)
                - angle_between(n1.normal, n2.normal);
            // Below 1e-6 (faces tangent-continuous across the edge) the plane is not defined
            // and the arc is a single direction, which `in_plane` already measures to first
            // order.
            let axis = n1.normal.cross(n2.normal);
            let out_of_plane = if axis.length() > 1e-6 {
                n.dot(axis.normalize()).abs().clamp(0.0, 1.0).asin()
            } else {
                0.0
            };
            in_plane + out_of_plane
        }
        [] => f64::INFINITY,
    };
    match (va, vb) {
        ([one], other) => arc_excess(-one.normal, other) <= tolerance,
        (other, [one]) => arc_excess(-one.normal, other) <= tolerance,
        _ => false,
    }
}

/// Whether the final pair of `state` is a touch: both points on a face or an edge, at least one
/// on a face, whose normal cones are opposed ([`cones_opposed`]) to [`TOUCH_ANGLE`] plus
/// `misalignment` (rad, how far the normals may turn between the pair and the exact touch).
/// `None` where the cones cannot tell: two edges, a vertex, or a point with no normal.
pub(crate) fn is_touch(a: &Body, b: &Body, state: &State, misalignment: f64) -> Option<bool> {
    let va = face_views(a, &state.la, &state.ea)?;
    let vb = face_views(b, &state.lb, &state.eb)?;
    if va.len() != 1 && vb.len() != 1 {
        return None;
    }
    Some(cones_opposed(&va, &vb, TOUCH_ANGLE + misalignment))
}

/// One face through a point: its location, evaluation and outward normal (A's frame).
#[derive(Clone, Copy, Debug)]
pub(crate) struct FaceView {
    pub loc: Loc,
    pub eval: FeatureEval,
    pub normal: DVec3,
}

/// The faces through the point of `loc`: the face itself, or an edge's two faces at the
/// edge's parameter. `None` for a vertex, a fixed point, or a face with no normal there.
pub(crate) fn face_views(body: &Body, loc: &Loc, eval: &FeatureEval) -> Option<Vec<FaceView>> {
    let view = |loc: Loc, eval: FeatureEval| {
        body.outward_at(&loc, &eval)
            .map(|normal| FaceView { loc, eval, normal })
    };
    match (body, loc) {
        (_, Some(FeatureLocation::Face { .. })) => Some(vec![view(*loc, *eval)?]),
        (Body::Solid { solid, .. }, Some(FeatureLocation::Edge { id, t })) => solid
            .edge(*id)
            .uses
            .iter()
            .map(|u| {
                let [fu, fv] = solid.use_params(u, *t);
                let face = Some(FeatureLocation::Face {
                    id: u.face,
                    u: fu,
                    v: fv,
                });
                let eval = body.eval(&face);
                (eval.n == 2).then_some(())?;
                view(face, eval)
            })
            .collect(),
        _ => None,
    }
}

/// The angle between two unit vectors (rad), accurate near 0 and π.
fn angle_between(a: DVec3, b: DVec3) -> f64 {
    a.cross(b).length().atan2(a.dot(b))
}

/// Whether a solve that is stationary on an edge or vertex may continue into an adjacent face.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Reentry {
    /// Continue into a face when f decreases into it.
    Allowed,
    /// Stay on the features reached and minimise f there, penetrating or not (no hand-over to
    /// the penetration solver): a seed projection only places the start (the pair solve tests
    /// re-entry itself, with the other feature's point as the pull), and on two edges the
    /// minimum of f is the candidate witness of [`crate::solver::penetration::edge_pair_witness`].
    Never,
}

/// The closest point to `target` on `body` near `start`: [`minimize`] against a fixed point
/// (which never penetrates, having no outward direction).
pub(crate) fn minimize_projection(
    body: &Body,
    target: DVec3,
    start: Loc,
    base_scale: f64,
    options: &NewtonOptions,
    reentry: Reentry,
) -> Solution {
    minimize(
        body,
        &Body::Point(target),
        settle(body, start),
        None,
        base_scale,
        options,
        reentry,
    )
}

/// The separated regime: minimises f from (`la`, `lb`), handing over (outcome
/// [`Outcome::Penetrating`]) as soon as the pair penetrates with parameters on both sides,
/// unless `reentry` is [`Reentry::Never`].
pub(crate) fn minimize(
    a: &Body,
    b: &Body,
    la: Loc,
    lb: Loc,
    base_scale: f64,
    options: &NewtonOptions,
    reentry: Reentry,
) -> Solution {
    minimize_known(a, b, (la, lb), base_scale, options, reentry, [None, None])
}

/// [`minimize`], the first state taking each face's evaluation from `known` where it is of that
/// face point ([`State::evaluated`]).
pub(crate) fn minimize_known(
    a: &Body,
    b: &Body,
    (la, lb): (Loc, Loc),
    base_scale: f64,
    options: &NewtonOptions,
    reentry: Reentry,
    known: [Option<&LocalFacePoint>; 2],
) -> Solution {
    let mut cur = State::evaluated(a, b, la, lb, base_scale, known);
    let (max_radius, mut radius) = cur.trust_radii();
    let mut switches = 0;
    let mut taken = [TakenEntries::default(); 2];
    // The face each side last stepped off onto an edge or vertex: re-entry prefers it.
    let mut came_from: [Option<FaceId>; 2] = [None, None];
    let end = |state, iterations, outcome| Solution {
        state,
        iterations,
        outcome,
    };
    // Whether `cur` is new since the last penetration test (a rejected step keeps it).
    let mut fresh = true;
    // Whether the next step may be a distance-Newton step: not straight after one was rejected
    // (its model failed there, e.g. approaching an intersection curve, where |d| has a kink).
    let mut distance_ok = true;
    let mut polishes = 0;
    for iteration in 0..options.max_iterations {
        if fresh && reentry == Reentry::Allowed && cur.penetrating_remembered(a, b) {
            return end(cur, iteration, Outcome::Penetrating);
        }
        fresh = true;
        if cur.stationary(options) {
            // From an edge or vertex, continue into an adjacent face if f decreases into it.
            let threshold = 64.0 * EPS * cur.scale;
            let entry_a = match reentry {
                Reentry::Allowed => {
                    reenter_untaken(a, &cur.la, -cur.d, threshold, &taken[0], came_from[0])
                }
                Reentry::Never => None,
            };
            let entry_b = if entry_a.is_none() && reentry == Reentry::Allowed {
                reenter_untaken(b, &cur.lb, cur.d, threshold, &taken[1], came_from[1])
            } else {
                None
            };
            taken[0].record(&cur.la, &entry_a);
            taken[1].record(&cur.lb, &entry_b);
            if entry_a.is_none() && entry_b.is_none() {
                // A stationary point with negative curvature (a maximum or saddle of f, e.g. two
                // seeds on the far sides) is left along that direction. Positive definite (it
                // factors) is the common case and needs no eigenvalues; near a touch the
                // distance itself may still fall (`touch_polish`).
                let factor = if cur.n == 0 {
                    None
                } else {
                    cholesky(&cur.hs, cur.n)
                };
                if cur.n == 0 || factor.is_some() {
                    if polishes < MAX_TOUCH_POLISHES
                        && factor.is_some_and(|l| touch_may_gain(&cur, &l))
                        && let Some(nearer) = touch_polish(a, b, &cur, radius, base_scale)
                    {
                        polishes += 1;
                        cur = nearer;
                        continue;
                    }
                    return end(cur, iteration, Outcome::Converged);
                }
                let eigen = sym_eigen(&cur.hs, cur.n);
                let floor = cur.eigen_floor(&eigen.values);
                if eigen.values[0] >= -floor {
                    return end(cur, iteration, Outcome::Converged);
                }
                match saddle_escape(a, b, &cur, &eigen, radius, base_scale) {
                    Some(lower) => cur = lower,
                    None => return end(cur, iteration, Outcome::Converged),
                }
                continue;
            }
            switches += 1;
            if switches > options.max_feature_switches {
                return end(cur, iteration, Outcome::SwitchLimit);
            }
            cur = State::new(a, b, entry_a.or(cur.la), entry_b.or(cur.lb), base_scale);
            continue;
        }
        let n = cur.n;
        // The distance step's model: f's Hessian with only the normal part of the features'
        // curvature, consistent with the tangentially corrected step it takes below.
        let model = cur.pole_frozen();
        let distance_step = distance_ok.then(|| distance_newton_step(&model)).flatten();
        let by_distance = distance_step.is_some();
        let mut step = match distance_step.or_else(|| newton_step(&model)) {
            Some(step) => step,
            None => {
                let eigen = sym_eigen(&model.hs, n);
                if eigen.values[..n].iter().any(|l| !l.is_finite()) {
                    return end(cur, iteration, Outcome::Stalled);
                }
                let floor = model.eigen_floor(&eigen.values).max(f64::MIN_POSITIVE);
                descent_step(&model, &eigen, floor)
            }
        };
        let length = step[..n].iter().map(|s| s * s).sum::<f64>().sqrt();
        if step[..n].iter().all(|s| s.abs() <= 4.0 * EPS * cur.scale) {
            // The Newton step is below what the coordinates can represent: nothing left to gain.
            return end(cur, iteration, Outcome::Converged);
        }
        let clipped = length.min(radius);
        for s in step.iter_mut().take(n) {
            *s *= clipped / length;
        }
        // Not in a projection onto a fixed point: it only places a seed (to 1e-3 rad), where
        // the pair solve's start was tuned with plain steps.
        let corrected = by_distance && !matches!(b, Body::Point(_));
        let (ta, tb) = if corrected {
            take_step(a, b, &cur, &tangential_correction(&cur, &step))
        } else {
            take_step(a, b, &cur, &step)
        };
        let trial = State::new(a, b, ta, tb, base_scale);
        let (m_cur, m_trial) = (cur.merit(), trial.merit());
        let switched_a = trial.la.map(|l| l.feature()) != cur.la.map(|l| l.feature());
        let switched_b = trial.lb.map(|l| l.feature()) != cur.lb.map(|l| l.feature());
        // A step onto another feature (a face's edge, an edge's vertex) evaluates the same
        // point on geometry that agrees only to the model tolerance, so f = ½|d|² may rise by
        // up to |d| x (the two gaps) with no move at all: a STEP cone's rim lies 9e-13 mm
        // above its edge, and a seed on that rim, whose minimum is along the edge, stalled
        // with every step onto the edge rejected.
        let jump = f64::from(u8::from(switched_a)) * a.feature_gap()
            + f64::from(u8::from(switched_b)) * b.feature_gap();
        let slack = 8.0 * EPS * cur.scale * ((2.0 * m_cur).sqrt() + EPS * cur.scale)
            + (2.0 * m_cur).sqrt() * jump;
        if m_trial.is_finite() && m_trial <= m_cur + slack {
            if switched_a || switched_b {
                switches += 1;
                if switches > options.max_feature_switches {
                    return end(trial, iteration + 1, Outcome::SwitchLimit);
                }
            }
            // After a step onto another feature the trust radius starts again where a solve
            // from there would: it had shrunk because the old feature pair's model failed
            // across the boundary, which says nothing of the new pair's. (Seeds on a tube's top
            // face under a loft reached the rim with a radius of 0.015 mm and spent six steps
            // doubling it to cover the 1 mm along the rim to the minimum.)
            if (switched_a || switched_b) && radius < 0.25 * max_radius {
                radius = 0.25 * max_radius;
            } else if clipped >= 0.9 * radius {
                radius = (2.0 * radius).min(max_radius);
            }
            for (origin, (from, to)) in came_from
                .iter_mut()
                .zip([(cur.la, trial.la), (cur.lb, trial.lb)])
            {
                if let (Some(FeatureLocation::Face { id, .. }), Some(to)) = (from, to)
                    && !matches!(to, FeatureLocation::Face { .. })
                {
                    *origin = Some(id);
                }
            }
            cur = trial;
            distance_ok = true;
        } else {
            radius = 0.25 * clipped;
            if radius < 4.0 * EPS * cur.scale {
                return end(cur, iteration + 1, Outcome::Stalled);
            }
            fresh = false;
            distance_ok = !by_distance;
        }
    }
    // Stationary where the iterations ran out is converged only if f descends into no face
    // next to an edge or vertex it ends on: the solve may have run out cycling between a
    // smooth edge and the face beside it (a jar's top rim under a bowl's rim, 0.015 rad off
    // the rim's normal, bowl-jar 11020319765632509870 of `soak 10000 --seed 13108`), and that
    // end is no minimum.
    let threshold = 64.0 * EPS * cur.scale;
    let descends_off = reentry == Reentry::Allowed
        && (reenter(a, &cur.la, -cur.d, threshold).is_some()
            || reenter(b, &cur.lb, cur.d, threshold).is_some());
    let outcome = if cur.stationary(options) && !descends_off {
        Outcome::Converged
    } else {
        Outcome::IterationLimit
    };
    end(cur, options.max_iterations, outcome)
}

/// Most distance steps [`touch_polish`] takes in one solve.
const MAX_TOUCH_POLISHES: u32 = 8;

/// Whether [`touch_polish`] may find a lower distance at the stationary `cur`, whose f Hessian
/// factors as `factor` (Cholesky): the decrease predicted by the distance's Newton model,
/// ½ gᵀM⁻¹g / |d| for M = H − g gᵀ/|d|², is at least a quarter of the gradient's floor. With
/// p = gᵀH⁻¹g from the factor (Sherman-Morrison: p = q / (1 + q/|d|²) for q = gᵀM⁻¹g), q is
/// p / (1 − p/|d|²), infinite where p reaches |d|². (H also holds the features' curvature
/// along d's tangential part, which the distance model leaves out: hence the margin.) Spares
/// every other converged solve the distance model's own factorisation.
fn touch_may_gain(cur: &State, factor: &[[f64; 4]; 4]) -> bool {
    let n = cur.n;
    let length2 = cur.d.length_squared();
    let x = cholesky_solve(factor, n, &cur.gs);
    let p: f64 = (0..n).map(|i| cur.gs[i] * x[i]).sum();
    let q = if p < length2 {
        p / (1.0 - p / length2)
    } else {
        f64::INFINITY
    };
    0.5 * q / length2.sqrt() > 0.25 * cur.gradient_floor()
}

/// A state nearer than `cur` by one Newton step on the distance |d| itself
/// ([`distance_newton_step`], clipped to `radius`), where `cur` is stationary for f = ½|d|² only
/// through the gradient's rounding floor: f's scaled gradient is |d| ∇|d|, so near a touch
/// (|d| of 1e-9 mm) it sinks below the floor while the distance's own gradient, and the
/// decrease its Newton model predicts, ½ |∇|d| · s| for the step s, is still far above the
/// coordinates' rounding. The step is taken when that prediction exceeds the floor, and kept
/// when |d| falls and the features stay. `None` otherwise: `cur` is the answer.
///
/// Why: a vase touching a bowl at 3.5e-12 mm (vase-bowl 2697845155447835510 of `soak 10000
/// --seed 10102`) stopped at |d| = 3.0e-9 mm, 2.2e-4 mm along the flat valley from the touch,
/// with f's gradient 7.8e-14 mm under its floor of 1.8e-13 while the distance's predicted
/// decrease was 7e-9 mm: where the solve stops in such a valley depended on where it started.
fn touch_polish(a: &Body, b: &Body, cur: &State, radius: f64, base_scale: f64) -> Option<State> {
    let model = cur.pole_frozen();
    let mut step = distance_newton_step(&model)?;
    let n = cur.n;
    let length = cur.d.length();
    let predicted = -0.5 * (0..n).map(|i| model.gs[i] * step[i]).sum::<f64>() / length;
    if predicted.is_nan() || predicted <= cur.gradient_floor() {
        return None;
    }
    let size = step[..n].iter().map(|s| s * s).sum::<f64>().sqrt();
    if size > radius {
        for s in step.iter_mut().take(n) {
            *s *= radius / size;
        }
    }
    let step = if matches!(b, Body::Point(_)) {
        step
    } else {
        tangential_correction(cur, &step)
    };
    let (ta, tb) = take_step(a, b, cur, &step);
    let trial = State::new(a, b, ta, tb, base_scale);
    let same = |x: Loc, y: Loc| x.map(|l| l.feature()) == y.map(|l| l.feature());
    (same(trial.la, cur.la) && same(trial.lb, cur.lb) && trial.merit() < cur.merit())
        .then_some(trial)
}

/// The state a step along the most negative curvature direction of `cur`'s Hessian reaches
/// with a lower objective: steps of `radius`, then a quarter of that, and so on down to the
/// rounding of the coordinates, each tried both ways. `None` when none descends: the negative
/// eigenvalue is rounding, not a saddle.
///
/// Why: at an exact touch (|d| = 3.5e-12 mm, vase on bowl 2697845155447835510 of
/// `soak 10000 --seed 10102`) f = ½|d|² is flat along the two points' common tangential motion,
/// and rounding gave that direction a slightly negative eigenvalue below the floor. The
/// unconditional step of the whole trust radius (40 mm) jumped to f = 1.3 mm on a rim, the
/// solve came back to the touch and jumped again, to its iteration limit, and the touch was
/// reported separated.
fn saddle_escape(
    a: &Body,
    b: &Body,
    cur: &State,
    eigen: &SymEigen,
    radius: f64,
    base_scale: f64,
) -> Option<State> {
    let floor = 4.0 * EPS * cur.scale;
    let mut length = radius;
    while length > floor {
        for sign in [1.0, -1.0] {
            let step: [f64; 4] = std::array::from_fn(|i| eigen.vectors[i][0] * sign * length);
            let (ta, tb) = take_step(a, b, cur, &step);
            let trial = State::new(a, b, ta, tb, base_scale);
            if trial.merit() < cur.merit() {
                return Some(trial);
            }
        }
        length *= 0.25;
    }
    None
}

/// The plain Newton step −H⁻¹g by Cholesky where it equals [`descent_step`]: H factors and
/// its smallest eigenvalue provably exceeds the floor of [`State::eigen_floor`] (taken with
/// ‖H‖_F ≥ the largest eigenvalue, so it is at least as high). `None` otherwise.
fn newton_step(cur: &State) -> Option<[f64; 4]> {
    positive_definite_solve(cur, &cur.hs)
}

/// The Newton step for the distance |P_a − P_b| itself rather than f = ½|P_a − P_b|², where the
/// connecting vector is within 30 degrees of the normals: −M⁻¹g with M = H − g gᵀ / |d|²
/// (|d| times the Hessian of |d|). `None` where that does not apply or M is not safely
/// positive definite; then Newton on f.
///
/// Why: along the rolling directions f = ½(σ + ½κδ²)² (gap σ, relative curvature κ, offset δ)
/// is quartic once δ² ≫ σ/κ, and Newton on f only cuts δ by a third per step there (dozens of
/// steps near touch), while |d| = σ + ½κδ² is quadratic and its Newton step is exact. Along the
/// sliding directions M differs from H by at most sin² of the angle between the connecting
/// vector and the normals (the scaled gradient is the tangential part of d), hence the
/// 30-degree limit; at the answer g = 0, so M = H and convergence stays quadratic. Where M is
/// positive definite so is H (M ≤ H), so this never replaces a saddle-free step.
fn distance_newton_step(cur: &State) -> Option<[f64; 4]> {
    by_size!(cur.n, distance_newton_step_n(cur))
}

/// [`distance_newton_step`] for `N` = `cur.n` variables.
fn distance_newton_step_n<const N: usize>(cur: &State) -> Option<[f64; 4]> {
    let n = N;
    let distance2 = cur.d.length_squared();
    let tangential2: f64 = cur.gs[..n].iter().map(|g| g * g).sum();
    // |d| well above rounding (its direction means something), the angle below 30 degrees.
    // Also rejects NaN: every comparison with NaN is false.
    if !(distance2 > (cur.gradient_floor() * 1e3).powi(2) && tangential2 <= 0.25 * distance2) {
        return None;
    }
    // The model consistent with the tangentially corrected step taken with it.
    let mut m = cur.normal_hessian();
    for i in 0..n {
        for j in 0..n {
            m[i][j] -= cur.gs[i] * cur.gs[j] / distance2;
        }
    }
    positive_definite_solve_n::<N>(cur, &m)
}

/// −M⁻¹g for the scaled gradient g of `cur`, where M factors and its smallest eigenvalue
/// provably exceeds the eigenvalue floor of `cur` with ‖M‖_F for the largest; `None` otherwise.
fn positive_definite_solve(cur: &State, m: &[[f64; 4]; 4]) -> Option<[f64; 4]> {
    by_size!(cur.n, positive_definite_solve_n(cur, m))
}

/// [`positive_definite_solve`] for `N` = `cur.n` variables.
fn positive_definite_solve_n<const N: usize>(cur: &State, m: &[[f64; 4]; 4]) -> Option<[f64; 4]> {
    let n = N;
    let l = cholesky_n::<N>(m)?;
    let frobenius = m[..n]
        .iter()
        .flat_map(|row| &row[..n])
        .map(|h| h * h)
        .sum::<f64>()
        .sqrt();
    let floor = (64.0 * EPS * (frobenius + cur.scale * cur.curvature)).max(f64::MIN_POSITIVE);
    if smallest_eigenvalue_bound::<N>(&l) < floor {
        return None;
    }
    let x = cholesky_solve_n::<N>(&l, &cur.gs);
    Some(std::array::from_fn(|i| -x[i]))
}

/// Newton step with every eigenvalue replaced by its floored magnitude: a descent direction of
/// f, exact Newton where the Hessian is positive definite.
fn descent_step(cur: &State, eigen: &SymEigen, floor: f64) -> [f64; 4] {
    let mut step = [0.0; 4];
    for k in 0..cur.n {
        let lambda = eigen.values[k].abs().max(floor);
        let q_dot_g: f64 = (0..cur.n).map(|i| eigen.vectors[i][k] * cur.gs[i]).sum();
        for (i, s) in step.iter_mut().enumerate().take(cur.n) {
            *s -= eigen.vectors[i][k] * q_dot_g / lambda;
        }
    }
    step
}

/// The projection of `d` onto the tangent space of the feature evaluated as `e` (its columns
/// ∂P/∂x_i), `None` with no parameters or a singular first fundamental form (a pole).
fn tangential_part(e: &FeatureEval, d: DVec3) -> Option<DVec3> {
    match e.n {
        1 => {
            let g = e.d[0].length_squared();
            (g > 0.0).then(|| e.d[0] * (d.dot(e.d[0]) / g))
        }
        2 => {
            let (g11, g12, g22) = (e.d[0].dot(e.d[0]), e.d[0].dot(e.d[1]), e.d[1].dot(e.d[1]));
            let det = g11 * g22 - g12 * g12;
            if det.is_nan() || det <= 1e-12 * g11 * g22 {
                return None;
            }
            let (r1, r2) = (d.dot(e.d[0]), d.dot(e.d[1]));
            Some(e.d[0] * ((g22 * r1 - g12 * r2) / det) + e.d[1] * ((g11 * r2 - g12 * r1) / det))
        }
        _ => None,
    }
}

/// The scaled `step` of `cur` with each side's parameters corrected so that its point moves,
/// to second order, along the tangent displacement the step's linear model predicts: the
/// second-order displacement q = ½ Σ ∂²P/∂x_i∂x_j Δx_i Δx_j has its tangential part removed by
/// the parameter change −G⁻¹ Jᵀ q (J the side's columns ∂P/∂x_i, G = JᵀJ its first fundamental
/// form); its normal part, the surface's curvature, is what the step's model
/// ([`State::normal_hessian`]) holds. A side whose G is singular (a pole) keeps its step. Taken
/// with the distance-Newton steps of a pair solve (near the answer: the connecting vector
/// within 30 degrees of the normals), where the model is the distance's along the rolling
/// directions; far steps and projections onto a point keep their plain steps.
///
/// Why: f's Hessian in the parameters models q through d · ∂²P, but the tangential part (the parametrisation's own curvature, not the surface's) enters f only
/// through |q_t|² ≈ (L² / 2ρ)² for a step of L mm where the parameter lines curve with radius ρ.
/// Where the gap's relative curvature κ is below 1 / ρ that exceeds f itself (½(κL² / 2)² at
/// the distance step's target) at every scale, so the step that would reach the minimum is
/// always rejected and the solve creeps: a goblet's flat foot (a disk in polar parameters, the
/// point 4.35 mm from its centre: 1 / ρ = 0.23 / mm) on a bowl's gently curved wall (κ = 0.006
/// and 0.033 / mm) stopped at the iteration limit 4e-9 mm from a touch. With the correction the
/// error is third order in L (the step along the parameter lines' own turn), as for a surface
/// parametrised by arc length, and the step is still plain Newton at the answer (q = O(L²)).
fn tangential_correction(cur: &State, step: &[f64; 4]) -> [f64; 4] {
    let mut out = *step;
    for (offset, e) in [(0, &cur.ea), (cur.na, &cur.eb)] {
        let m = e.n;
        if m == 0 {
            continue;
        }
        let dx: [f64; 2] = std::array::from_fn(|i| {
            if i < m {
                step[offset + i] / cur.speed[offset + i]
            } else {
                0.0
            }
        });
        let mut q = DVec3::ZERO;
        for i in 0..m {
            for j in 0..m {
                q += 0.5 * e.dd[i][j] * dx[i] * dx[j];
            }
        }
        let rhs: [f64; 2] = std::array::from_fn(|i| if i < m { -e.d[i].dot(q) } else { 0.0 });
        let correction = if m == 1 {
            let g = e.d[0].length_squared();
            if g.is_nan() || g <= 0.0 {
                continue;
            }
            [rhs[0] / g, 0.0]
        } else {
            let (g11, g12, g22) = (e.d[0].dot(e.d[0]), e.d[0].dot(e.d[1]), e.d[1].dot(e.d[1]));
            let det = g11 * g22 - g12 * g12;
            // A pole or a degenerate patch: no tangent frame to correct in.
            if det.is_nan() || det <= 1e-12 * g11 * g22 {
                continue;
            }
            [
                (g22 * rhs[0] - g12 * rhs[1]) / det,
                (g11 * rhs[1] - g12 * rhs[0]) / det,
            ]
        };
        if correction.iter().all(|c| c.is_finite()) {
            for i in 0..m {
                out[offset + i] += correction[i] * cur.speed[offset + i];
            }
        }
    }
    out
}

/// Applies the scaled step: periodic parameters move at most a quarter turn (the whole step is
/// shortened to keep its direction), and the step is cut where a bounded parameter first reaches
/// its side, which is then set exactly so that [`settle`] switches feature, or where a face
/// point first leaves its trimmed region, which then goes onto the trim's edge there
/// ([`settle_step`]): both features move by the same fraction of the step.
pub(crate) fn take_step(a: &Body, b: &Body, cur: &State, step: &[f64; 4]) -> (Loc, Loc) {
    let (xa, _) = params(&cur.la);
    let (xb, _) = params(&cur.lb);
    let (da, db) = (a.domains(&cur.la), b.domains(&cur.lb));
    let mut x = [xa[0], xa[1], xb[0], xb[1]];
    let mut delta = [0.0; 4];
    let ranges = [da[0], da[1], db[0], db[1]];
    let mut slot = [0usize; 4];
    for i in 0..cur.n {
        slot[i] = if i < cur.na { i } else { 2 + i - cur.na };
        delta[slot[i]] = step[i] / cur.speed[i];
    }
    // A coordinate on its bound that the step pushes outward is held there, so that the other
    // components still move: a start on a corner of a face's rectangle (re-entry from the
    // vertex there) slides along the side it can follow instead of stopping, and settling
    // onto the vertex again. (A rounded box's corner against a jar cycled vertex -> face ->
    // edge end -> vertex to the switch limit.)
    for &s in &slot[..cur.n] {
        let range = ranges[s];
        let outward =
            (x[s] <= range.min && delta[s] < 0.0) || (x[s] >= range.max && delta[s] > 0.0);
        if !range.periodic && outward {
            delta[s] = 0.0;
        }
    }
    let mut alpha = 1.0_f64;
    let mut hit = None;
    for &s in &slot[..cur.n] {
        let range = ranges[s];
        if range.periodic {
            alpha = alpha.min(0.5 * PI / delta[s].abs().max(f64::MIN_POSITIVE));
        }
    }
    for &s in &slot[..cur.n] {
        let range = ranges[s];
        if range.periodic || delta[s] == 0.0 {
            continue;
        }
        let bound = if delta[s] > 0.0 { range.max } else { range.min };
        let room = (bound - x[s]) / delta[s];
        if room < alpha {
            alpha = room.max(0.0);
            hit = Some((s, bound));
        }
    }
    let start = x;
    for &s in &slot[..cur.n] {
        x[s] += alpha * delta[s];
    }
    if let Some((s, bound)) = hit {
        x[s] = bound;
    }
    // A face point that leaves its trimmed region cuts the whole step there, as a side does,
    // and goes onto the trim's edge ([`settle_step`]).
    let (la, exit_a) = settle_step(a, &cur.la, with_params(&cur.la, [x[0], x[1]]));
    let (lb, exit_b) = settle_step(b, &cur.lb, with_params(&cur.lb, [x[2], x[3]]));
    let exit = match (exit_a, exit_b) {
        (Some(ea), Some(eb)) if eb.0 < ea.0 => Some((1, eb)),
        (Some(ea), _) => Some((0, ea)),
        (None, Some(eb)) => Some((1, eb)),
        (None, None) => None,
    };
    if let Some((side, (beta, on))) = exit {
        for &s in &slot[..cur.n] {
            x[s] = start[s] + beta * alpha * delta[s];
        }
        return if side == 0 {
            (Some(on), settle(b, with_params(&cur.lb, [x[2], x[3]])))
        } else {
            (settle(a, with_params(&cur.la, [x[0], x[1]])), Some(on))
        };
    }
    (la, lb)
}
