//! The cone of outward normals of a solid at a feature location, and the local curvature there:
//! what the surface-normal property checks a contact normal against.
//!
//! - A regular face point: the single outward normal N(u, v).
//! - An edge point: the arc of directions between the two faces' outward normals at that point
//!   (each face evaluated on the side the edge runs along), which all lie normal to the edge's
//!   tangent. For a ridge this is the normal cone; for a valley or a smooth edge the same
//!   arc is checked (for a smooth edge it is a single direction).
//! - A vertex (a pole or apex on the axis of revolution), or a face point where the face has no
//!   tangent plane (an apex): the circular cone about the mean of the faces' normals sampled
//!   around the vertex (16 values of the periodic parameter, 1e-7 of the parameter span inside
//!   the collapsed side), with half-angle the largest angle of a sample from that mean.
//! - A corner where edges end (a vertex of trimmed faces): the convex cone spanned by the
//!   outward normals of the faces meeting there, each evaluated at the vertex (through the
//!   p-curve of an edge ending there). For a convex corner that is its normal cone; for a
//!   corner with a valley edge it is a superset (the check is then lenient there, as the arc of
//!   a valley edge is).

use geom_param::{Boundary, DVec3, FaceId, FeatureLocation, ParamSide, Solid, VertexId};

/// Outward normal directions at a feature location (object frame).
#[derive(Clone, Debug, PartialEq)]
pub enum NormalCone {
    /// One direction.
    Single(DVec3),
    /// The shorter great-circle arc between two directions.
    Arc(DVec3, DVec3),
    /// Directions within `half_angle` (rad) of `axis`.
    Circular {
        /// Unit axis.
        axis: DVec3,
        /// Half-angle (rad).
        half_angle: f64,
    },
    /// Non-negative combinations of these unit directions (the faces' normals at a corner).
    Spanned(Vec<DVec3>),
}

/// The angle between two vectors (rad), accurate for small and near-π angles.
#[must_use]
pub fn angle(a: DVec3, b: DVec3) -> f64 {
    a.cross(b).length().atan2(a.dot(b))
}

impl NormalCone {
    /// This cone turned by `rotation` (object frame to world frame).
    #[must_use]
    pub fn rotated(self, rotation: geom_param::DQuat) -> Self {
        match self {
            Self::Single(n) => Self::Single(rotation * n),
            Self::Arc(n1, n2) => Self::Arc(rotation * n1, rotation * n2),
            Self::Circular { axis, half_angle } => Self::Circular {
                axis: rotation * axis,
                half_angle,
            },
            Self::Spanned(normals) => {
                Self::Spanned(normals.into_iter().map(|n| rotation * n).collect())
            }
        }
    }

    /// How far (rad) the unit direction `n` lies outside the cone; 0 inside.
    #[must_use]
    pub fn excess(&self, n: DVec3) -> f64 {
        match *self {
            Self::Single(m) => angle(n, m),
            Self::Arc(n1, n2) => (angle(n, n1) + angle(n, n2) - angle(n1, n2)).max(0.0),
            Self::Circular { axis, half_angle } => (angle(n, axis) - half_angle).max(0.0),
            Self::Spanned(ref normals) => spanned_excess(normals, n),
        }
    }
}

/// The angle (rad) from the unit direction `n` to the convex cone spanned by `normals`: 0
/// inside, else the angle to its projection onto the cone (π/2 when that projection is the
/// apex).
///
/// The projection of a point onto a finitely generated cone in R³ lies in the relative
/// interior of a face spanned by at most three independent generators (Carathéodory), so it
/// is the nearest of the candidates: a triple that writes `n` with non-negative coefficients
/// (then `n` is inside), the projections onto the planes of pairs with non-negative
/// coefficients, and the projections onto single rays.
fn spanned_excess(normals: &[DVec3], n: DVec3) -> f64 {
    const INDEPENDENT: f64 = 1e-12;
    let k = normals.len();
    for i in 0..k {
        for j in i + 1..k {
            for l in j + 1..k {
                let (a, b, c) = (normals[i], normals[j], normals[l]);
                let det = a.dot(b.cross(c));
                if det.abs() <= INDEPENDENT {
                    continue;
                }
                // Cramer's rule for n = x a + y b + z c.
                let x = n.dot(b.cross(c)) / det;
                let y = a.dot(n.cross(c)) / det;
                let z = a.dot(b.cross(n)) / det;
                if x >= 0.0 && y >= 0.0 && z >= 0.0 {
                    return 0.0;
                }
            }
        }
    }
    let mut best: Option<DVec3> = None;
    let mut consider = |p: DVec3| {
        if best.is_none_or(|q| n.distance_squared(p) < n.distance_squared(q)) {
            best = Some(p);
        }
    };
    for (i, &a) in normals.iter().enumerate() {
        consider(a * n.dot(a).max(0.0));
        for &b in &normals[i + 1..] {
            // n's projection onto span(a, b): the 2 x 2 normal equations.
            let (aa, ab, bb) = (a.dot(a), a.dot(b), b.dot(b));
            let det = aa * bb - ab * ab;
            if det <= INDEPENDENT {
                continue;
            }
            let (na, nb) = (n.dot(a), n.dot(b));
            let x = (na * bb - nb * ab) / det;
            let y = (nb * aa - na * ab) / det;
            if x >= 0.0 && y >= 0.0 {
                consider(a * x + b * y);
            }
        }
    }
    match best {
        Some(p) if p.length_squared() > 0.0 => angle(n, p),
        _ => std::f64::consts::FRAC_PI_2,
    }
}

