//! Independent ground truth for contacts between two exact solids (the oracle the report and
//! the soak tests compare the pipeline with).
//!
//! Independence is the point: the oracle uses only geom-param's exact
//! [`Solid`](geom_param::Solid) (faces' `Surface::eval` and domains, trims, edges' curves and
//! uses, vertices, adjacency) and glam; no stage crate, no component meshes or hulls. Any B-rep:
//! faces over their whole parameter rectangle (solids of revolution) or trimmed by loops of
//! edges, edges closed or ending at vertices. The solids as the oracle evaluates them are in
//! `solids/`. Method:
//!
//! 1. Sample every face on a (u, v) grid with world spacing about [`OracleOptions::spacing`]
//!    (boundary rows included), only near the other solid's bounding box
//!    (`samples::sampling`). A trimmed face is gridded over its trim's box and keeps the
//!    samples inside the trim (a grid of cells classified once answers away from the boundary,
//!    `solids::trim_grid`; near it the exact p-curves decide, a corner by its sector); the
//!    edges that run along no rectangle side are sampled on their own curves, their end
//!    vertices (corners) included.
//! 2. For each sample the nearest sample of the other solid (own kd-tree, `samples::kdtree`);
//!    samples whose nearest distance is a discrete local minimum among their own face's
//!    samples within 1.5 spacings are candidates, from both sides (`minima::local_minima`).
//! 3. Each candidate is polished by Levenberg–Marquardt on f = ½|S_a − S_b|² over
//!    (u_a, v_a, u_b, v_b) with bounds as active constraints, crossing edges and turning at
//!    poles (`polishing::polish`). On a trimmed face the bound is the trim: a step that leaves
//!    it stops on the crossed edge, where the point is held with the edge's t as its
//!    parameter; from an edge the polish moves into a face with descent, onto the end vertex
//!    when descent runs past the end, and from a vertex along an edge or into a face with
//!    descent (`polishing::feature_moves`). A minimum is accepted when stationary over the
//!    parameters of the features it is on (3-d residual), second-order (reduced Hessian PSD
//!    over them) and not descending into a neighbouring face, edge or vertex (at an edge or
//!    corner: the connecting vector in the normal cone). Near touching, points involving a
//!    trimmed face, an edge or a vertex are first pinned by the descent of step 4 (from either
//!    side).
//! 4. Penetration: the deepest inside sample of each overlap region, and every crossing the
//!    minimum search met, start a descent of A's signed distance to B; its minimum is the
//!    witness, polished by plain Newton on ∇f = 0; from both sides (`minima::penetration`). A
//!    witness must have one point inside the other solid with the other point as its nearest
//!    boundary point (samples and projections onto the exact faces; beyond the sampled band,
//!    no sample of either solid nearer); otherwise it is a depth through the material and is
//!    dropped (a separated minimum only where its segment passes behind that nearer part,
//!    `minima::found::separated_through_material`). The descent moves over trims, edges and
//!    vertices as the polish does (not across the sides of a face without trim onto an edge
//!    shared with another such face), so a witness may lie inside a trimmed face, on an edge
//!    or at a corner.
//! 5. Regions (`minima::regions`): an accepted point joined to a lower one by a path along an
//!    edge or straight on a face holding both points of one side, along which the signed
//!    distance of the walking point to the other solid never exceeds the higher one's by more
//!    than 5 x tolerance, is no separate minimum: it is listed as a member of the lower one's
//!    region ([`OracleReport::members`]), which is reported once. This is what makes a
//!    continuous contact (flat on flat) one answer, and what removes points the polish
//!    accepted on the slope beside a touch (its residual test is absolute, so at |r| ~ 1e-7 mm
//!    any slope passes). Each reported point carries the oracle's own error bound from the
//!    conditioning of its pair (`polishing::conditioning`,
//!    [`OracleContact::point_error_estimate`]).
//! 6. The whole search runs again at spacing / √2 on a shifted grid and the two sets are
//!    compared ([`CrossCheck`]).
//!
//! Frames: everything reported is in the world frame, lengths in mm.
//!
//! Definitions the search enforces: a minimum is accepted only where the undamped Newton step
//! is short (not merely the damped one: next to a shallow crossing the residual is small while
//! f drops to zero a Newton step away); a minimum is dropped when either point has a nearer
//! sample of the other solid than the pair's distance (a distance measured through a wall,
//! past a nearer part of the surface), a separated one only when its segment passes behind
//! that nearer part (a part beside the segment, not across it, leaves the minimum standing);
//! a witness whose Newton polish leaves the descent's depth (an apex
//! polished onto the crossing curve) is kept at the descent's own pair; two coinciding points
//! are a touch (a contact at distance 0), not a crossing, when some direction lies in A's
//! normal cone with its opposite in B's (a face's cone is its normal, an edge's the wedge of
//! its faces' normals, a corner's the cone its edges allow).
//!
//! Known limits: two minima closer than about 1.5 spacings can merge into one; a penetration
//! witness on an edge between two faces without trims (the ridges of solids of revolution)
//! is not reported (an apex is: it is a pole of its face); nor is one where an edge of each
//! solid pokes into the other (two ridges crossing: either edge's signed distance to the other
//! solid has a kink, not a stationary point, at its deepest); a touch at distance 0 between a
//! vertex and an edge or vertex counts as a crossing; the cones of edges and corners are
//! read from the adjacent faces' tangent directions (at a corner from its edges), exact for
//! convex edges and corners whose faces are less than 180° apart; a non-isolated minimum (a
//! circle or segment of equal distance) is one region whose points are an arbitrary set on it,
//! and minima on different faces of both solids are never joined into one region.

// Index loops mirror the matrix notation of the small dense systems (H_ij, g_k).
#![allow(clippy::needless_range_loop)]

pub mod closed_form;
mod cross_check;
mod error;
mod minima;
mod options;
mod oracle;
mod polishing;
mod report;
mod samples;
mod solids;

pub use closed_form::{ClosedFormScene, ExpectedContact};
pub use error::OracleError;
pub use options::OracleOptions;
pub use oracle::{SAMPLE_BUDGET, find_contacts};
pub use report::{CrossCheck, OracleContact, OracleReport, OracleState, RegionMember};
