//! Why a surface, curve, placement or B-spline could not be built from its inputs.

/// A construction input that does not describe a valid surface or curve. Every constructor of
/// the analytic and NURBS geometry returns this instead of panicking or producing NaN later.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum GeometryError {
    /// A coordinate, radius, angle, knot, weight or range bound is NaN or infinite.
    #[error("{what} is not a finite number")]
    NonFinite {
        /// The offending input.
        what: &'static str,
    },
    /// A radius (or an ellipse's semi-axis) that must be positive is zero or negative.
    #[error("{what} is {value} mm but must be > 0")]
    NonPositiveRadius {
        /// The offending input.
        what: &'static str,
        /// Its value (mm).
        value: f64,
    },
    /// A cone's radius at v = 0 is negative (0 is allowed: the placement is at the apex).
    #[error("the cone radius at v = 0 is {radius} mm but must be >= 0")]
    NegativeRadius {
        /// The offending radius (mm).
        radius: f64,
    },
    /// A torus whose major radius does not exceed its minor radius (not a ring torus).
    #[error("torus major radius {major} mm must exceed its minor radius {minor} mm")]
    NotRingTorus {
        /// Major radius R (mm).
        major: f64,
        /// Minor radius r (mm).
        minor: f64,
    },
    /// A cone semi-angle outside the open interval (0, π/2).
    #[error("cone semi-angle {angle} rad is outside (0, π/2)")]
    BadSemiAngle {
        /// The offending angle (rad).
        angle: f64,
    },
    /// A placement whose axis or reference direction is zero, or whose two directions are
    /// parallel, so no orthonormal frame follows.
    #[error("degenerate placement: {reason}")]
    DegeneratePlacement {
        /// What is degenerate.
        reason: &'static str,
    },
    /// A direction vector (line, extrusion, axis of revolution) that is zero.
    #[error("{what} is the zero vector")]
    ZeroDirection {
        /// The offending input.
        what: &'static str,
    },
    /// A B-spline degree of 0 or above [`crate::MAX_DEGREE`].
    #[error("B-spline degree {degree} is outside 1..={max}")]
    BadDegree {
        /// The offending degree.
        degree: usize,
        /// [`crate::MAX_DEGREE`].
        max: usize,
    },
    /// Fewer control points than degree + 1 in one direction.
    #[error("{count} control points are too few for degree {degree} (need at least degree + 1)")]
    TooFewControlPoints {
        /// Number of control points in that direction.
        count: usize,
        /// The degree in that direction.
        degree: usize,
    },
    /// A knot vector whose length is not control count + degree + 1.
    #[error("knot vector has {found} knots; degree and control count require {expected}")]
    KnotCount {
        /// control count + degree + 1.
        expected: usize,
        /// The length given.
        found: usize,
    },
    /// A knot smaller than the one before it.
    #[error("knot {index} ({knot}) is smaller than the knot before it")]
    DecreasingKnots {
        /// Index of the offending knot.
        index: usize,
        /// Its value.
        knot: f64,
    },
    /// A knot repeated more than degree + 1 times at an end, or more than degree times inside
    /// the domain (the curve would break apart there).
    #[error("knot {knot} has multiplicity {multiplicity}, above the allowed {max}")]
    KnotMultiplicity {
        /// The repeated knot value.
        knot: f64,
        /// How many times it occurs.
        multiplicity: usize,
        /// The largest multiplicity allowed at that place.
        max: usize,
    },
    /// A NURBS weight that is zero or negative.
    #[error("weight {index} is {weight} but must be > 0")]
    NonPositiveWeight {
        /// Index of the weight (row-major for surfaces).
        index: usize,
        /// Its value.
        weight: f64,
    },
    /// A control net that is not rectangular, or weights that do not match the control points
    /// one to one.
    #[error("{what}: expected {expected} entries, found {found}")]
    CountMismatch {
        /// Which list is off.
        what: &'static str,
        /// The count required.
        expected: usize,
        /// The count given.
        found: usize,
    },
    /// A parameter range (or a B-spline's knot domain) with min >= max.
    #[error("parameter range [{min}, {max}] is empty or reversed")]
    EmptyRange {
        /// Its lower end.
        min: f64,
        /// Its upper end.
        max: f64,
    },
    /// A range flagged periodic that is not exactly one period long, a range longer than one
    /// period, or a periodic flag on a parameter that does not wrap.
    #[error(
        "parameter range [{min}, {max}] flagged periodic = {periodic} does not fit period {period:?}"
    )]
    BadPeriod {
        /// Its lower end.
        min: f64,
        /// Its upper end.
        max: f64,
        /// The flag given.
        periodic: bool,
        /// The parameter's period, `None` when it does not wrap.
        period: Option<f64>,
    },
    /// A range that leaves the surface's valid parameters (a sphere's v beyond ±π/2, a cone's v
    /// beyond its apex).
    #[error("parameter range [{min}, {max}] leaves the valid interval [{lower}, {upper}]")]
    RangeOutsideSurface {
        /// Its lower end.
        min: f64,
        /// Its upper end.
        max: f64,
        /// Smallest valid parameter.
        lower: f64,
        /// Largest valid parameter.
        upper: f64,
    },
    /// A NURBS flagged periodic whose two ends (first and last control rows or columns, in
    /// homogeneous coordinates) do not coincide.
    #[error("NURBS flagged periodic does not close: its ends are {gap:e} apart")]
    NotClosed {
        /// Largest distance between matching end points (mm, homogeneous).
        gap: f64,
    },
}
