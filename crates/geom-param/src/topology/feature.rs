//! Feature identities and points located on exact features.

/// Index of a face in its [`crate::Solid`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct FaceId(pub u32);

/// Index of an edge in its [`crate::Solid`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct EdgeId(pub u32);

/// Index of a vertex in its [`crate::Solid`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct VertexId(pub u32);

/// Index of a surface component in its [`crate::ObjectModel`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct ComponentId(pub u32);

/// Which exact feature something lies on, without parameters.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum FeatureId {
    /// A face (two parameters).
    Face(FaceId),
    /// An edge (one parameter).
    Edge(EdgeId),
    /// A vertex (no parameter).
    Vertex(VertexId),
}

/// A point on an exact feature, given by the feature and its parameters.
///
/// Face parameters are the (u, v) of the face's [`crate::Surface`]; an edge parameter is the t of
/// its [`crate::Curve`]. Periodic parameters may be given outside their domain and are wrapped by
/// whoever evaluates them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FeatureLocation {
    /// On face `id` at (u, v).
    Face {
        /// The face.
        id: FaceId,
        /// First parameter.
        u: f64,
        /// Second parameter.
        v: f64,
    },
    /// On edge `id` at t.
    Edge {
        /// The edge.
        id: EdgeId,
        /// Curve parameter.
        t: f64,
    },
    /// At vertex `id`.
    Vertex {
        /// The vertex.
        id: VertexId,
    },
}

impl FeatureLocation {
    /// The feature this location is on.
    #[must_use]
    pub fn feature(&self) -> FeatureId {
        match *self {
            Self::Face { id, .. } => FeatureId::Face(id),
            Self::Edge { id, .. } => FeatureId::Edge(id),
            Self::Vertex { id } => FeatureId::Vertex(id),
        }
    }

    /// The parameters as a slice-like list: `[u, v]`, `[t]` or `[]`.
    #[must_use]
    pub fn params(&self) -> Vec<f64> {
        match *self {
            Self::Face { u, v, .. } => vec![u, v],
            Self::Edge { t, .. } => vec![t],
            Self::Vertex { .. } => Vec::new(),
        }
    }
}
