//! A solid placed in the world frame: face, edge and vertex evaluation with the pose applied
//! to the point and every derivative, the faces' regions (rectangle or trim), and the
//! adjacency moves the polishers need (crossing an edge, a pole).

use crate::solids::held::Held;
use crate::solids::trim_grid::TrimGrid;
use geom_param::{
    Boundary, CurvePoint, DPose3, EdgeId, EdgeUse, FaceId, FeatureLocation, ParamSide, Solid,
    SurfacePoint, Trim, VertexId,
};
use glam::{DMat3, DVec2, DVec3};

/// A (u, v) within this fraction of its trim's extent of the trim's boundary counts as inside
/// (rounding of the p-curves' nearest points).
pub(crate) const TRIM_TOLERANCE: f64 = 1e-12;

/// `solid` under `pose`: world = R · local + t.
#[derive(Clone, Debug)]
pub(crate) struct PosedSolid<'a> {
    pub solid: &'a Solid,
    rotation: DMat3,
    translation: DVec3,
    /// Per face, its trim's containment grid (`None` without trim).
    grids: Vec<Option<TrimGrid>>,
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

/// Normals averaged around an apex ([`PosedSolid::apex_outward`]).
const APEX_RING: usize = 16;

impl<'a> PosedSolid<'a> {
    pub fn new(solid: &'a Solid, pose: &DPose3) -> Self {
        let grids = solid
            .faces
            .iter()
            .map(|f| f.trim.as_ref().map(TrimGrid::new))
            .collect();
        Self {
            solid,
            rotation: DMat3::from_quat(pose.rotation),
            translation: pose.translation,
            grids,
        }
    }

    /// The largest extent of `face`'s trim box in (u, v) (0 for a face without trim).
    pub fn trim_extent(&self, face: FaceId) -> f64 {
        self.grids[face.0 as usize]
            .as_ref()
            .map_or(0.0, |g| g.extent)
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

    /// World-frame point and derivatives of `edge` at t (periodic wrapped, others clamped).
    pub fn eval_edge(&self, edge: EdgeId, t: f64) -> CurvePoint {
        let c = self.solid.eval_edge(edge, t);
        CurvePoint {
            point: self.rotation * c.point + self.translation,
            d1: self.rotation * c.d1,
            d2: self.rotation * c.d2,
        }
    }

    /// World-frame position of a vertex.
    pub fn vertex_point(&self, vertex: VertexId) -> DVec3 {
        self.rotation * self.solid.vertex(vertex).point + self.translation
    }

    /// The point held as `held` (face `face` at `uv` when free on it) as a surface point:
    /// on an edge, ∂/∂u is the curve's d/dt and ∂/∂v vanishes; at a vertex every derivative
    /// vanishes. Parameters that do not exist are thereby frozen (see [`Held::dims`]).
    pub fn eval_held(&self, face: FaceId, uv: [f64; 2], held: Held) -> SurfacePoint {
        match held {
            Held::Face => self.eval(face, uv[0], uv[1]),
            Held::Edge { edge, t, .. } => {
                let c = self.eval_edge(edge, t);
                SurfacePoint {
                    point: c.point,
                    du: c.d1,
                    dv: DVec3::ZERO,
                    duu: c.d2,
                    duv: DVec3::ZERO,
                    dvv: DVec3::ZERO,
                }
            }
            Held::Vertex(v) => SurfacePoint {
                point: self.vertex_point(v),
                du: DVec3::ZERO,
                dv: DVec3::ZERO,
                duu: DVec3::ZERO,
                duv: DVec3::ZERO,
                dvv: DVec3::ZERO,
            },
        }
    }

    /// The trim of `face`, `None` when the face is its whole parameter rectangle.
    pub fn trim(&self, face: FaceId) -> Option<&'a Trim> {
        self.solid.face(face).trim.as_ref()
    }

    /// Whether (u, v) lies in `face`'s region: inside its trim (the boundary included to
    /// [`TRIM_TOLERANCE`]); a face without trim is its whole rectangle, which
    /// [`PosedSolid::normalize`] keeps every point in.
    pub fn inside(&self, face: FaceId, uv: [f64; 2]) -> bool {
        let tolerance = TRIM_TOLERANCE * self.trim_extent(face);
        self.contains(face, uv, tolerance)
    }

    /// Whether (u, v) lies in `face`'s trimmed region, the boundary included within
    /// `tolerance` (parameter units); always for a face without trim.
    pub fn contains(&self, face: FaceId, uv: [f64; 2], tolerance: f64) -> bool {
        match (self.trim(face), &self.grids[face.0 as usize]) {
            (Some(trim), Some(grid)) => grid.contains(trim, DVec2::from(uv), tolerance),
            _ => true,
        }
    }

