//! A profile segment revolved about the z axis.
//!
//! S(u, v) = (r(v) cos u, r(v) sin u, z(v)), u in [0, 2π) periodic (angle about z, rad),
//! v in [0, 1] the segment parameter. With the profile walked counter-clockwise around the
//! material, ∂S/∂u × ∂S/∂v = r (z' cos u, z' sin u, -r') points outwards wherever r > 0.

use crate::curves::curve::ParamRange;
use crate::revolution::profile_segment::ProfileSegment;
use crate::surfaces::surface::{PrincipalCurvatures, Surface, SurfacePoint};
use glam::DVec3;
use std::f64::consts::TAU;

/// Relative size below which r counts as zero (the face touches the axis) and dz/ds counts as
/// zero (the tangent is horizontal, so the face closes smoothly at a pole).
const AXIS_EPS: f64 = 1e-12;

/// The surface swept by one profile segment turning once about the z axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RevolvedSurface {
    /// The generating segment in the (r, z) half-plane.
    pub segment: ProfileSegment,
}

impl RevolvedSurface {
    /// Whether the point at v is on the axis, and if so whether the face closes smoothly there
    /// (a pole: horizontal tangent) rather than in a point (an apex).
    fn axis_state(&self, v: f64) -> AxisState {
        let p = self.segment.eval(v);
        let scale = p.d1.length();
        if p.point.x.abs() > AXIS_EPS * scale.max(p.point.length()) {
            AxisState::OffAxis
        } else if p.d1.y.abs() <= 1e-9 * scale {
            AxisState::Pole
        } else {
            AxisState::Apex
        }
    }
}

enum AxisState {
    OffAxis,
    Pole,
    Apex,
}

impl Surface for RevolvedSurface {
    fn eval(&self, u: f64, v: f64) -> SurfacePoint {
        let p = self.segment.eval(v);
        let (sin, cos) = u.sin_cos();
        let (r, z) = (p.point.x, p.point.y);
        let (r1, z1) = (p.d1.x, p.d1.y);
        let (r2, z2) = (p.d2.x, p.d2.y);
        SurfacePoint {
            point: DVec3::new(r * cos, r * sin, z),
            du: DVec3::new(-r * sin, r * cos, 0.0),
            dv: DVec3::new(r1 * cos, r1 * sin, z1),
            duu: DVec3::new(-r * cos, -r * sin, 0.0),
            duv: DVec3::new(-r1 * sin, r1 * cos, 0.0),
            dvv: DVec3::new(r2 * cos, r2 * sin, z2),
        }
    }

    fn domain(&self) -> [ParamRange; 2] {
        [
            ParamRange {
                min: 0.0,
                max: TAU,
                periodic: true,
            },
            ParamRange {
                min: 0.0,
                max: 1.0,
                periodic: false,
            },
        ]
    }

    /// (z' cos u, z' sin u, -r') / |(r', z')|: defined at a pole too, where it is ±z;
    /// `None` at a cone apex.
    fn normal(&self, u: f64, v: f64) -> Option<DVec3> {
        if let AxisState::Apex = self.axis_state(v) {
            return None;
        }
        let n2 = self.segment.eval(v).outward_normal();
        let (sin, cos) = u.sin_cos();
        Some(DVec3::new(n2.x * cos, n2.x * sin, n2.y))
    }

    /// Meridian curvature (r'z'' - z'r'')/|t|³ and parallel curvature z'/(r |t|); at a pole the
    /// parallel curvature tends to the meridian one. `None` at a cone apex.
    fn principal_curvatures(&self, _u: f64, v: f64) -> Option<PrincipalCurvatures> {
        let p = self.segment.eval(v);
        let meridian = p.signed_curvature();
        let parallel = match self.axis_state(v) {
            AxisState::Apex => return None,
            AxisState::Pole => meridian,
            AxisState::OffAxis => p.d1.y / (p.point.x * p.d1.length()),
        };
        Some(PrincipalCurvatures {
            min: meridian.min(parallel),
            max: meridian.max(parallel),
        })
    }
}
