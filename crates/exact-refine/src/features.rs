//! Features as the solver sees them: a face, edge or vertex of a solid (or a fixed point)
//! evaluated uniformly in A's frame, and the switches between them that keep parameters in
//! their domains (wrapping, onto a bounding edge or vertex, back into an adjacent face).

pub(crate) mod feature_eval;
pub(crate) mod feature_switch;
