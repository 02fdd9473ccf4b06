//! Per-face measures that size a general face's mesh: the typical lengths |S_u| and |S_v| that
//! turn its parameter plane into a plane of millimetres, and the target triangle edge length
//! that its largest curvature allows.

use crate::topology::feature::FaceId;
use crate::topology::solid::Solid;
use glam::DVec2;

/// How much longer than the curvature's equilateral side a face's target length may be.
const CURVATURE_SLACK: f64 = 4.0;
/// Samples per parameter direction (at the cell centres of a GRID x GRID grid).
const GRID: usize = 9;

/// How a face's parameter plane is scaled and how long its triangle edges may be.
#[derive(Clone, Copy, Debug)]
pub(crate) struct FaceMetric {
    /// Median |∂S/∂u| and |∂S/∂v| over the box (mm per parameter unit), both > 0.
    pub scale: DVec2,
    /// Target edge length (mm): the object's `max_length`, or less on a face whose largest
    /// principal curvature magnitude κ_max (sampled) is high, but never below
    /// CURVATURE_SLACK x sqrt(6 budget / κ_max) (an equilateral triangle of side h on a sphere
    /// of radius 1/κ deviates by about h² κ / 6). The slack leaves curvature to the
    /// error refinement, which grades the mesh where the face bends most instead of refining
    /// the whole face to its most curved point.
    pub target_length: f64,
}

/// The parameter box of face `id`: its trim's loops' box, or its whole domain.
///
/// # Errors
/// A reason when the box is empty or not finite.
pub(crate) fn param_box(solid: &Solid, id: FaceId) -> Result<(DVec2, DVec2), String> {
    let face = solid.face(id);
    let (lo, hi) = match &face.trim {
        Some(trim) => trim.bounds(),
        None => {
            let [du, dv] = face.surface.domain();
            (DVec2::new(du.min, dv.min), DVec2::new(du.max, dv.max))
        }
    };
    if !(lo.is_finite() && hi.is_finite() && hi.x > lo.x && hi.y > lo.y) {
        return Err(format!(
            "its parameter region [{}, {}] x [{}, {}] is empty or unbounded",
            lo.x, hi.x, lo.y, hi.y
        ));
    }
    Ok((lo, hi))
}

/// Measures face `id` on a grid over its parameter box.
///
/// # Errors
/// A reason when the surface does not evaluate to finite derivatives, or its derivatives vanish
/// over the whole box.
pub(crate) fn face_metric(
    solid: &Solid,
    id: FaceId,
    budget: f64,
    max_length: f64,
) -> Result<FaceMetric, String> {
    let (lo, hi) = param_box(solid, id)?;
    let surface = &solid.face(id).surface;
    let [du, dv] = surface.domain();
    let mut lengths_u = Vec::with_capacity(GRID * GRID);
    let mut lengths_v = Vec::with_capacity(GRID * GRID);
    let mut curvature = 0.0_f64;
    for i in 0..GRID {
        for j in 0..GRID {
            let f = DVec2::new(
                (i as f64 + 0.5) / GRID as f64,
                (j as f64 + 0.5) / GRID as f64,
            );
            let uv = lo + f * (hi - lo);
            let (u, v) = (du.normalize(uv.x), dv.normalize(uv.y));
            let p = surface.eval(u, v);
            if !(p.point.is_finite() && p.du.is_finite() && p.dv.is_finite()) {
                return Err(format!("its surface is not finite at (u, v) = ({u}, {v})"));
            }
            lengths_u.push(p.du.length());
            lengths_v.push(p.dv.length());
            if let Some(k) = surface.principal_curvatures(u, v) {
                for kappa in [k.min.abs(), k.max.abs()] {
                    if kappa.is_finite() {
                        curvature = curvature.max(kappa);
                    }
                }
            }
        }
    }
    let scale = DVec2::new(typical(&mut lengths_u), typical(&mut lengths_v));
    if !(scale.x > 0.0 && scale.y > 0.0 && scale.is_finite()) {
        return Err(
            "its parametrisation is degenerate (∂S/∂u or ∂S/∂v vanishes everywhere)".into(),
        );
    }
    let from_curvature = if curvature > 0.0 {
        (6.0 * budget / curvature).sqrt()
    } else {
        f64::INFINITY
    };
    Ok(FaceMetric {
        scale,
        target_length: max_length.min(CURVATURE_SLACK * from_curvature),
    })
}

/// The median of `lengths`, or their largest value when the median is 0 (a face that is
/// singular over more than half its box).
fn typical(lengths: &mut [f64]) -> f64 {
    lengths.sort_by(f64::total_cmp);
    let median = lengths[lengths.len() / 2];
    if median > 0.0 {
        median
    } else {
        lengths.last().copied().unwrap_or(0.0)
    }
}
