//! The three-stage pipeline, generic over its stages.

use crate::merge::{distances_agree, insert_or_merge};
use crate::options::{ContactOptions, OptionsError, QueryDepth};
use crate::report::{Contact, PairReport, PairState};
use bvh_hybrid::{BroadPhase, HybridBvh};
use exact_refine::{
    BoundaryDistance, NearestBoundary, NewtonRefiner, RefinedContact, Refiner, WitnessCheck,
    WitnessSide,
};
use geom_param::{
    ComponentId, DPose3, DVec3, FeatureLocation, LoadError, MeshOptions, ObjectDescription,
    ObjectModel, Seed, Solid,
};
use mesh_narrowphase::{
    ComponentRef, ContactBand, MeshNarrowphase, MeshOutput, MeshPhase, MeshVerdict, RegionProbes,
};
use std::time::Instant;

/// An object with all its preprocessing: the exact model and each stage's prepared data. Built
/// once by [`ContactPipeline::prepare`] and shared by every query.
pub struct PreparedObject<B: BroadPhase = HybridBvh, M: MeshPhase = MeshNarrowphase> {
    /// The exact model with its components and meshes.
    pub model: ObjectModel,
    /// Stage 1's tree.
    pub tree: B::Tree,
    /// Stage 2's per-object data.
    pub mesh: M::Prepared,
    /// Centre (object frame, mm) of a ball holding the exact surface: the centre of the
    /// meshes' vertex box.
    pub bounding_centre: DVec3,
    /// Radius (mm) of that ball: the largest distance of a mesh vertex from the centre plus
    /// the largest chordal error.
    pub bounding_radius: f64,
}

/// Caller-owned working memory of queries: pass the same one to every query of a thread so
/// that steady-state queries allocate nothing.
pub struct QueryScratch<
    B: BroadPhase = HybridBvh,
    M: MeshPhase = MeshNarrowphase,
    R: Refiner = NewtonRefiner,
> {
    broad: B::Scratch,
    mesh: M::Scratch,
    refine: R::Scratch,
    pairs: Vec<(ComponentId, ComponentId)>,
    mesh_out: MeshOutput,
    seeds: Vec<Seed>,
    probes: Vec<RegionProbes>,
}

impl<B: BroadPhase, M: MeshPhase, R: Refiner> Default for QueryScratch<B, M, R> {
    fn default() -> Self {
        Self {
            broad: B::Scratch::default(),
            mesh: M::Scratch::default(),
            refine: R::Scratch::default(),
            pairs: Vec::new(),
            mesh_out: MeshOutput::default(),
            seeds: Vec::new(),
            probes: Vec::new(),
        }
    }
}

impl<B: BroadPhase, M: MeshPhase, R: Refiner> QueryScratch<B, M, R> {
    /// Stage 3's part, for warm frames that refine without Stages 1-2.
    pub(crate) fn refine_scratch(&mut self) -> &mut R::Scratch {
        &mut self.refine
    }
}

/// Contact detection between pairs of prepared objects (paper section II).
///
/// Swap a stage by naming its type: `ContactPipeline::<MyBroadPhase>::with_stages(..)`.
pub struct ContactPipeline<
    B: BroadPhase = HybridBvh,
    M: MeshPhase = MeshNarrowphase,
    R: Refiner = NewtonRefiner,
> {
    /// Stage 1.
    pub broad: B,
    /// Stage 2.
    pub mesh: M,
    /// Stage 3.
    pub refiner: R,
    options: ContactOptions,
}

impl ContactPipeline {
    /// The default stages with `options`.
    ///
    /// # Errors
    /// [`OptionsError`] when the options cannot work together.
    pub fn new(options: ContactOptions) -> Result<Self, OptionsError> {
        Self::with_stages(
            HybridBvh::default(),
            MeshNarrowphase::default(),
            NewtonRefiner::default(),
            options,
        )
    }
}

impl<B: BroadPhase, M: MeshPhase, R: Refiner> ContactPipeline<B, M, R> {
    /// A pipeline from the given stages.
    ///
    /// # Errors
    /// [`OptionsError`] when the options cannot work together.
    pub fn with_stages(
        broad: B,
        mesh: M,
        refiner: R,
        options: ContactOptions,
    ) -> Result<Self, OptionsError> {
        options.validate()?;
        Ok(Self {
            broad,
            mesh,
            refiner,
            options,
        })
    }

