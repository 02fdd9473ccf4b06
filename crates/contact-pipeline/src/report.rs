//! What a query returns: the pair's state, its contacts and per-stage statistics.

use exact_refine::{RefineDiagnostics, RefineStatus};
use geom_param::FeatureLocation;
use glam::DVec3;

/// The interaction state of a pair (paper eq. 1): with d the minimum distance, contact when
/// delta1 <= d <= delta2, penetration below delta1, separated above delta2.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum PairState {
    /// d > delta2 everywhere.
    #[default]
    Separated,
    /// Every local minimum of distance found is >= delta1 and at least one is <= delta2.
    Contact,
    /// The surfaces interpenetrate by more than -delta1 somewhere (the meshes intersect, or an
    /// exact minimum lies below delta1).
    Penetration,
}

/// One contact: a local minimum of the distance between the two surfaces inside the band, or
/// (`distance < delta1`) one penetration region's depth.
///
/// Each contact is one representative pair of its region of near-minimal distance. Around an
/// isolated minimum the gap rises as `distance + ½ κ s²` (κ =
/// `diagnostics.gap_curvature`, s the slide in mm): [`Contact::flat_extent`] is how far that
/// region reaches at a given tolerance, and the points themselves are good to
/// `diagnostics.point_error_estimate`. A *continuous contact* (the paper's section IV: flat
/// face on flat face, parallel cylinders, concentric spheres), where the gap is constant along
/// some direction to rounding, has no isolated minimum: it is flagged
/// ([`Contact::is_continuous`], status `RefineStatus::ContinuousContact`, κ = 0, infinite point
/// error estimate), its distance is exact, its points are one pair of the set, and the pipeline
/// reports one contact per connected region found (seeds refined into the same region, on the
/// same pair of features at the same distance with the same normal, are merged).
///
/// A penetration contact is the region's exact penetration witness: a critical pair with
/// opposed normals, one of whose points lies inside the other solid with the other point as
/// its nearest boundary point (between two edges or vertices, the other point's flanks left
/// out), so `-distance` is that point's depth along `normal`: moving B by `-distance * normal`
/// brings the pair to touch. Stage 3 certifies it against Stage 2's meshes and, where they
/// cannot decide, the exact faces they list near the point (`exact_refine::check_witness`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Contact {
    /// Closest point on object A (world frame, mm); for a penetration, A's point of the
    /// witness (inside B).
    pub point_a: DVec3,
    /// Closest point on object B (world frame, mm); for a penetration, B's point of the
    /// witness (inside A).
    pub point_b: DVec3,
    /// Signed distance (mm): point_b = point_a + distance * normal; negative for a
    /// penetration (the depth is -distance).
    pub distance: f64,
    /// Unit normal from A to B (world frame): A's outward normal at `point_a` when that is on
    /// a face, else B's outward normal at `point_b` negated when that is on a face, else for
    /// two edges their common normal turned away from A, else the direction of the connecting
    /// vector.
    pub normal: DVec3,
    /// The exact feature of A and its parameters.
    pub location_a: FeatureLocation,
    /// The exact feature of B and its parameters.
    pub location_b: FeatureLocation,
    /// The refiner's account of how the point was found (iterations, residual, conditioning).
    pub diagnostics: RefineDiagnostics,
}

impl Contact {
    /// Whether this is one representative pair of a continuous contact: the gap is constant
    /// to rounding along some direction (status `RefineStatus::ContinuousContact`), so the
    /// distance is exact and the points are any pair of the degenerate set.
    #[must_use]
    pub fn is_continuous(&self) -> bool {
        self.diagnostics.status == RefineStatus::ContinuousContact
    }

    /// Half-length (mm) of the region around the reported pair over which the gap stays within
    /// `tolerance` (mm) of `distance`, along the gap's flattest direction, to second order:
    /// √(2 tolerance / κ) with κ = `diagnostics.gap_curvature` (1/mm). Infinite for a
    /// continuous contact (κ = 0: the region ends where its features do, which is not
    /// measured); 0 when `tolerance` is not a non-negative number or κ is infinite (a vertex
    /// against a vertex).
    #[must_use]
    pub fn flat_extent(&self, tolerance: f64) -> f64 {
        let kappa = self.diagnostics.gap_curvature;
        if tolerance.is_nan() || tolerance < 0.0 || kappa.is_nan() {
            return 0.0;
        }
        if kappa <= 0.0 {
            return f64::INFINITY;
        }
        (2.0 * tolerance / kappa).sqrt()
    }
}

/// Which stages ran for a query, their wall times and their counts.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct StageStats {
    /// Stage 1 ran (always, for a full query).
    pub broad_ran: bool,
    /// Stage 2 ran on at least one component pair.
    pub mesh_ran: bool,
    /// Stage 3 ran on at least one seed.
    pub refine_ran: bool,
    /// Wall time of Stage 1 (µs).
    pub broad_us: f64,
    /// Wall time of Stage 2 (µs).
    pub mesh_us: f64,
    /// Wall time of Stage 3 (µs).
    pub refine_us: f64,
    /// Component pairs reported by Stage 1.
    pub component_pairs: usize,
    /// Seeds produced by Stage 2.
    pub seeds: usize,
    /// Seeds refined by Stage 3.
    pub refined: usize,
    /// Component pairs whose meshes intersected but whose penetration Stage 3 had to confirm.
    pub mesh_overlaps: usize,
    /// Refined seeds that duplicated an earlier contact and were merged into it.
    pub merged: usize,
    /// Refined seeds below delta1 that Stage 3's witness check found measured through the
    /// material (`exact_refine::WitnessCheck::ThroughMaterial`, dropped, and
    /// `Overlapping`, kept as a penetration witness point only where the point inside lies
    /// deeper than -delta1).
    pub through_material: usize,
}

impl StageStats {
    /// Total of the three stage times (µs).
    #[must_use]
    pub fn total_us(&self) -> f64 {
        self.broad_us + self.mesh_us + self.refine_us
    }
}

/// The result of one pair query.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PairReport {
    /// Separated, contact or penetration.
    pub state: PairState,
    /// Every contact (local minimum of distance inside the band), each once; when
    /// penetrating, also one entry per penetration region with `distance < delta1` (its exact
    /// depth, see [`Contact`]), merged like contacts. A region whose depth Stage 3 could not
    /// certify (no seed, not converged, the witness check undecided, or a pair measured through
    /// the material with a point inside the other solid deeper than -delta1) has a witness point
    /// in `penetration_witnesses` but no entry here; with [`crate::QueryDepth::StateOnly`]
    /// the query stops at the first one.
    pub contacts: Vec<Contact>,
    /// When penetrating: the centres of the intersecting mesh regions and the midpoints of the
    /// refined penetration pairs (world frame), as witness points; for a pair measured through
    /// the material, its point inside the other solid.
    pub penetration_witnesses: Vec<DVec3>,
    /// What ran and how long it took.
    pub stats: StageStats,
}

impl PairReport {
    /// Empties the report, keeping its allocations.
    pub fn clear(&mut self) {
        self.state = PairState::Separated;
        self.contacts.clear();
        self.penetration_witnesses.clear();
        self.stats = StageStats::default();
    }
}
