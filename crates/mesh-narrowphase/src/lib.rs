//! Stage 2 of the paper (mesh phase): for each pair of surface components that Stage 1 found
//! close, decide from their polygonal meshes whether they are separated, penetrating or in
//! contact, and for each contact hand Stage 3 a seed: approximately closest points on both
//! meshes with the exact features and parameters they correspond to.
//!
//! - Convex pairs: GJK between the components' convex hulls ([`convex_pair`]) with a support
//!   map that hill-climbs over the hull's vertex adjacency and warm-starts from the last frame
//!   ([`hill_climb_support`]).
//! - Pairs with a concave component (and convex pairs whose hulls overlap, since a hull is not
//!   its surface): exact triangle-triangle tests ([`triangle_intersection`]) over a simultaneous
//!   traversal of triangle trees ([`triangle_bvh`]), first mesh against mesh (penetration), then
//!   an outward-offset proxy mesh ([`proxy_mesh`]) against the other mesh; the colliding
//!   triangles are grouped into connected regions whose intersection loops give the centres
//!   p_ci ([`collision_regions`]), projected onto both meshes into seeds ([`seeds`]).
//!
//! The boundary is the [`MeshPhase`] trait ([`mesh_phase`]); [`MeshNarrowphase`] is its default
//! implementation ([`default_phase`]).
//!
//! What this crate deliberately does not know: how component pairs were found (Stage 1), how
//! seeds are refined into exact closest points and what contact means for them (Stage 3), and
//! how the surfaces are parametrised beyond the meshes' per-vertex and per-triangle
//! correspondences in `geom-param`. It depends on no other stage crate.

pub mod collision_regions;
pub mod convex_pair;
pub mod default_phase;
pub mod hill_climb_support;
pub mod mesh_phase;
pub mod plane_filter;
pub mod prepared_object;
pub mod proxy_mesh;
pub mod seeds;
pub mod triangle_bvh;
pub mod triangle_intersection;

pub use default_phase::{MeshNarrowphase, MeshNarrowphaseOptions, MeshScratch};
pub use mesh_phase::{
    ComponentRef, ContactBand, MeshInputError, MeshOutput, MeshPhase, MeshStats, MeshVerdict,
    RegionProbes,
};
pub use prepared_object::PreparedObject;
