//! The Stage 1 boundary: which pairs of surface components might be within the margin.

use geom_param::{ComponentId, DPose3, ObjectModel};

/// Stage 1 of the contact pipeline (paper section II, Stage 1): from two prepared objects and
/// their relative pose, the pairs of surface components that may be within the margin `delta`
/// of each other, so that Stages 2 and 3 only look at those.
///
/// # Frames and units
/// Every object has its own frame (the frame of its [`ObjectModel`]: meshes, hulls and exact
/// features are all expressed in it). A query receives `pose_ab`, the pose of object B in the
/// frame of object A: a point of B maps to A's frame by `point_in_a = pose_ab * point_in_b`
/// (the convention of parry's `pos12`). Lengths are millimetres.
///
/// # Margin
/// [`BroadPhase::build`] takes the margin `delta` (mm, the paper's tolerance of section III-A),
/// which must exceed the largest motion of one time step so that a contact is never first seen
/// as a penetration. Each object's volumes cover its components' **exact** surfaces (not only
/// their meshes) inflated by `delta / 2`, so two trees built with the same `delta` report a
/// pair whenever the two exact components come within `delta` of each other.
///
/// # Guarantees
/// - **No misses**: every component pair whose exact surfaces are closer than the margin
///   (with both trees built with that margin) is reported; more generally every pair whose
///   leaf volumes intersect is reported. Overlap tests are exact for the volumes used, with a
///   rounding slack that only ever errs towards reporting.
/// - **False positives only cost time**: a reported pair may be farther apart than the margin.
/// - **No allocation in steady state**: the traversal stack lives in the caller-owned
///   [`BroadPhase::Scratch`], and `out` is reused; both only grow.
/// - **No panics on bad input**: a margin, mesh or pose that cannot be bounded (not finite,
///   negative margin, empty mesh) makes the affected volumes unbounded, so the affected pairs
///   are reported rather than missed.
///
/// # Notes for implementors
/// A tree must not borrow the object (it is `Send + Sync` and shared by all queries), and
/// `overlapping_components` must give the same set of pairs whatever the scratch contents:
/// scratch may carry what the last query learnt (as [`crate::HybridBvh`] carries its
/// traversal front, the node pairs it found apart and by how much) only where that proves
/// the answer, never as a guess (a pair may be left out only when its volumes are certainly
/// still apart).
pub trait BroadPhase {
    /// Per-object preprocessing (built once, shared by all queries).
    type Tree: Send + Sync;
    /// Caller-owned scratch (traversal stack, what the last query learnt, etc.).
    type Scratch: Default + Send;

    /// Builds the tree of `object` whose every volume covers its components' exact surfaces
    /// inflated by `margin / 2` (so two leaves overlap whenever their components come within
    /// `margin`).
    ///
    /// `margin` is in mm and should be positive and finite; otherwise (and for a component
    /// whose mesh has no finite vertex) the affected volumes are unbounded, which reports
    /// their pairs on every query instead of missing them.
    ///
    /// # Panics
    /// Never, for any input.
    fn build(&self, object: &ObjectModel, margin: f64) -> Self::Tree;

    /// Clears `out` and pushes every (component of A, component of B) whose leaf volumes
    /// overlap; `pose_ab` is B's pose in A's frame (point_in_a = pose_ab * point_in_b).
    ///
    /// Each pair appears once; the order is unspecified. A pose with a non-finite entry
    /// cannot separate anything, so every pair is reported.
    ///
    /// # Panics
    /// Never, for any input.
    fn overlapping_components(
        &self,
        a: &Self::Tree,
        b: &Self::Tree,
        pose_ab: &DPose3,
        scratch: &mut Self::Scratch,
        out: &mut Vec<(ComponentId, ComponentId)>,
    );
}
