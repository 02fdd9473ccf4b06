//! [`ExactDispatcher`]: parry's [`QueryDispatcher`] answered by the contact pipeline for every
//! pair that involves an [`ExactShape`], and by a fallback dispatcher (parry's default) for
//! the rest.

use crate::counters::{DispatchCounters, DispatchPath};
use crate::exact_shape::ExactShape;
use crate::primitives::PrimitiveCache;
use contact_pipeline::{
    CoherenceOptions, Contact as PipelineContact, PairReport, PairState, QueryScratch,
};
use parry3d_f64::math::{Pose, Real, Vector};
use parry3d_f64::query::details::ShapeCastOptions;
use parry3d_f64::query::{
    ClosestPoints, Contact, DefaultQueryDispatcher, NonlinearRigidMotion, QueryDispatcher,
    ShapeCastHit, ShapeDistance, ShapeIntersection, Unsupported,
};
use parry3d_f64::shape::{Compound, Shape};
use std::sync::{Arc, Mutex};

/// What the dispatcher does with a question the pipeline cannot answer exactly: a pair of an
/// exact shape with a parry shape it cannot represent (anything but `Ball` and `Cuboid`), a
/// distance or closest points farther than the pipeline's band (delta2: the pipeline finds
/// every minimum up to there and no farther), or a penetration whose depth the pipeline could
/// not certify.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum BeyondReach {
    /// Answer `Err(Unsupported)` (and, for contact manifolds, leave none): never a wrong
    /// answer. Rapier ignores an unsupported pair, so such a pair does not collide.
    #[default]
    Unsupported,
    /// Hand the question to the fallback dispatcher with each exact shape replaced by its
    /// closed mesh ([`ExactShape::closed_mesh`], a parry `TriMesh`): an answer within the
    /// meshes' chordal errors of the exact one, not exact. A distance known to exceed delta2
    /// is never reported below delta2.
    MeshApproximation,
}

/// Options of an [`ExactDispatcher`].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct DispatcherOptions {
    /// Options of the coherent queries behind contact manifolds (one
    /// [`contact_pipeline::PairCache`] per pair, kept in parry's manifold workspace).
    pub coherence: CoherenceOptions,
    /// What to do beyond the pipeline's reach.
    pub beyond_reach: BeyondReach,
}

/// A parry query dispatcher that answers exactly, with the contact pipeline, every pair of
/// two [`ExactShape`]s (prepared by the same pipeline) and every pair of an [`ExactShape`]
/// with a parry `Ball` or `Cuboid` (turned into an exact sphere or box of the same size,
/// prepared once per size and cached), in either argument order; pairs without an exact
/// shape go to `fallback` (parry's [`DefaultQueryDispatcher`] by default), so mixed scenes
/// work. The rest ([`BeyondReach`]) is `Unsupported` or, on request, a mesh approximation.
///
/// Frames and units follow parry: `pos12` is the second shape's pose in the first one's frame;
/// points come back in each shape's own frame, normals from the first shape to the second;
/// lengths in the shapes' unit, which is the pipeline's millimetre (see [`ExactShape`]).
/// Distances are the pipeline's: exact (Stage 3 converged on the exact surfaces) and signed,
/// negative for a penetration depth (a point of one shape inside the other, to its nearest
/// boundary point: the pipeline's witness).
///
/// Not supported (always `Unsupported`, whatever [`BeyondReach`] says): shape casts (linear and
/// nonlinear time of impact), exact shapes inside a parry `Compound` (parry's compound code
/// would ask its own dispatcher about the parts), and two exact shapes of different pipelines.
///
/// Chaining: this type already falls back on `fallback` for pairs it does not own; chaining
/// it *after* another dispatcher with [`QueryDispatcher::chain`] is fine, but do not chain
/// parry's default dispatcher after it for the same pairs, or an `Unsupported` it gave for an
/// exact shape would reach parry, which can answer some of those pairs wrongly (a triangle
/// mesh against an unknown shape yields no contact at all).
pub struct ExactDispatcher<D = DefaultQueryDispatcher> {
    pub(crate) fallback: D,
    pub(crate) options: DispatcherOptions,
    primitives: PrimitiveCache,
    scratches: Mutex<Vec<QueryScratch>>,
    pub(crate) counters: Arc<DispatchCounters>,
}

