//! Plain Newton polishing of a pair of surface points, x = (u_a, v_a, u_b, v_b), on
//! f(x) = ½ |S_a(u_a, v_a) − S_b(u_b, v_b)|² (world frame, mm²).
//!
//! With r = S_a − S_b and the columns c = (S_a,u, S_a,v, −S_b,u, −S_b,v) the gradient is
//! g_k = r · c_k and the exact Hessian H = cᵀc + (r · S_a,ij on A's block, −r · S_b,ij on B's).
//!
//! - [`minimise`]: Levenberg–Marquardt on f with u wrapped where periodic and v kept in the face
//!   domain. A parameter at a bound whose descent leaves the face is an active constraint
//!   (that is how minima on ridge edges are found). At an edge the polish carries on across it
//!   when f descends into the neighbouring face; at a pole or apex it turns the running
//!   parameter towards the steepest descent into the face.
//!   On a trimmed face the region is the trim instead: a step that leaves it stops where it
//!   crosses the boundary and the point is held on the crossed edge, with the edge's t as its
//!   one parameter ([`crate::polishing::feature_moves`]); from an edge the polish moves into
//!   either face when f descends into it, onto the end vertex when descent runs past the edge's
//!   end, and from a vertex along any edge or into any face there with descent.
//!
//! A point held on an edge or at a vertex ([`Held`]) keeps its slots: the edge's t is the
//! first parameter of its solid (its column the curve's tangent, its second derivative the
//! curve's), the second slot (both at a vertex) does not exist and is never free.
//!
//! Residuals are measured in 3-d: |g_k| / |c_k| is the component of the connecting vector
//! along parameter direction k, which stays meaningful at a pole where |c_k| -> 0.

use crate::polishing::feature_moves::{self, MAX_SWITCHES, TrimStep};
use crate::polishing::linalg::{self, N};
use crate::polishing::pair::Pair;
use crate::solids::held::Held;
use crate::solids::posed::PosedSolid;
use geom_param::{Boundary, FaceId, ParamSide, SurfacePoint};
use glam::DVec3;

/// Hops across edges or turns at poles before a polish gives up (guards against cycling).
const MAX_MOVES: u32 = 16;
/// Directions probed at a pole or apex for descent into the face.
const POLE_DIRECTIONS: usize = 32;

/// `x` and `y`, slot by slot.
pub(crate) fn both(x: [bool; N], y: [bool; N]) -> [bool; N] {
    std::array::from_fn(|k| x[k] && y[k])
}

/// Stopping rules shared by the polishers.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Limits {
    /// Residual (mm) below which a point is stationary.
    pub tolerance: f64,
    /// Largest 3-d move of either point per step (mm).
    pub step: f64,
    /// Evaluation cap.
    pub iterations: u32,
}

/// Value, gradient and Hessian of f at a pair.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Eval {
    pub pa: SurfacePoint,
    pub pb: SurfacePoint,
    /// S_a − S_b.
    pub r: DVec3,
    pub cols: [DVec3; N],
    pub g: [f64; N],
    pub h: [[f64; N]; N],
}

impl Eval {
    pub fn f(&self) -> f64 {
        0.5 * self.r.length_squared()
    }
}

/// Evaluates f, its gradient and exact Hessian.
pub(crate) fn evaluate(a: &PosedSolid, b: &PosedSolid, p: &Pair) -> Eval {
    let pa = a.eval_held(p.fa, p.a, p.held_a);
    let pb = b.eval_held(p.fb, p.b, p.held_b);
    let r = pa.point - pb.point;
    let cols = [pa.du, pa.dv, -pb.du, -pb.dv];
    let mut g = [0.0; N];
    let mut h = [[0.0; N]; N];
    for i in 0..N {
        g[i] = r.dot(cols[i]);
        for j in 0..N {
            h[i][j] = cols[i].dot(cols[j]);
        }
    }
    h[0][0] += r.dot(pa.duu);
    h[0][1] += r.dot(pa.duv);
    h[1][0] += r.dot(pa.duv);
    h[1][1] += r.dot(pa.dvv);
    h[2][2] -= r.dot(pb.duu);
    h[2][3] -= r.dot(pb.duv);
    h[3][2] -= r.dot(pb.duv);
    h[3][3] -= r.dot(pb.dvv);
    Eval {
        pa,
        pb,
        r,
        cols,
        g,
        h,
    }
}

