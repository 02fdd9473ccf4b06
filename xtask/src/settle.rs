//! Bringing two objects into contact with the pipeline's own distances: the settle procedure
//! behind the paper scenes ([`crate::scenes`]) and the soak's pose generator
//! ([`crate::soak::pose_generator`]).
//!
//! Object A stands at the identity pose; only B moves. **Touch:** B moves along an approach
//! direction until the minimum distance is a gap g1 (bisection on the exact distance reported
//! by the pipeline). **Tilt:** B turns about the first contact point, about a chosen world axis,
//! while a translation along the first contact's normal keeps that contact at g1, until a second
//! local minimum reaches a second gap g2 (bisection on the angle). Both gaps must lie inside
//! the contact band, where the pipeline reports distances.

use contact_pipeline::{ContactPipeline, PairReport, PairState, PreparedObject, QueryScratch};
use geom_param::{DPose3, DQuat, DVec3};

/// Queries of one pair with A at the origin.
pub struct Settler<'p> {
    pipeline: &'p ContactPipeline,
    a: &'p PreparedObject,
    b: &'p PreparedObject,
    scratch: QueryScratch,
}

/// How a tilt turns B (world frame).
#[derive(Clone, Copy, Debug)]
pub struct TiltSpec {
    /// World axis of the rotation about the first contact (its sign sets the direction).
    pub axis: DVec3,
    /// Largest rotation tried (rad).
    pub max_angle: f64,
    /// Gap held at the first contact while turning (mm).
    pub first_gap: f64,
    /// Gap at which the second contact stops the turn (mm).
    pub second_gap: f64,
}

/// The smallest distance of a report for bisection (mm): −inf when penetrating, +inf when
/// separated, the smallest contact distance otherwise.
#[must_use]
pub fn min_distance(report: &PairReport) -> f64 {
    match report.state {
        PairState::Penetration => f64::NEG_INFINITY,
        PairState::Separated => f64::INFINITY,
        PairState::Contact => report
            .contacts
            .iter()
            .map(|c| c.distance)
            .fold(f64::INFINITY, f64::min),
    }
}

/// `pose` moved by `by` (world frame, mm).
#[must_use]
pub fn translated(pose: &DPose3, by: DVec3) -> DPose3 {
    DPose3 {
        rotation: pose.rotation,
        translation: pose.translation + by,
    }
}

/// `pose` turned by `angle` (rad) about the world axis through `pivot`.
#[must_use]
pub fn turned(pose: &DPose3, pivot: DVec3, axis: DVec3, angle: f64) -> DPose3 {
    let r = DQuat::from_axis_angle(axis, angle);
    DPose3 {
        rotation: (r * pose.rotation).normalize(),
        translation: pivot + r * (pose.translation - pivot),
    }
}

/// Finds x in [lo, hi] with f(x) = target, given f(lo) > target >= f(hi) (f need not be
/// continuous: it may jump to -inf or +inf where the state changes).
pub fn bisect(mut lo: f64, mut hi: f64, mut f: impl FnMut(f64) -> f64, target: f64) -> f64 {
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        let value = f(mid);
        if (value - target).abs() < 1e-10 || (hi - lo).abs() < 1e-14 {
            return mid;
        }
        if value > target { lo = mid } else { hi = mid }
    }
    0.5 * (lo + hi)
}

