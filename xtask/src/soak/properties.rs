//! Properties every pose must satisfy, checked without an oracle (in the spirit of coal's
//! tests): each contact's own consistency, normals normal to both exact surfaces, the flip of
//! the state when B moves along the normal of the global minimum, and the same answer after a
//! rigid motion of the whole scene and with the objects swapped.
//!
//! Tolerances come from the contact's own diagnostics (see [`ContactTolerances`]); none is a
//! free constant except the rounding floors.

use crate::rng::SplitMix64;
use crate::soak::normal_cone::{angle, local_curvature, normal_cone};
use contact_pipeline::{
    Contact, ContactPipeline, PairReport, PairState, PreparedObject, QueryScratch,
};
use geom_param::{DPose3, DVec3, FeatureLocation, Solid};

/// Which property failed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Property {
    /// A NaN or infinity where the report promises a finite number.
    Finite,
    /// |normal| = 1, point_b = point_a + distance x normal, and each point is where its feature
    /// location evaluates to.
    Consistency,
    /// The normal lies in A's cone of outward normals at point_a and its negation in B's at
    /// point_b.
    SurfaceNormal,
    /// Moving B along the global minimum's normal so that its distance is delta1 - eps gives a
    /// penetration; delta1 + eps keeps that contact in the band.
    Flip,
    /// A rigid motion of the whole scene moves the contacts with it.
    RigidMotion,
    /// Swapping A and B swaps the points and negates the normals.
    Swap,
}

impl Property {
    /// Short name for tables.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Finite => "finite",
            Self::Consistency => "consistency",
            Self::SurfaceNormal => "surface-normal",
            Self::Flip => "flip",
            Self::RigidMotion => "rigid-motion",
            Self::Swap => "swap",
        }
    }
}

/// One failed property, with what was seen.
#[derive(Clone, Debug, PartialEq)]
pub struct PropertyFailure {
    /// Which property.
    pub property: Property,
    /// What was expected and what came out.
    pub detail: String,
}

/// Relative rounding floor: 64 ε.
const ROUNDING: f64 = 64.0 * f64::EPSILON;
/// Largest flip eps, relative to the band width: beyond it the flip is not tested.
const FLIP_MAX_EPS: f64 = 0.1;
/// Angle floor (rad) for normals built from coordinates of ~1e2 mm.
const ANGLE_FLOOR: f64 = 1e-9;
/// The pipeline's merge tolerance relative to the object size: two points this close are one
/// contact (`contact_pipeline`'s `merge_tolerance`), used where the point error estimate is
/// infinite (a continuous contact, where any point of the degenerate set is an answer).
const SAME_POINT: f64 = 1e-6;

/// What a contact's diagnostics allow, for comparing it with another answer for the same minimum.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContactTolerances {
    /// Points (mm): `point_error_estimate` (or 1e-6 x size where it is infinite) plus rounding.
    pub point: f64,
    /// Distance (mm): `error_estimate` plus rounding.
    pub distance: f64,
    /// Normal (rad): 1e-9 + the local curvature of both features x the point error, plus, when
    /// A's point is on an edge or vertex (the normal is then the direction of the connecting
    /// vector), twice the point error over |distance|.
    pub normal: f64,
}

impl ContactTolerances {
    /// The tolerances of `c` between solids `a` and `b` of size `size` (mm).
    #[must_use]
    pub fn of(c: &Contact, a: &Solid, b: &Solid, size: f64) -> Self {
        let coord = size + c.point_a.length().max(c.point_b.length());
        let pe = c.diagnostics.point_error_estimate;
        let pe = if pe.is_finite() {
            pe
        } else {
            SAME_POINT * size
        };
        let point = pe + ROUNDING * coord;
        let kappa = local_curvature(a, &c.location_a) + local_curvature(b, &c.location_b);
        // The pipeline's normal is a face's outward normal when either point is on a face, the
        // common normal of two edges, otherwise the direction of the connecting vector, good
        // to the point error over the distance.
        let exact = |l: &FeatureLocation| matches!(l, FeatureLocation::Face { .. });
        let edge = |l: &FeatureLocation| matches!(l, FeatureLocation::Edge { .. });
        let direction = if exact(&c.location_a)
            || exact(&c.location_b)
            || (edge(&c.location_a) && edge(&c.location_b))
        {
            0.0
        } else {
            2.0 * point / c.distance.abs()
        };
        Self {
            point,
            distance: c.diagnostics.error_estimate + ROUNDING * coord,
            normal: ANGLE_FLOOR + 4.0 * kappa * point + direction,
        }
    }

