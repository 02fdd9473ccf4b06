//! A NURBS curve swept along a vector as a NURBS surface (ruled, degree 1 across).

use crate::curves::curve::ParamRange;
use crate::curves::nurbs_curve::NurbsCurve;
use crate::geometry_checks::{checked_range, finite_vector};
use crate::geometry_error::GeometryError;
use crate::surfaces::nurbs_surface::NurbsSurface;
use glam::DVec3;

impl NurbsSurface {
    /// S(u, v) = C(u) + v d for v in `v_range`, exactly the parametrisation of
    /// [`crate::LinearExtrusionSurface`]: row i of the net is [P_i + v_min d, P_i + v_max d]
    /// with weights [w_i, w_i], the v knots are [v_min, v_min, v_max, v_max] (degree 1).
    /// Periodic in u when the curve is.
    ///
    /// # Errors
    /// [`GeometryError::NonFinite`], [`GeometryError::ZeroDirection`],
    /// [`GeometryError::EmptyRange`] or [`GeometryError::BadPeriod`].
    pub fn extrusion(
        curve: &NurbsCurve,
        direction: DVec3,
        v_range: ParamRange,
    ) -> Result<Self, GeometryError> {
        if finite_vector("extrusion direction", direction)? == DVec3::ZERO {
            return Err(GeometryError::ZeroDirection {
                what: "extrusion direction",
            });
        }
        let v = checked_range(v_range, None)?;
        let points = curve
            .control_points()
            .iter()
            .map(|&p| vec![p + v.min * direction, p + v.max * direction])
            .collect();
        let weights = curve.weights().iter().map(|&w| vec![w, w]).collect();
        Self::new(
            [curve.basis().degree(), 1],
            [
                curve.basis().knots().to_vec(),
                vec![v.min, v.min, v.max, v.max],
            ],
            points,
            weights,
            [curve.is_periodic(), false],
        )
    }
}
