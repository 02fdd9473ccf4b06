//! Rational B-spline (NURBS) numerics shared by curves and surfaces, after Piegl & Tiller,
//! *The NURBS Book* (2nd ed., 1997): knot spans and basis derivatives (A2.1, A2.3), curve and
//! surface derivatives on the homogeneous control net (A3.2, A3.6) with their rational
//! quotients (A4.2, A4.4), and the exact circle and swept surfaces (A7.1, A8.1).
//!
//! Evaluation allocates nothing: every scratch array is sized by [`MAX_DEGREE`].

pub(crate) mod basis;
pub(crate) mod circle_arc;
pub(crate) mod control_point;
pub(crate) mod curve_derivatives;
pub(crate) mod extrusion;
pub(crate) mod rational_bspline_curve;
pub(crate) mod revolution;
pub(crate) mod surface_derivatives;

/// The highest B-spline degree accepted (constructors reject higher degrees with
/// [`crate::GeometryError::BadDegree`]); it sizes the stack scratch of every evaluation.
pub const MAX_DEGREE: usize = 9;

/// Scratch length for one span's basis functions: degree + 1.
pub(crate) const MAX_ORDER: usize = MAX_DEGREE + 1;

/// Binomial coefficients C(k, i) for k, i <= 2 (the derivative orders evaluated).
pub(crate) const BINOMIAL: [[f64; 3]; 3] = [[1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [1.0, 2.0, 1.0]];

/// Relative gap (to the control net's extent) within which the two ends of a NURBS flagged
/// periodic count as the same point.
pub(crate) const CLOSURE_RELATIVE_TOL: f64 = 1e-9;
