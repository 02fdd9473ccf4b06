//! Exact parametric model of general curved solids (paper section III).
//!
//! - Exact features: [`Surface`] (faces), [`Curve`] (edges) and vertices, assembled into a
//!   [`Solid`] with adjacency and outward orientation. Nothing in these traits assumes
//!   revolution.
//! - Geometry for general solids, parametrised as STEP and OpenCASCADE do: analytic surfaces in
//!   a [`Placement`] ([`Plane`], [`CylinderSurface`], [`ConeSurface`], [`SphereSurface`],
//!   [`TorusSurface`]), swept surfaces ([`LinearExtrusionSurface`], [`RevolutionSurface`]),
//!   [`NurbsSurface`] and [`ReversedSurface`]; curves [`LineCurve`], [`CircleCurve`],
//!   [`EllipseCurve`], [`NurbsCurve`] and the p-curve [`NurbsCurve2`]. Constructors validate
//!   their input and return a [`GeometryError`]; evaluation allocates nothing (B-spline degrees
//!   up to [`MAX_DEGREE`]).
//! - Solids of revolution built from a [`Profile`] of [`ProfileSegment`]s (lines, circular arcs,
//!   cubic Beziers in the (r, z) half-plane), read from the object file format by
//!   [`ObjectDescription`] (feature `json`).
//! - Surface components ([`SurfaceComponent`], convex or concave, found from the curvature) and
//!   their dual representation: a [`ComponentMesh`] whose vertices know their exact
//!   [`FeatureLocation`], plus a [`ConvexHull`] for convex components. All of it is built once in
//!   [`ObjectModel::from_profile`] (solids of revolution) or [`ObjectModel::from_solid`]
//!   (general B-rep solids with trimmed faces).
//! - [`Seed`]: the vocabulary Stage 2 hands to Stage 3.
//!
//! Units: millimetres and radians; frames: the object's own frame (its axis of revolution is z).
//!
//! # Cargo features
//! - `json` (off by default): [`ObjectDescription::from_json`] and
//!   [`ObjectDescription::to_json`] via serde_json.
//! - `step` (off by default): [`step::read_step`] reads the solids of a STEP file
//!   (ISO 10303-21, AP203/AP214/AP242 B-rep geometry) into validated [`Solid`]s.

mod builders;
mod curves;
mod geometry_checks;
mod geometry_error;
mod io;
mod nurbs;
mod object_model;
mod revolution;
mod seed;
mod surfaces;
mod tessellation;
mod topology;

pub use builders::build_error::BuildError;
pub use builders::extrusion::{PlanarProfile, PlanarSegment, extrude};
pub use builders::loft::{EllipseSection, loft};
pub use builders::rounded_box::rounded_box;
pub use builders::sew::sew_rectangles;
pub use builders::tube::tube;
pub use curves::circle_curve::CircleCurve;
pub use curves::circle_edge::CircleEdge;
pub use curves::curve::{Curve, CurvePoint, ParamRange};
pub use curves::curve2::{Circle2, Curve2, Curve2Point, Line2};
pub use curves::ellipse_curve::EllipseCurve;
pub use curves::iso_curve::IsoCurve;
pub use curves::line_curve::LineCurve;
pub use curves::nurbs_curve::NurbsCurve;
pub use curves::nurbs_curve2::NurbsCurve2;
pub use geometry_error::GeometryError;
pub use io::object_description::{LoadError, ObjectDescription};
pub use io::object_file::{ObjectFile, ObjectFileError};
#[cfg(feature = "step")]
pub use io::solid_description::StepSolidRef;
pub use io::solid_description::{SolidDescription, SolidLoadError, SolidSpec};
pub use nurbs::MAX_DEGREE;
pub use nurbs::basis::{BSplineBasis, BasisDerivatives};
pub use nurbs::control_point::ControlPoint;
pub use nurbs::rational_bspline_curve::RationalBSplineCurve;
pub use object_model::{MIN_RELATIVE_TOLERANCE, MeshOptions, ModelError, ObjectModel};
pub use revolution::profile::{Closure, Profile, SegmentSpec};
pub use revolution::profile_error::ProfileError;
pub use revolution::profile_segment::{
    ArcSegment, CubicBezier, LineSegment, ProfilePoint, ProfileSegment,
};
pub use seed::{Seed, SeedPoint};
pub use surfaces::cone_surface::ConeSurface;
pub use surfaces::cylinder_surface::CylinderSurface;
pub use surfaces::linear_extrusion_surface::LinearExtrusionSurface;
pub use surfaces::nurbs_surface::NurbsSurface;
pub use surfaces::placement::Placement;
pub use surfaces::plane::Plane;
pub use surfaces::reversed_surface::ReversedSurface;
pub use surfaces::revolution_surface::RevolutionSurface;
pub use surfaces::revolved_surface::RevolvedSurface;
pub use surfaces::sphere_surface::SphereSurface;
pub use surfaces::surface::{PrincipalCurvatures, Surface, SurfacePoint};
pub use surfaces::torus_surface::TorusSurface;
pub use tessellation::component_mesh::ComponentMesh;
pub use tessellation::convex_hull::ConvexHull;
pub use topology::components::{ComponentKind, SurfaceComponent};
pub use topology::convexity::{
    classify_convexity, classify_edge, classify_face, classify_joint, classify_revolved_face,
};
pub use topology::feature::{ComponentId, EdgeId, FaceId, FeatureId, FeatureLocation, VertexId};
pub use topology::pole_meridians::{POLE_MERIDIANS, PoleMeridians, meridian_tangent};
pub use topology::solid::{
    Boundary, Edge, EdgeConvexity, EdgeOn, EdgeUse, Face, FaceConvexity, ParamSide, Solid, Vertex,
};
pub use topology::trim::{Trim, TrimEntry, TrimLoop, TrimNearest};
pub use topology::validate::{TopologyError, validate};

#[cfg(feature = "step")]
pub use io::step;

pub use glam::{DQuat, DVec2, DVec3};
/// A rigid motion (rotation + translation) in f64: parry's (glamx's) `DPose3`.
pub use parry3d_f64::math::Pose as DPose3;
