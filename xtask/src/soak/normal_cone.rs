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

use geom_param::{Boundary, DVec3, FaceId, FeatureLocation, ParamSide, Solid, VertexId};

/// Outward normal directions at a feature location (object frame).
#[derive(Clone, Copy, Debug, PartialEq)]
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
        }
    }

    /// How far (rad) the unit direction `n` lies outside the cone; 0 inside.
    #[must_use]
    pub fn excess(&self, n: DVec3) -> f64 {
        match *self {
            Self::Single(m) => angle(n, m),
            Self::Arc(n1, n2) => (angle(n, n1) + angle(n, n2) - angle(n1, n2)).max(0.0),
            Self::Circular { axis, half_angle } => (angle(n, axis) - half_angle).max(0.0),
        }
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
    circular(&normals)
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