    /// Whether (u, v) lies in `face`'s region away from its trim's boundary (farther than
    /// 1e-9 of the trim's extent); for a face without trim, whether (u, v) is on no side of
    /// the rectangle other than a pole or apex (a smooth point of the surface).
    pub fn interior(&self, face: FaceId, uv: [f64; 2]) -> bool {
        match self.trim(face) {
            Some(trim) => {
                let p = DVec2::from(uv);
                self.contains(face, uv, 0.0)
                    && trim
                        .nearest(p)
                        .is_some_and(|n| n.distance > 1e-9 * self.trim_extent(face))
            }
            None => self
                .sides_at(face, uv, 0.0)
                .into_iter()
                .all(|side| matches!(self.boundary(face, side), Boundary::Vertex(_))),
        }
    }

    /// The use of `edge` on `face` (the first one when both uses are on it).
    pub fn use_on(&self, edge: EdgeId, face: FaceId) -> usize {
        let uses = self.solid.edge(edge).uses;
        usize::from(uses[0].face != face && uses[1].face == face)
    }

    /// Face parameters of edge use `use_` at t, wrapped or clamped into the face's domain.
    pub fn use_params(&self, use_: &EdgeUse, t: f64) -> [f64; 2] {
        self.normalize(use_.face, self.solid.use_params(use_, t))
    }

    /// The unit world-frame direction from edge use `use_` at t into its face (tangent to
    /// the face, across the edge), `None` where the face's parametrisation is singular.
    pub fn inward(&self, use_: &EdgeUse, t: f64) -> Option<DVec3> {
        let [u, v] = self.use_params(use_, t);
        let d = self.solid.use_inward(use_, t);
        let s = self.eval(use_.face, u, v);
        (s.du * d.x + s.dv * d.y).try_normalize()
    }

    /// The unit directions along which the edges ending at `vertex` leave it.
    pub fn edges_leaving(&self, vertex: VertexId) -> Vec<(EdgeId, f64, DVec3)> {
        let mut out = Vec::new();
        for &edge in &self.solid.vertex(vertex).edges {
            let Some(ends) = self.solid.edge(edge).ends else {
                continue;
            };
            let range = self.solid.edge(edge).curve.domain();
            for (end, t, sign) in [(ends[0], range.min, 1.0), (ends[1], range.max, -1.0)] {
                if end != vertex {
                    continue;
                }
                if let Some(d) = (self.eval_edge(edge, t).d1 * sign).try_normalize() {
                    out.push((edge, t, d));
                }
            }
        }
        out
    }

    /// A unit outward direction that tells outside from inside at a held point: the face's
    /// normal on a face; the normalised sum of the adjacent faces' normals at an edge or
    /// vertex (its scalar product with any direction of the normal cone of a convex edge or
    /// corner whose faces are less than 180° apart is positive, and negative for the opposite
    /// of one). At an apex (a point of a collapsed side where the face has no normal) it is
    /// the mean of the face's normals around the apex ([`Self::apex_outward`]), the axis of a
    /// cone's tip.
    pub fn sign_normal(&self, face: FaceId, uv: [f64; 2], held: Held) -> Option<DVec3> {
        match held {
            Held::Face => self
                .normal(face, uv[0], uv[1])
                .or_else(|| self.apex_outward(face, uv)),
            Held::Edge { edge, t, .. } => {
                let mut sum = DVec3::ZERO;
                for use_ in &self.solid.edge(edge).uses {
                    let [u, v] = self.use_params(use_, t);
                    sum += self.normal(use_.face, u, v).unwrap_or(DVec3::ZERO);
                }
                sum.try_normalize()
            }
            Held::Vertex(vertex) => {
                let mut sum = DVec3::ZERO;
                let mut seen: Vec<FaceId> = Vec::new();
                for (edge, t, _) in self.edges_leaving(vertex) {
                    for use_ in &self.solid.edge(edge).uses {
                        if seen.contains(&use_.face) {
                            continue;
                        }
                        seen.push(use_.face);
                        let [u, v] = self.use_params(use_, t);
                        sum += self.normal(use_.face, u, v).unwrap_or(DVec3::ZERO);
                    }
                }
                sum.try_normalize().or_else(|| self.apex_outward(face, uv))
            }
        }
    }

    /// The mean outward normal around an apex at (u, v) of `face`: the face's normals at
    /// [`APEX_RING`] points of the running parameter, a 1e-6 fraction of the pinned
    /// parameter's span inside the collapsed side; `None` off a collapsed side or where the
    /// mean vanishes.
    fn apex_outward(&self, face: FaceId, uv: [f64; 2]) -> Option<DVec3> {
        let side = self
            .sides_at(face, uv, 0.0)
            .into_iter()
            .find(|&side| matches!(self.boundary(face, side), Boundary::Vertex(_)))?;
        let pinned = self.side_param(face, side);
        let running = self.range(face, 1 - pinned.index);
        let inside = pinned.value + pinned.inward * 1e-6 * self.range(face, pinned.index).span();
        let mut sum = DVec3::ZERO;
        for k in 0..APEX_RING {
            let mut at = [0.0; 2];
            at[pinned.index] = inside;
            at[1 - pinned.index] =
                running.min + (k as f64 + 0.5) / APEX_RING as f64 * running.span();
            sum += self.normal(face, at[0], at[1]).unwrap_or(DVec3::ZERO);
        }
        sum.try_normalize()
    }

