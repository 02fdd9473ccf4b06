//! Frame-to-frame coherence: a caller-owned per-pair cache ([`PairCache`]) that carries the last
//! answer into the next query, which then refines only the minima it tracks (Stage 3 warm
//! started from their feature locations) while a motion certificate shows that no other minimum
//! can have entered the band, and runs the full query otherwise. Contacts keep their
//! [`ContactId`] while they persist.
//!
//! # The certificate
//! Let D(x, P) = |p_a(x) − P p_b(x)| be the distance between a point pair x of the two surfaces
//! with B posed in A's frame by P (mm). The full query at P0 runs Stage 2 with the band widened
//! to `delta2 + s` (the slack s = `slack_fraction · (margin − delta2)`, so the widened band is
//! still inside the margin Stage 1 honours) and the cache keeps every local minimum it refined
//! in `[delta1, delta2 + s]` (the *tracked* minima). At a later P1 the cache computes
//!
//! ```text
//! moved = |P1 c − P0 c| + ω · r_B,   ω = angle of R1 R0⁻¹ ∈ [0, π],
//! ```
//!
//! with c and r_B the centre (B's frame) and radius of a ball holding B's surface
//! ([`PreparedObject::bounding_centre`], [`PreparedObject::bounding_radius`]): the length of the
//! path of any point of B in A's frame under the motion from P0 to P1 that moves c straight
//! at a constant rate and turns B about c at the constant rate ω (a point c + y moves at a
//! speed of at most |P1 c − P0 c| + ω |y|, |y| <= r_B). Along that path D(x, ·) changes by
//! at most `moved` for every fixed x, and so does the value of a local minimum followed
//! continuously (at a minimum ∇ₓD = 0, so d/ds D(x(s), s) = ∂D/∂s). Hence, when
//! `moved <= s`:
//! 1. a minimum at P1 with value <= delta2 followed back to P0 had value <= delta2 + s there,
//!    so it is one of the tracked minima (the full query found it: that is the pipeline's
//!    completeness, the same one a cold query relies on), whatever component pair it lies in
//!    (a component pair farther apart than the margin at P0 is farther than
//!    margin − s >= delta2 at P1);
//! 2. a minimum above `delta2 + s` at P0 stays above `delta2` at P1 and is not missed; by
//!    the same bound a tracked minimum last refined at P' with value v is not refined again
//!    while v − moved(P', P1) > delta2 (it cannot be in the band yet);
//! 3. each tracked minimum is followed by Newton from its last feature locations (or, while B
//!    moves at a steady pace, from their linear extrapolation, see [`warm_start`]), which the
//!    cache checks: every refinement must converge ([`RefineStatus::Converged`]) to an isolated
//!    local minimum (point error below [`ISOLATED_POINT_ERROR`]) at or above delta1, and no two
//!    tracked minima may reach the same point pair (a minimum that vanished or was jumped
//!    over). Any failure runs the full query instead.
//!
//! What motion cannot rule out is the *birth* of a minimum–saddle pair inside the band along
//! the path (a fold of the critical set, which needs a degenerate critical point: locally
//! conformal surfaces). The cache therefore never tracks a degenerate minimum
//! ([`RefineStatus::ContinuousContact`], or points known only loosely) and runs the full query
//! for such a pair every frame, and it limits a warm chain to
//! [`CoherenceOptions::max_warm_frames`] frames. Penetrating pairs always run the full query, as
//! does [`QueryDepth::StateOnly`].
//!
//! # Contact ids
//! A warm frame's contact keeps the id of the tracked minimum it came from. After a full query
//! each contact takes the id of the last frame's contact on the same feature pair nearest to it
//! (both points compared in their own object's frames), or failing that of any feature pair,
//! within [`CoherenceOptions::id_match_distance`]; each old id goes to one contact at most,
//! nearest pairs first; the rest get new ids.

use crate::merge::insert_or_merge;
use crate::options::QueryDepth;
use crate::pipeline::{
    ContactPipeline, FullQueryRecord, PreparedObject, QueryError, QueryScratch, check_pose,
    merge_tolerance, micros, to_world,
};
use crate::report::{PairReport, PairState};
use bvh_hybrid::BroadPhase;
use exact_refine::{RefineStatus, RefinedContact, Refiner};
use geom_param::{
    ComponentId, DPose3, FeatureId, FeatureLocation, ObjectModel, ParamRange, Seed, SeedPoint,
};
use glam::DVec3;
use mesh_narrowphase::MeshPhase;
use std::time::Instant;

