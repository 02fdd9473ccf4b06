//! Why a baseline mesh or query could not be built.

use parry3d_f64::shape::TriMeshBuilderError;

/// Errors of [`crate::BaselineMesh::new`] and [`crate::MeshOnlyBaseline::contacts`].
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum BaselineError {
    /// The requested triangle count is below what the solid's topology needs (3 vertices per
    /// ring, 2 strips between two poles) or above [`crate::BaselineMesh::MAX_TRIANGLES`].
    #[error("target of {target} triangles is outside [{minimum}, {maximum}] for this solid")]
    BadTarget {
        /// The requested count.
        target: usize,
        /// The fewest triangles this solid can be meshed with.
        minimum: usize,
        /// The most triangles a baseline mesh may have.
        maximum: usize,
    },
    /// A face whose parametrisation the tessellator does not handle: it needs u periodic
    /// (glued to itself) and both v sides on an edge whose parameter runs over the face's u
    /// domain, or on a vertex.
    #[error("face {face} is not supported: {reason}")]
    UnsupportedFace {
        /// Index of the face in the solid.
        face: u32,
        /// What is not supported.
        reason: &'static str,
    },
    /// The solid has no faces, or a face of zero extent.
    #[error("the solid has no faces or a face of zero extent")]
    EmptySolid,
    /// A triangle of (near) zero area: the solid has a degenerate edge or face.
    #[error("triangle {triangle} has zero area")]
    DegenerateTriangle {
        /// Index of the triangle.
        triangle: usize,
    },
    /// The mesh is not closed with consistent orientation: a directed edge is used by no
    /// triangle in reverse or by more than one triangle.
    #[error("mesh edge ({0}, {1}) is not shared by exactly two consistently oriented triangles")]
    NotClosed(u32, u32),
    /// The signed volume of the mesh is not positive: its triangles face inwards.
    #[error("mesh signed volume {volume} mm^3 is not positive (inward faces)")]
    NotOutward {
        /// The signed volume (mm³).
        volume: f64,
    },
    /// parry refused the mesh.
    #[error("parry refused the mesh: {0}")]
    Parry(#[from] TriMeshBuilderError),
    /// parry accepted the mesh but did not compute the pseudo-normals that the
    /// `ORIENTED | FIX_INTERNAL_EDGES` flags ask for.
    #[error("parry did not compute the mesh's pseudo-normals")]
    NoPseudoNormals,
    /// The object description could not be built into a solid.
    #[error("object could not be built: {0}")]
    Load(#[from] geom_param::LoadError),
    /// A pose with a non-finite component or a rotation quaternion whose norm is off 1 by more
    /// than 1e-6.
    #[error("pose of object {object} is not a rigid motion")]
    BadPose {
        /// "a" or "b".
        object: &'static str,
    },
    /// The prediction distance is negative or not finite.
    #[error("prediction {0} mm is not a finite non-negative distance")]
    BadPrediction(f64),
    /// parry's dispatcher does not support the shape pair (never for two triangle meshes).
    #[error("parry does not support this shape pair")]
    Unsupported,
}