    /// The options in force.
    #[must_use]
    pub fn options(&self) -> &ContactOptions {
        &self.options
    }

    /// Preprocesses a built object model for this pipeline's stages (its meshes must have been
    /// built with the tolerance the caller wants; see [`Self::prepare_description`]).
    #[must_use]
    pub fn prepare(&self, model: ObjectModel) -> PreparedObject<B, M> {
        let tree = self.broad.build(&model, self.options.margin);
        let mesh = self.mesh.prepare(&model);
        let (bounding_centre, bounding_radius) = bounding_ball(&model);
        PreparedObject {
            model,
            tree,
            mesh,
            bounding_centre,
            bounding_radius,
        }
    }

    /// Validates, builds (at the options' chordal tolerance) and preprocesses an object.
    ///
    /// # Errors
    /// [`LoadError`] for an invalid profile or unusable tolerance.
    pub fn prepare_description(
        &self,
        description: &ObjectDescription,
    ) -> Result<PreparedObject<B, M>, LoadError> {
        let model = description.build(&MeshOptions {
            chordal_tolerance: self.options.chordal_tolerance,
        })?;
        Ok(self.prepare(model))
    }

    /// Queries one pair. `pose_a` and `pose_b` place the objects in the world frame; every
    /// point and normal of the report is in the world frame.
    ///
    /// # Errors
    /// [`QueryError`] for a pose that is not a rigid motion (non-finite, or a rotation
    /// quaternion whose norm is off 1 by more than 1e-6), or a pair a stage refuses.
    pub fn query(
        &self,
        a: &PreparedObject<B, M>,
        pose_a: &DPose3,
        b: &PreparedObject<B, M>,
        pose_b: &DPose3,
        scratch: &mut QueryScratch<B, M, R>,
    ) -> Result<PairReport, QueryError> {
        let mut report = PairReport::default();
        self.query_into(a, pose_a, b, pose_b, scratch, &mut report)?;
        Ok(report)
    }

    /// As [`Self::query`], writing into `report` (cleared first) to reuse its allocations.
    ///
    /// # Errors
    /// As [`Self::query`].
    pub fn query_into(
        &self,
        a: &PreparedObject<B, M>,
        pose_a: &DPose3,
        b: &PreparedObject<B, M>,
        pose_b: &DPose3,
        scratch: &mut QueryScratch<B, M, R>,
        report: &mut PairReport,
    ) -> Result<(), QueryError> {
        self.query_recorded(a, pose_a, b, pose_b, scratch, report, None)
    }

