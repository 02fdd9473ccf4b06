//! The Stage 3 boundary: the [`Refiner`] trait. Its result types are in
//! [`crate::refined_contact`].

use crate::checks::witness_check::{NearestBoundary, WitnessCheck, check_witness};
use crate::refined_contact::RefinedContact;
use geom_param::{DPose3, Seed, Solid};

/// Stage 3 of the paper: from a seed (approximately closest points on two exact features),
/// the exact closest point pair of those features, with diagnostics.
///
/// # Contract
/// - **Frames.** Everything is computed and returned in A's object frame. B is posed in A's
///   frame by `pose_ab`: `point_in_a = pose_ab * point_in_b`. `seed.a.local_point` is in A's
///   frame, `seed.b.local_point` in B's own frame; `seed.a.location` is a feature of `a`,
///   `seed.b.location` one of `b`.
/// - **Units.** Millimetres and radians.
/// - **What "closest" means.** For separated features, a local minimum of |P_a − P_b| over the
///   two features (the seed decides which one). For penetrating features, the pair whose
///   connecting vector is anti-parallel to the normals and which locally maximises the depth:
///   a critical point of ½|P_a − P_b|² that is a saddle of it (see
///   [`RefineDiagnostics::is_local_minimum`]). [`RefinedContact::distance`] is signed: negative
///   when penetrating, measured along [`RefinedContact::normal`].
/// - **Features move.** When the closest point leaves a face across a side, the result is on
///   the bounding edge or vertex (and back onto a face when the minimum is inside it);
///   `location_a` and `location_b` are the final features with their parameters wrapped into
///   the domain.
/// - **Non-convergence is a value.** The result always has finite points and a unit normal;
///   [`RefineDiagnostics::status`] says whether they are the answer.
///
/// # Panics
/// Never: ids that do not belong to the solids, a non-finite pose or non-finite seed
/// points give [`RefineStatus::InvalidInput`].
///
/// # Errors
/// None are returned: every outcome, including bad input, is a [`RefineStatus`].
///
/// [`RefineDiagnostics::is_local_minimum`]: crate::RefineDiagnostics::is_local_minimum
/// [`RefineDiagnostics::status`]: crate::RefineDiagnostics::status
/// [`RefineStatus::InvalidInput`]: crate::RefineStatus::InvalidInput
/// [`RefineStatus`]: crate::RefineStatus
pub trait Refiner {
    /// Caller-owned scratch (if any), reused across calls so that a query allocates nothing.
    type Scratch: Default + Send;

    /// Refines `seed` (seed.a on solid `a`, seed.b on solid `b`, each `SeedPoint::local_point`
    /// in its own object frame) with B posed in A's frame by `pose_ab`
    /// (point_in_a = pose_ab * point_in_b).
    fn refine(
        &self,
        a: &Solid,
        b: &Solid,
        pose_ab: &DPose3,
        seed: &Seed,
        scratch: &mut Self::Scratch,
    ) -> RefinedContact;

    /// Whether a penetrating result of [`Self::refine`] (`witness.distance < 0`) is a witness:
    /// one of its points lies inside the other solid with the other point as its nearest
    /// boundary point, against `near_a` (A's boundary, queried in A's frame) and `near_b`
    /// (B's, queried in B's own frame); see [`check_witness`], which the default
    /// implementation calls. A refiner sees two features
    /// only, so this needs a query over each whole boundary: the pipeline passes Stage 2's
    /// meshes ([`NearestBoundary`]). A pair that fails is measured through the material and is
    /// no penetration witness ([`WitnessCheck::ThroughMaterial`]); where one of its points lies
    /// inside the other solid all the same, the solids overlap at least that point's depth
    /// ([`WitnessCheck::Overlapping`]).
    ///
    /// # Panics
    /// Never: non-finite points give [`WitnessCheck::Undecided`].
    fn check_witness(
        &self,
        pose_ab: &DPose3,
        witness: &RefinedContact,
        near_a: &dyn NearestBoundary,
        near_b: &dyn NearestBoundary,
    ) -> WitnessCheck {
        check_witness(pose_ab, witness, near_a, near_b)
    }
}