/// A tracked minimum's refined point may be off the true minimum by at most this (mm) for the
/// cache to follow it: a looser point is a near-degenerate minimum, where a fold can create a
/// new minimum next to it.
pub const ISOLATED_POINT_ERROR: f64 = 1e-7;

/// Most Newton steps a warm refinement may take: following a minimum over a small motion takes
/// a few quadratically converging steps; more means the iteration went looking elsewhere.
pub const WARM_MAX_ITERATIONS: u32 = 12;

/// A followed minimum's points may move, each in its own object's frame, by at most this many
/// times the motion bound since it was last refined (plus [`ISOLATED_POINT_ERROR`]): a minimum
/// followed continuously moves with the motion, times the ratio of the surfaces' radii of
/// curvature to their relative one, which this allows up to.
pub const WARM_POINT_TRAVEL: f64 = 20.0;

/// Options of coherent queries.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CoherenceOptions {
    /// The slack s as a fraction of `margin − delta2`, in (0, 1]: the full query's band reaches
    /// `delta2 + s` and warm frames go on while B moved (relative to A, see the module
    /// documentation) by at most s since it. Larger: longer warm chains, more tracked minima.
    /// Default 0.25.
    pub slack_fraction: f64,
    /// Largest number of warm frames in a row before a full query (>= 0). Default 64.
    pub max_warm_frames: u32,
    /// Largest distance (mm, each point in its own object's frame) over which a contact found
    /// by a full query takes the id of the last frame's contact. Default 1.0.
    pub id_match_distance: f64,
}

impl Default for CoherenceOptions {
    fn default() -> Self {
        Self {
            slack_fraction: 0.25,
            max_warm_frames: 64,
            id_match_distance: 1.0,
        }
    }
}

/// A contact's identity across frames: equal ids in two frames of one [`PairCache`] mean the
/// same persisting contact (a physics solver carries its impulse over). Ids are numbered per
/// cache, that is per pair (from 1): key them by the pair and the id together.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct ContactId(pub u64);

/// How a coherent query was answered.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FrameKind {
    /// All three stages, with the band widened to track minima for the next frames.
    Full,
    /// Stage 3 only, from the tracked minima, under the motion certificate.
    Warm,
}

/// One tracked minimum: where it was when last refined (a seed on its features' parameters,
/// the points in their own objects' frames, the distance and B's pose in A's frame then), and
/// the id of its contact when it was last inside the band.
#[derive(Clone, Copy, Debug)]
struct Tracked {
    /// Feature locations with non-finite points: the refiner starts from the parameters.
    seed: Seed,
    local_a: DVec3,
    local_b: DVec3,
    distance: f64,
    at: DPose3,
    id: Option<ContactId>,
    /// The refinement before the last one, when the last one was a warm frame's.
    before: Option<Before>,
}

/// A tracked minimum's feature locations and B's pose at the refinement before its last one:
/// with the last one, a velocity of the minimum's parameters and of the pose.
#[derive(Clone, Copy, Debug)]
struct Before {
    a: FeatureLocation,
    b: FeatureLocation,
    at: DPose3,
}

impl Tracked {
    /// The minimum `m` refined with B posed by `pose_ab` in A's frame, `inverse_ab` being
    /// `pose_ab.inverse()`.
    #[allow(clippy::too_many_arguments)]
    fn new(
        m: &RefinedContact,
        ca: ComponentId,
        cb: ComponentId,
        pose_ab: &DPose3,
        inverse_ab: &DPose3,
        model_a: &ObjectModel,
        model_b: &ObjectModel,
        id: Option<ContactId>,
    ) -> Self {
        Self {
            seed: seed_from(m, ca, cb, model_a, model_b),
            local_a: m.point_a,
            local_b: *inverse_ab * m.point_b,
            distance: m.distance,
            at: *pose_ab,
            id,
            before: None,
        }
    }
}

/// The last frame's contact, for matching ids after a full query: points in the world frame
/// (each taken to its own object's frame with [`PairCache::last_poses`] when a full query
/// needs them, so a warm frame does not transform them) and features.
#[derive(Clone, Copy, Debug)]
struct LastContact {
    point_a: DVec3,
    point_b: DVec3,
    features: (FeatureId, FeatureId),
    id: ContactId,
}

