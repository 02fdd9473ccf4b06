//! Stage 2 of the paper (mesh phase): for each pair of surface components that Stage 1 found
//! close, decide from their polygonal meshes whether they are separated, penetrating or in
//! contact, and for each contact hand Stage 3 a seed: approximately closest points on both
//! meshes with the exact features and parameters they correspond to.
//!
//! - Convex pairs: GJK between the components' convex hulls ([`convex::convex_pair`]) with a
//!   support map that hill-climbs over the hull's vertex adjacency and warm-starts from the last
//!   frame ([`convex::hill_climb_support`]).
//! - Pairs with a concave component (and convex pairs whose hulls overlap, since a hull is not its
//!   surface), by default: a hierarchy of exact surface patches per component
//!   ([`cones::patch_tree`]: mesh pieces with deviation bounds, normal cones and bands
//!   ([`cones::normal_cone`]), curvature tensors), traversed pairwise ([`cones::cone_traversal`])
//!   with the band as a distance cutoff and normal cones ruling out critical pairs of the distance;
//!   pairs certified to hold one minimum at most are seeded from second-order models, the leaf
//!   pairs left from their closest points ([`triangles::triangle_distance`]), and overlapping
//!   leaves get exact triangle tests ([`triangles::triangle_intersection`]). Each component pair's
//!   traversal front is kept for the next query ([`cones::cone_front`]).
//! - The paper's proxy-mesh path, selectable ([`ConcavePath::ProxyRegions`]): exact
//!   triangle-triangle tests over a simultaneous traversal of triangle trees
//!   ([`triangles::triangle_bvh`]), first mesh against mesh (penetration), then an outward-offset
//!   proxy mesh ([`proxy::proxy_mesh`]) against the other mesh; the colliding triangles are grouped
//!   into connected regions whose intersection loops give the centres p_ci
//!   ([`triangles::collision_regions`]), projected onto both meshes into seeds ([`seeds`]).
//!
//! The boundary is the [`MeshPhase`] trait ([`mesh_phase`]); [`MeshNarrowphase`] is its default
//! implementation ([`default_phase`]), whose [`MeshNarrowphaseOptions::concave_path`] selects
//! the triangle path.
//!
//! What this crate deliberately does not know: how component pairs were found (Stage 1), how
//! seeds are refined into exact closest points and what contact means for them (Stage 3), and
//! how the surfaces are parametrised beyond the meshes' per-vertex and per-triangle
//! correspondences in `geom-param`. It depends on no other stage crate.

pub mod cones;
pub mod convex;
pub mod default_phase;
pub mod mesh_phase;
pub mod nearest_boundary;
mod pair_key;
pub mod prepared_object;
pub mod proxy;
mod query_side;
pub mod seeds;
pub mod triangles;

pub use default_phase::{ConcavePath, MeshNarrowphase, MeshNarrowphaseOptions, MeshScratch};
pub use mesh_phase::{
    ComponentRef, ContactBand, MeshBoundaryPoint, MeshInputError, MeshOutput, MeshPhase, MeshStats,
    MeshVerdict, RegionProbes,
};
pub use prepared_object::PreparedObject;
