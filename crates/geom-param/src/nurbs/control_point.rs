//! The vector spaces the NURBS numerics run on (2D p-curves, 3D curves and surfaces).

use glam::{DVec2, DVec3};
use std::fmt::Debug;
use std::ops::{Add, Mul, Sub};

/// A control point type for rational B-splines: a real vector space with a norm. Implemented
/// for [`DVec2`] (curves in a face's (u, v) plane) and [`DVec3`] (curves and surfaces in the
/// object frame, mm).
pub trait ControlPoint:
    Copy
    + Debug
    + PartialEq
    + Send
    + Sync
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<f64, Output = Self>
    + 'static
{
    /// The zero vector.
    const ZERO: Self;

    /// Euclidean length.
    fn norm(self) -> f64;

    /// Whether every coordinate is finite.
    fn all_finite(self) -> bool;
}

impl ControlPoint for DVec2 {
    const ZERO: Self = DVec2::ZERO;

    fn norm(self) -> f64 {
        self.length()
    }

    fn all_finite(self) -> bool {
        self.is_finite()
    }
}

impl ControlPoint for DVec3 {
    const ZERO: Self = DVec3::ZERO;

    fn norm(self) -> f64 {
        self.length()
    }

    fn all_finite(self) -> bool {
        self.is_finite()
    }
}

/// Largest distance of a control point from the first one (0 for an empty or one-point net): the
/// length scale of the net, for relative tolerances.
pub(crate) fn net_extent<P: ControlPoint>(points: &[P]) -> f64 {
    points.first().map_or(0.0, |&first| {
        points
            .iter()
            .map(|&p| (p - first).norm())
            .fold(0.0, f64::max)
    })
}
