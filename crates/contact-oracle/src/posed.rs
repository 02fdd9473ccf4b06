//! A solid placed in the world frame: face evaluation with the pose applied to the point and
//! every derivative, and the adjacency moves the polishers need (crossing an edge, a pole).

use geom_param::{Boundary, DPose3, FaceId, ParamSide, Solid, SurfacePoint};
use glam::{DMat3, DVec3};

/// `solid` under `pose`: world = R · local + t.
#[derive(Clone, Copy, Debug)]
pub(crate) struct PosedSolid<'a> {
    pub solid: &'a Solid,
    rotation: DMat3,
    translation: DVec3,
}

/// Which parameter a side constrains and the value it pins it to.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct SideParam {
    /// 0 for u, 1 for v.
    pub index: usize,
    /// The bound.
    pub value: f64,
    /// +1 when moving into the face increases the parameter (a min side), -1 otherwise.
    pub inward: f64,
}

impl<'a> PosedSolid<'a> {
    pub fn new(solid: &'a Solid, pose: &DPose3) -> Self {
        Self {
            solid,
            rotation: DMat3::from_quat(pose.rotation),
            translation: pose.translation,
        }
    }

    /// World-frame point and derivatives of `face` at (u, v) (periodic wrapped, others clamped).
    pub fn eval(&self, face: FaceId, u: f64, v: f64) -> SurfacePoint {
        let s = self.solid.eval_face(face, u, v);
        let r = self.rotation;
        SurfacePoint {
            point: r * s.point + self.translation,
            du: r * s.du,
            dv: r * s.dv,
            duu: r * s.duu,
            duv: r * s.duv,
            dvv: r * s.dvv,
        }
    }

    /// World-frame unit outward normal, `None` where the face has no tangent plane.
    pub fn normal(&self, face: FaceId, u: f64, v: f64) -> Option<DVec3> {
        let surface = &self.solid.face(face).surface;
        let [du, dv] = surface.domain();
        surface
            .normal(du.normalize(u), dv.normalize(v))
            .map(|n| self.rotation * n)
    }

    /// The (min, max, periodic) of parameter `index` of `face`.
    pub fn range(&self, face: FaceId, index: usize) -> geom_param::ParamRange {
        self.solid.face(face).surface.domain()[index]
    }

    /// Wraps periodic parameters and clamps the others into the face's domain.
    pub fn normalize(&self, face: FaceId, uv: [f64; 2]) -> [f64; 2] {
        let [du, dv] = self.solid.face(face).surface.domain();
        [du.normalize(uv[0]), dv.normalize(uv[1])]
    }

    /// The non-periodic sides of `face` that (u, v) lies on (within `eps` in parameter units).
    pub fn sides_at(&self, face: FaceId, uv: [f64; 2], eps: f64) -> Vec<ParamSide> {
        let domain = self.solid.face(face).surface.domain();
        let mut out = Vec::new();
        for (index, (lo, hi)) in [
            (ParamSide::UMin, ParamSide::UMax),
            (ParamSide::VMin, ParamSide::VMax),
        ]
        .into_iter()
        .enumerate()
        {
            let range = domain[index];
            if range.periodic {
                continue;
            }
            if uv[index] <= range.min + eps * range.span() {
                out.push(lo);
            } else if uv[index] >= range.max - eps * range.span() {
                out.push(hi);
            }
        }
        out
    }

    /// The parameter a side pins.
    pub fn side_param(&self, face: FaceId, side: ParamSide) -> SideParam {
        let [du, dv] = self.solid.face(face).surface.domain();
        match side {
            ParamSide::UMin => SideParam {
                index: 0,
                value: du.min,
                inward: 1.0,
            },
            ParamSide::UMax => SideParam {
                index: 0,
                value: du.max,
                inward: -1.0,
            },
            ParamSide::VMin => SideParam {
                index: 1,
                value: dv.min,
                inward: 1.0,
            },
            ParamSide::VMax => SideParam {
                index: 1,
                value: dv.max,
                inward: -1.0,
            },
        }
    }

    /// What lies across `side` of `face`.
    pub fn boundary(&self, face: FaceId, side: ParamSide) -> Boundary {
        self.solid.face(face).boundary(side)
    }

    /// The same point seen from the face across the edge on `side`: (neighbour face, its side,
    /// its parameters). The edge parameter equals the face parameter running along the side on
    /// both faces (geom-param's convention), so that parameter carries over unchanged.
    pub fn across(
        &self,
        face: FaceId,
        side: ParamSide,
        uv: [f64; 2],
    ) -> Option<(FaceId, ParamSide, [f64; 2])> {
        let Boundary::Edge(edge) = self.boundary(face, side) else {
            return None;
        };
        let uses = self.solid.edge(edge).uses;
        let (this, other) = if uses[0].face == face && uses[0].on.side() == Some(side) {
            (uses[0], uses[1])
        } else {
            (uses[1], uses[0])
        };
        // FIXME(general solids): an edge on a trimmed face is not crossed here yet.
        let other_side = other.on.side()?;
        let here = self.side_param(face, side);
        let there = self.side_param(other.face, other_side);
        // Running parameter here -> edge parameter -> running parameter there.
        let t = this.on.edge_param(uv[1 - here.index]);
        let mut out = [0.0; 2];
        out[there.index] = there.value;
        out[1 - there.index] = other.on.running(t);
        Some((other.face, other_side, self.normalize(other.face, out)))
    }
}