/// The outcome of a polish.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Polished {
    pub pair: Pair,
    pub eval: Eval,
    /// Largest tangential component of r along a free parameter direction (mm).
    pub residual: f64,
    /// Which parameters are held at a bound.
    pub active: [bool; N],
    pub iterations: u32,
    /// Residual below tolerance, with no pending move across an edge or pole.
    pub converged: bool,
}

/// Which solid and face-local parameter index a pair parameter is.
fn split(k: usize) -> (bool, usize) {
    (k < 2, k % 2)
}

/// Parameter `k` of the pair: a face's u or v, an edge's t (slot 0), 0 where none exists.
pub(crate) fn params(p: &Pair, k: usize) -> f64 {
    let (on_a, i) = split(k);
    let (_, uv, held) = p.side(on_a);
    match held {
        Held::Face => uv[i],
        Held::Edge { t, .. } if i == 0 => t,
        _ => 0.0,
    }
}

/// Sets parameter `k` (ignored where it does not exist).
pub(crate) fn set(p: &mut Pair, k: usize, value: f64) {
    let (on_a, i) = split(k);
    let held = if on_a { &mut p.held_a } else { &mut p.held_b };
    match held {
        Held::Face => {
            if on_a {
                p.a[i] = value;
            } else {
                p.b[i] = value;
            }
        }
        Held::Edge { t, .. } if i == 0 => *t = value,
        _ => {}
    }
}

/// Wraps periodic parameters and clamps the others into their face's domain (an edge's t into
/// the curve's); a point held on an edge gets its use's (u, v) at t.
pub(crate) fn normalize(a: &PosedSolid, b: &PosedSolid, mut p: Pair) -> Pair {
    for (on_a, solid) in [(true, a), (false, b)] {
        let (face, uv, held) = p.side(on_a);
        match held {
            Held::Face => p.set_side(on_a, face, solid.normalize(face, uv), held),
            Held::Edge { edge, t, use_index } => {
                let t = solid.solid.edge(edge).curve.domain().normalize(t);
                let use_ = solid.solid.edge(edge).uses[use_index];
                let held = Held::Edge { edge, t, use_index };
                p.set_side(on_a, use_.face, solid.use_params(&use_, t), held);
            }
            Held::Vertex(_) => {}
        }
    }
    p
}

/// The side parameter `k` sits on, if it is at a bound of a non-periodic range of a face
/// without trim (a trimmed face's region is its trim, see [`feature_moves`]).
fn side_of(a: &PosedSolid, b: &PosedSolid, p: &Pair, k: usize) -> Option<ParamSide> {
    let (on_a, i) = split(k);
    let (solid, face) = if on_a { (a, p.fa) } else { (b, p.fb) };
    if p.side(on_a).2 != Held::Face || solid.trim(face).is_some() {
        return None;
    }
    let range = solid.range(face, i);
    if range.periodic {
        return None;
    }
    let x = params(p, k);
    let (lo, hi) = if i == 0 {
        (ParamSide::UMin, ParamSide::UMax)
    } else {
        (ParamSide::VMin, ParamSide::VMax)
    };
    if x <= range.min {
        Some(lo)
    } else if x >= range.max {
        Some(hi)
    } else {
        None
    }
}

