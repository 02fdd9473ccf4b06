//! Inputs the oracle refuses.

/// Why [`crate::find_contacts`] could not run. Every variant is an input problem; the oracle
/// does not fail on geometry it was able to sample.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum OracleError {
    /// A pose has a non-finite rotation or translation, or a rotation far from unit length.
    #[error("pose of solid {which} is not a finite rigid motion")]
    BadPose {
        /// "a" or "b".
        which: &'static str,
    },
    /// Spacing or tolerance not finite and positive, or reach not finite and non-negative.
    #[error("unusable options: spacing {spacing} mm, reach {reach} mm, tolerance {tolerance} mm")]
    BadOptions {
        /// Requested sample spacing (mm).
        spacing: f64,
        /// Requested reach (mm).
        reach: f64,
        /// Requested tolerance (mm).
        tolerance: f64,
    },
    /// A solid has no faces, or a face whose geometry evaluates to non-finite values.
    #[error("solid {which} has no usable faces")]
    BadSolid {
        /// "a" or "b".
        which: &'static str,
    },
    /// Sampling at this spacing would exceed the sample budget (memory and time bound).
    #[error("spacing {spacing} mm needs about {needed} samples, more than the budget of {budget}")]
    TooManySamples {
        /// Requested sample spacing (mm).
        spacing: f64,
        /// Estimated number of samples needed.
        needed: usize,
        /// The cap ([`crate::SAMPLE_BUDGET`]).
        budget: usize,
    },
}