impl<'p> Settler<'p> {
    /// A settler for the pair (a, b) under `pipeline`'s options.
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
        }
    }

    /// The pipeline's options.
    #[must_use]
    pub fn options(&self) -> &contact_pipeline::ContactOptions {
        self.pipeline.options()
    }

    /// The pipeline's report with A at the identity and B at `pose_b`.
    ///
    /// # Errors
    /// The pipeline's error for a pose that is not a rigid motion.
    pub fn try_query(&mut self, pose_b: &DPose3) -> Result<PairReport, String> {
        self.pipeline
            .query(self.a, &DPose3::IDENTITY, self.b, pose_b, &mut self.scratch)
            .map_err(|e| e.to_string())
    }

    /// As [`Self::try_query`], with a failed query read as separated (+inf for
    /// [`min_distance`]): every pose the settler builds comes from unit quaternions and finite
    /// translations, so this does not happen.
    fn query(&mut self, pose_b: &DPose3) -> PairReport {
        self.try_query(pose_b).unwrap_or_default()
    }

    /// Moves B from `start` along `approach` (unit, world frame) in steps of half the margin,
    /// at most `max_travel` mm, until the minimum distance is `gap` (mm, inside the band).
    ///
    /// # Errors
    /// When B does not start clear of A or never comes within `gap` of it.
    pub fn touch(
        &mut self,
        start: &DPose3,
        approach: DVec3,
        gap: f64,
        max_travel: f64,
    ) -> Result<DPose3, String> {
        let step = 0.5 * self.pipeline.options().margin;
        if min_distance(&self.query(start)) <= gap {
            return Err("B does not start clear of A".into());
        }
        let mut t = 0.0;
        while t < max_travel {
            let next = t + step;
            if min_distance(&self.query(&translated(start, approach * next))) <= gap {
                let found = bisect(
                    t,
                    next,
                    |x| min_distance(&self.query(&translated(start, approach * x))),
                    gap,
                );
                return Ok(translated(start, approach * found));
            }
            t = next;
        }
        Err("B never reaches A".into())
    }

    /// `pose` moved along `away` in 5 mm steps until Stage 1 reports no component pair, then
    /// 5 mm more: a separated pose that stops after Stage 1.
    pub fn clear_of_broad_phase(&mut self, pose: &DPose3, away: DVec3) -> DPose3 {
        let mut moved = 5.0;
        while moved < 1000.0
            && self
                .query(&translated(pose, away * moved))
                .stats
                .component_pairs
                > 0
        {
            moved += 5.0;
        }
        translated(pose, away * (moved + 5.0))
    }

    /// The first contact (nearest `pivot`) and the smallest distance among the others
    /// (-inf when penetrating, +inf when there is none).
    fn split_contacts(
        &mut self,
        pose: &DPose3,
        pivot: DVec3,
    ) -> (Option<(f64, DVec3, DVec3)>, f64) {
        let report = self.query(pose);
        if report.state == PairState::Penetration {
            return (None, f64::NEG_INFINITY);
        }
        let nearest = report.contacts.iter().enumerate().min_by(|(_, x), (_, y)| {
            x.point_b
                .distance(pivot)
                .total_cmp(&y.point_b.distance(pivot))
        });
        let Some((k, first)) = nearest else {
            return (None, f64::INFINITY);
        };
        let others = report
            .contacts
            .iter()
            .enumerate()
            .filter(|(i, _)| *i != k)
            .map(|(_, c)| c.distance)
            .fold(f64::INFINITY, f64::min);
        (Some((first.distance, first.point_b, first.normal)), others)
    }

    /// Keeps the contact nearest `pivot` at `gap` by moving B along that contact's normal.
    fn resettle(&mut self, pose: DPose3, pivot: DVec3, gap: f64) -> (DPose3, DVec3, f64) {
        let mut pose = pose;
        let mut pivot = pivot;
        let mut others = f64::INFINITY;
        for _ in 0..4 {
            let (first, rest) = self.split_contacts(&pose, pivot);
            others = rest;
            let Some((distance, point_b, normal)) = first else {
                break;
            };
            pivot = point_b;
            if (distance - gap).abs() < 1e-12 {
                break;
            }
            pose = translated(&pose, normal * (gap - distance));
        }
        (pose, pivot, others)
    }

    /// Turns B about its first contact (the first one `touched` reports) until a second
    /// contact reaches `spec.second_gap`, in steps of 0.01 rad then bisection on the angle.
    ///
    /// # Errors
    /// When `touched` has no contact, or no second contact comes within `spec.max_angle`.
    pub fn tilt(&mut self, touched: DPose3, spec: &TiltSpec) -> Result<DPose3, String> {
        let report = self.query(&touched);
        let first = report
            .contacts
            .first()
            .ok_or("no first contact after touching")?;
        let (mut pose, mut pivot) = (touched, first.point_b);
        let step = 0.01;
        let mut angle = 0.0;
        while angle < spec.max_angle {
            let (next, next_pivot, others) =
                self.resettle(turned(&pose, pivot, spec.axis, step), pivot, spec.first_gap);
            angle += step;
            if others <= spec.second_gap {
                // Bisect the last step on the second contact's distance.
                let (base, base_pivot, axis) = (pose, pivot, spec.axis);
                let mut at = |x: f64| {
                    self.resettle(
                        turned(&base, base_pivot, axis, x),
                        base_pivot,
                        spec.first_gap,
                    )
                };
                let found = bisect(0.0, step, |x| at(x).2, spec.second_gap);
                let (settled, _, second) = at(found);
                // A second minimum that appears inside the band (not coming down through
                // delta2) is at the edge of existing there: no scene to keep.
                if (second - spec.second_gap).abs() > 1e-6 {
                    return Err(format!(
                        "the second contact appears at {second} mm, not continuously at {} mm",
                        spec.second_gap
                    ));
                }
                return Ok(settled);
            }
            pose = next;
            pivot = next_pivot;
        }
        Err(format!("no second contact within {} rad", spec.max_angle))
    }
}