    /// As [`Self::query_into`]; with `record`, Stage 2 runs with the band widened to
    /// `delta2 + record.slack` and every refined local minimum in `[delta1, delta2 + slack]`
    /// is also noted in `record` (A's frame) for [`crate::coherence`]. The report itself holds
    /// the contacts inside the band only, as without `record`.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn query_recorded(
        &self,
        a: &PreparedObject<B, M>,
        pose_a: &DPose3,
        b: &PreparedObject<B, M>,
        pose_b: &DPose3,
        scratch: &mut QueryScratch<B, M, R>,
        report: &mut PairReport,
        mut record: Option<&mut FullQueryRecord>,
    ) -> Result<(), QueryError> {
        report.clear();
        if let Some(record) = record.as_deref_mut() {
            record.minima.clear();
        }
        // Rotations within 1e-6 of unit are accepted and normalised, so that no output is
        // scaled by |q|².
        let pose_a = &check_pose(pose_a, "a")?;
        let pose_b = &check_pose(pose_b, "b")?;
        let options = &self.options;
        let pose_ab = pose_a.inverse() * *pose_b;

        // Stage 1.
        let start = Instant::now();
        self.broad.overlapping_components(
            &a.tree,
            &b.tree,
            &pose_ab,
            &mut scratch.broad,
            &mut scratch.pairs,
        );
        report.stats.broad_ran = true;
        report.stats.broad_us = micros(start);
        report.stats.component_pairs = scratch.pairs.len();
        if scratch.pairs.is_empty() {
            return Ok(());
        }

        // Stage 2.
        let start = Instant::now();
        let band = ContactBand {
            margin: options.margin,
            delta1: options.delta1,
            delta2: options.delta2 + record.as_deref().map_or(0.0, |r| r.slack),
        };
        scratch.seeds.clear();
        scratch.probes.clear();
        let mut penetrating = false;
        let mut mesh_overlaps = 0;
        // Some pair's meshes intersect and their chordal errors sum to at most delta2: the
        // exact surfaces come within delta2 of each other there (each mesh lies within its
        // error of its surface), so the pair is not separated.
        let mut overlap_within_band = false;
        for &(ca, cb) in &scratch.pairs {
            let verdict = self.mesh.query(
                ComponentRef {
                    object: &a.model,
                    prepared: &a.mesh,
                    component: ca,
                },
                ComponentRef {
                    object: &b.model,
                    prepared: &b.mesh,
                    component: cb,
                },
                &pose_ab,
                &band,
                &mut scratch.mesh,
                &mut scratch.mesh_out,
            );
            match verdict {
                MeshVerdict::Separated => {}
                MeshVerdict::Penetrating => {
                    // Intersecting meshes prove penetration only deeper than the chordal errors
                    // (concave meshes lie outside their surfaces): with seeds, Stage 3 decides.
                    report.penetration_witnesses.extend(
                        scratch
                            .mesh_out
                            .penetration_centres
                            .iter()
                            .map(|p| *pose_a * *p),
                    );
                    if scratch.mesh_out.seeds.is_empty() {
                        penetrating = true;
                    } else {
                        mesh_overlaps += 1;
                        overlap_within_band |= a.model.meshes[ca.0 as usize].chordal_error
                            + b.model.meshes[cb.0 as usize].chordal_error
                            <= options.delta2;
                        take_seeds(&scratch.mesh_out, &mut scratch.seeds, &mut scratch.probes);
                    }
                }
                MeshVerdict::Seeds => {
                    take_seeds(&scratch.mesh_out, &mut scratch.seeds, &mut scratch.probes);
                }
                MeshVerdict::InvalidInput(e) => return Err(QueryError::MeshPhase(e.to_string())),
            }
        }
        report.stats.mesh_ran = true;
        report.stats.mesh_us = micros(start);
        report.stats.seeds = scratch.seeds.len();
        if penetrating {
            report.state = PairState::Penetration;
            return Ok(());
        }
        if scratch.seeds.is_empty() {
            return Ok(());
        }

        // Stage 3.
        let start = Instant::now();
        report.stats.refine_ran = true;
        let scale = a.model.scale.max(b.model.scale);
        // Some seed's refinement ended below delta1 without converging (see the end).
        let mut unconverged_below = false;
        for (i, seed) in scratch.seeds.iter().enumerate() {
            let refined = self.refiner.refine(
                &a.model.solid,
                &b.model.solid,
                &pose_ab,
                seed,
                &mut scratch.refine,
            );
            report.stats.refined += 1;
            unconverged_below |=
                refined.distance < options.delta1 && !refined.diagnostics.converged;
            if let Some(record) = record.as_deref_mut() {
                record.note(&refined, seed, options.delta1, options.delta2, scale);
            }
            if self.take(&refined, (a, b, &pose_ab), pose_a, scale, report) {
                break;
            }
            // A contact region whose centre seed converged far from the centre holds more than
            // that minimum: refine its end seed farther from the contact found. (A penetration
            // has decided the state; its witnesses come from the mesh-mesh regions.)
            let far_end = scratch
                .probes
                .iter()
                .find(|p| p.centre_seed == i)
                .filter(|_| refined.distance >= options.delta1)
                .and_then(|p| far_end(p, &refined, &pose_ab));
            if let Some(end) = far_end {
                let refined = self.refiner.refine(
                    &a.model.solid,
                    &b.model.solid,
                    &pose_ab,
                    end,
                    &mut scratch.refine,
                );
                report.stats.refined += 1;
                unconverged_below |=
                    refined.distance < options.delta1 && !refined.diagnostics.converged;
                if let Some(record) = record.as_deref_mut() {
                    record.note(&refined, end, options.delta1, options.delta2, scale);
                }
                if self.take(&refined, (a, b, &pose_ab), pose_a, scale, report) {
                    break;
                }
            }
        }
        report.stats.refine_us = micros(start);
        if report.state != PairState::Penetration
            && report.contacts.is_empty()
            && mesh_overlaps > 0
            && (unconverged_below || report.stats.through_material > 0 || overlap_within_band)
        {
            // The meshes intersect and no seed gave an answer, but one ended on overlapping
            // surfaces, unconverged or with a witness the check could not certify (a thin
            // wall, such as a goblet's rim, poking into the other solid passes within the
            // meshes' error of its own far side), or the intersecting meshes' errors are
            // within the band, so that the surfaces are not separated and no contact in the
            // band was found: the pair is taken as penetrating. None of these decides anything
            // where another seed found a contact.
            report.state = PairState::Penetration;
        }
        if report.state != PairState::Penetration {
            // The mesh overlaps were within the chordal errors: no penetration after all.
            report.penetration_witnesses.clear();
            if !report.contacts.is_empty() {
                report.state = PairState::Contact;
            }
        }
        report.stats.mesh_overlaps = mesh_overlaps;
        Ok(())
    }
}