/// Residual over the parameters not in `active` (see the module docs). Where u's direction
/// vanishes (a pole) the tangent plane is spanned by S_v and ∂S_v/∂u, so the latter stands in
/// for S_u: otherwise half of the pole's tangent plane would go unchecked. A point held at a
/// pole or apex (v active there) has no u residual.
pub(crate) fn residual(e: &Eval, movable: [bool; N], active: [bool; N]) -> f64 {
    let scale = e.cols.iter().map(|c| c.length()).fold(0.0, f64::max);
    (0..N)
        .filter(|&k| movable[k] && !active[k])
        .filter_map(|k| {
            let mut col = e.cols[k];
            if col.length() <= 1e-9 * scale && k % 2 == 0 {
                if active[k + 1] {
                    // Held at the vertex: its first-order condition (no descent into the face
                    // along any meridian) was checked when v was made active; at an apex the
                    // connecting vector lies in a cone of normals, not along one.
                    return None;
                }
                col = if k == 0 { e.pa.duv } else { -e.pb.duv };
            }
            let len = col.length();
            (len > 1e-12 * scale).then(|| e.r.dot(col).abs() / len)
        })
        .fold(0.0, f64::max)
}

/// Derivative of f when the point of parameter `k`'s solid moves by unit speed along `w`.
fn directional(e: &Eval, k: usize, w: DVec3) -> f64 {
    if k < 2 { e.r.dot(w) } else { -e.r.dot(w) }
}

/// Whether an edge ending at `vertex` has a use on a face other than `face`: the vertex is a
/// corner where faces meet, not only the pole or apex of `face` (whose seam ends there).
fn meets_other_faces(solid: &PosedSolid, face: FaceId, vertex: geom_param::VertexId) -> bool {
    solid.edges_leaving(vertex).iter().any(|&(edge, _, _)| {
        solid
            .solid
            .edge(edge)
            .uses
            .iter()
            .any(|use_| use_.face != face)
    })
}

/// At a pole or apex (the side collapses to a vertex): the running parameter value with the
/// steepest descent into the face, if there is descent at all.
fn turn_at_vertex(
    a: &PosedSolid,
    b: &PosedSolid,
    p: &Pair,
    k: usize,
    side: ParamSide,
    e: &Eval,
    tolerance: f64,
) -> Option<Pair> {
    let (on_a, i) = split(k);
    let (solid, face) = if on_a { (a, p.fa) } else { (b, p.fb) };
    let sp = solid.side_param(face, side);
    let running = 1 - i;
    let range = solid.range(face, running);
    let mut best: Option<(f64, f64)> = None;
    for n in 0..POLE_DIRECTIONS {
        let t = range.min + range.span() * n as f64 / POLE_DIRECTIONS as f64;
        let mut uv = [0.0; 2];
        uv[i] = sp.value;
        uv[running] = t;
        let s = solid.eval(face, uv[0], uv[1]);
        let w = if i == 0 { s.du } else { s.dv } * sp.inward;
        let len = w.length();
        if len == 0.0 {
            continue;
        }
        let slope = directional(e, k, w / len);
        if slope < -tolerance && best.is_none_or(|(b, _)| slope < b) {
            best = Some((slope, t));
        }
    }
    let (_, t) = best?;
    let mut q = *p;
    set(&mut q, k - i + running, t);
    Some(q)
}

/// The same point on the face across the edge at `side`, if f descends into that face.
fn hop_across(
    a: &PosedSolid,
    b: &PosedSolid,
    p: &Pair,
    k: usize,
    side: ParamSide,
    e: &Eval,
    tolerance: f64,
) -> Option<Pair> {
    let (on_a, _) = split(k);
    let (solid, face, uv) = if on_a { (a, p.fa, p.a) } else { (b, p.fb, p.b) };
    let (other, other_uv, into) = solid.across(face, side, uv)?;
    let s = solid.eval(other, other_uv[0], other_uv[1]);
    let w = s.du * into.x + s.dv * into.y;
    let len = w.length();
    if len == 0.0 || directional(e, k, w / len) >= -tolerance {
        return None;
    }
    let mut q = *p;
    if on_a {
        q.fa = other;
        q.a = other_uv;
    } else {
        q.fb = other;
        q.b = other_uv;
    }
    Some(q)
}

