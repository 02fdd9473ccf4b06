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
//! - [`stationary`]: plain Newton on ∇f = 0 (penetration witnesses are saddles of f).
//!
//! Residuals are measured in 3-d: |g_k| / |c_k| is the component of the connecting vector
//! along parameter direction k, which stays meaningful at a pole where |c_k| -> 0.

use crate::linalg::{self, N};
use crate::posed::PosedSolid;
use geom_param::{Boundary, FaceId, ParamSide, SurfacePoint};
use glam::DVec3;

/// Hops across edges or turns at poles before a polish gives up (guards against cycling).
const MAX_MOVES: u32 = 16;
/// Directions probed at a pole or apex for descent into the face.
const POLE_DIRECTIONS: usize = 32;

/// A pair of face points: A's face and (u, v), B's face and (u, v).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Pair {
    pub fa: FaceId,
    pub a: [f64; 2],
    pub fb: FaceId,
    pub b: [f64; 2],
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
    let pa = a.eval(p.fa, p.a[0], p.a[1]);
    let pb = b.eval(p.fb, p.b[0], p.b[1]);
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

fn params(p: &Pair, k: usize) -> f64 {
    if k < 2 { p.a[k] } else { p.b[k - 2] }
}

fn set(p: &mut Pair, k: usize, value: f64) {
    if k < 2 {
        p.a[k] = value;
    } else {
        p.b[k - 2] = value;
    }
}

fn normalize(a: &PosedSolid, b: &PosedSolid, mut p: Pair) -> Pair {
    p.a = a.normalize(p.fa, p.a);
    p.b = b.normalize(p.fb, p.b);
    p
}

/// The side parameter `k` sits on, if it is at a bound of a non-periodic range.
fn side_of(a: &PosedSolid, b: &PosedSolid, p: &Pair, k: usize) -> Option<ParamSide> {
    let (on_a, i) = split(k);
    let (solid, face) = if on_a { (a, p.fa) } else { (b, p.fb) };
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
    let (other, other_side, other_uv) = solid.across(face, side, uv)?;
    let sp = solid.side_param(other, other_side);
    let s = solid.eval(other, other_uv[0], other_uv[1]);
    let w = if sp.index == 0 { s.du } else { s.dv } * sp.inward;
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
    let mut p = normalize(a, b, start);
    let mut e = evaluate(a, b, &p);
    let mut mu = 1e-3;
    let mut iterations = 1_u32;
    let mut moves = 0_u32;
    // 3-d length of the last attempted step: near a touching contact (gap -> 0) f is quartic
    // along the common tangent, the residual is tiny long before the points settle, so the
    // polish also waits for the steps to die out (linear convergence, ratio 2/3). A damped
    // step can be short only because the damping is large, so the undamped Newton step must
    // be short too (`newton_reach`), except within 10 x tolerance of touching: there H is
    // singular to rounding along the common tangent, the Newton step is noise, and a touch is
    // told from a crossing by the normals (`local_minima::polish`).
    let mut last_step = f64::INFINITY;
    loop {
        // Active set: movable parameters at a bound whose descent direction leaves the face.
        let mut active = [false; N];
        let mut moved = false;
        for k in (0..N).filter(|&k| movable[k]) {
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
            if let Boundary::Vertex(_) = boundary {
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
        let res = residual(&e, movable, active);
        let settled = last_step <= 100.0 * limits.tolerance
            && (e.r.length() <= 10.0 * limits.tolerance
                || newton_reach(&e, movable, active).is_none_or(|s| s <= 100.0 * limits.tolerance));
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
                        converged: hop.is_none(),
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
                converged: res <= limits.tolerance,
            };
        }
        // Damped Newton step on the free parameters.
        let free: Vec<usize> = (0..N).filter(|&k| movable[k] && !active[k]).collect();
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
        let q = normalize(a, b, q);
        let trial = evaluate(a, b, &q);
        // f is only known to rounding (64 ulp of the coordinates times |r|); inside that band
        // a step counts as progress when it lowers the residual, which stays well resolved
        // (without this, LM stalls at residual ~ sqrt(stiffness x rounding) near a shallow
        // minimum).
        let coordinates = e.pa.point.length().max(e.pb.point.length());
        let rounding = 64.0 * f64::EPSILON * coordinates * e.r.length();
        let progress = trial.f() <= e.f()
            || (trial.f() <= e.f() + rounding
                && residual(&trial, movable, active) < residual(&e, movable, active));
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

/// Plain Newton on ∇f = 0 over all four parameters (no bounds are active: a witness is an
/// interior stationary point), with backtracking on the squared residual.
pub(crate) fn stationary(a: &PosedSolid, b: &PosedSolid, start: Pair, limits: &Limits) -> Polished {
    let all = [true; N];
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
        let every: [usize; N] = std::array::from_fn(|k| k);
        let (m, rhs) = reduced_system(&e, &every, pole_damping);
        let Some(delta) = linalg::solve(&m, &rhs, N) else {
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
            for k in 0..N {
                set(&mut q, k, params(&p, k) + scale * delta[k]);
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
