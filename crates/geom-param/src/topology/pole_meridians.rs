//! The meridians along which a face leaves a vertex its side collapses into (a pole of a
//! sphere or dome, a cone's apex): the face's derivative across the side, sampled along it.
//!
//! Where a side of a face's parameter rectangle collapses into a vertex, every point of the
//! side is the vertex, and the derivative across the side at running parameter t is the
//! direction of the meridian that leaves the vertex there. At a smooth pole these directions
//! span the tangent plane; at an apex they sweep a cone. A solver standing on the vertex
//! chooses among them to move into the face; they depend on the solid alone, so a solid
//! computes them once, at first use ([`Solid::pole_meridians`]). (Not the triangle fans the
//! tessellation puts round a pole.)

use crate::topology::feature::{FaceId, VertexId};
use crate::topology::solid::{Boundary, Face, ParamSide, Solid};
use glam::DVec3;

/// Meridians sampled in a [`PoleMeridians`]: evenly spaced over the side, from its
/// start (k / 16 of the range for k = 0..16).
pub const POLE_MERIDIANS: usize = 16;

/// The directions in which face `face` leaves vertex `vertex` across its side `side` (the
/// side collapses into the vertex), in the solid's frame.
#[derive(Clone, Debug, PartialEq)]
pub struct PoleMeridians {
    /// The vertex.
    pub vertex: VertexId,
    /// The face with a side collapsed into it.
    pub face: FaceId,
    /// That side.
    pub side: ParamSide,
    /// The running parameter of each sample (the parameter along the side: v on a u side,
    /// u on a v side), `range.min + range.span() * k / POLE_MERIDIANS`.
    pub at: [f64; POLE_MERIDIANS],
    /// The face's derivative across the side at each sample, turned to point into the face
    /// (∂S/∂u on u_min, −∂S/∂u on u_max, and so on; not normalised, mm per unit parameter).
    pub tangents: [DVec3; POLE_MERIDIANS],
    /// The same derivative half the side's range further on (the meridian opposite at a pole
    /// of revolution; on a periodic side, the sample `(k + POLE_MERIDIANS / 2) % 16`; on a
    /// non-periodic side, evaluated there, beyond the range for the later samples). At a
    /// smooth pole it points opposite to [`Self::tangents`]; at an apex it does not.
    pub opposite: [DVec3; POLE_MERIDIANS],
}

/// The derivative of `face` across its side `side` at running parameter `t`, turned to point
/// into the face (∂S/∂u on u_min, −∂S/∂u on u_max, and so on; not normalised): where the side
/// collapses into a vertex, the direction of the meridian that leaves the vertex at t. A
/// solver that needs a meridian between the samples of [`PoleMeridians`] evaluates it here.
#[must_use]
pub fn meridian_tangent(face: &Face, side: ParamSide, t: f64) -> DVec3 {
    let domain = face.surface.domain();
    let [u, v] = side.params_at(&domain, t);
    let s = face.surface.eval(u, v);
    match side {
        ParamSide::UMin => s.du,
        ParamSide::UMax => -s.du,
        ParamSide::VMin => s.dv,
        ParamSide::VMax => -s.dv,
    }
}

/// The meridians of every face side of `solid` that collapses into a vertex, in vertex order.
pub(crate) fn pole_meridians(solid: &Solid) -> Vec<PoleMeridians> {
    let mut all = Vec::new();
    for (v, vertex) in solid.vertices.iter().enumerate() {
        let id = VertexId(v as u32);
        for &face_id in &vertex.faces {
            let Some(face) = solid.faces.get(face_id.0 as usize) else {
                continue;
            };
            for side in [
                ParamSide::UMin,
                ParamSide::UMax,
                ParamSide::VMin,
                ParamSide::VMax,
            ] {
                if face.boundary(side) != Boundary::Vertex(id) {
                    continue;
                }
                let surface = &face.surface;
                let domain = surface.domain();
                let across_v = matches!(side, ParamSide::VMin | ParamSide::VMax);
                let range = domain[usize::from(!across_v)];
                let tangent_at = |t: f64| meridian_tangent(face, side, t);
                let at: [f64; POLE_MERIDIANS] = std::array::from_fn(|k| {
                    range.min + range.span() * k as f64 / POLE_MERIDIANS as f64
                });
                let tangents = at.map(tangent_at);
                let opposite = if range.periodic {
                    std::array::from_fn(|k| tangents[(k + POLE_MERIDIANS / 2) % POLE_MERIDIANS])
                } else {
                    at.map(|t| tangent_at(t + 0.5 * range.span()))
                };
                all.push(PoleMeridians {
                    vertex: id,
                    face: face_id,
                    side,
                    at,
                    tangents,
                    opposite,
                });
            }
        }
    }
    all
}
