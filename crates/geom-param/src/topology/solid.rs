//! The boundary representation of a solid: faces, edges and vertices with adjacency and outward
//! orientation, whatever surface and curve types they carry.
//!
//! A face is its surface over either the whole parameter rectangle of the surface's domain
//! (each side bounded by an edge, a collapsed vertex, or glued to the opposite side when the
//! parameter is periodic) or a trimmed region of it ([`Trim`]: an outer loop and holes, each a
//! cycle of edges with a p-curve on the face). Every edge lies on exactly two faces
//! ([`EdgeUse`]); the edge's own parameter t runs along both.

use crate::curves::curve::{Curve, CurvePoint, ParamRange};
use crate::curves::curve2::Curve2Point;
use crate::surfaces::surface::{Surface, SurfacePoint};
use crate::topology::feature::{EdgeId, FaceId, FeatureLocation, VertexId};
use crate::topology::pole_meridians::{PoleMeridians, pole_meridians};
use crate::topology::trim::Trim;
use glam::{DVec2, DVec3};
use std::sync::OnceLock;

/// One side of a face's parameter rectangle.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ParamSide {
    /// u = u_min.
    UMin,
    /// u = u_max.
    UMax,
    /// v = v_min.
    VMin,
    /// v = v_max.
    VMax,
}

impl ParamSide {
    /// The face parameters (u, v) of this side's point at running parameter `t` (v on a u
    /// side, u on a v side), with `domain` the face's surface domain.
    #[must_use]
    pub fn params_at(self, domain: &[ParamRange; 2], t: f64) -> [f64; 2] {
        match self {
            Self::UMin => [domain[0].min, t],
            Self::UMax => [domain[0].max, t],
            Self::VMin => [t, domain[1].min],
            Self::VMax => [t, domain[1].max],
        }
    }
}

/// What the face meets across one side of its parameter rectangle.
///
/// A trimmed face's sides are [`Boundary::Trimmed`] (its loops bound it instead), except that a
/// periodic parameter's sides stay [`Boundary::Periodic`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Boundary {
    /// The parameter is periodic: the side is glued to the opposite one.
    Periodic,
    /// An edge. The edge's parameter t equals the face parameter that runs along this side.
    Edge(EdgeId),
    /// The side collapses to a single point (a pole or apex).
    Vertex(VertexId),
    /// The side lies outside the face's trimmed region: the [`Trim`]'s loops bound the face.
    Trimmed,
}

/// Convexity of a face, from its principal curvatures with respect to the outward normal.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum FaceConvexity {
    /// Both principal curvatures >= 0 everywhere and not both identically 0.
    Convex,
    /// Both principal curvatures identically 0: a plane region.
    Flat,
    /// Some principal curvature < 0 somewhere (saddles included).
    Concave,
}

/// Convexity of an edge: the sign of the crease between its two faces.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum EdgeConvexity {
    /// The surface turns towards the material across the edge (a ridge).
    Convex,
    /// The surface turns away from the material across the edge (a valley).
    Concave,
    /// Tangent-continuous across the edge.
    Smooth,
}

/// A face: a surface patch over its parameter rectangle, or over a trimmed region of it.
#[derive(Debug)]
pub struct Face {
    /// The exact geometry, oriented so that ∂S/∂u × ∂S/∂v points out of the material.
    pub surface: Box<dyn Surface>,
    /// What lies beyond each side of the parameter rectangle, indexed by [`ParamSide`] order
    /// (u_min, u_max, v_min, v_max). [`Boundary::Trimmed`] on every non-periodic side of a
    /// trimmed face.
    pub boundary: [Boundary; 4],
    /// The trimmed region, or `None` when the face is the whole parameter rectangle.
    pub trim: Option<Trim>,
    /// Convex, flat or concave.
    pub convexity: FaceConvexity,
}

impl Face {
    /// What lies beyond `side`.
    #[must_use]
    pub fn boundary(&self, side: ParamSide) -> Boundary {
        self.boundary[side as usize]
    }
}