impl ExactDispatcher {
    /// Exact answers for exact shapes, parry's default dispatcher for the rest.
    #[must_use]
    pub fn new(options: DispatcherOptions) -> Self {
        Self::with_fallback(DefaultQueryDispatcher, options)
    }
}

impl<D> ExactDispatcher<D> {
    /// Exact answers for exact shapes, `fallback` for the rest.
    #[must_use]
    pub fn with_fallback(fallback: D, options: DispatcherOptions) -> Self {
        Self {
            fallback,
            options,
            primitives: PrimitiveCache::default(),
            scratches: Mutex::new(Vec::new()),
            counters: Arc::new(DispatchCounters::default()),
        }
    }

    /// The options in force.
    #[must_use]
    pub fn options(&self) -> &DispatcherOptions {
        &self.options
    }

    /// A handle on the counts of answers by path, shared with this dispatcher (keep it before
    /// handing the dispatcher to rapier).
    #[must_use]
    pub fn counters(&self) -> Arc<DispatchCounters> {
        Arc::clone(&self.counters)
    }

    /// How this dispatcher sees the pair `(g1, g2)`.
    pub(crate) fn resolve(&self, g1: &dyn Shape, g2: &dyn Shape) -> Resolved {
        let e1 = g1.as_shape::<ExactShape>();
        let e2 = g2.as_shape::<ExactShape>();
        let pipeline = match (e1, e2) {
            (Some(s), _) | (None, Some(s)) => Arc::clone(s.pipeline()),
            (None, None) => {
                let hides_exact = |g: &dyn Shape| {
                    g.as_shape::<Compound>().is_some_and(|c| {
                        c.shapes()
                            .iter()
                            .any(|(_, s)| s.as_shape::<ExactShape>().is_some())
                    })
                };
                return if hides_exact(g1) || hides_exact(g2) {
                    Resolved::Refused
                } else {
                    Resolved::Fallback
                };
            }
        };
        let exact = |e: Option<&ExactShape>, g: &dyn Shape| match e {
            Some(s) => Arc::ptr_eq(s.pipeline(), &pipeline).then(|| s.clone()),
            None => self.primitives.exact_of(&pipeline, g),
        };
        match (exact(e1, g1), exact(e2, g2)) {
            (Some(a), Some(b)) => Resolved::Exact(Box::new((a, b))),
            _ if g1.as_shape::<Compound>().is_some() || g2.as_shape::<Compound>().is_some() => {
                Resolved::Refused
            }
            _ if e1.is_some() && e2.is_some() => Resolved::Refused,
            _ => Resolved::OutOfReach,
        }
    }

    /// Runs one (non-coherent) pipeline query of `pair` at `pos12` into a report, with a
    /// pooled scratch. `None` when the pipeline refuses the pose (not a rigid motion).
    pub(crate) fn query(
        &self,
        pair: &(ExactShape, ExactShape),
        pos12: &Pose,
    ) -> Option<PairReport> {
        let (a, b) = pair;
        let pool = || {
            self.scratches
                .lock()
                .unwrap_or_else(std::sync::PoisonError::into_inner)
        };
        let mut scratch = pool().pop().unwrap_or_default();
        let result = a.pipeline().query(
            a.object(),
            a.placement(),
            b.object(),
            &(*pos12 * *b.placement()),
            &mut scratch,
        );
        pool().push(scratch);
        self.counters.note(DispatchPath::Exact);
        result.ok()
    }
}

/// How the dispatcher sees a pair of shapes.
pub(crate) enum Resolved {
    /// Both shapes exact (as given, or a converted primitive), same pipeline.
    Exact(Box<(ExactShape, ExactShape)>),
    /// An exact shape with a parry shape it cannot represent: [`BeyondReach`] decides.
    OutOfReach,
    /// Not supported at all (see [`ExactDispatcher`]).
    Refused,
    /// No exact shape: the fallback's pair.
    Fallback,
}

/// The delta2 of the pipeline of `pair` (mm).
pub(crate) fn band_top(pair: &(ExactShape, ExactShape)) -> f64 {
    pair.0.pipeline().options().delta2
}

/// A penetrating report with no certified depth: no contact below zero to report.
pub(crate) fn depthless_penetration(report: &PairReport) -> bool {
    report.state == PairState::Penetration && !report.contacts.iter().any(|c| c.distance < 0.0)
}