/// `p` with every movable v that lies within 1e-3 of its range from a vertex side moved onto
/// it, when f there is no larger than at `p` (to rounding).
fn vertex_snap(
    a: &PosedSolid,
    b: &PosedSolid,
    p: &Pair,
    e: &Eval,
    movable: [bool; N],
) -> Option<Pair> {
    let mut q = *p;
    let mut snapped = false;
    for k in [1, 3].into_iter().filter(|&k| movable[k]) {
        if p.side(k < 2).2 != Held::Face {
            continue;
        }
        let (solid, face) = if k == 1 { (a, p.fa) } else { (b, p.fb) };
        let range = solid.range(face, 1);
        let v = params(p, k);
        for (bound, side) in [(range.min, ParamSide::VMin), (range.max, ParamSide::VMax)] {
            let near = v != bound && (v - bound).abs() <= 1e-3 * range.span();
            if near && matches!(solid.boundary(face, side), Boundary::Vertex(_)) {
                set(&mut q, k, bound);
                snapped = true;
            }
        }
    }
    if !snapped {
        return None;
    }
    let coordinates = e.pa.point.length().max(e.pb.point.length());
    let rounding = 64.0 * f64::EPSILON * coordinates * e.r.length();
    (evaluate(a, b, &q).f() <= e.f() + rounding).then_some(q)
}