/// Caller-owned state of one pair of objects across frames (see the module documentation):
/// keep one per pair, pass it to every [`ContactPipeline::query_coherent`] of that pair in
/// order. It remembers which objects it was used with and starts over (full query, new ids)
/// when given others.
#[derive(Clone, Debug, Default)]
pub struct PairCache {
    /// Identity of the objects and options the state belongs to.
    key: Option<[u64; 6]>,
    /// B's pose in A's frame at the last full query, when its minima are tracked.
    reference: Option<DPose3>,
    slack: f64,
    /// B's bounding ball (centre in B's frame, radius), for the motion bound.
    ball_b: (DVec3, f64),
    warm_frames: u32,
    tracked: Vec<Tracked>,
    last: Vec<LastContact>,
    /// A's and B's world poses (normalised) of the frame of `last`.
    last_poses: (DPose3, DPose3),
    ids: Vec<ContactId>,
    next_id: u64,
    kind: Option<FrameKind>,
    /// Whether the last report was a penetration (the next full query then runs unrecorded).
    penetrating: bool,
    record: FullQueryRecord,
    /// Buffer of a warm frame's refinements (tracked index, result).
    refined_now: Vec<(usize, RefinedContact)>,
}

impl PairCache {
    /// An empty cache (the first query is a full one).
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    /// The ids of the last report's contacts, in the report's order.
    #[must_use]
    pub fn contact_ids(&self) -> &[ContactId] {
        &self.ids
    }

    /// How the last query was answered (`None` before the first).
    #[must_use]
    pub fn last_frame(&self) -> Option<FrameKind> {
        self.kind
    }

    /// How many minima the warm frames follow (0 when the next query must be full).
    #[must_use]
    pub fn tracked_minima(&self) -> usize {
        if self.reference.is_some() {
            self.tracked.len()
        } else {
            0
        }
    }

    /// Forgets the tracked minima (the next query is full) but keeps the ids for matching.
    pub fn invalidate(&mut self) {
        self.reference = None;
        self.tracked.clear();
    }
}

impl<B: BroadPhase, M: MeshPhase, R: Refiner> ContactPipeline<B, M, R> {
    /// Queries one pair as [`Self::query_into`] does (same report, world frame), using and
    /// updating `cache`: a warm frame (Stage 3 only, from the tracked minima) when the motion
    /// certificate of the [module documentation](crate::coherence) holds and every tracked
    /// minimum refines cleanly, the full query otherwise. The contacts' ids are then in
    /// [`PairCache::contact_ids`]. Returns which path answered.
    ///
    /// # Errors
    /// As [`Self::query`]; and [`QueryError::BadCoherence`] for unusable `coherence` options.
    #[allow(clippy::too_many_arguments)]
    pub fn query_coherent(
        &self,
        a: &PreparedObject<B, M>,
        pose_a: &DPose3,
        b: &PreparedObject<B, M>,
        pose_b: &DPose3,
        coherence: &CoherenceOptions,
        cache: &mut PairCache,
        scratch: &mut QueryScratch<B, M, R>,
        report: &mut PairReport,
    ) -> Result<FrameKind, QueryError> {
        let fraction = coherence.slack_fraction;
        if !(fraction > 0.0 && fraction <= 1.0 && coherence.id_match_distance >= 0.0) {
            return Err(QueryError::BadCoherence(format!(
                "slack_fraction = {fraction} must be in (0, 1] and id_match_distance = {} >= 0",
                coherence.id_match_distance
            )));
        }
        let checked_a = check_pose(pose_a, "a")?;
        let checked_b = check_pose(pose_b, "b")?;
        let pose_ab = checked_a.inverse() * checked_b;
        let options = self.options();
        let key = [
            std::ptr::from_ref(a) as u64,
            std::ptr::from_ref(b) as u64,
            a.model.solid.faces.len() as u64 | ((b.model.solid.faces.len() as u64) << 32),
            options.margin.to_bits(),
            options.delta2.to_bits() ^ options.delta1.to_bits().rotate_left(17),
            fraction.to_bits(),
        ];
        if cache.key != Some(key) {
            cache.key = Some(key);
            cache.invalidate();
            cache.last.clear();
            cache.ids.clear();
            cache.penetrating = false;
        }
        // The last frame's contacts, for a full query's ids; the buffer is refilled below.
        let mut last = std::mem::take(&mut cache.last);

        let warm_allowed = options.depth == QueryDepth::Contacts
            && cache.warm_frames < coherence.max_warm_frames
            && cache
                .reference
                .is_some_and(|p0| motion_bound(&p0, &pose_ab, cache.ball_b) <= cache.slack);
        let kind = if warm_allowed && self.warm(a, b, &checked_a, &pose_ab, cache, scratch, report)
        {
            cache.warm_frames += 1;
            FrameKind::Warm
        } else {
            let full = self.full(
                a, pose_a, b, pose_b, &pose_ab, fraction, cache, scratch, report,
            );
            if let Err(e) = full {
                cache.last = last;
                return Err(e);
            }
            assign_full_ids(cache, &last, report, &checked_a, &checked_b, coherence);
            FrameKind::Full
        };
        cache.kind = Some(kind);
        last.clear();
        last.extend(
            report
                .contacts
                .iter()
                .zip(&cache.ids)
                .map(|(c, &id)| LastContact {
                    point_a: c.point_a,
                    point_b: c.point_b,
                    features: (c.location_a.feature(), c.location_b.feature()),
                    id,
                }),
        );
        cache.last = last;
        cache.last_poses = (checked_a, checked_b);
        Ok(kind)
    }