impl<B: BroadPhase, M: MeshPhase, R: Refiner> ContactPipeline<B, M, R> {
    /// Enters one refined seed into `report`: below delta1 and converged a penetration, unless
    /// Stage 3's witness check ([`Refiner::check_witness`] over Stage 2's meshes and the exact
    /// solids) finds the pair measured through the material (then it is dropped: no evidence of
    /// anything, unless a point of it lies inside the other solid deeper than -delta1, which
    /// then is the penetration's witness point and nothing more); a witness point (merged with
    /// an earlier one within the merge tolerance), and, when the check certifies the pair and it
    /// is the solver's deepest pair (second-order test passed), a contact with negative
    /// distance (merged likewise). An unconverged pair below
    /// delta1 proves nothing (one that stopped short on the way to an edge pair's witness may
    /// be below delta1 where the converged answer is a contact in the band) and is dropped
    /// here; the query falls back on it only when nothing converged. In the band and a local
    /// minimum a contact (merged likewise); anything else dropped. The tuple is (A, B, B's
    /// pose in A's frame); `scale` is the larger object's size (mm). Returns true when the
    /// query may stop (depth [`QueryDepth::StateOnly`] and the state is known).
    fn take(
        &self,
        refined: &RefinedContact,
        (a, b, pose_ab): (&PreparedObject<B, M>, &PreparedObject<B, M>, &DPose3),
        pose_a: &DPose3,
        scale: f64,
        report: &mut PairReport,
    ) -> bool {
        let options = &self.options;
        let state_only = options.depth == QueryDepth::StateOnly;
        if refined.distance < options.delta1 && refined.diagnostics.converged {
            let check = self.refiner.check_witness(
                pose_ab,
                refined,
                &MeshBoundary::<B, M>::new(&self.mesh, a),
                &MeshBoundary::<B, M>::new(&self.mesh, b),
            );
            // The pair's midpoint as the witness point; a pair measured through the material is
            // dropped (no evidence of anything), unless one of its points lies inside the other
            // solid deeper than -delta1: the solids overlap beyond the band there, though the
            // pair does not measure the depth, and that point is the witness.
            let witness = match check {
                WitnessCheck::Certified | WitnessCheck::Undecided => {
                    Some(0.5 * (refined.point_a + refined.point_b))
                }
                WitnessCheck::ThroughMaterial { .. } => None,
                WitnessCheck::Overlapping { side, depth } => {
                    (-depth < options.delta1).then_some(match side {
                        WitnessSide::B => refined.point_a,
                        WitnessSide::A => refined.point_b,
                    })
                }
            };
            if matches!(
                check,
                WitnessCheck::ThroughMaterial { .. } | WitnessCheck::Overlapping { .. }
            ) {
                report.stats.through_material += 1;
            }
            let Some(witness) = witness else {
                return false;
            };
            report.state = PairState::Penetration;
            let witness = *pose_a * witness;
            let tolerance = merge_tolerance(refined, scale);
            if report
                .penetration_witnesses
                .iter()
                .all(|w| w.distance(witness) > tolerance)
            {
                report.penetration_witnesses.push(witness);
            }
            if check == WitnessCheck::Certified
                && refined.diagnostics.is_local_minimum
                && insert_or_merge(
                    &mut report.contacts,
                    to_world(refined, pose_a),
                    tolerance,
                    (&a.model.solid, &b.model.solid),
                )
            {
                report.stats.merged += 1;
            }
            return state_only;
        }
        if refined.distance > options.delta2 || !refined.diagnostics.is_local_minimum {
            return false;
        }
        let tolerance = merge_tolerance(refined, scale);
        if insert_or_merge(
            &mut report.contacts,
            to_world(refined, pose_a),
            tolerance,
            (&a.model.solid, &b.model.solid),
        ) {
            report.stats.merged += 1;
        }
        state_only
    }
}

