//! Independent ground truth for contacts between two exact solids (the oracle the report and
//! the soak tests compare the pipeline with).
//!
//! Independence is the point: the oracle uses only geom-param's exact [`Solid`](geom_param::Solid) (faces'
//! `Surface::eval` and domains, edge/vertex adjacency) and glam; no stage crate, no component
//! meshes or hulls. Method:
//!
//! 1. Sample every face on a (u, v) grid with world spacing about [`OracleOptions::spacing`]
//!    (boundary rows included), only near the other solid's bounding box (`sampling`).
//! 2. For each sample the nearest sample of the other solid (own kd-tree); samples whose
//!    nearest distance is a discrete local minimum within 1.5 spacings are candidates, from
//!    both sides (`local_minima`).
//! 3. Each candidate is polished by Levenberg–Marquardt on f = ½|S_a − S_b|² over
//!    (u_a, v_a, u_b, v_b) with bounds as active constraints, crossing edges and turning at
//!    poles, and accepted when stationary (3-d residual), second-order (reduced Hessian PSD)
//!    and not descending into a neighbouring face (`polish`).
//! 4. Penetration: the deepest inside sample of each overlap region, and every crossing the
//!    minimum search met, start a descent of A's signed distance to B; its minimum is the
//!    witness, polished by plain Newton on ∇f = 0; from both sides (`penetration`).
//! 5. The whole search runs again at spacing / √2 on a shifted grid and the two sets are
//!    compared ([`CrossCheck`]).
//!
//! Frames: everything reported is in the world frame, lengths in mm.
//!
//! Definitions the search enforces: a minimum is accepted only where the undamped Newton step
//! is short (not merely the damped one: next to a shallow crossing the residual is small while
//! f drops to zero a Newton step away); a minimum is dropped when either point has a nearer
//! sample of the other solid than the pair's distance (a distance measured through a wall,
//! past a nearer part of the surface); a witness whose Newton polish leaves the descent's depth (an apex
//! polished onto the crossing curve) is kept at the descent's own pair.
//!
//! Known limits: two minima closer than about 1.5 spacings can merge into one; a penetration
//! witness on an edge of A (or B, from B's side) is not reported (an apex is: it is a pole of
//! its face); a non-isolated minimum (a circle or segment of equal distance) yields an
//! arbitrary set of points on it.

// Index loops mirror the matrix notation of the small dense systems (H_ij, g_k).
#![allow(clippy::needless_range_loop)]

pub mod closed_form;
mod cross_check;
mod error;
mod found;
mod kdtree;
mod linalg;
mod local_minima;
mod options;
mod oracle;
mod penetration;
mod polish;
mod posed;
mod report;
mod sampling;

pub use closed_form::{ClosedFormScene, ExpectedContact};
pub use error::OracleError;
pub use options::OracleOptions;
pub use oracle::{SAMPLE_BUDGET, find_contacts};
pub use report::{CrossCheck, OracleContact, OracleReport, OracleState};