/// The report's contact of least (signed) distance.
fn nearest(report: &PairReport) -> Option<&PipelineContact> {
    report
        .contacts
        .iter()
        .min_by(|x, y| x.distance.total_cmp(&y.distance))
}

/// Parry's contact from a pipeline contact whose frame is the first shape's (`pos12` places
/// the second shape there): `point2` and `normal2` go to the second shape's frame.
pub(crate) fn parry_contact(c: &PipelineContact, pos12: &Pose) -> Contact {
    Contact::new(
        c.point_a,
        pos12.inverse_transform_point(c.point_b),
        c.normal,
        -(pos12.rotation.inverse() * c.normal),
        c.distance,
    )
}

/// Each exact shape of `g` replaced by its closed mesh.
pub(crate) fn meshed(g: &dyn Shape) -> &dyn Shape {
    match g.as_shape::<ExactShape>() {
        Some(s) => &s.closed_mesh().trimesh,
        None => g,
    }
}

impl<D: QueryDispatcher> ExactDispatcher<D> {
    /// The fallback's answer on meshes when [`BeyondReach::MeshApproximation`], else
    /// `Unsupported`.
    fn beyond<T>(
        &self,
        g1: &dyn Shape,
        g2: &dyn Shape,
        ask: impl FnOnce(&D, &dyn Shape, &dyn Shape) -> Result<T, Unsupported>,
    ) -> Result<T, Unsupported> {
        match self.options.beyond_reach {
            BeyondReach::Unsupported => {
                self.counters.note(DispatchPath::Unsupported);
                Err(Unsupported)
            }
            BeyondReach::MeshApproximation => {
                self.counters.note(DispatchPath::Mesh);
                ask(&self.fallback, meshed(g1), meshed(g2))
            }
        }
    }

    fn refused<T>(&self) -> Result<T, Unsupported> {
        self.counters.note(DispatchPath::Unsupported);
        Err(Unsupported)
    }
}

impl<D: QueryDispatcher> QueryDispatcher for ExactDispatcher<D> {
    /// Intersecting when the exact surfaces touch or overlap: a penetration, or a minimum of
    /// distance <= 0. Exact for every distance (Stage 1 or 2 proves separation beyond the band).
    fn intersection_test(
        &self,
        pos12: &Pose,
        g1: &dyn Shape,
        g2: &dyn Shape,
    ) -> Result<ShapeIntersection, Unsupported> {
        match self.resolve(g1, g2) {
            Resolved::Fallback => self.fallback.intersection_test(pos12, g1, g2),
            Resolved::Refused => self.refused(),
            Resolved::OutOfReach => {
                self.beyond(g1, g2, |d, m1, m2| d.intersection_test(pos12, m1, m2))
            }
            Resolved::Exact(pair) => {
                let report = self.query(&pair, pos12).ok_or(Unsupported)?;
                let intersecting = report.state == PairState::Penetration
                    || report.contacts.iter().any(|c| c.distance <= 0.0);
                Ok(ShapeIntersection::new(intersecting))
            }
        }
    }

    /// The exact minimum distance, 0 when touching or penetrating, when it is at most the
    /// pipeline's delta2; beyond it, [`BeyondReach`] decides (a mesh distance is raised to
    /// delta2, which the exact one is known to exceed).
    fn distance(
        &self,
        pos12: &Pose,
        g1: &dyn Shape,
        g2: &dyn Shape,
    ) -> Result<ShapeDistance, Unsupported> {
        match self.resolve(g1, g2) {
            Resolved::Fallback => self.fallback.distance(pos12, g1, g2),
            Resolved::Refused => self.refused(),
            Resolved::OutOfReach => self.beyond(g1, g2, |d, m1, m2| d.distance(pos12, m1, m2)),
            Resolved::Exact(pair) => {
                let report = self.query(&pair, pos12).ok_or(Unsupported)?;
                if report.state == PairState::Penetration {
                    return Ok(ShapeDistance::new(0.0));
                }
                match nearest(&report) {
                    Some(c) => Ok(ShapeDistance::new(c.distance.max(0.0))),
                    None => {
                        let floor = band_top(&pair);
                        self.beyond(g1, g2, |d, m1, m2| d.distance(pos12, m1, m2))
                            .map(|mut r| {
                                r.distance = r.distance.max(floor);
                                r
                            })
                    }
                }
            }
        }
    }

