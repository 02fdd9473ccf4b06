//! Stage 3 of the paper (section II): exact distance computation between the exact parametric
//! features that Stage 2 found closest.
//!
//! A [`Refiner`] takes a [`geom_param::Seed`] (approximately closest points on two features, one
//! on each solid) and returns the exact closest pair of those features as a [`RefinedContact`]:
//! both points, the signed distance, the normal, the final features with their parameters, and
//! [`RefineDiagnostics`] saying how far to trust all of it.
//!
//! [`NewtonRefiner`] is the default: it starts at the seed's feature locations (whose parameters
//! Stage 2 interpolates from the mesh vertices' exact correspondences: the paper's projection onto
//! the exact features, to within the mesh's chordal error; a seed point whose parameters are not
//! finite is projected onto its feature along the normal), then runs a safeguarded Newton iteration
//! on ½|P_a − P_b|² over the parameters of both features, for every pair kind (vertex, edge and
//! face on either side): trust region, inertia-controlled steps (descent when separated, the depth
//! saddle when penetrating), Newton steps on the distance itself where f is quartic (near touch,
//! and after a stationary end while they predict a fall above the gradient's rounding floor: f's
//! gradient |d| ∇|d| sinks under it at a touch first), periodic wrapping, feature switching at face
//! sides and poles, and non-convergence and degenerate (continuous) contact reported as values. A
//! solve allocates nothing; from a Stage 2 seed it takes 2-4 Newton steps. `docs/STABILITY.md` at
//! the workspace root tabulates the stiff and extreme cases, and `benches/refine.rs` times every
//! pair kind.
//!
//! What it deliberately does not know: meshes, hulls, bounding volumes and components (that is
//! Stages 1 and 2), which seed to refine or whether two objects are in contact (the pipeline
//! decides that from the signed distance), and surfaces of revolution: it only uses the
//! `Surface`/`Curve` traits and the `Solid` adjacency of `geom-param`.
//!
//! A penetration witness is a critical pair of two features; whether one of its points lies
//! inside the other solid with the other point as its nearest boundary point (and the pair is
//! not measured through the material) needs the rest of both boundaries:
//! [`Refiner::check_witness`] takes a [`NearestBoundary`] query per object (the pipeline passes
//! Stage 2's meshes and the exact solids) and measures each point's distance to the other
//! boundary (`checks/witness_check.rs`).
//!
//! Where the code is: the boundary ([`Refiner`] in `refiner.rs`, its results in
//! `refined_contact.rs`) and [`NewtonRefiner`] (`newton_refiner.rs`) at the top; `solver/`
//! solves one pair (seed projection, safeguarded Newton, the penetration witness, the crossing
//! probe, and the pair solve that runs them), over `features/` (evaluation of faces, edges and
//! vertices, and switching between them) and `linalg/` (the small symmetric Hessians);
//! `checks/` judges a finished solve (diagnostics, the witness's nearest-boundary test).
//!
//! Units: millimetres and radians. Frames: results in A's object frame.

mod checks;
mod features;
mod linalg;
mod newton_refiner;
mod options;
mod refined_contact;
mod refiner;
mod solver;

pub use checks::witness_check::{
    BoundaryDistance, NearestBoundary, WitnessCheck, WitnessSide, check_witness,
};
pub use newton_refiner::NewtonRefiner;
pub use options::NewtonOptions;
pub use refined_contact::{RefineDiagnostics, RefineStatus, RefinedContact};
pub use refiner::Refiner;
