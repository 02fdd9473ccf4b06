//! The exact circle and circular arc as a rational quadratic B-spline (The NURBS Book A7.1).

use crate::curves::curve::ParamRange;
use crate::geometry_checks::{checked_range, finite, finite_vector, positive};
use crate::geometry_error::GeometryError;
use crate::nurbs::rational_bspline_curve::RationalBSplineCurve;
use crate::surfaces::placement::Placement;
use glam::DVec3;
use std::f64::consts::{FRAC_PI_2, PI, TAU};

/// Relative slack with which a sweep counts as a full turn.
const FULL_TURN_RELATIVE_SLACK: f64 = 1e-12;

/// Control points, weights and knots of a rational quadratic circular arc.
pub(crate) struct ArcNet {
    /// Knots: start (×3), the joints between sub-arcs (×2 each), start + sweep (×3).
    pub(crate) knots: Vec<f64>,
    /// 2 × arcs + 1 points: joint, tangent intersection, joint, ...
    pub(crate) points: Vec<DVec3>,
    /// 1 at the joints, cos(Δθ / 2) at the tangent intersections.
    pub(crate) weights: Vec<f64>,
}

/// The arc centre + radius (cos θ x + sin θ y) for θ from `start` through `start + sweep`
/// (rad, 0 < sweep <= 2π; x, y orthonormal) split into 1 to 4 equal sub-arcs of
/// Δθ <= π/2 (A7.1, MakeNurbsCircle). The middle point of each sub-arc is where the end
/// tangents meet, centre + radius / cos(Δθ/2) (cos θ_mid x + sin θ_mid y), with weight
/// cos(Δθ/2). A full turn repeats its first point exactly at the end. A zero radius gives a net
/// collapsed to the centre (a pole of a surface of revolution).
pub(crate) fn arc_net(
    center: DVec3,
    x: DVec3,
    y: DVec3,
    radius: f64,
    start: f64,
    sweep: f64,
) -> ArcNet {
    let arcs: u32 = if sweep <= FRAC_PI_2 {
        1
    } else if sweep <= PI {
        2
    } else if sweep <= 1.5 * PI {
        3
    } else {
        4
    };
    let step = sweep / f64::from(arcs);
    let middle_weight = (0.5 * step).cos();
    let at = |angle: f64, distance: f64| {
        let (sin, cos) = angle.sin_cos();
        center + distance * (cos * x + sin * y)
    };
    let mut points = vec![at(start, radius)];
    let mut weights = vec![1.0];
    let mut knots = vec![start; 3];
    for i in 1..=arcs {
        let end = start + f64::from(i) * step;
        points.push(at(end - 0.5 * step, radius / middle_weight));
        points.push(at(end, radius));
        weights.extend([middle_weight, 1.0]);
        let knot = if i == arcs { start + sweep } else { end };
        knots.extend(std::iter::repeat_n(knot, if i == arcs { 3 } else { 2 }));
    }
    if sweep >= TAU * (1.0 - FULL_TURN_RELATIVE_SLACK) {
        points[2 * arcs as usize] = points[0];
    }
    ArcNet {
        knots,
        points,
        weights,
    }
}

impl RationalBSplineCurve<DVec3> {
    /// The exact arc O + R (cos θ x + sin θ y) of `placement` (centre O, plane spanned by x, y)
    /// for θ from `start` through `start + sweep` (rad, 0 < sweep <= 2π) as a rational
    /// quadratic NURBS (A7.1): 1 to 4 sub-arcs of at most π/2, knots at the sub-arcs' joint
    /// angles, so the parameter t runs over [start, start + sweep] and equals the angle θ at
    /// the joints (not between them). Periodic when the sweep is a full turn.
    ///
    /// # Errors
    /// [`GeometryError::NonPositiveRadius`], [`GeometryError::NonFinite`],
    /// [`GeometryError::EmptyRange`] for sweep <= 0, [`GeometryError::BadPeriod`] for
    /// sweep > 2π.
    pub fn circle_arc(
        placement: &Placement,
        radius: f64,
        start: f64,
        sweep: f64,
    ) -> Result<Self, GeometryError> {
        positive("circle radius", radius)?;
        finite_vector("circle centre", placement.origin)?;
        let range = ParamRange {
            min: finite("arc start", start)?,
            max: start + finite("arc sweep", sweep)?,
            periodic: false,
        };
        checked_range(range, Some(TAU))?;
        let net = arc_net(
            placement.origin,
            placement.x,
            placement.y,
            radius,
            start,
            sweep,
        );
        let full = sweep >= TAU * (1.0 - FULL_TURN_RELATIVE_SLACK);
        Self::new(2, net.knots, net.points, net.weights, full)
    }
}