const SIDES: [ParamSide; 4] = [
    ParamSide::UMin,
    ParamSide::UMax,
    ParamSide::VMin,
    ParamSide::VMax,
];

/// Normals of `face` sampled around its side collapsed into a vertex: 16 values of the running
/// parameter, 1e-7 of the span inside the side.
fn normals_near_side(solid: &Solid, face: FaceId, side: ParamSide, out: &mut Vec<DVec3>) {
    let surface = &solid.face(face).surface;
    let [du, dv] = surface.domain();
    for k in 0..16 {
        let (u, v) = match side {
            ParamSide::UMin | ParamSide::UMax => {
                let inside = if side == ParamSide::UMin { 1e-7 } else { -1e-7 };
                let u = if side == ParamSide::UMin {
                    du.min
                } else {
                    du.max
                };
                (
                    u + inside * du.span(),
                    dv.min + dv.span() * f64::from(k) / 16.0,
                )
            }
            ParamSide::VMin | ParamSide::VMax => {
                let inside = if side == ParamSide::VMin { 1e-7 } else { -1e-7 };
                let v = if side == ParamSide::VMin {
                    dv.min
                } else {
                    dv.max
                };
                (
                    du.min + du.span() * f64::from(k) / 16.0,
                    v + inside * dv.span(),
                )
            }
        };
        if let Some(n) = surface.normal(u, v) {
            out.push(n);
        }
    }
}

/// The circular cone about the mean of `normals`; `None` when there are none.
fn circular(normals: &[DVec3]) -> Option<NormalCone> {
    let axis = normals.iter().copied().sum::<DVec3>().try_normalize()?;
    let half_angle = normals.iter().map(|n| angle(*n, axis)).fold(0.0, f64::max);
    Some(NormalCone::Circular { axis, half_angle })
}

fn vertex_cone(solid: &Solid, id: VertexId) -> Option<NormalCone> {
    let mut normals = Vec::new();
    for &face in &solid.vertex(id).faces {
        for side in SIDES {
            if solid.face(face).boundary(side) == Boundary::Vertex(id) {
                normals_near_side(solid, face, side, &mut normals);
            }
        }
    }
    if !normals.is_empty() {
        return circular(&normals);
    }
    corner_cone(solid, id)
}

/// The cone spanned by the outward normals, at the vertex, of the faces of the edges ending at
/// corner `id`; `None` when no edge ends there.
fn corner_cone(solid: &Solid, id: VertexId) -> Option<NormalCone> {
    /// Normals closer than this (rad) are one generator.
    const SAME: f64 = 1e-12;
    let mut normals: Vec<DVec3> = Vec::new();
    for &e in &solid.vertex(id).edges {
        let edge = solid.edge(e);
        let Some(ends) = edge.ends else { continue };
        let domain = edge.curve.domain();
        for (end, t) in [(ends[0], domain.min), (ends[1], domain.max)] {
            if end != id {
                continue;
            }
            for u in &edge.uses {
                let [fu, fv] = solid.use_params(u, t);
                if let Some(n) = solid.face(u.face).surface.normal(fu, fv)
                    && normals.iter().all(|m| angle(*m, n) > SAME)
                {
                    normals.push(n);
                }
            }
        }
    }
    (!normals.is_empty()).then_some(NormalCone::Spanned(normals))
}