/// Where an edge runs on one of its faces.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EdgeOn {
    /// Along a side of the face's parameter rectangle: the edge's parameter t equals the face
    /// parameter that runs along the side (u on a v side, v on a u side).
    Side(ParamSide),
    /// Along a side of the face's parameter rectangle, running against the edge: the face
    /// parameter that runs along the side equals −t. Lets a builder join two rectangle faces
    /// whose running parameters grow in opposite directions along their common edge.
    SideReversed(ParamSide),
    /// On the face's trim: entry `index` of loop `loop_index` of [`Face::trim`], whose p-curve
    /// gives the face's (u, v) at each t of the edge.
    Trim {
        /// Loop of the face's trim (0 = outer).
        loop_index: u32,
        /// Position in that loop.
        index: u32,
    },
}

impl EdgeOn {
    /// The side of the parameter rectangle, for [`EdgeOn::Side`] and [`EdgeOn::SideReversed`].
    #[must_use]
    pub fn side(&self) -> Option<ParamSide> {
        match *self {
            Self::Side(side) | Self::SideReversed(side) => Some(side),
            Self::Trim { .. } => None,
        }
    }

    /// The running parameter along a side at edge parameter `t` (t or −t), or `t` itself for
    /// a trim entry.
    #[must_use]
    pub fn running(&self, t: f64) -> f64 {
        match self {
            Self::SideReversed(_) => -t,
            _ => t,
        }
    }

    /// The edge parameter where the running parameter along a side is `running` (the
    /// inverse of [`EdgeOn::running`]).
    #[must_use]
    pub fn edge_param(&self, running: f64) -> f64 {
        self.running(running)
    }
}

/// How an edge lies on one of its faces.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct EdgeUse {
    /// The face.
    pub face: FaceId,
    /// Where on the face the edge runs.
    pub on: EdgeOn,
}

/// An edge: a curve where two faces meet.
#[derive(Debug)]
pub struct Edge {
    /// The exact geometry.
    pub curve: Box<dyn Curve>,
    /// The two faces that meet here, with where the edge runs on each.
    pub uses: [EdgeUse; 2],
    /// The vertices at the start (t = t_min) and end (t = t_max) of a non-periodic curve;
    /// `None` for a closed (periodic) edge.
    pub ends: Option<[VertexId; 2]>,
    /// Ridge, valley or smooth.
    pub convexity: EdgeConvexity,
}

/// A vertex: an isolated point where a face collapses (a pole or apex) or edges meet.
#[derive(Debug)]
pub struct Vertex {
    /// Position in the object frame (mm).
    pub point: DVec3,
    /// The faces with a side collapsed into this vertex.
    pub faces: Vec<FaceId>,
    /// The edges ending here.
    pub edges: Vec<EdgeId>,
}

/// A closed, outward-oriented boundary representation.
#[derive(Debug, Default)]
pub struct Solid {
    /// Faces, indexed by [`FaceId`].
    pub faces: Vec<Face>,
    /// Edges, indexed by [`EdgeId`].
    pub edges: Vec<Edge>,
    /// Vertices, indexed by [`VertexId`].
    pub vertices: Vec<Vertex>,
    /// The model tolerance (mm): how far an edge may lie from its faces, a vertex from its
    /// edges' ends, and a p-curve's point from its edge's point. 0 is read as the default,
    /// [`Solid::DEFAULT_TOLERANCE`].
    pub tolerance: f64,
    /// The meridians of the face sides collapsed into vertices, computed at the first call of
    /// [`Solid::pole_meridians`] (so a solid must not be changed after it has been queried).
    pub(crate) pole_meridians: OnceLock<Vec<PoleMeridians>>,
}

impl Solid {
    /// A solid of these faces, edges and vertices, with model tolerance `tolerance` (mm, 0 for
    /// [`Solid::DEFAULT_TOLERANCE`]). Nothing is checked here: see [`crate::validate`].
    #[must_use]
    pub fn new(faces: Vec<Face>, edges: Vec<Edge>, vertices: Vec<Vertex>, tolerance: f64) -> Self {
        Self {
            faces,
            edges,
            vertices,
            tolerance,
            pole_meridians: OnceLock::new(),
        }
    }

