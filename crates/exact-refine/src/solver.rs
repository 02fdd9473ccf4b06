//! Solving one pair of features: projection of the seed points, the safeguarded Newton
//! minimisation of ½|P_a − P_b|², the nested solver for penetration witnesses, the probe that
//! tells a touch from a small-angle crossing, and the pair solve that runs them in turn.

pub(crate) mod crossing_probe;
pub(crate) mod newton;
pub(crate) mod pair_solve;
pub(crate) mod penetration;
pub(crate) mod projection;