    /// The full query with the widened band; sets up the tracked minima when the answer allows
    /// warm frames (no penetration, every minimum isolated).
    ///
    /// A penetrating pair is answered by the plain query: its witnesses and depths come from
    /// the seeds of Stage 2's mesh overlaps, which the widened band changes (it adds seeds, and
    /// so may add regions), and the report must be the cold query's. So a full query right
    /// after a penetration runs unrecorded (nothing is tracked while the pair penetrates), and
    /// a recorded one that comes out penetrating is run again unrecorded.
    #[allow(clippy::too_many_arguments)]
    fn full(
        &self,
        a: &PreparedObject<B, M>,
        pose_a: &DPose3,
        b: &PreparedObject<B, M>,
        pose_b: &DPose3,
        pose_ab: &DPose3,
        fraction: f64,
        cache: &mut PairCache,
        scratch: &mut QueryScratch<B, M, R>,
        report: &mut PairReport,
    ) -> Result<(), QueryError> {
        let options = self.options();
        cache.invalidate();
        cache.warm_frames = 0;
        if options.depth != QueryDepth::Contacts || cache.penetrating {
            let result = self.query_into(a, pose_a, b, pose_b, scratch, report);
            cache.penetrating = report.state == PairState::Penetration;
            return result;
        }
        let slack = fraction * (options.margin - options.delta2);
        let mut record = std::mem::take(&mut cache.record);
        record.slack = slack;
        let mut result =
            self.query_recorded(a, pose_a, b, pose_b, scratch, report, Some(&mut record));
        if result.is_ok() && report.state == PairState::Penetration {
            result = self.query_into(a, pose_a, b, pose_b, scratch, report);
        }
        cache.penetrating = report.state == PairState::Penetration;
        let trackable = result.is_ok()
            && report.state != PairState::Penetration
            && record.minima.iter().all(|(m, _, _)| isolated(m));
        if trackable {
            let inverse_ab = pose_ab.inverse();
            cache
                .tracked
                .extend(record.minima.iter().map(|(m, ca, cb)| {
                    Tracked::new(m, *ca, *cb, pose_ab, &inverse_ab, &a.model, &b.model, None)
                }));
            cache.reference = Some(*pose_ab);
            cache.slack = slack;
            cache.ball_b = (b.bounding_centre, b.bounding_radius);
        }
        cache.record = record;
        result
    }