    /// The meridians of the face sides that collapse into vertex `vertex` ([`PoleMeridians`]), each face
    /// side once; empty where none does. Computed for the whole solid at the first call, then
    /// read.
    pub fn pole_meridians(&self, vertex: VertexId) -> impl Iterator<Item = &PoleMeridians> + '_ {
        let all = self.pole_meridians.get_or_init(|| pole_meridians(self));
        let start = all.partition_point(|m| m.vertex < vertex);
        all[start..].iter().take_while(move |m| m.vertex == vertex)
    }

    /// The tolerance of a solid built in code (mm): edges meet their faces to rounding.
    pub const DEFAULT_TOLERANCE: f64 = 1e-7;

    /// The model tolerance (mm): [`Solid::tolerance`], or [`Solid::DEFAULT_TOLERANCE`] where it
    /// is 0.
    #[must_use]
    pub fn model_tolerance(&self) -> f64 {
        if self.tolerance > 0.0 {
            self.tolerance
        } else {
            Self::DEFAULT_TOLERANCE
        }
    }

    /// The face with this id.
    ///
    /// # Panics
    /// If the id does not belong to this solid.
    #[must_use]
    pub fn face(&self, id: FaceId) -> &Face {
        &self.faces[id.0 as usize]
    }

    /// The edge with this id.
    ///
    /// # Panics
    /// If the id does not belong to this solid.
    #[must_use]
    pub fn edge(&self, id: EdgeId) -> &Edge {
        &self.edges[id.0 as usize]
    }

    /// The vertex with this id.
    ///
    /// # Panics
    /// If the id does not belong to this solid.
    #[must_use]
    pub fn vertex(&self, id: VertexId) -> &Vertex {
        &self.vertices[id.0 as usize]
    }

    /// Evaluates a face at (u, v), wrapping periodic parameters and clamping others.
    #[must_use]
    pub fn eval_face(&self, id: FaceId, u: f64, v: f64) -> SurfacePoint {
        let surface = &self.face(id).surface;
        let [du, dv] = surface.domain();
        surface.eval(du.normalize(u), dv.normalize(v))
    }

    /// Evaluates an edge at t, wrapping a periodic parameter and clamping otherwise.
    #[must_use]
    pub fn eval_edge(&self, id: EdgeId, t: f64) -> CurvePoint {
        let curve = &self.edge(id).curve;
        curve.eval(curve.domain().normalize(t))
    }

    /// The point at a feature location, in the object frame.
    #[must_use]
    pub fn point_at(&self, location: &FeatureLocation) -> DVec3 {
        match *location {
            FeatureLocation::Face { id, u, v } => self.eval_face(id, u, v).point,
            FeatureLocation::Edge { id, t } => self.eval_edge(id, t).point,
            FeatureLocation::Vertex { id } => self.vertex(id).point,
        }
    }

    /// The unit outward normal at a face location, or `None` where the face has no tangent
    /// plane there (and for edges and vertices, whose normal is a cone, not a vector).
    #[must_use]
    pub fn face_normal_at(&self, location: &FeatureLocation) -> Option<DVec3> {
        match *location {
            FeatureLocation::Face { id, u, v } => {
                let surface = &self.face(id).surface;
                let [du, dv] = surface.domain();
                surface.normal(du.normalize(u), dv.normalize(v))
            }
            _ => None,
        }
    }
}

impl Solid {
    /// The p-curve point of edge use `use_` at edge parameter `t`: the face's (u, v) there and
    /// its first and second derivatives with respect to t. On a side, the running parameter is
    /// t and the other one the side's bound.
    ///
    /// # Panics
    /// If the use names a face, loop or entry that does not exist (a solid that
    /// [`Solid::validate`] accepts has none).
    #[must_use]
    pub fn use_eval(&self, use_: &EdgeUse, t: f64) -> Curve2Point {
        let face = self.face(use_.face);
        match use_.on {
            EdgeOn::Side(side) | EdgeOn::SideReversed(side) => {
                let domain = face.surface.domain();
                let r = use_.on.running(t);
                let point = match side {
                    ParamSide::UMin => DVec2::new(domain[0].min, r),
                    ParamSide::UMax => DVec2::new(domain[0].max, r),
                    ParamSide::VMin => DVec2::new(r, domain[1].min),
                    ParamSide::VMax => DVec2::new(r, domain[1].max),
                };
                let along = match side {
                    ParamSide::UMin | ParamSide::UMax => DVec2::Y,
                    ParamSide::VMin | ParamSide::VMax => DVec2::X,
                };
                let d1 = use_.on.running(1.0) * along;
                Curve2Point {
                    point,
                    d1,
                    d2: DVec2::ZERO,
                }
            }
            EdgeOn::Trim { loop_index, index } => {
                let trim = face.trim.as_ref().expect("a trim use names a trimmed face");
                trim.loops[loop_index as usize].entries[index as usize]
                    .pcurve
                    .eval(t)
            }
        }
    }

