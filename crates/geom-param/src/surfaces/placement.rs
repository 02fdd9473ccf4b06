//! A right-handed orthonormal frame placed in the object frame (STEP's AXIS2_PLACEMENT_3D).

use crate::geometry_checks::finite_vector;
use crate::geometry_error::GeometryError;
use glam::DVec3;

/// Relative size below which the reference direction counts as parallel to the axis: its part
/// orthogonal to z is shorter than this times its length.
const PARALLEL_RELATIVE_EPS: f64 = 1e-12;

/// A local frame: origin (mm) and unit axes x, y, z with y = z × x, all in the object frame.
/// A local point (a, b, c) is the object point `origin + a x + b y + c z`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Placement {
    /// Origin of the frame (mm, object frame).
    pub origin: DVec3,
    /// Unit x axis (the reference direction, orthogonal to z).
    pub x: DVec3,
    /// Unit y axis, z × x.
    pub y: DVec3,
    /// Unit z axis (the placement's axis).
    pub z: DVec3,
}

impl Placement {
    /// The object frame itself: origin 0, axes x, y, z.
    pub const IDENTITY: Self = Self {
        origin: DVec3::ZERO,
        x: DVec3::X,
        y: DVec3::Y,
        z: DVec3::Z,
    };

    /// The frame at `origin` with axis `axis` (normalised) and x the part of `ref_direction`
    /// orthogonal to the axis (normalised), y = z × x: STEP's AXIS2_PLACEMENT_3D.
    ///
    /// # Errors
    /// [`GeometryError::NonFinite`] for a NaN or infinite input;
    /// [`GeometryError::DegeneratePlacement`] when `axis` or `ref_direction` is zero or they are
    /// parallel.
    pub fn new(origin: DVec3, axis: DVec3, ref_direction: DVec3) -> Result<Self, GeometryError> {
        finite_vector("placement origin", origin)?;
        finite_vector("placement axis", axis)?;
        finite_vector("placement reference direction", ref_direction)?;
        let z = axis
            .try_normalize()
            .ok_or(GeometryError::DegeneratePlacement {
                reason: "the axis is zero",
            })?;
        let length = ref_direction.length();
        if length == 0.0 {
            return Err(GeometryError::DegeneratePlacement {
                reason: "the reference direction is zero",
            });
        }
        let orthogonal = ref_direction - z * z.dot(ref_direction);
        if orthogonal.length() <= PARALLEL_RELATIVE_EPS * length {
            return Err(GeometryError::DegeneratePlacement {
                reason: "the reference direction is parallel to the axis",
            });
        }
        let x = orthogonal.normalize();
        Ok(Self {
            origin,
            x,
            y: z.cross(x),
            z,
        })
    }

    /// The object-frame point at local coordinates `local` (mm).
    #[must_use]
    pub fn local_to_object(&self, local: DVec3) -> DVec3 {
        self.origin + self.vector(local)
    }

    /// The object-frame vector with local components `local` (a direction or a derivative:
    /// rotated, not translated).
    #[must_use]
    pub fn vector(&self, local: DVec3) -> DVec3 {
        local.x * self.x + local.y * self.y + local.z * self.z
    }
}