    /// Refines every tracked minimum at `pose_ab` into `report` (cleared first). Returns false,
    /// leaving the cache's tracked minima unusable, when one of the checks of the module
    /// documentation fails.
    #[allow(clippy::too_many_arguments)]
    fn warm(
        &self,
        a: &PreparedObject<B, M>,
        b: &PreparedObject<B, M>,
        pose_a: &DPose3,
        pose_ab: &DPose3,
        cache: &mut PairCache,
        scratch: &mut QueryScratch<B, M, R>,
        report: &mut PairReport,
    ) -> bool {
        report.clear();
        let options = self.options();
        let start = Instant::now();
        let scale = a.model.scale.max(b.model.scale);
        cache.ids.clear();
        let ball = cache.ball_b;
        let inverse_ab = pose_ab.inverse();
        // The motion bound since the pose a minimum was last refined at: minima refined in the
        // same frame share it, so the last one is kept.
        let mut last_bound: Option<(DPose3, f64)> = None;
        // Whether B's motion is steady since the two poses a minimum was last refined at (the
        // same for minima refined in the same frames, so the last answer is kept).
        let mut last_steady: Option<(DPose3, DPose3, bool)> = None;
        // Pass 1: refine the minima that may be in the band now (a minimum's value changes by
        // at most the motion since it was refined) and check that each was followed.
        let mut refined_now = std::mem::take(&mut cache.refined_now);
        refined_now.clear();
        for (k, t) in cache.tracked.iter().enumerate() {
            let moved = match last_bound {
                Some((at, moved)) if same_pose(&at, &t.at) => moved,
                _ => {
                    let moved = motion_bound(&t.at, pose_ab, ball);
                    last_bound = Some((t.at, moved));
                    moved
                }
            };
            if t.distance - moved > options.delta2 {
                continue;
            }
            let seed = match t.before {
                Some(before) => {
                    let steady = match last_steady {
                        Some((at0, at1, steady))
                            if same_pose(&at0, &before.at) && same_pose(&at1, &t.at) =>
                        {
                            steady
                        }
                        _ => {
                            let steady = steady_motion(&before.at, &t.at, pose_ab, ball, moved);
                            last_steady = Some((before.at, t.at, steady));
                            steady
                        }
                    };
                    if steady {
                        warm_start(t, &before, &a.model, &b.model)
                    } else {
                        t.seed
                    }
                }
                None => t.seed,
            };
            let refined = self.refiner.refine(
                &a.model.solid,
                &b.model.solid,
                pose_ab,
                &seed,
                scratch.refine_scratch(),
            );
            report.stats.refined += 1;
            let travel = WARM_POINT_TRAVEL * moved + ISOLATED_POINT_ERROR;
            let local_b = inverse_ab * refined.point_b;
            let followed = isolated(&refined)
                && refined.diagnostics.iterations <= WARM_MAX_ITERATIONS
                && refined.point_a.distance(t.local_a) <= travel
                && local_b.distance(t.local_b) <= travel
                && refined.distance >= options.delta1;
            let tolerance = merge_tolerance(&refined, scale);
            let distinct = refined_now.iter().all(|(_, r)| {
                r.point_a.distance(refined.point_a) > tolerance
                    || r.point_b.distance(refined.point_b) > tolerance
            });
            if !(followed && distinct) {
                cache.invalidate();
                cache.refined_now = refined_now;
                return false;
            }
            refined_now.push((k, refined));
        }
        report.stats.refine_ran = !refined_now.is_empty();
        // Pass 2: update them and report those in the band, in tracking order.
        for (k, refined) in &refined_now {
            let t = &mut cache.tracked[*k];
            let before = Before {
                a: t.seed.a.location,
                b: t.seed.b.location,
                at: t.at,
            };
            *t = Tracked::new(
                refined,
                t.seed.a.component,
                t.seed.b.component,
                pose_ab,
                &inverse_ab,
                &a.model,
                &b.model,
                t.id,
            );
            t.before = Some(before);
            if refined.distance <= options.delta2 {
                let tolerance = merge_tolerance(refined, scale);
                // Distinct points (checked above): never merged.
                insert_or_merge(
                    &mut report.contacts,
                    to_world(refined, pose_a),
                    tolerance,
                    (&a.model.solid, &b.model.solid),
                );
                let id = *t.id.get_or_insert_with(|| {
                    cache.next_id += 1;
                    ContactId(cache.next_id)
                });
                cache.ids.push(id);
            } else {
                t.id = None;
            }
        }
        if !report.contacts.is_empty() {
            report.state = PairState::Contact;
        }
        report.stats.refine_us = micros(start);
        cache.refined_now = refined_now;
        true
    }
}

