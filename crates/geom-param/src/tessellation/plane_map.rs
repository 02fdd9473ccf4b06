//! The plane a face's region is triangulated in: (u, v) scaled to millimetres by typical
//! derivative lengths, with one parameter warped where needed so that the map is close to
//! conformal, and triangles that are well shaped in the plane are well shaped on the surface.
//!
//! With |S_u| = a(v) and |S_v| = b(v) depending on v only and S_u ⊥ S_v (every surface of
//! revolution, sphere, cone and cylinder), x = ā (u - u₀) and y = ā ∫ b(v)/a(v) dv give
//! ds² = (a(v)/ā)² (dx² + dy²): angles are preserved and lengths scaled by a(v)/ā. A constant
//! scaling alone stretches triangles by a(v)/ā, which on a disk from its centre ring to its rim
//! is a factor of ten or more. The warp is measured, not assumed: medians of |S_u| and |S_v|
//! over the other parameter on a grid. When |S_u| varies along v (or |S_v| along u) by more than
//! [`WARP_RATIO`], the varying direction is warped; otherwise both are scaled by their medians.

use crate::topology::feature::FaceId;
use crate::topology::solid::Solid;
use glam::DVec2;

/// Samples along the warped parameter (table of its plane coordinate).
const TABLE: usize = 257;
/// Samples across it, whose median is taken.
const ACROSS: usize = 9;
/// Smallest variation (max over min) of the across-derivative length that warps.
const WARP_RATIO: f64 = 1.5;

/// Medians along one parameter: its values, and the derivative lengths across and along it.
struct Profile {
    params: Vec<f64>,
    across: Vec<f64>,
    along: Vec<f64>,
}

/// A monotone table from the warped parameter to its plane coordinate.
#[derive(Clone, Debug)]
struct Warp {
    /// Which parameter is warped (0 = u, 1 = v).
    axis: usize,
    /// Parameter values, increasing.
    params: Vec<f64>,
    /// Plane coordinates, increasing.
    plane: Vec<f64>,
}

/// The map from a face's (u, v) to its triangulation plane (mm) and back.
#[derive(Clone, Debug)]
pub(crate) struct PlaneMap {
    lo: DVec2,
    /// mm per parameter unit on each unwarped axis.
    scale: DVec2,
    warp: Option<Warp>,
    /// Smallest ratio of the surface's length to the plane's (1 without a warp).
    min_stretch: f64,
    /// Largest ratio of the surface's length to the plane's (1 without a warp).
    max_stretch: f64,
}

