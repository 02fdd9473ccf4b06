//! The boundary representation of a solid: faces, edges and vertices with adjacency and outward
//! orientation, whatever surface and curve types they carry.

use crate::curves::curve::{Curve, CurvePoint};
use crate::surfaces::surface::{Surface, SurfacePoint};
use crate::topology::feature::{EdgeId, FaceId, FeatureLocation, VertexId};
use glam::DVec3;

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

/// What the face meets across one side of its parameter rectangle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Boundary {
    /// The parameter is periodic: the side is glued to the opposite one.
    Periodic,
    /// An edge. The edge's parameter t equals the face parameter that runs along this side.
    Edge(EdgeId),
    /// The side collapses to a single point (a pole or apex).
    Vertex(VertexId),
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

/// A face: a surface patch over a parameter rectangle.
#[derive(Debug)]
pub struct Face {
    /// The exact geometry, oriented so that ∂S/∂u × ∂S/∂v points out of the material.
    pub surface: Box<dyn Surface>,
    /// What lies beyond each side of the parameter rectangle, indexed by [`ParamSide`] order
    /// (u_min, u_max, v_min, v_max).
    pub boundary: [Boundary; 4],
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

/// How an edge lies on one of its faces.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct EdgeUse {
    /// The face.
    pub face: FaceId,
    /// The side of the face's parameter rectangle the edge runs along.
    pub side: ParamSide,
}

/// An edge: a curve where two faces meet.
#[derive(Debug)]
pub struct Edge {
    /// The exact geometry.
    pub curve: Box<dyn Curve>,
    /// The two faces that meet here, with the side of each one the edge runs along.
    pub uses: [EdgeUse; 2],
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
}

impl Solid {
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