/// A minimum the cache can follow: converged, isolated, points known to
/// [`ISOLATED_POINT_ERROR`].
fn isolated(m: &RefinedContact) -> bool {
    m.diagnostics.status == RefineStatus::Converged
        && m.diagnostics.is_local_minimum
        && m.diagnostics.point_error_estimate <= ISOLATED_POINT_ERROR
}

/// Whether B moves at a steady pace: the pose one more step of the motion from `at0` (the pose
/// of the refinement before the last) to `at1` (the last) would reach is nearer to `pose_ab`,
/// in the motion bound, than `at1` itself is (`moved`).
fn steady_motion(
    at0: &DPose3,
    at1: &DPose3,
    pose_ab: &DPose3,
    ball: (DVec3, f64),
    moved: f64,
) -> bool {
    let step = *at1 * at0.inverse();
    motion_bound(&(step * *at1), pose_ab, ball) < moved
}

/// The start of a tracked minimum's refinement while B moves at a steady pace: each side's
/// parameters moved on by their last change (x1 + (x1 − x0), a periodic change taken the
/// short way round), the predictor of a constant-velocity path; a side on another feature than
/// before, on a vertex, or whose prediction leaves its feature's parameter range starts where
/// it was. Only the start moves: the answer is Newton's from there, checked like any other
/// (module documentation, point 3), and a minimum followed over a small motion converges in
/// one step fewer from a start that is off by the change of its velocity rather than by its
/// velocity.
fn warm_start(t: &Tracked, before: &Before, model_a: &ObjectModel, model_b: &ObjectModel) -> Seed {
    let mut seed = t.seed;
    seed.a.location = extrapolated(before.a, t.seed.a.location, model_a);
    seed.b.location = extrapolated(before.b, t.seed.b.location, model_b);
    seed
}

/// `now` moved on by its change since `previous` (see [`warm_start`]), or `now`.
fn extrapolated(
    previous: FeatureLocation,
    now: FeatureLocation,
    model: &ObjectModel,
) -> FeatureLocation {
    let on = |range: ParamRange, x0: f64, x1: f64| {
        let mut change = x1 - x0;
        if range.periodic {
            let period = range.max - range.min;
            change -= period * (change / period).round();
        }
        let x = x1 + change;
        (x.is_finite() && (range.periodic || (x > range.min && x < range.max))).then_some(x)
    };
    let solid = &model.solid;
    let moved = match (previous, now) {
        (
            FeatureLocation::Face {
                id: f0,
                u: u0,
                v: v0,
            },
            FeatureLocation::Face { id, u, v },
        ) if f0 == id => solid.faces.get(id.0 as usize).and_then(|face| {
            let [du, dv] = face.surface.domain();
            Some(FeatureLocation::Face {
                id,
                u: on(du, u0, u)?,
                v: on(dv, v0, v)?,
            })
        }),
        (FeatureLocation::Edge { id: e0, t: t0 }, FeatureLocation::Edge { id, t }) if e0 == id => {
            solid.edges.get(id.0 as usize).and_then(|edge| {
                Some(FeatureLocation::Edge {
                    id,
                    t: on(edge.curve.domain(), t0, t)?,
                })
            })
        }
        _ => None,
    };
    moved.unwrap_or(now)
}

/// Whether two poses are the same bits (so that a function of one is the same for the other).
fn same_pose(p: &DPose3, q: &DPose3) -> bool {
    let bits = |p: &DPose3| {
        [
            p.translation.x,
            p.translation.y,
            p.translation.z,
            p.rotation.x,
            p.rotation.y,
            p.rotation.z,
            p.rotation.w,
        ]
        .map(f64::to_bits)
    };
    bits(p) == bits(q)
}

/// The path length bound of the module documentation: |P1 c − P0 c| + ω r (mm) for the ball
/// (c, r), ω the rotation angle of R1 R0⁻¹.
fn motion_bound(p0: &DPose3, p1: &DPose3, (centre, radius): (DVec3, f64)) -> f64 {
    let relative = p1.rotation * p0.rotation.inverse();
    // Angle from the quaternion's vector part and scalar part (stable near 0 and π).
    let w = relative.w.abs();
    let v = DVec3::new(relative.x, relative.y, relative.z).length();
    let omega = 2.0 * v.atan2(w);
    (*p1 * centre - *p0 * centre).length() + omega * radius
}

