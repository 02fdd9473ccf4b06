//! A NURBS curve revolved about an axis as a NURBS surface (The NURBS Book A8.1).

use crate::curves::nurbs_curve::NurbsCurve;
use crate::geometry_checks::{finite, finite_vector, unit_direction};
use crate::geometry_error::GeometryError;
use crate::nurbs::circle_arc::arc_net;
use crate::surfaces::nurbs_surface::NurbsSurface;
use glam::DVec3;

impl NurbsSurface {
    /// `curve` revolved right-handedly about the line through `axis_point` along `axis` by
    /// `sweep` (rad, 0 < sweep <= 2π), exactly (A8.1, MakeRevolvedSurf): u along the circles
    /// (degree 2, the knots of [`NurbsCurve::circle_arc`] from 0 to `sweep`: u equals the
    /// rotation angle at the sub-arc joints), v the curve's own parameter. Each control point
    /// P_j of weight w_j becomes the column of arc control points about its foot on the axis,
    /// with weights w_j times the arc's. Periodic in u when the sweep is a full turn, in v when
    /// the curve is.
    ///
    /// With the curve running counter-clockwise around the material in a half-plane bounded by
    /// the axis (as a [`crate::RevolvedSurface`] profile), S_u × S_v points outwards.
    ///
    /// # Errors
    /// [`GeometryError::NonFinite`], [`GeometryError::ZeroDirection`] for a zero axis,
    /// [`GeometryError::EmptyRange`] or [`GeometryError::BadPeriod`] for a sweep outside
    /// (0, 2π].
    pub fn revolution(
        curve: &NurbsCurve,
        axis_point: DVec3,
        axis: DVec3,
        sweep: f64,
    ) -> Result<Self, GeometryError> {
        finite_vector("axis point", axis_point)?;
        let k = unit_direction("axis of revolution", axis)?;
        finite("sweep", sweep)?;
        // Validates the sweep (and gives the u knots) on a unit circle.
        let unit = NurbsCurve::circle_arc(&crate::Placement::IDENTITY, 1.0, 0.0, sweep)?;
        let count_v = curve.control_points().len();
        let count_u = unit.control_points().len();
        let mut points = vec![Vec::with_capacity(count_v); count_u];
        let mut weights = vec![Vec::with_capacity(count_v); count_u];
        for (&p, &w) in curve.control_points().iter().zip(curve.weights()) {
            let foot = axis_point + k * k.dot(p - axis_point);
            let radial = p - foot;
            let radius = radial.length();
            let x = if radius > 0.0 {
                radial / radius
            } else {
                k.any_orthonormal_vector()
            };
            let arc = arc_net(foot, x, k.cross(x), radius, 0.0, sweep);
            for (i, (&q, &wq)) in arc.points.iter().zip(&arc.weights).enumerate() {
                points[i].push(q);
                weights[i].push(wq * w);
            }
        }
        Self::new(
            [2, curve.basis().degree()],
            [
                unit.basis().knots().to_vec(),
                curve.basis().knots().to_vec(),
            ],
            points,
            weights,
            [unit.is_periodic(), curve.is_periodic()],
        )
    }
}