    /// The exact contact of least signed distance (a penetration's certified depth, or the
    /// nearest minimum) when it is within `prediction`; `None` when the exact distance is known
    /// to exceed `prediction`. A penetration without a certified depth, or a `prediction`
    /// beyond delta2 with no minimum inside the band, is beyond reach.
    fn contact(
        &self,
        pos12: &Pose,
        g1: &dyn Shape,
        g2: &dyn Shape,
        prediction: Real,
    ) -> Result<Option<Contact>, Unsupported> {
        match self.resolve(g1, g2) {
            Resolved::Fallback => self.fallback.contact(pos12, g1, g2, prediction),
            Resolved::Refused => self.refused(),
            Resolved::OutOfReach => {
                self.beyond(g1, g2, |d, m1, m2| d.contact(pos12, m1, m2, prediction))
            }
            Resolved::Exact(pair) => {
                let report = self.query(&pair, pos12).ok_or(Unsupported)?;
                let beyond =
                    |s: &Self| s.beyond(g1, g2, |d, m1, m2| d.contact(pos12, m1, m2, prediction));
                if depthless_penetration(&report) {
                    return beyond(self);
                }
                match nearest(&report) {
                    Some(c) if c.distance <= prediction => Ok(Some(parry_contact(c, pos12))),
                    Some(_) => Ok(None),
                    None if prediction <= band_top(&pair) => Ok(None),
                    None => beyond(self),
                }
            }
        }
    }

    /// `Intersecting` when the exact surfaces touch or overlap; else the exact closest points
    /// (each in its shape's frame) when within `max_dist`, `Disjoint` when the exact distance is
    /// known to exceed `max_dist`; a `max_dist` beyond delta2 with no minimum inside the band
    /// is beyond reach.
    fn closest_points(
        &self,
        pos12: &Pose,
        g1: &dyn Shape,
        g2: &dyn Shape,
        max_dist: Real,
    ) -> Result<ClosestPoints, Unsupported> {
        match self.resolve(g1, g2) {
            Resolved::Fallback => self.fallback.closest_points(pos12, g1, g2, max_dist),
            Resolved::Refused => self.refused(),
            Resolved::OutOfReach => self.beyond(g1, g2, |d, m1, m2| {
                d.closest_points(pos12, m1, m2, max_dist)
            }),
            Resolved::Exact(pair) => {
                let report = self.query(&pair, pos12).ok_or(Unsupported)?;
                if report.state == PairState::Penetration {
                    return Ok(ClosestPoints::Intersecting);
                }
                match nearest(&report) {
                    Some(c) if c.distance <= 0.0 => Ok(ClosestPoints::Intersecting),
                    Some(c) if c.distance <= max_dist => Ok(ClosestPoints::WithinMargin(
                        c.point_a,
                        pos12.inverse_transform_point(c.point_b),
                    )),
                    Some(_) => Ok(ClosestPoints::Disjoint),
                    None if max_dist <= band_top(&pair) => Ok(ClosestPoints::Disjoint),
                    None => self.beyond(g1, g2, |d, m1, m2| {
                        d.closest_points(pos12, m1, m2, max_dist)
                    }),
                }
            }
        }
    }

    /// Only for pairs without an exact shape (the fallback's); `Unsupported` otherwise.
    fn cast_shapes(
        &self,
        pos12: &Pose,
        local_vel12: Vector,
        g1: &dyn Shape,
        g2: &dyn Shape,
        options: ShapeCastOptions,
    ) -> Result<Option<ShapeCastHit>, Unsupported> {
        match self.resolve(g1, g2) {
            Resolved::Fallback => self
                .fallback
                .cast_shapes(pos12, local_vel12, g1, g2, options),
            _ => self.refused(),
        }
    }

    /// Only for pairs without an exact shape (the fallback's); `Unsupported` otherwise.
    fn cast_shapes_nonlinear(
        &self,
        motion1: &NonlinearRigidMotion,
        g1: &dyn Shape,
        motion2: &NonlinearRigidMotion,
        g2: &dyn Shape,
        start_time: Real,
        end_time: Real,
        stop_at_penetration: bool,
    ) -> Result<Option<ShapeCastHit>, Unsupported> {
        match self.resolve(g1, g2) {
            Resolved::Fallback => self.fallback.cast_shapes_nonlinear(
                motion1,
                g1,
                motion2,
                g2,
                start_time,
                end_time,
                stop_at_penetration,
            ),
            _ => self.refused(),
        }
    }
}