    /// The sum of two contacts' tolerances (two answers each with its own error).
    #[must_use]
    pub fn plus(self, other: Self) -> Self {
        Self {
            point: self.point + other.point,
            distance: self.distance + other.distance,
            normal: self.normal + other.normal,
        }
    }
}

/// A contact expected in another report: where its points, distance and normal should be.
#[derive(Clone, Copy, Debug)]
struct Expected {
    point_a: DVec3,
    point_b: DVec3,
    distance: f64,
    normal: DVec3,
    tolerances: ContactTolerances,
}

/// Runs the properties for one ordered pair.
pub struct PropertyChecker<'p> {
    pipeline: &'p ContactPipeline,
    a: &'p PreparedObject,
    b: &'p PreparedObject,
    scratch: QueryScratch,
    size: f64,
}

fn finite_contact(c: &Contact) -> bool {
    c.point_a.is_finite()
        && c.point_b.is_finite()
        && c.distance.is_finite()
        && c.normal.is_finite()
        && c.diagnostics.gradient_norm.is_finite()
        && c.diagnostics.error_estimate.is_finite()
        && !c.diagnostics.point_error_estimate.is_nan()
        && !c.diagnostics.condition.is_nan()
}

impl<'p> PropertyChecker<'p> {
    /// A checker for the ordered pair (a, b) under `pipeline`.
    #[must_use]
    pub fn new(
        pipeline: &'p ContactPipeline,
        a: &'p PreparedObject,
        b: &'p PreparedObject,
    ) -> Self {
        Self {
            pipeline,
            a,
            b,
            scratch: QueryScratch::default(),
            size: a.model.scale.max(b.model.scale),
        }
    }

    fn query(
        &mut self,
        swapped: bool,
        pose_a: &DPose3,
        pose_b: &DPose3,
    ) -> Result<PairReport, String> {
        let (a, b) = if swapped {
            (self.b, self.a)
        } else {
            (self.a, self.b)
        };
        self.pipeline
            .query(a, pose_a, b, pose_b, &mut self.scratch)
            .map_err(|e| e.to_string())
    }

    /// Every property of `report`, the pipeline's answer for A at the identity and B at
    /// `pose_b`. `rng` draws the rigid motion.
    ///
    /// # Errors
    /// A message when a re-query fails (the poses are rigid motions, so it does not).
    pub fn check(
        &mut self,
        pose_b: &DPose3,
        report: &PairReport,
        rng: &mut SplitMix64,
    ) -> Result<Vec<PropertyFailure>, String> {
        let mut failures = Vec::new();
        for c in &report.contacts {
            self.check_contact(c, pose_b, &mut failures);
        }
        self.check_flip(pose_b, report, &mut failures)?;
        let motion = DPose3 {
            rotation: rng.rotation(),
            translation: rng.direction() * rng.uniform(0.0, 500.0),
        };
        let moved = self.query(false, &motion, &(motion * *pose_b))?;
        let expected: Vec<Expected> = report
            .contacts
            .iter()
            .map(|c| Expected {
                point_a: motion * c.point_a,
                point_b: motion * c.point_b,
                distance: c.distance,
                normal: motion.rotation * c.normal,
                tolerances: self.tolerances(c),
            })
            .collect();
        self.compare(
            Property::RigidMotion,
            report.state,
            &expected,
            &moved,
            false,
            &mut failures,
        );
        let swapped = self.query(true, pose_b, &DPose3::IDENTITY)?;
        let expected: Vec<Expected> = report
            .contacts
            .iter()
            .map(|c| Expected {
                point_a: c.point_b,
                point_b: c.point_a,
                distance: c.distance,
                normal: -c.normal,
                tolerances: self.tolerances(c),
            })
            .collect();
        self.compare(
            Property::Swap,
            report.state,
            &expected,
            &swapped,
            true,
            &mut failures,
        );
        Ok(failures)
    }

