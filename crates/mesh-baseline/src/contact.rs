//! A contact as the baseline reports it, and matching it to a true contact.

use glam::DVec3;

/// One contact point of the baseline, in the world frame (mm).
///
/// `normal` is a unit vector from A towards B (A's outward normal cone at `point_a`, as parry's
/// pseudo-normals constrain it) and `point_b ≈ point_a + distance · normal`; `distance` is
/// negative when the meshes overlap (parry's penetration depth along `normal`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BaselineContact {
    /// Point on mesh A (world frame, mm).
    pub point_a: DVec3,
    /// Point on mesh B (world frame, mm).
    pub point_b: DVec3,
    /// Signed distance along `normal` (mm), negative for overlap.
    pub distance: f64,
    /// Unit normal from A towards B (world frame).
    pub normal: DVec3,
}

impl BaselineContact {
    /// Midpoint of the two contact points (world frame, mm).
    #[must_use]
    pub fn midpoint(&self) -> DVec3 {
        0.5 * (self.point_a + self.point_b)
    }
}

/// The baseline contact whose midpoint is nearest `point` (world frame, mm; typically the
/// midpoint of a true contact), as (index into `contacts`, distance between the two points in
/// mm); `None` when `contacts` is empty.
#[must_use]
pub fn nearest_to(contacts: &[BaselineContact], point: DVec3) -> Option<(usize, f64)> {
    contacts
        .iter()
        .map(|c| c.midpoint().distance(point))
        .enumerate()
        .min_by(|a, b| a.1.total_cmp(&b.1))
}