/// One prepared object's meshes as Stage 3's [`NearestBoundary`] query, with its exact solid
/// (the pipeline adapts Stage 2's [`MeshPhase::nearest_boundary_point`] and
/// [`MeshPhase::faces_near`] to it; neither stage knows the other).
struct MeshBoundary<'p, B: BroadPhase, M: MeshPhase> {
    phase: &'p M,
    object: &'p PreparedObject<B, M>,
}

impl<'p, B: BroadPhase, M: MeshPhase> MeshBoundary<'p, B, M> {
    fn new(phase: &'p M, object: &'p PreparedObject<B, M>) -> Self {
        Self { phase, object }
    }
}

impl<B: BroadPhase, M: MeshPhase> NearestBoundary for MeshBoundary<'_, B, M> {
    fn nearest_boundary(&self, local_point: DVec3, reach: f64) -> Option<BoundaryDistance> {
        self.phase
            .nearest_boundary_point(&self.object.model, &self.object.mesh, local_point, reach)
            .map(|n| BoundaryDistance {
                point: n.point,
                distance: n.distance,
                error_bound: n.error_bound,
            })
    }

    fn solid(&self) -> Option<&Solid> {
        Some(&self.object.model.solid)
    }

    fn faces_near(&self, local_point: DVec3, radius: f64) -> Vec<FeatureLocation> {
        self.phase
            .faces_near(&self.object.model, &self.object.mesh, local_point, radius)
    }
}

/// What a full query notes for [`crate::coherence`]: the band's widening and every distinct
/// refined local minimum in `[delta1, delta2 + slack]`, in refinement order, in A's frame,
/// with the components of the seed it came from.
#[derive(Clone, Debug, Default)]
pub(crate) struct FullQueryRecord {
    /// Widening of the band's upper end (mm), >= 0.
    pub slack: f64,
    /// The minima, each once (merged as contacts are).
    pub minima: Vec<(RefinedContact, ComponentId, ComponentId)>,
}

impl FullQueryRecord {
    /// Notes `refined` (from `seed`) when it is a local minimum in the widened band and not the
    /// same minimum as one already noted (points within [`merge_tolerance`], distances within
    /// their error estimates: as contacts are merged).
    fn note(
        &mut self,
        refined: &RefinedContact,
        seed: &Seed,
        delta1: f64,
        delta2: f64,
        scale: f64,
    ) {
        let d = refined.distance;
        if !(refined.diagnostics.is_local_minimum && d >= delta1 && d <= delta2 + self.slack) {
            return;
        }
        let tolerance = merge_tolerance(refined, scale);
        let same = self.minima.iter().any(|(m, _, _)| {
            m.point_a.distance(refined.point_a) <= tolerance
                && m.point_b.distance(refined.point_b) <= tolerance
                && distances_agree(
                    (m.distance, m.diagnostics.error_estimate),
                    (refined.distance, refined.diagnostics.error_estimate),
                    [m.point_a, m.point_b, refined.point_a, refined.point_b],
                )
        });
        if !same {
            self.minima
                .push((*refined, seed.a.component, seed.b.component));
        }
    }
}

/// A ball holding every exact surface point: the centre of the meshes' vertex box, and the
/// largest distance of a vertex from it plus the largest chordal error (mm). A model without
/// mesh vertices gets the origin and radius 0.
fn bounding_ball(model: &ObjectModel) -> (DVec3, f64) {
    let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
    let mut chordal = 0.0_f64;
    for mesh in &model.meshes {
        chordal = chordal.max(mesh.chordal_error);
        for p in &mesh.positions {
            lo = lo.min(*p);
            hi = hi.max(*p);
        }
    }
    if lo.x > hi.x {
        return (DVec3::ZERO, 0.0);
    }
    let centre = 0.5 * (lo + hi);
    let reach = model
        .meshes
        .iter()
        .flat_map(|m| &m.positions)
        .map(|p| p.distance(centre))
        .fold(0.0, f64::max);
    (centre, reach + chordal)
}