    /// The face parameters where edge use `use_` is at edge parameter `t`.
    ///
    /// # Panics
    /// As [`Solid::use_eval`].
    #[must_use]
    pub fn use_params(&self, use_: &EdgeUse, t: f64) -> [f64; 2] {
        let p = self.use_eval(use_, t).point;
        [p.x, p.y]
    }

    /// The direction in the face's (u, v) plane that points from edge use `use_` at `t` into
    /// the face (perpendicular to the p-curve, not normalised): the left of the boundary's
    /// traversal direction, which keeps the face on its left (outer loops counter-clockwise,
    /// holes clockwise, rectangle sides alike).
    ///
    /// # Panics
    /// As [`Solid::use_eval`].
    #[must_use]
    pub fn use_inward(&self, use_: &EdgeUse, t: f64) -> DVec2 {
        match use_.on {
            EdgeOn::Side(side) | EdgeOn::SideReversed(side) => match side {
                ParamSide::UMin => DVec2::X,
                ParamSide::UMax => DVec2::NEG_X,
                ParamSide::VMin => DVec2::Y,
                ParamSide::VMax => DVec2::NEG_Y,
            },
            EdgeOn::Trim { loop_index, index } => {
                let face = self.face(use_.face);
                let trim = face.trim.as_ref().expect("a trim use names a trimmed face");
                let entry = &trim.loops[loop_index as usize].entries[index as usize];
                let d1 = entry.pcurve.eval(t).d1;
                let along = if entry.reversed { -d1 } else { d1 };
                along.perp()
            }
        }
    }

    /// The edges on face `id`'s boundary: every edge with a use on it, ascending.
    #[must_use]
    pub fn face_edges(&self, id: FaceId) -> Vec<EdgeId> {
        let mut out: Vec<EdgeId> = (0..self.edges.len())
            .filter(|&e| self.edges[e].uses.iter().any(|u| u.face == id))
            .map(|e| EdgeId(u32::try_from(e).expect("fewer than 2^32 edges")))
            .collect();
        out.dedup();
        out
    }

    /// Whether the feature at `location` lies on face `id`: the face itself, an edge with a
    /// use on it, or one of its vertices ([`Self::face_vertices`]).
    #[must_use]
    pub fn face_holds(&self, id: FaceId, location: &FeatureLocation) -> bool {
        match *location {
            FeatureLocation::Face { id: face, .. } => face == id,
            FeatureLocation::Edge { id: edge, .. } => {
                self.edge(edge).uses.iter().any(|u| u.face == id)
            }
            FeatureLocation::Vertex { id: vertex } => self.face_vertices(id).contains(&vertex),
        }
    }

    /// Whether the boundary point at `location` lies on a face that holds `own`
    /// ([`Self::face_holds`]): on such a face, on an edge of one, or at a vertex of one. The
    /// faces beside an edge or a vertex are its flanks, which pass near any point in its cone
    /// of normals.
    #[must_use]
    pub fn beside(&self, location: &FeatureLocation, own: &FeatureLocation) -> bool {
        let holds = |face: FaceId| self.face_holds(face, own);
        match *location {
            FeatureLocation::Face { id, .. } => holds(id),
            FeatureLocation::Edge { id, .. } => self.edge(id).uses.iter().any(|u| holds(u.face)),
            FeatureLocation::Vertex { id } => (0..self.faces.len()).any(|f| {
                let face = FaceId(u32::try_from(f).expect("fewer than 2^32 faces"));
                self.face_vertices(face).contains(&id) && holds(face)
            }),
        }
    }

    /// The vertices of face `id`: the ends of its edges and the vertices its sides collapse
    /// into, ascending.
    #[must_use]
    pub fn face_vertices(&self, id: FaceId) -> Vec<VertexId> {
        let mut out: Vec<VertexId> = self
            .face(id)
            .boundary
            .iter()
            .filter_map(|b| match b {
                Boundary::Vertex(v) => Some(*v),
                _ => None,
            })
            .collect();
        for e in self.face_edges(id) {
            if let Some(ends) = self.edge(e).ends {
                out.extend(ends);
            }
        }
        out.sort_unstable();
        out.dedup();
        out
    }
}
