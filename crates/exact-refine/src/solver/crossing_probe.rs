//! Touch or crossing? A converged pair whose gap is within its own error estimate is a touch
//! only if the surfaces do not cross next to it.
//!
//! Where two surfaces are nearly conformal (two pencils crossing at 0.0156 rad, a goblet lying
//! along a paperweight) the gap hardly changes along some direction, so the pair solve places
//! its points only to `point_error_estimate` along it and knows the gap only to
//! `error_estimate`. A stationary pair at |d| ≈ 0 there can be a point of the curve where the
//! surfaces cross at a small angle (seen: stopped at d = 2.6e-11 and −5e-11 mm, 0.05 mm from
//! the overlaps of −3.8e-4 and −1.6e-4 mm the poses were built with). Its normals are apart by
//! that angle, but at |d| ≈ 0 stationarity bounds the angle between d and the normals only by
//! residual / |d|, which is then large, and the second-order test counts eigenvalues of size
//! |d| x curvature: neither tells a touch from such a crossing.
//!
//! The surfaces themselves can. Two surfaces that meet with tangent planes tilted by α cross
//! there, and to second order (curvature scale κ) the overlap lens reaches about α / κ to one
//! side along the tilt direction t (the other normal's component in the own tangent plane).
//! An edge that meets a face at an angle α out of the face's tangent plane crosses it, and its
//! part inside the other solid reaches about α / κ along its tangent to one side.
//! [`overlap_near`] moves each face point along ±t, and each edge point along ±its tangent,
//! by α / κ x {1, 4, 16, 64} (at most 1 / κ),
//! projects the moved point onto the other side's feature, and keeps the deepest moved point
//! that lies behind the other side's outward normal at its projection by more than rounding: a
//! point of one boundary inside the other solid, which proves the surfaces cross there. The
//! caller then solves for the penetration witness from it.

use crate::features::feature_eval::{Body, Loc};
use crate::options::NewtonOptions;
use crate::solver::newton::{EPS, State, TOUCH_ANGLE, slide_on_edge, slide_on_face};
use crate::solver::projection::project;

/// Probe lengths, in units of the predicted lens size α / κ.
const PROBE_MULTIPLES: [f64; 4] = [1.0, 4.0, 16.0, 64.0];

/// The deepest probe near `state` (see the module docs): a pair (a moved face or edge point and its
/// projection onto the other side's feature, A's location first) whose moved point lies behind
/// the other side's outward normal, and that signed distance (mm, below −1e3 ε x scale).
/// `None` when no probe does, or neither point is on a face with the other's normal tilted by
/// more than [`TOUCH_ANGLE`] nor on an edge whose tangent leaves the other's tangent plane by
/// more than that.
pub(crate) fn overlap_near(
    a: &Body,
    b: &Body,
    state: &State,
    base_scale: f64,
    options: &NewtonOptions,
) -> Option<(Loc, Loc, f64)> {
    let threshold = 1e3 * EPS * state.scale;
    let curvature = state.curvature.max(1.0 / state.scale);
    let mut deepest: Option<(Loc, Loc, f64)> = None;
    for a_moves in [true, false] {
        let (own, other, own_loc, other_loc, own_eval, other_eval) = if a_moves {
            (a, b, state.la, state.lb, &state.ea, &state.eb)
        } else {
            (b, a, state.lb, state.la, &state.eb, &state.ea)
        };
        let (Some(n_own), Some(n_other)) = (
            own.outward_at(&own_loc, own_eval),
            other.outward_at(&other_loc, other_eval),
        ) else {
            continue;
        };
        // The direction to probe along and the sine of the crossing angle. On a face: the
        // other normal, negated, in the own tangent plane (length sin α). On an edge: its
        // unit tangent, which meets the other's tangent plane at asin |t̂ · n_other|.
        let (direction, sine) = match own_eval.n {
            2 => {
                let tilt = -n_other + n_own * n_other.dot(n_own);
                let sine = tilt.length();
                (tilt / sine, sine)
            }
            1 => {
                let tangent = own_eval.d[0].normalize_or_zero();
                (tangent, tangent.dot(n_other).abs())
            }
            _ => continue,
        };
        if sine.is_nan() || sine <= TOUCH_ANGLE {
            continue;
        }
        let lens = sine / curvature;
        for multiple in PROBE_MULTIPLES {
            let length = (multiple * lens).min(1.0 / curvature);
            for sign in [1.0, -1.0] {
                let step = direction * (sign * length);
                let moved = if own_eval.n == 2 {
                    slide_on_face(own, &own_loc, own_eval, step)
                } else {
                    slide_on_edge(own, &own_loc, own_eval, step)
                };
                let point = own.eval(&moved).point;
                let on_other = project(other, other_loc, point, base_scale, options).state;
                let Some(n) = other.outward_at(&on_other.la, &on_other.ea) else {
                    continue;
                };
                let gap = (point - on_other.ea.point).dot(n);
                if gap < -threshold && deepest.is_none_or(|(_, _, g)| gap < g) {
                    deepest = Some(if a_moves {
                        (moved, on_other.la, gap)
                    } else {
                        (on_other.la, moved, gap)
                    });
                }
            }
        }
    }
    deepest
}
