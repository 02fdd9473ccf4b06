//! Polishing a pair of points into an exact critical pair: the pair itself, Levenberg–Marquardt
//! and plain Newton on ½|S_a − S_b|², the moves between faces, edges and vertices where a step
//! leaves a trim or an edge ends, the tiny dense systems they solve, and the error bound from
//! the conditioning of a polished pair.

pub(crate) mod conditioning;
pub(crate) mod feature_moves;
pub(crate) mod linalg;
pub(crate) mod pair;
pub(crate) mod polish;
