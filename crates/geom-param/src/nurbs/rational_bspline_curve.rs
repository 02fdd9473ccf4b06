//! A rational B-spline (NURBS) curve over any control point space: the numerics behind
//! [`crate::NurbsCurve`] (3D) and [`crate::NurbsCurve2`] (p-curves).

use crate::curves::curve::ParamRange;
use crate::geometry_error::GeometryError;
use crate::nurbs::CLOSURE_RELATIVE_TOL;
use crate::nurbs::basis::BSplineBasis;
use crate::nurbs::control_point::{ControlPoint, net_extent};
use crate::nurbs::curve_derivatives::rational_curve_derivatives;

/// C(t) = Σ_i N_{i,p}(t) w_i P_i / Σ_i N_{i,p}(t) w_i for t in the basis domain [u_p, u_{n+1}]:
/// degree p <= [`crate::MAX_DEGREE`], knots with multiplicities (clamped or not), weights > 0.
///
/// Periodic means the curve closes (C(u_p) = C(u_{n+1}) within 1e-9 of the control polygon's
/// extent) and its parameter wraps; derivatives at the seam are those of the start. Outside
/// the domain a parameter is wrapped (periodic) or clamped, so evaluation never extrapolates.
#[derive(Clone, Debug, PartialEq)]
pub struct RationalBSplineCurve<P: ControlPoint> {
    basis: BSplineBasis,
    control_points: Vec<P>,
    weights: Vec<f64>,
    periodic: bool,
}

impl<P: ControlPoint> RationalBSplineCurve<P> {
    /// The curve of degree `degree` over `knots` with `control_points` P_i and `weights` w_i
    /// (one per point), closed and wrapping when `periodic`.
    ///
    /// # Errors
    /// [`GeometryError::CountMismatch`] when weights and points differ in number, every error
    /// of [`BSplineBasis::new`], [`GeometryError::NonFinite`] for a point or weight,
    /// [`GeometryError::NonPositiveWeight`], and [`GeometryError::NotClosed`] for a periodic
    /// curve whose ends differ.
    pub fn new(
        degree: usize,
        knots: Vec<f64>,
        control_points: Vec<P>,
        weights: Vec<f64>,
        periodic: bool,
    ) -> Result<Self, GeometryError> {
        if weights.len() != control_points.len() {
            return Err(GeometryError::CountMismatch {
                what: "weights (one per control point)",
                expected: control_points.len(),
                found: weights.len(),
            });
        }
        let basis = BSplineBasis::new(degree, knots, control_points.len())?;
        check_points_and_weights(&control_points, &weights)?;
        let curve = Self {
            basis,
            control_points,
            weights,
            periodic,
        };
        if periodic {
            let (start, end) = curve.basis.domain();
            let gap = (curve.derivatives_in_domain(end)[0] - curve.derivatives_in_domain(start)[0])
                .norm();
            if gap > CLOSURE_RELATIVE_TOL * net_extent(&curve.control_points) {
                return Err(GeometryError::NotClosed { gap });
            }
        }
        Ok(curve)
    }

    /// The knot vector and degree.
    #[must_use]
    pub fn basis(&self) -> &BSplineBasis {
        &self.basis
    }

    /// The control points P_i.
    #[must_use]
    pub fn control_points(&self) -> &[P] {
        &self.control_points
    }

    /// The weights w_i (> 0).
    #[must_use]
    pub fn weights(&self) -> &[f64] {
        &self.weights
    }

    /// Whether the curve closes and its parameter wraps.
    #[must_use]
    pub fn is_periodic(&self) -> bool {
        self.periodic
    }

    /// The domain [u_p, u_{n+1}] with the periodic flag.
    #[must_use]
    pub fn param_range(&self) -> ParamRange {
        let (min, max) = self.basis.domain();
        ParamRange {
            min,
            max,
            periodic: self.periodic,
        }
    }

    /// [C(t), C'(t), C''(t)] exactly (A2.1, A2.3, A3.2, A4.2), t wrapped or clamped into the
    /// domain first. No allocation.
    #[must_use]
    pub fn derivatives(&self, t: f64) -> [P; 3] {
        self.derivatives_in_domain(self.param_range().normalize(t))
    }

    fn derivatives_in_domain(&self, t: f64) -> [P; 3] {
        rational_curve_derivatives(&self.basis, &self.control_points, &self.weights, t)
    }
}

/// Every point finite, every weight finite and > 0 (weights indexed as given, row-major for a
/// net).
pub(crate) fn check_points_and_weights<P: ControlPoint>(
    points: &[P],
    weights: &[f64],
) -> Result<(), GeometryError> {
    if !points.iter().all(|p| p.all_finite()) {
        return Err(GeometryError::NonFinite {
            what: "control point",
        });
    }
    for (index, &weight) in weights.iter().enumerate() {
        if !weight.is_finite() {
            return Err(GeometryError::NonFinite { what: "weight" });
        }
        if weight <= 0.0 {
            return Err(GeometryError::NonPositiveWeight { index, weight });
        }
    }
    Ok(())
}
