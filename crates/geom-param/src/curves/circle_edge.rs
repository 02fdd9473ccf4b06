//! A circle about the z axis: the edge where two revolved faces meet.

use crate::curves::curve::{Curve, CurvePoint, ParamRange};
use glam::DVec3;
use std::f64::consts::TAU;

/// C(t) = (r cos t, r sin t, z), t in [0, 2π) periodic: the same angle as the u parameter of
/// the revolved faces on either side.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CircleEdge {
    /// Radius (mm), > 0.
    pub radius: f64,
    /// Height (mm).
    pub z: f64,
}

impl Curve for CircleEdge {
    fn eval(&self, t: f64) -> CurvePoint {
        let (sin, cos) = t.sin_cos();
        let r = self.radius;
        CurvePoint {
            point: DVec3::new(r * cos, r * sin, self.z),
            d1: DVec3::new(-r * sin, r * cos, 0.0),
            d2: DVec3::new(-r * cos, -r * sin, 0.0),
        }
    }

    fn domain(&self) -> ParamRange {
        ParamRange {
            min: 0.0,
            max: TAU,
            periodic: true,
        }
    }
}
