//! Starting points: each seed point projected onto its exact feature along the normal (the
//! closest point on the feature, by the same safeguarded Newton with the other side fixed), as
//! in the paper's Stage 3.

use crate::features::feature_eval::{Body, Loc};
use crate::options::NewtonOptions;
use crate::solver::newton::{Reentry, Solution, minimize_projection};
use geom_param::DVec3;

/// The closest point to `target` (A's frame) on `body`'s feature near `start`, switching feature
/// where the projection leaves a face but never back into one (from an edge seed next to a face,
/// that would only be undone by the pair solve). `base_scale` as in
/// [`crate::solver::pair_solve::solve`].
pub(crate) fn project(
    body: &Body,
    start: Loc,
    target: DVec3,
    base_scale: f64,
    options: &NewtonOptions,
) -> Solution {
    minimize_projection(body, target, start, base_scale, options, Reentry::Never)
}