/// A seed on `m`'s features and parameters, with the component of each face, or `ca` / `cb`
/// for an edge or vertex. Its points are not finite: the refiner starts from the parameters
/// (the [`Refiner`] contract allows either), which are the exact minimum already, so no
/// projection is needed.
fn seed_from(
    m: &RefinedContact,
    ca: ComponentId,
    cb: ComponentId,
    model_a: &ObjectModel,
    model_b: &ObjectModel,
) -> Seed {
    let component = |location: &FeatureLocation, model: &ObjectModel, fallback| match location {
        FeatureLocation::Face { id, .. } if (id.0 as usize) < model.solid.faces.len() => {
            model.component_of_face(*id)
        }
        _ => fallback,
    };
    Seed {
        a: SeedPoint {
            component: component(&m.location_a, model_a, ca),
            local_point: DVec3::NAN,
            location: m.location_a,
        },
        b: SeedPoint {
            component: component(&m.location_b, model_b, cb),
            local_point: DVec3::NAN,
            location: m.location_b,
        },
    }
}

/// Ids for a full query's contacts: the last frame's contact on the same features nearest in
/// both objects' frames (within `id_match_distance`), then any nearest, nearest pairs first;
/// new ids for the rest. Also hands the ids to the tracked minima whose points are a contact's.
fn assign_full_ids(
    cache: &mut PairCache,
    old: &[LastContact],
    report: &PairReport,
    pose_a: &DPose3,
    pose_b: &DPose3,
    coherence: &CoherenceOptions,
) {
    let (inv_a, inv_b) = (pose_a.inverse(), pose_b.inverse());
    let (old_inv_a, old_inv_b) = (cache.last_poses.0.inverse(), cache.last_poses.1.inverse());
    let mut candidates: Vec<(bool, f64, usize, usize)> = Vec::new();
    for (i, c) in report.contacts.iter().enumerate() {
        let (la, lb) = (inv_a * c.point_a, inv_b * c.point_b);
        let features = (c.location_a.feature(), c.location_b.feature());
        for (j, o) in old.iter().enumerate() {
            let (old_a, old_b) = (old_inv_a * o.point_a, old_inv_b * o.point_b);
            let d = la.distance(old_a).max(lb.distance(old_b));
            if d <= coherence.id_match_distance {
                candidates.push((o.features != features, d, i, j));
            }
        }
    }
    candidates.sort_by(|x, y| {
        x.0.cmp(&y.0)
            .then(x.1.total_cmp(&y.1))
            .then((x.2, x.3).cmp(&(y.2, y.3)))
    });
    let mut ids: Vec<Option<ContactId>> = vec![None; report.contacts.len()];
    let mut used = vec![false; old.len()];
    for (_, _, i, j) in candidates {
        if ids[i].is_none() && !used[j] {
            ids[i] = Some(old[j].id);
            used[j] = true;
        }
    }
    cache.ids = ids
        .into_iter()
        .map(|id| {
            id.unwrap_or_else(|| {
                cache.next_id += 1;
                ContactId(cache.next_id)
            })
        })
        .collect();
    // The tracked minima inside the band are the report's contacts (the same refinements).
    let pose_a_copy = *pose_a;
    for t in &mut cache.tracked {
        let point_a = pose_a_copy * t.local_a;
        t.id = report
            .contacts
            .iter()
            .zip(&cache.ids)
            .filter(|(c, _)| c.point_a.distance(point_a) <= 1e-6 * (1.0 + point_a.length()))
            .map(|(_, &id)| id)
            .next();
    }
}

#[cfg(test)]
mod tests {
    use super::{extrapolated, motion_bound, steady_motion};
    use crate::{ContactOptions, ContactPipeline};
    use geom_param::{DPose3, DQuat, DVec3, FaceId, FeatureLocation, ObjectDescription, VertexId};

    /// A ball of radius 10 mm: one face of revolution, u the angle about z (periodic, [0, 2π)),
    /// v in [0, 1] from pole to pole.
    fn ball() -> geom_param::ObjectModel {
        let pipeline = ContactPipeline::new(ContactOptions::default()).expect("options");
        let ball = ObjectDescription::from_json(
            r#"{"name": "ball", "profile": [{"arc": {"center": [0, 0], "from": [0, -10], "to": [0, 10], "ccw": true}}]}"#,
        )
        .expect("description");
        pipeline.prepare_description(&ball).expect("prepares").model
    }