/// Levenberg–Marquardt minimisation of f over the `movable` parameters from `start`.
pub(crate) fn minimise(
    a: &PosedSolid,
    b: &PosedSolid,
    start: Pair,
    movable: [bool; N],
    limits: &Limits,
) -> Polished {
    let mut p = feature_moves::enter_trims(a, b, normalize(a, b, start), movable);
    let mut e = evaluate(a, b, &p);
    let mut mu = 1e-3;
    let mut iterations = 1_u32;
    let mut moves = 0_u32;
    // Moves between a face, an edge and a vertex (trimmed faces, edges with ends), and whether
    // one was due when their count ran out.
    let mut switches = 0_u32;
    let mut blocked = false;
    // 3-d length of the last attempted step: near a touching contact (gap -> 0) f is quartic
    // along the common tangent, the residual is tiny long before the points settle, so the
    // polish also waits for the steps to die out (linear convergence, ratio 2/3). A damped
    // step can be short only because the damping is large, so the undamped Newton step must
    // be short too (`newton_reach`), except within 10 x tolerance of touching: there H is
    // singular to rounding along the common tangent, the Newton step is noise, and a touch is
    // told from a crossing by the normals (`local_minima::polish`).
    let mut last_step = f64::INFINITY;
    loop {
        // Off an edge or vertex where f descends into a neighbouring feature.
        let mut moved = false;
        // f changes by r · w when A's point moves by w, by −r · w when B's does.
        let rates = [movable[0].then_some(e.r), movable[2].then_some(-e.r)];
        if let Some(q) = feature_moves::leave(a, b, &p, rates, limits.tolerance) {
            if switches < MAX_SWITCHES {
                p = q;
                switches += 1;
                moved = true;
            } else {
                blocked = true;
            }
        }
        // The parameters that exist and may move.
        let mv = both(movable, p.dims());
        // Active set: movable parameters at a bound whose descent direction leaves the face.
        let mut active = [false; N];
        for k in (0..N).filter(|&k| mv[k] && !moved) {
            let Some(side) = side_of(a, b, &p, k) else {
                continue;
            };
            // Descent into the face along this parameter (per unit length).
            let inward = match side {
                ParamSide::UMin | ParamSide::VMin => 1.0,
                ParamSide::UMax | ParamSide::VMax => -1.0,
            };
            let slope = inward * e.g[k] / e.cols[k].length().max(f64::MIN_POSITIVE);
            let (on_a, _) = split(k);
            let boundary = if on_a {
                a.boundary(p.fa, side)
            } else {
                b.boundary(p.fb, side)
            };
            if let Boundary::Vertex(vertex) = boundary {
                // At a pole or apex only one meridian is seen at a time: when it offers no
                // descent into the face, look round for one that does.
                if slope < -0.1 * limits.tolerance {
                    continue;
                }
                let turned = (moves < MAX_MOVES)
                    .then(|| turn_at_vertex(a, b, &p, k, side, &e, 0.1 * limits.tolerance))
                    .flatten();
                if let Some(q) = turned {
                    p = q;
                    moves += 1;
                    moved = true;
                    break;
                }
                // No meridian of this face descends. Where other faces meet at the vertex (a
                // rounded box's corner, where a sphere's pole meets the fillets and the flat
                // face), descent may still lead into one of them: the point is that vertex,
                // held there, and leaves into whichever edge or face descends (or stays, a
                // minimum only if nothing does). Treated as a bound, such a pole passed for a
                // minimum with the connecting vector 5° off the surface's normal.
                let (solid, face, uv) = if on_a { (a, p.fa, p.a) } else { (b, p.fb, p.b) };
                if moves < MAX_MOVES && meets_other_faces(solid, face, vertex) {
                    p.set_side(on_a, face, uv, Held::Vertex(vertex));
                    moves += 1;
                    moved = true;
                    break;
                }
                active[k] = true;
                continue;
            }
            if slope < 0.0 {
                continue;
            }
            active[k] = true;
        }
        if moved {
            e = evaluate(a, b, &p);
            iterations += 1;
            last_step = f64::INFINITY;
            continue;
        }
        let res = residual(&e, mv, active);
        let settled = last_step <= 100.0 * limits.tolerance
            && (e.r.length() <= 10.0 * limits.tolerance
                || newton_reach(&e, mv, active).is_none_or(|s| s <= 100.0 * limits.tolerance));
        if res <= limits.tolerance && settled {
            // Settled next to a pole or apex, where the parametrisation is polar and the steps
            // crawl: if the vertex itself is no farther (to rounding), carry on from there.
            if moves < MAX_MOVES {
                if let Some(q) = vertex_snap(a, b, &p, &e, movable) {
                    p = q;
                    moves += 1;
                    e = evaluate(a, b, &p);
                    iterations += 1;
                    last_step = f64::INFINITY;
                    continue;
                }
            }
            // Stationary on this face: a minimum of the union only if no edge it is held at
            // offers descent into the neighbouring face.
            let hop = (0..N).filter(|&k| active[k]).find_map(|k| {
                let side = side_of(a, b, &p, k)?;
                hop_across(a, b, &p, k, side, &e, limits.tolerance)
            });
            match hop {
                Some(q) if moves < MAX_MOVES => {
                    p = q;
                    moves += 1;
                    e = evaluate(a, b, &p);
                    iterations += 1;
                    mu = 1e-3;
                    last_step = f64::INFINITY;
                    continue;
                }
                _ => {
                    return Polished {
                        pair: p,
                        eval: e,
                        residual: res,
                        active,
                        iterations,
                        converged: hop.is_none() && !blocked,
                    };
                }
            }
        }
        if iterations >= limits.iterations || mu > 1e20 {
            return Polished {
                pair: p,
                eval: e,
                residual: res,
                active,
                iterations,
                converged: res <= limits.tolerance && !blocked,
            };
        }
        // Damped Newton step on the free parameters. At a pole or apex u runs round the vertex
        // at zero speed: it is no coordinate there (the meridian was chosen by the turn above),
        // and left free the step turns it back through the coupling d · S_uv, so v never
        // leaves the pole (a dome's pole 0.0146 mm under a tilted plane was turned towards the
        // descent and back 16 times and then accepted as a minimum).
        let scale = e.cols.iter().map(|c| c.length()).fold(0.0, f64::max);
        let at_pole = |k: usize| k % 2 == 0 && e.cols[k].length() <= 1e-9 * scale;
        let free: Vec<usize> = (0..N)
            .filter(|&k| mv[k] && !active[k] && !at_pole(k))
            .collect();
        let n = free.len();
        let (m, rhs) = reduced_system(&e, &free, |speed2, floor| mu * speed2.max(floor));
        iterations += 1;
        let Some(delta) = linalg::solve(&m, &rhs, n) else {
            mu *= 10.0;
            continue;
        };
        let reach = point_reach(&e, &free, &delta);
        let scale = if reach > limits.step {
            limits.step / reach
        } else {
            1.0
        };
        last_step = scale * reach;
        let mut q = p;
        for (i, &k) in free.iter().enumerate() {
            set(&mut q, k, params(&p, k) + scale * delta[i]);
        }
        // A step that leaves a trimmed face stops on the edge it crosses; one that leaves it
        // where it starts holds the point on that edge (as a side's bound becomes active).
        let (q, cut) = match feature_moves::cut_at_trims(a, b, &p, q, mv) {
            TrimStep::Inside(q) => (q, false),
            TrimStep::Cut(q) => (q, true),
            TrimStep::Hold(q, on_a) => {
                // Held on the edge only where f does not descend into the face (as a side's
                // bound is active only where the gradient points out, and as `leave` releases
                // the point exactly where it does): otherwise the step is refused and damped
                // towards the gradient, which points in.
                let rate = if on_a { e.r } else { -e.r };
                let solid = if on_a { a } else { b };
                let stay =
                    feature_moves::stays_in_face(solid, q.side(on_a).2, rate, limits.tolerance);
                if stay || switches >= MAX_SWITCHES {
                    mu *= 8.0;
                } else {
                    p = normalize(a, b, q);
                    switches += 1;
                    e = evaluate(a, b, &p);
                    last_step = f64::INFINITY;
                }
                continue;
            }
        };
        let q = normalize(a, b, q);
        let trial = evaluate(a, b, &q);
        // f is only known to rounding (64 ulp of the coordinates times |r|); inside that band
        // a step counts as progress when it lowers the residual, which stays well resolved
        // (without this, LM stalls at residual ~ sqrt(stiffness x rounding) near a shallow
        // minimum). A step cut at a trim must lower f: otherwise a point released from an edge
        // could be cut back onto it without end.
        let coordinates = e.pa.point.length().max(e.pb.point.length());
        let rounding = 64.0 * f64::EPSILON * coordinates * e.r.length();
        let progress = if cut {
            trial.f() < e.f()
        } else {
            trial.f() <= e.f()
                || (trial.f() <= e.f() + rounding
                    && residual(&trial, mv, active) < residual(&e, mv, active))
        };
        if progress {
            p = q;
            e = trial;
            mu = (mu * 0.3).max(1e-15);
        } else {
            mu *= 8.0;
        }
    }
}