    /// The exact feature a point is on: the held edge or vertex; for a point free on a face
    /// without trim, the edge along the rectangle side it lies on (t = the side's running
    /// parameter), the common end of two such edges at a corner, or an apex vertex (a
    /// collapsed side where the face has no normal; a pole is a smooth point of the face);
    /// otherwise the face. A point within `snap` (mm) of its trimmed face's boundary is on
    /// the boundary's edge, and a point on an edge within `snap` of an end on that vertex.
    pub fn location(&self, face: FaceId, uv: [f64; 2], held: Held, snap: f64) -> FeatureLocation {
        let point = self.eval_held(face, uv, held).point;
        let mut held = held;
        if let (Held::Face, Some(trim)) = (held, self.trim(face)) {
            if let Some(n) = trim.nearest(DVec2::from(uv)) {
                let edge = trim.loops[n.loop_index].entries[n.index].edge;
                if self.eval_edge(edge, n.t).point.distance(point) <= snap {
                    held = Held::Edge {
                        edge,
                        t: n.t,
                        use_index: self.use_on(edge, face),
                    };
                }
            }
        }
        if let Held::Edge { edge, .. } = held {
            for v in self.solid.edge(edge).ends.into_iter().flatten() {
                if self.vertex_point(v).distance(point) <= snap {
                    return FeatureLocation::Vertex { id: v };
                }
            }
        }
        if held != Held::Face || self.trim(face).is_some() {
            return held.location(face, uv);
        }
        let mut edges = Vec::new();
        for side in self.sides_at(face, uv, 0.0) {
            match self.boundary(face, side) {
                Boundary::Edge(_) => {
                    if let Some(Held::Edge { edge, t, .. }) = self.edge_on_side(face, side, uv) {
                        edges.push((edge, t));
                    }
                }
                Boundary::Vertex(id) if self.normal(face, uv[0], uv[1]).is_none() => {
                    return FeatureLocation::Vertex { id };
                }
                _ => {}
            }
        }
        match edges[..] {
            [(id, t)] => FeatureLocation::Edge { id, t },
            [(e0, _), (e1, _)] => {
                let ends = |e: EdgeId| self.solid.edge(e).ends.map(Vec::from).unwrap_or_default();
                match ends(e0).into_iter().find(|v| ends(e1).contains(v)) {
                    Some(id) => FeatureLocation::Vertex { id },
                    None => held.location(face, uv),
                }
            }
            _ => held.location(face, uv),
        }
    }

    /// The point (u, v) of a face without trim taken on the edge along `side` (t from the
    /// running parameter through the side's use, [`geom_param::EdgeOn::edge_param`]), if an edge bounds
    /// that side.
    pub fn edge_on_side(&self, face: FaceId, side: ParamSide, uv: [f64; 2]) -> Option<Held> {
        let Boundary::Edge(edge) = self.boundary(face, side) else {
            return None;
        };
        let uses = self.solid.edge(edge).uses;
        let use_index = uses
            .iter()
            .position(|u| u.face == face && u.on.side() == Some(side))?;
        let running = uv[1 - self.side_param(face, side).index];
        Some(Held::Edge {
            edge,
            t: uses[use_index].on.edge_param(running),
            use_index,
        })
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

    /// The same point seen from the face across the edge on `side`: (neighbour face, its
    /// parameters, the (u, v) direction into it). The edge parameter t is the face parameter
    /// running along the side, or its negative ([`geom_param::EdgeOn::edge_param`]); the neighbour's
    /// parameters are its use's p-curve (or side) at that t, and the direction its use's
    /// inward one.
    pub fn across(
        &self,
        face: FaceId,
        side: ParamSide,
        uv: [f64; 2],
    ) -> Option<(FaceId, [f64; 2], DVec2)> {
        let Boundary::Edge(edge) = self.boundary(face, side) else {
            return None;
        };
        let uses = self.solid.edge(edge).uses;
        let (this, other) = if uses[0].face == face && uses[0].on.side() == Some(side) {
            (uses[0], uses[1])
        } else {
            (uses[1], uses[0])
        };
        let here = self.side_param(face, side);
        // Running parameter here -> edge parameter.
        let t = this.on.edge_param(uv[1 - here.index]);
        Some((
            other.face,
            self.use_params(&other, t),
            self.solid.use_inward(&other, t),
        ))
    }
}