    /// The prediction moves each parameter on by its last change (a periodic one the short way
    /// across 2π), and keeps a location whose prediction would leave its range, changes
    /// feature, or has no parameters.
    #[test]
    fn extrapolation_moves_parameters_on_by_their_last_change() {
        let model = ball();
        let face = |u, v| FeatureLocation::Face {
            id: FaceId(0),
            u,
            v,
        };
        let two_pi = std::f64::consts::TAU;
        // u went from 6.2 across 2π to 0.05: a change of 0.05 + 2π − 6.2.
        let FeatureLocation::Face { u, v, .. } =
            extrapolated(face(6.2, 0.5), face(0.05, 0.52), &model)
        else {
            panic!("a face stays a face");
        };
        assert!((u - (0.05 + (0.05 + two_pi - 6.2))).abs() < 1e-12, "u {u}");
        assert!((v - 0.54).abs() < 1e-12, "v {v}");
        // v would reach 1.03, beyond the pole: the start stays where it is.
        assert_eq!(
            extrapolated(face(1.0, 0.95), face(1.0, 0.99), &model),
            face(1.0, 0.99)
        );
        let vertex = FeatureLocation::Vertex { id: VertexId(0) };
        assert_eq!(extrapolated(vertex, face(1.0, 0.5), &model), face(1.0, 0.5));
        assert_eq!(extrapolated(face(1.0, 0.5), vertex, &model), vertex);
    }

    /// Equal steps of a turn are steady; a step that undoes the last one (a reversal) and a
    /// pause are not.
    #[test]
    fn steady_motion_is_a_repeated_step() {
        let ball = (DVec3::new(0.0, 0.0, 5.0), 10.0);
        let turn = |angle: f64| {
            DPose3::from_parts(DVec3::new(20.0, 0.0, 0.0), DQuat::from_rotation_x(angle))
        };
        let (p0, p1) = (turn(0.0), turn(1e-3));
        let moved = |p: &DPose3| motion_bound(&p1, p, ball);
        let p2 = turn(2e-3);
        assert!(steady_motion(&p0, &p1, &p2, ball, moved(&p2)));
        assert!(!steady_motion(&p0, &p1, &p0, ball, moved(&p0)));
        assert!(!steady_motion(&p0, &p1, &p1, ball, moved(&p1)));
    }

    /// The bound covers the straight displacement of every point of the ball (sampled densely
    /// on its sphere, where the largest displacement lies), and equals the closed forms of a
    /// pure translation and a pure turn about the centre.
    #[test]
    fn motion_bound_covers_every_point_of_the_ball() {
        let centre = DVec3::new(3.0, -2.0, 40.0);
        let radius = 25.0;
        let p0 = DPose3::from_parts(
            DVec3::new(10.0, 5.0, -3.0),
            DQuat::from_euler(glam::EulerRot::XYZ, 0.3, -0.2, 1.1),
        );
        let shift = DVec3::new(0.01, -0.02, 0.005);
        let translated = DPose3::from_parts(p0.translation + shift, p0.rotation);
        let tolerance = 1e-12 * radius;
        assert!(
            (motion_bound(&p0, &translated, (centre, radius)) - shift.length()).abs() < tolerance
        );
        let angle = 1e-3;
        let turn = DQuat::from_axis_angle(DVec3::new(1.0, 2.0, 2.0) / 3.0, angle);
        let c_world = p0 * centre;
        let turned = DPose3::from_parts(c_world - turn * c_world, turn) * p0;
        assert!((motion_bound(&p0, &turned, (centre, radius)) - angle * radius).abs() < 1e-9);
        for p1 in [translated, turned, DPose3::from_parts(shift, turn) * p0] {
            let bound = motion_bound(&p0, &p1, (centre, radius));
            for i in 0..40 {
                for j in 0..80 {
                    let (theta, phi) = (
                        std::f64::consts::PI * (i as f64 + 0.5) / 40.0,
                        std::f64::consts::TAU * j as f64 / 80.0,
                    );
                    let x = centre
                        + radius
                            * DVec3::new(
                                theta.sin() * phi.cos(),
                                theta.sin() * phi.sin(),
                                theta.cos(),
                            );
                    assert!((p1 * x).distance(p0 * x) <= bound + tolerance);
                }
            }
        }
    }
}