/// 3-d length of the undamped Newton step −H⁻¹g over the free parameters (movable, not
/// active): the largest move of either point, in mm. `None` where the reduced Hessian is
/// singular.
///
/// The residual alone does not make a point stationary: near a shallow crossing of the two
/// surfaces (f -> 0 along the crossing curve) the free directions together span r while each
/// is nearly normal to it, so every component r · c_k / |c_k| is small although f drops to zero
/// a Newton step away (e.g. a rim meeting a plane at a slope of 1.6e-3: |r| = 1.3e-6 mm,
/// residual 1.1e-9 mm, zero 8e-4 mm along the rim).
fn newton_reach(e: &Eval, movable: [bool; N], active: [bool; N]) -> Option<f64> {
    let free: Vec<usize> = (0..N).filter(|&k| movable[k] && !active[k]).collect();
    let n = free.len();
    if n == 0 {
        return Some(0.0);
    }
    let (m, rhs) = reduced_system(e, &free, pole_damping);
    let delta = linalg::solve(&m, &rhs, n)?;
    Some(point_reach(e, &free, &delta))
}

/// The Newton system H δ = −g restricted to the `free` parameters (row i is parameter
/// `free[i]`), with `damping(|c_k|², floor)` added to each diagonal entry, where c_k is the
/// parameter's column (∂P/∂x_k, mm per unit) and floor = 1e-12 x the largest |c|².
fn reduced_system(
    e: &Eval,
    free: &[usize],
    damping: impl Fn(f64, f64) -> f64,
) -> ([[f64; N]; N], [f64; N]) {
    let floor = 1e-12
        * e.cols
            .iter()
            .map(|c| c.length_squared())
            .fold(0.0, f64::max);
    let mut m = [[0.0; N]; N];
    let mut rhs = [0.0; N];
    for (i, &ki) in free.iter().enumerate() {
        for (j, &kj) in free.iter().enumerate() {
            m[i][j] = e.h[ki][kj];
        }
        m[i][i] += damping(e.cols[ki].length_squared(), floor);
        rhs[i] = -e.g[ki];
    }
    (m, rhs)
}