impl PlaneMap {
    /// The map for face `face` over the parameter box [lo, hi].
    ///
    /// # Errors
    /// A reason when the surface's derivatives are not finite or vanish everywhere.
    pub fn new(solid: &Solid, face: FaceId, lo: DVec2, hi: DVec2) -> Result<Self, String> {
        let at = |axis: usize, t: f64, s: f64| -> Result<DVec2, String> {
            let uv = if axis == 0 {
                DVec2::new(t, s)
            } else {
                DVec2::new(s, t)
            };
            let p = solid.eval_face(face, uv.x, uv.y);
            let d = DVec2::new(p.du.length(), p.dv.length());
            if d.is_finite() {
                Ok(d)
            } else {
                Err(format!(
                    "its surface's derivatives are not finite at (u, v) = ({}, {})",
                    uv.x, uv.y
                ))
            }
        };
        // Per warp candidate axis: along it, the medians (over the other parameter) of the
        // derivative lengths across and along it.
        let mut best: Option<(f64, usize, Profile)> = None;
        let mut medians_all = [Vec::new(), Vec::new()];
        for axis in 0..2 {
            let other = 1 - axis;
            let mut params = Vec::with_capacity(TABLE);
            let mut across = Vec::with_capacity(TABLE);
            let mut along = Vec::with_capacity(TABLE);
            for i in 0..TABLE {
                let t = lo[axis] + (hi[axis] - lo[axis]) * i as f64 / (TABLE - 1) as f64;
                let mut a = Vec::with_capacity(ACROSS);
                let mut b = Vec::with_capacity(ACROSS);
                for j in 0..ACROSS {
                    let s = lo[other] + (hi[other] - lo[other]) * (j as f64 + 0.5) / ACROSS as f64;
                    let d = at(axis, t, s)?;
                    a.push(d[other]);
                    b.push(d[axis]);
                }
                params.push(t);
                across.push(median(&mut a));
                along.push(median(&mut b));
            }
            medians_all[other].extend(across.iter().copied());
            let (min, max) = across
                .iter()
                .fold((f64::INFINITY, 0.0_f64), |(lo, hi), &x| {
                    (lo.min(x), hi.max(x))
                });
            if min > 0.0 && along.iter().all(|&b| b > 0.0) {
                let ratio = max / min;
                if ratio > WARP_RATIO && best.as_ref().is_none_or(|b| ratio > b.0) {
                    best = Some((
                        ratio,
                        axis,
                        Profile {
                            params,
                            across,
                            along,
                        },
                    ));
                }
            }
        }
        let scale = DVec2::new(median(&mut medians_all[0]), median(&mut medians_all[1]));
        if !(scale.x > 0.0 && scale.y > 0.0) {
            return Err(
                "its parametrisation is degenerate (∂S/∂u or ∂S/∂v vanishes everywhere)".into(),
            );
        }
        let Some((
            _,
            axis,
            Profile {
                params,
                across,
                along,
            },
        )) = best
        else {
            return Ok(Self {
                lo,
                scale,
                warp: None,
                min_stretch: 1.0,
                max_stretch: 1.0,
            });
        };
        // y(t) = ā ∫ b/a dt by the trapezoid rule, ā the across axis's median.
        let bar = scale[1 - axis];
        let mut plane = Vec::with_capacity(TABLE);
        plane.push(0.0);
        for i in 1..TABLE {
            let m0 = along[i - 1] / across[i - 1];
            let m1 = along[i] / across[i];
            let step = 0.5 * (m0 + m1) * (params[i] - params[i - 1]) * bar;
            plane.push(plane[i - 1] + step);
        }
        let min_stretch = across.iter().fold(f64::INFINITY, |m, &a| m.min(a)) / bar;
        let max_stretch = across.iter().fold(0.0_f64, |m, &a| m.max(a)) / bar;
        Ok(Self {
            lo,
            scale,
            warp: Some(Warp {
                axis,
                params,
                plane,
            }),
            min_stretch,
            max_stretch,
        })
    }

    /// The plane point of (u, v) (mm).
    pub fn plane_point(&self, uv: DVec2) -> DVec2 {
        let mut p = (uv - self.lo) * self.scale;
        if let Some(w) = &self.warp {
            p[w.axis] = interpolate(&w.params, &w.plane, uv[w.axis]);
        }
        p
    }

    /// The (u, v) of a plane point.
    pub fn params_of(&self, plane: DVec2) -> DVec2 {
        let mut uv = self.lo + plane / self.scale;
        if let Some(w) = &self.warp {
            uv[w.axis] = interpolate(&w.plane, &w.params, plane[w.axis]);
        }
        uv
    }

    /// The smallest ratio of surface length to plane length over the box (<= 1): plane
    /// triangles must be this much smaller than a surface target length somewhere.
    pub fn min_stretch(&self) -> f64 {
        self.min_stretch
    }

    /// The largest ratio of surface length to plane length over the box (>= 1).
    pub fn max_stretch(&self) -> f64 {
        self.max_stretch
    }
}

/// Piecewise-linear interpolation of the increasing table (xs, ys) at x, extended linearly
/// beyond its ends.
fn interpolate(xs: &[f64], ys: &[f64], x: f64) -> f64 {
    let n = xs.len();
    let k = xs.partition_point(|&t| t <= x).clamp(1, n - 1);
    let (x0, x1, y0, y1) = (xs[k - 1], xs[k], ys[k - 1], ys[k]);
    if x1 == x0 {
        return y0;
    }
    y0 + (x - x0) * (y1 - y0) / (x1 - x0)
}

/// The median of `values` (NaN-free), or their largest when the median is 0.
fn median(values: &mut [f64]) -> f64 {
    values.sort_by(f64::total_cmp);
    let m = values[values.len() / 2];
    if m > 0.0 {
        m
    } else {
        values.last().copied().unwrap_or(0.0)
    }
}