    fn tolerances(&self, c: &Contact) -> ContactTolerances {
        ContactTolerances::of(c, &self.a.model.solid, &self.b.model.solid, self.size)
    }

    /// Finite numbers, consistency and surface normals of one contact (A at the identity).
    fn check_contact(&self, c: &Contact, pose_b: &DPose3, failures: &mut Vec<PropertyFailure>) {
        let mut fail =
            |property, detail: String| failures.push(PropertyFailure { property, detail });
        if !finite_contact(c) {
            fail(Property::Finite, format!("{c:?}"));
            return;
        }
        let tol = self.tolerances(c);
        let coord = self.size + c.point_a.length().max(c.point_b.length());
        if (c.normal.length() - 1.0).abs() > ROUNDING {
            fail(
                Property::Consistency,
                format!("|normal| - 1 = {:e}", c.normal.length() - 1.0),
            );
        }
        // The connecting vector's tangential part is the final residual (gradient_norm per
        // parameter direction, at most two directions per side).
        let relation = (c.point_b - c.point_a - c.distance * c.normal).length();
        let relation_tol = ROUNDING * coord + 4.0 * c.diagnostics.gradient_norm;
        if relation > relation_tol {
            fail(
                Property::Consistency,
                format!("|point_b - point_a - d n| = {relation:e} > {relation_tol:e}"),
            );
        }
        let at_a = self.a.model.solid.point_at(&c.location_a);
        let at_b = *pose_b * self.b.model.solid.point_at(&c.location_b);
        for (which, point, at) in [("a", c.point_a, at_a), ("b", c.point_b, at_b)] {
            let off = point.distance(at);
            if off > ROUNDING * coord {
                fail(
                    Property::Consistency,
                    format!("point_{which} is {off:e} mm from its feature location"),
                );
            }
        }
        let cones = [
            (
                "a",
                normal_cone(&self.a.model.solid, &c.location_a),
                c.normal,
            ),
            (
                "b",
                normal_cone(&self.b.model.solid, &c.location_b).map(|k| k.rotated(pose_b.rotation)),
                -c.normal,
            ),
        ];
        for (which, cone, n) in cones {
            match cone {
                None => fail(
                    Property::SurfaceNormal,
                    format!("no normal cone at location_{which}"),
                ),
                Some(cone) => {
                    let excess = cone.excess(n);
                    if excess > tol.normal {
                        fail(
                            Property::SurfaceNormal,
                            format!(
                                "d {:e}: normal {:e} rad outside {which}'s cone {cone:?} (tol {:e}) at {:?}",
                                c.distance,
                                excess,
                                tol.normal,
                                if which == "a" {
                                    c.location_a
                                } else {
                                    c.location_b
                                }
                            ),
                        );
                    }
                }
            }
        }
    }

    /// The flip: with d the smallest contact distance and n its normal, B moved by
    /// -(d - delta1) - eps along n penetrates, and by -(d - delta1) + eps keeps that contact (its
    /// points moved with B) at delta1 + eps. Translating B along n keeps the closest pair a
    /// critical pair at distance d + s exactly, and the minimum distance is 1-Lipschitz in the
    /// translation, so nothing else can come below delta1 + eps. eps = max(100 x the
    /// distance error estimate, 1e-9 x size); skipped when eps exceeds a tenth of the band (the
    /// contact's distance is then too uncertain to test the flip).
    fn check_flip(
        &mut self,
        pose_b: &DPose3,
        report: &PairReport,
        failures: &mut Vec<PropertyFailure>,
    ) -> Result<(), String> {
        if report.state != PairState::Contact {
            return Ok(());
        }
        let Some(c) = report
            .contacts
            .iter()
            .min_by(|x, y| x.distance.total_cmp(&y.distance))
        else {
            return Ok(());
        };
        let options = self.pipeline.options();
        let delta1 = options.delta1;
        let eps = (100.0 * c.diagnostics.error_estimate).max(1e-9 * self.size);
        if eps > FLIP_MAX_EPS * (options.delta2 - delta1) {
            // The distance is too uncertain for delta1 +- eps to test anything.
            return Ok(());
        }
        let shift = |s: f64| DPose3 {
            rotation: pose_b.rotation,
            translation: pose_b.translation + c.normal * s,
        };
        let base = -(c.distance - delta1);
        let into = self.query(false, &DPose3::IDENTITY, &shift(base - eps))?;
        if into.state != PairState::Penetration {
            failures.push(PropertyFailure {
                property: Property::Flip,
                detail: format!(
                    "moved to delta1 - {eps:e}: state {:?}, contacts {:?}",
                    into.state,
                    into.contacts.iter().map(|c| c.distance).collect::<Vec<_>>()
                ),
            });
        }
        let s = base + eps;
        let kept = self.query(false, &DPose3::IDENTITY, &shift(s))?;
        let tol = self.tolerances(c);
        let expected = Expected {
            point_a: c.point_a,
            point_b: c.point_b + c.normal * s,
            distance: delta1 + eps,
            normal: c.normal,
            tolerances: tol,
        };
        let found = kept.state == PairState::Contact
            && kept
                .contacts
                .iter()
                .any(|k| self.matches(&expected, k, false));
        if !found {
            failures.push(PropertyFailure {
                property: Property::Flip,
                detail: format!(
                    "moved to delta1 + {eps:e}: state {:?}, contacts (d, point_a) {:?}; expected d {:e} at {:?}",
                    kept.state,
                    kept.contacts
                        .iter()
                        .map(|k| (k.distance, k.point_a))
                        .collect::<Vec<_>>(),
                    expected.distance,
                    expected.point_a
                ),
            });
        }
        Ok(())
    }

