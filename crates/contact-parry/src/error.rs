//! Why an [`crate::ExactShape`] could not be built.

use geom_param::ModelError;

/// Why an [`crate::ExactShape`] could not be built from a prepared object.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ShapeError {
    /// The object has no mesh triangles (nothing to bound, weigh or ray-cast).
    #[error("object `{name}` has no mesh triangles")]
    EmptyMesh {
        /// The object's name.
        name: String,
    },
    /// The component meshes, welded at equal vertex positions, do not form a closed,
    /// consistently oriented surface: the directed edge `from -> to` (welded vertex indices) is
    /// not matched by exactly one reverse edge, so no volume (and no inside) is defined.
    #[error("object `{name}`: the welded mesh is not closed at edge {from} -> {to}")]
    NotClosed {
        /// The object's name.
        name: String,
        /// Start vertex of the unmatched directed edge.
        from: u32,
        /// End vertex of the unmatched directed edge.
        to: u32,
    },
    /// The welded mesh encloses no positive volume (mm³): inward-oriented or degenerate.
    #[error("object `{name}`: the welded mesh encloses volume {volume} mm^3, not > 0")]
    NotOutward {
        /// The object's name.
        name: String,
        /// The signed volume found (mm³).
        volume: f64,
    },
    /// Parry refused the welded mesh.
    #[error("object `{name}`: parry refused the mesh: {reason}")]
    Parry {
        /// The object's name.
        name: String,
        /// Parry's message.
        reason: String,
    },
    /// A primitive (a ball's sphere, a cuboid's box) could not be built as an exact solid.
    #[error("cannot build the exact solid of a parry {kind}: {reason}")]
    Primitive {
        /// "ball" or "cuboid".
        kind: &'static str,
        /// What the builder said.
        reason: String,
    },
    /// An exact model could not be meshed.
    #[error(transparent)]
    Model(#[from] ModelError),
}