/// Damping only where a direction vanishes (a pole's u): the floor there, nothing elsewhere.
fn pole_damping(speed2: f64, floor: f64) -> f64 {
    if speed2 <= floor { floor } else { 0.0 }
}

/// The largest move of either point (mm) for the parameter step `delta` over `free`.
fn point_reach(e: &Eval, free: &[usize], delta: &[f64; N]) -> f64 {
    free.iter()
        .enumerate()
        .map(|(i, &k)| (e.cols[k] * delta[i]).length())
        .fold(0.0, f64::max)
}

/// Plain Newton on ∇f = 0 over all the pair's parameters (no bounds are active: a witness is
/// an interior stationary point; a point held on an edge moves along it only), with
/// backtracking on the squared residual.
pub(crate) fn stationary(a: &PosedSolid, b: &PosedSolid, start: Pair, limits: &Limits) -> Polished {
    let all = start.dims();
    let none = [false; N];
    let merit = |e: &Eval| {
        let scale = e.cols.iter().map(|c| c.length()).fold(0.0, f64::max);
        (0..N)
            .filter_map(|k| {
                let len = e.cols[k].length();
                (len > 1e-12 * scale).then(|| (e.g[k] / len).powi(2))
            })
            .sum::<f64>()
    };
    let mut p = normalize(a, b, start);
    let mut e = evaluate(a, b, &p);
    let mut iterations = 1_u32;
    loop {
        let res = residual(&e, all, none);
        if res <= limits.tolerance || iterations >= limits.iterations {
            return Polished {
                pair: p,
                eval: e,
                residual: res,
                active: none,
                iterations,
                converged: res <= limits.tolerance,
            };
        }
        // Tiny Levenberg damping only where the plain system is singular (a pole's u).
        let every: Vec<usize> = (0..N).filter(|&k| all[k]).collect();
        let (m, rhs) = reduced_system(&e, &every, pole_damping);
        let Some(delta) = linalg::solve(&m, &rhs, every.len()) else {
            return Polished {
                pair: p,
                eval: e,
                residual: res,
                active: none,
                iterations,
                converged: false,
            };
        };
        let reach = point_reach(&e, &every, &delta);
        let mut scale = if reach > limits.step {
            limits.step / reach
        } else {
            1.0
        };
        let base = merit(&e);
        let mut accepted = false;
        for _ in 0..20 {
            let mut q = p;
            for (i, &k) in every.iter().enumerate() {
                set(&mut q, k, params(&p, k) + scale * delta[i]);
            }
            let q = normalize(a, b, q);
            let trial = evaluate(a, b, &q);
            iterations += 1;
            if merit(&trial) < base {
                p = q;
                e = trial;
                accepted = true;
                break;
            }
            scale *= 0.5;
        }
        if !accepted {
            let res = residual(&e, all, none);
            return Polished {
                pair: p,
                eval: e,
                residual: res,
                active: none,
                iterations,
                converged: res <= limits.tolerance,
            };
        }
    }
}