    /// Whether `got` is the contact `expected` describes (`swapped`: `got` is from the query
    /// with B as the first object).
    fn matches(&self, expected: &Expected, got: &Contact, swapped: bool) -> bool {
        let (sa, sb) = if swapped {
            (&self.b.model.solid, &self.a.model.solid)
        } else {
            (&self.a.model.solid, &self.b.model.solid)
        };
        let tol = expected
            .tolerances
            .plus(ContactTolerances::of(got, sa, sb, self.size));
        got.point_a.distance(expected.point_a) <= tol.point
            && got.point_b.distance(expected.point_b) <= tol.point
            && (got.distance - expected.distance).abs() <= tol.distance
            && angle(got.normal, expected.normal) <= tol.normal
    }

    /// Compares a re-query with the contacts it should have: the same state and a one-to-one
    /// match, except for contacts within their distance tolerance of delta1 or delta2
    /// (borderline: either answer is right).
    fn compare(
        &self,
        property: Property,
        state: PairState,
        expected: &[Expected],
        got: &PairReport,
        swapped: bool,
        failures: &mut Vec<PropertyFailure>,
    ) {
        let options = self.pipeline.options();
        let near_edge = |d: f64, tol: f64| {
            (d - options.delta1).abs() <= tol || (d - options.delta2).abs() <= tol
        };
        let borderline = expected
            .iter()
            .any(|e| near_edge(e.distance, e.tolerances.distance))
            || got.contacts.iter().any(|c| {
                near_edge(
                    c.distance,
                    c.diagnostics.error_estimate + ROUNDING * self.size,
                )
            });
        if got.state != state && !borderline {
            failures.push(PropertyFailure {
                property,
                detail: format!("state {:?}, expected {state:?}", got.state),
            });
            return;
        }
        if got.state != state {
            return;
        }
        for e in expected {
            if !got.contacts.iter().any(|c| self.matches(e, c, swapped))
                && !near_edge(e.distance, e.tolerances.distance)
            {
                failures.push(PropertyFailure {
                    property,
                    detail: format!(
                        "contact d {:e} at {:?} / {:?} not found; got (d, point_a) {:?}",
                        e.distance,
                        e.point_a,
                        e.point_b,
                        got.contacts
                            .iter()
                            .map(|c| (c.distance, c.point_a))
                            .collect::<Vec<_>>()
                    ),
                });
            }
        }
        for c in &got.contacts {
            let extra = !expected.iter().any(|e| self.matches(e, c, swapped));
            if extra
                && !near_edge(
                    c.distance,
                    c.diagnostics.error_estimate + ROUNDING * self.size,
                )
            {
                failures.push(PropertyFailure {
                    property,
                    detail: format!(
                        "extra contact d {:e} at {:?} / {:?}",
                        c.distance, c.point_a, c.point_b
                    ),
                });
            }
        }
    }
}