/// Appends one mesh query's seeds to `seeds` and its region probes to `probes`, with the
/// probes' centre-seed indices moved to the seeds' new positions.
fn take_seeds(out: &MeshOutput, seeds: &mut Vec<Seed>, probes: &mut Vec<RegionProbes>) {
    let offset = seeds.len();
    seeds.extend_from_slice(&out.seeds);
    probes.extend(out.probes.iter().map(|p| RegionProbes {
        centre_seed: p.centre_seed + offset,
        ..*p
    }));
}

/// A refined centre seed whose contact lies farther than this fraction of its region's radius
/// from the region's centre, across the contact normal, leaves part of the region unexplained.
/// One isolated minimum makes the region about an ellipse centred on it, so its centre seed
/// converges near the centre (the centre, in the loop's plane, stands off a curved surface by
/// the loop's sagitta, which lies along the normal and is not counted); 1/4 leaves room for a
/// region made lopsided by a face boundary or the mesh without refining a probe for every
/// contact.
const PROBE_DISPLACEMENT: f64 = 0.25;

/// The end seed of `probes`'s region to refine after its centre seed gave `refined` (A's
/// frame), or `None` when `refined` accounts for the region: B's contact point lies within
/// [`PROBE_DISPLACEMENT`] x radius of the centre across the contact normal (the loop lies on
/// B's mesh), or is not finite. The end chosen is the one farther from the refined contact.
fn far_end<'p>(
    probes: &'p RegionProbes,
    refined: &RefinedContact,
    pose_ab: &DPose3,
) -> Option<&'p Seed> {
    let found = refined.point_b;
    let offset = probes.centre - found;
    let n = refined.normal;
    let displacement = (offset - n * n.dot(offset)).length();
    // Written so that a NaN displacement (a non-finite contact) refines no probe.
    let off_centre = displacement > PROBE_DISPLACEMENT * probes.radius;
    if !off_centre {
        return None;
    }
    let [e1, e2] = &probes.ends;
    let away = |e: &Seed| (*pose_ab * e.b.local_point).distance(found);
    Some(if away(e1) >= away(e2) { e1 } else { e2 })
}

/// Why a query could not run.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum QueryError {
    /// A pose with a non-finite component or a rotation that is not a unit quaternion.
    #[error("pose of object {object} is not a rigid motion: {reason}")]
    BadPose {
        /// "a" or "b".
        object: &'static str,
        /// What is wrong.
        reason: String,
    },
    /// The mesh phase refused the pair (prepared data from another pipeline, for instance).
    #[error("mesh phase refused the pair: {0}")]
    MeshPhase(String),
    /// Coherence options that cannot work (see [`crate::CoherenceOptions`]).
    #[error("bad coherence options: {0}")]
    BadCoherence(String),
}

pub(crate) fn check_pose(pose: &DPose3, object: &'static str) -> Result<DPose3, QueryError> {
    let q = pose.rotation;
    if !(q.is_finite() && pose.translation.is_finite()) {
        return Err(QueryError::BadPose {
            object,
            reason: "a component is not a finite number".into(),
        });
    }
    let norm = q.length();
    if (norm - 1.0).abs() > 1e-6 {
        return Err(QueryError::BadPose {
            object,
            reason: format!("rotation quaternion has norm {norm}"),
        });
    }
    Ok(DPose3 {
        rotation: q / norm,
        translation: pose.translation,
    })
}

/// Two refined seeds are the same minimum when their points agree to this distance (mm): far
/// above the solver's point accuracy, far below any two distinct minima of the fixtures.
pub(crate) fn merge_tolerance(refined: &RefinedContact, scale: f64) -> f64 {
    (1e-6 * scale).max(100.0 * refined.diagnostics.point_error_estimate)
}

pub(crate) fn to_world(refined: &RefinedContact, pose_a: &DPose3) -> Contact {
    Contact {
        point_a: *pose_a * refined.point_a,
        point_b: *pose_a * refined.point_b,
        distance: refined.distance,
        normal: pose_a.rotation * refined.normal,
        location_a: refined.location_a,
        location_b: refined.location_b,
        diagnostics: refined.diagnostics,
    }
}

pub(crate) fn micros(start: Instant) -> f64 {
    start.elapsed().as_secs_f64() * 1e6
}
