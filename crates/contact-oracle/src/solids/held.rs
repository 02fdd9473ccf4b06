//! Where one point of a polished pair lies: free on its face, held on an edge, or at a vertex.
//!
//! A pair always names a face and (u, v) for each point (what the report gives); a point held
//! on an edge or at a vertex is evaluated on that feature's own geometry instead (the edge's
//! curve at t, the vertex's position), and its face and (u, v) are one of the edge's uses at t
//! (or, at a vertex, the use of an edge ending there).

use geom_param::{EdgeId, FaceId, FeatureLocation, VertexId};

/// The feature a point of a pair is on.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Held {
    /// On its face at the pair's (u, v), inside the face's region (rectangle or trim).
    Face,
    /// On `edge` at curve parameter `t`; the pair's face is the edge's use `use_index`.
    Edge {
        edge: EdgeId,
        t: f64,
        use_index: usize,
    },
    /// At a vertex.
    Vertex(VertexId),
}

impl Held {
    /// Which of the point's two parameter slots exist: (u, v) on a face, t (first slot) on an
    /// edge, none at a vertex.
    pub fn dims(self) -> [bool; 2] {
        match self {
            Self::Face => [true, true],
            Self::Edge { .. } => [true, false],
            Self::Vertex(_) => [false, false],
        }
    }

    /// The exact feature location, with `face` and `uv` for a point free on its face.
    pub fn location(self, face: FaceId, uv: [f64; 2]) -> FeatureLocation {
        match self {
            Self::Face => FeatureLocation::Face {
                id: face,
                u: uv[0],
                v: uv[1],
            },
            Self::Edge { edge, t, .. } => FeatureLocation::Edge { id: edge, t },
            Self::Vertex(id) => FeatureLocation::Vertex { id },
        }
    }
}
