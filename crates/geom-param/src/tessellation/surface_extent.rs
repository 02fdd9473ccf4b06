//! The extent of a general solid's surface, sampled before it is meshed: its vertices, points
//! along its edges and a grid over each face's region.

use crate::object_model::ModelError;
use crate::topology::feature::FaceId;
use crate::topology::solid::Solid;
use glam::{DVec2, DVec3};

/// Samples per edge and per parameter direction of a face.
const SAMPLES: usize = 17;

/// The axis-aligned box (min, max) of sampled points of the solid's surface (mm, object frame):
/// every vertex, 17 points along every edge, and a 17 x 17 grid over every face's parameter box
/// (for a trimmed face, the grid points inside its trim, plus its trim polylines). It lies
/// inside the exact surface's box and approaches it as faces are flat between samples.
///
/// # Errors
/// [`ModelError::Tessellation`] for a face or edge that evaluates to a non-finite point, or a
/// face without a bounded parameter region.
pub(crate) fn sampled_extent(solid: &Solid) -> Result<(DVec3, DVec3), ModelError> {
    let mut lo = DVec3::splat(f64::INFINITY);
    let mut hi = DVec3::splat(f64::NEG_INFINITY);
    let mut add = |p: DVec3| {
        lo = lo.min(p);
        hi = hi.max(p);
    };
    for v in &solid.vertices {
        add(v.point);
    }
    for (k, edge) in solid.edges.iter().enumerate() {
        let range = edge.curve.domain();
        for i in 0..SAMPLES {
            let t = range.min + range.span() * i as f64 / (SAMPLES - 1) as f64;
            let p = edge.curve.eval(t).point;
            if !p.is_finite() {
                return Err(ModelError::Tessellation {
                    face: edge.uses[0].face,
                    reason: format!("edge {k} is not finite at t = {t}"),
                });
            }
            add(p);
        }
    }
    for (k, face) in solid.faces.iter().enumerate() {
        let id = FaceId(k as u32);
        let fail = |reason: String| ModelError::Tessellation { face: id, reason };
        let (flo, fhi) = super::face_metric::param_box(solid, id).map_err(fail)?;
        let mut params: Vec<DVec2> = Vec::new();
        for i in 0..SAMPLES {
            for j in 0..SAMPLES {
                let f = DVec2::new(i as f64, j as f64) / (SAMPLES - 1) as f64;
                params.push(flo + f * (fhi - flo));
            }
        }
        if let Some(trim) = &face.trim {
            params.retain(|&uv| trim.contains(uv, 0.0));
            for l in &trim.loops {
                for e in &l.entries {
                    params.extend(e.polyline().iter().map(|&(_, uv)| uv));
                }
            }
        }
        for uv in params {
            let p = solid.eval_face(id, uv.x, uv.y).point;
            if !p.is_finite() {
                return Err(fail(format!(
                    "its surface is not finite at (u, v) = ({}, {})",
                    uv.x, uv.y
                )));
            }
            add(p);
        }
    }
    if !(lo.is_finite() && hi.is_finite()) {
        return Err(ModelError::Tessellation {
            face: FaceId(0),
            reason: "the solid has no faces".into(),
        });
    }
    Ok((lo, hi))
}
