//! Tolerances and caps of the Newton refinement.

/// Tolerances and caps of [`crate::NewtonRefiner`], with documented defaults.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NewtonOptions {
    /// Stop when, for every parameter, the component of the connecting vector P_a - P_b along
    /// the feature's unit tangent is at most `angle_tolerance` x |P_a - P_b| plus the rounding
    /// floor 16 ε x (coordinate scale): the connecting vector is then parallel to each normal
    /// to this sine. Default 1e-13 (Newton converges quadratically, so the last step takes the
    /// residual from ~1e-7 to rounding; a looser value only saves that step).
    pub angle_tolerance: f64,
    /// Cap on Newton steps per solve (the seed projections and the pair solve each have their
    /// own). Default 64: well-seeded solves take 2-6, flat (near-conformal) ones up to ~40. A
    /// pair solve that reaches the cap continues once from where it stopped (at an exact touch
    /// Newton converges only linearly), so it takes at most twice this many steps before it
    /// reports [`crate::RefineStatus::IterationLimit`].
    pub max_iterations: u32,
    /// Cap on feature switches (face to edge or vertex and back) per solve, so a minimum that
    /// sits on a crease cannot make the iteration bounce for ever. Default 8.
    pub max_feature_switches: u32,
}

impl Default for NewtonOptions {
    fn default() -> Self {
        Self {
            angle_tolerance: 1e-13,
            max_iterations: 64,
            max_feature_switches: 8,
        }
    }
}