/// The cone of outward normals at `location` (object frame), or `None` where none can be
/// formed (a vertex with no face collapsing into it).
#[must_use]
pub fn normal_cone(solid: &Solid, location: &FeatureLocation) -> Option<NormalCone> {
    match *location {
        FeatureLocation::Face { id, .. } => match solid.face_normal_at(location) {
            Some(n) => Some(NormalCone::Single(n)),
            None => {
                // An apex inside a face location: the cone of the sides on the axis.
                let mut normals = Vec::new();
                for side in SIDES {
                    if let Boundary::Vertex(_) = solid.face(id).boundary(side) {
                        normals_near_side(solid, id, side, &mut normals);
                    }
                }
                circular(&normals)
            }
        },
        FeatureLocation::Edge { id, t } => {
            let edge = solid.edge(id);
            let t = edge.curve.domain().normalize(t);
            let mut normals = edge.uses.iter().filter_map(|u| {
                let [fu, fv] = solid.use_params(u, t);
                solid.face(u.face).surface.normal(fu, fv)
            });
            match (normals.next(), normals.next()) {
                (Some(n1), Some(n2)) => Some(NormalCone::Arc(n1, n2)),
                (Some(n), None) | (None, Some(n)) => Some(NormalCone::Single(n)),
                (None, None) => None,
            }
        }
        FeatureLocation::Vertex { id } => vertex_cone(solid, id),
    }
}

/// The largest absolute principal curvature (1/mm) of the faces at `location`: the face's own
/// at a face point, the larger of the two faces' on an edge, 0 at a vertex (a fixed point) or
/// where the curvature is undefined.
#[must_use]
pub fn local_curvature(solid: &Solid, location: &FeatureLocation) -> f64 {
    let at = |face: FaceId, u: f64, v: f64| {
        let surface = &solid.face(face).surface;
        let [du, dv] = surface.domain();
        surface
            .principal_curvatures(du.normalize(u), dv.normalize(v))
            .map_or(0.0, |k| k.min.abs().max(k.max.abs()))
    };
    match *location {
        FeatureLocation::Face { id, u, v } => at(id, u, v),
        FeatureLocation::Edge { id, t } => {
            let edge = solid.edge(id);
            let t = edge.curve.domain().normalize(t);
            edge.uses
                .iter()
                .map(|u| {
                    let [fu, fv] = solid.use_params(u, t);
                    at(u.face, fu, fv)
                })
                .fold(0.0, f64::max)
        }
        FeatureLocation::Vertex { .. } => 0.0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::{FRAC_PI_2, FRAC_PI_4};

    /// The cone of a box corner: the positive octant's three axes.
    fn octant() -> NormalCone {
        NormalCone::Spanned(vec![DVec3::X, DVec3::Y, DVec3::Z])
    }

    #[test]
    fn a_spanned_cone_holds_the_combinations_of_its_normals() {
        assert_eq!(octant().excess(DVec3::ONE.normalize()), 0.0);
        assert_eq!(octant().excess(DVec3::new(1.0, 2.0, 0.5).normalize()), 0.0);
    }

    #[test]
    fn outside_a_spanned_cone_the_excess_is_the_angle_to_its_projection() {
        // Onto a face of the octant: (1, -1, 0) projects to (1, 0, 0).
        let n = DVec3::new(1.0, -1.0, 0.0).normalize();
        assert!((octant().excess(n) - FRAC_PI_4).abs() < 1e-15);
        // Onto a side plane: (1, 1, -1) projects to (1, 1, 0), at atan(1 / sqrt 2).
        let n = DVec3::new(1.0, 1.0, -1.0).normalize();
        assert!((octant().excess(n) - (1.0 / 2f64.sqrt()).atan()).abs() < 1e-15);
        // Opposite the octant: the projection is the apex.
        assert_eq!(octant().excess(-DVec3::ONE.normalize()), FRAC_PI_2);
    }

    #[test]
    fn a_two_normal_cone_is_the_quarter_plane_between_them() {
        let wedge = NormalCone::Spanned(vec![DVec3::X, DVec3::Y]);
        // In the plane, outside: the angle to the nearer normal.
        let n = DVec3::new(-1.0, 2.0, 0.0).normalize();
        assert!((wedge.excess(n) - 0.5f64.atan()).abs() < 1e-15);
        // Off the plane above the arc: the angle to the plane.
        let n = DVec3::new(1.0, 1.0, 1.0).normalize();
        assert!((wedge.excess(n) - (1.0 / 2f64.sqrt()).atan()).abs() < 1e-15);
    }
}
