//! Exact parametric model of general curved solids (paper section III).
//!
//! - Exact features: [`Surface`] (faces), [`Curve`] (edges) and vertices, assembled into a
//!   [`Solid`] with adjacency and outward orientation. Nothing in these traits assumes
//!   revolution.
//! - Solids of revolution built from a [`Profile`] of [`ProfileSegment`]s (lines, circular arcs,
//!   cubic Beziers in the (r, z) half-plane), read from the object file format by
//!   [`ObjectDescription`] (feature `json`).
//! - Surface components ([`SurfaceComponent`], convex or concave, found from the curvature) and
//!   their dual representation: a [`ComponentMesh`] whose vertices know their exact
//!   [`FeatureLocation`], plus a [`ConvexHull`] for convex components. All of it is built once in
//!   [`ObjectModel::from_profile`].
//! - [`Seed`]: the vocabulary Stage 2 hands to Stage 3.
//!
//! Units: millimetres and radians; frames: the object's own frame (its axis of revolution is z).
//!
//! # Cargo features
//! - `json` (off by default): [`ObjectDescription::from_json`] and
//!   [`ObjectDescription::to_json`] via serde_json.

mod circle_edge;
mod component_mesh;
mod components;
mod convex_hull;
mod convexity;
mod curve;
mod feature;
mod object_description;
mod object_model;
mod profile;
mod profile_error;
mod profile_segment;
mod revolve;
mod revolved_surface;
mod seed;
mod solid;
mod surface;
mod tessellation;

pub use circle_edge::CircleEdge;
pub use component_mesh::ComponentMesh;
pub use components::{ComponentKind, SurfaceComponent};
pub use convex_hull::ConvexHull;
pub use convexity::{classify_joint, classify_revolved_face};
pub use curve::{Curve, CurvePoint, ParamRange};
pub use feature::{ComponentId, EdgeId, FaceId, FeatureId, FeatureLocation, VertexId};
pub use object_description::{LoadError, ObjectDescription};
pub use object_model::{MIN_RELATIVE_TOLERANCE, MeshOptions, ModelError, ObjectModel};
pub use profile::{Closure, Profile, SegmentSpec};
pub use profile_error::ProfileError;
pub use profile_segment::{ArcSegment, CubicBezier, LineSegment, ProfilePoint, ProfileSegment};
pub use revolved_surface::RevolvedSurface;
pub use seed::{Seed, SeedPoint};
pub use solid::{
    Boundary, Edge, EdgeConvexity, EdgeUse, Face, FaceConvexity, ParamSide, Solid, Vertex,
};
pub use surface::{PrincipalCurvatures, Surface, SurfacePoint};

pub use glam::{DQuat, DVec2, DVec3};
/// A rigid motion (rotation + translation) in f64: parry's (glamx's) `DPose3`.
pub use parry3d_f64::math::Pose as DPose3;
