//! The paper's scenes (Table 3, Figs. 3-6), found by a settle procedure.
//!
//! For each pair, object A stands at the origin and object B starts clear of it with a chosen
//! orientation. **Touch:** B moves along the approach direction until the minimum distance is
//! the first gap g1 (bisection on the exact distance reported by the pipeline). **Rotate:** B
//! turns about the first contact point, about a chosen axis, while a translation along the
//! first contact's normal keeps that contact at g1, until a second local minimum reaches the
//! second gap g2 (bisection on the angle). Both gaps are inside the contact band. From the same
//! run come a single-contact scene (after the touch), a separated scene (the touch moved back by
//! 5 mm) and, for the pencil and the bowl, a penetrating scene.

use contact_pipeline::{
    ContactOptions, ContactPipeline, PairReport, PairState, PreparedObject, QueryScratch,
};
use geom_param::{DPose3, DQuat, DVec3, ObjectDescription};
use serde_json::{Value, json};

/// Gaps of the first and second contact (mm), inside the default band [-0.001, 0.1].
const FIRST_GAP: f64 = 0.02;
const SECOND_GAP: f64 = 0.05;

/// How a pair is brought together.
struct SettleSpec {
    pair: &'static str,
    a: &'static str,
    b: &'static str,
    /// B's orientation.
    rotation: DQuat,
    /// B's start position (clear of A).
    start: DVec3,
    /// Unit direction B moves in to touch A.
    approach: DVec3,
    /// World axis of the rotation about the first contact (its sign sets the direction).
    tilt_axis: DVec3,
    /// Largest rotation tried (rad).
    max_tilt: f64,
}

fn specs() -> Vec<SettleSpec> {
    use std::f64::consts::FRAC_PI_2;
    vec![
        // The pencil lying across the paperweight's ball, then tipping onto the base's rim.
        SettleSpec {
            pair: "pencil-paperweight",
            a: "paperweight",
            b: "pencil",
            rotation: DQuat::from_rotation_y(FRAC_PI_2),
            start: DVec3::new(-60.0, 0.0, 70.0),
            approach: DVec3::NEG_Z,
            tilt_axis: DVec3::Y,
            max_tilt: 1.2,
        },
        // The paperweight's ball against the goblet's cup, then its base against the foot.
        SettleSpec {
            pair: "paperweight-goblet",
            a: "goblet",
            b: "paperweight",
            rotation: DQuat::from_rotation_y(0.3),
            start: DVec3::new(120.0, 0.0, 60.0),
            approach: DVec3::NEG_X,
            tilt_axis: DVec3::NEG_Y,
            max_tilt: 1.2,
        },
        // The pencil lowered into the bowl tip first, then leaning onto the rim (Fig. 3).
        SettleSpec {
            pair: "pencil-bowl",
            a: "bowl",
            b: "pencil",
            // Tip down at 45°, lowered onto the bowl's inner bottom, then the body onto the rim.
            rotation: DQuat::from_rotation_y(0.75 * std::f64::consts::PI),
            start: DVec3::new(-115.5, 0.0, 155.5),
            approach: DVec3::NEG_Z,
            tilt_axis: DVec3::NEG_Y,
            max_tilt: 1.0,
        },
        // Two vases side by side: bellies touching, then one leaning onto the other's neck.
        SettleSpec {
            pair: "vase-vase",
            a: "vase",
            b: "vase",
            rotation: DQuat::IDENTITY,
            start: DVec3::new(100.0, 0.0, 0.0),
            approach: DVec3::NEG_X,
            tilt_axis: DVec3::NEG_Y,
            max_tilt: 1.5,
        },
    ]
}

/// Queries of one pair with A at the origin.
struct Settler {
    pipeline: ContactPipeline,
    a: PreparedObject,
    b: PreparedObject,
    scratch: QueryScratch,
}

/// The smallest distance of a report for bisection: -inf when penetrating, +inf when separated.
fn min_distance(report: &PairReport) -> f64 {
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

fn translated(pose: &DPose3, by: DVec3) -> DPose3 {
    DPose3 {
        rotation: pose.rotation,
        translation: pose.translation + by,
    }
}

/// `pose` turned by `angle` about the world axis through `pivot`.
fn turned(pose: &DPose3, pivot: DVec3, axis: DVec3, angle: f64) -> DPose3 {
    let r = DQuat::from_axis_angle(axis, angle);
    DPose3 {
        rotation: (r * pose.rotation).normalize(),
        translation: pivot + r * (pose.translation - pivot),
    }
}

/// Finds x in [lo, hi] with f(x) = target, given f(lo) > target >= f(hi) (f need not be
/// continuous: it may jump to -inf or +inf where the state changes).
fn bisect(mut lo: f64, mut hi: f64, mut f: impl FnMut(f64) -> f64, target: f64) -> f64 {
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

impl Settler {
    fn query(&mut self, pose_b: &DPose3) -> PairReport {
        self.pipeline
            .query(
                &self.a,
                &DPose3::IDENTITY,
                &self.b,
                pose_b,
                &mut self.scratch,
            )
            .expect("settle poses are built from unit quaternions")
    }

    /// Moves B from `start` along `approach` until the minimum distance is `gap`.
    fn touch(&mut self, start: &DPose3, approach: DVec3, gap: f64) -> Result<DPose3, String> {
        let step = 0.5 * self.pipeline.options().margin;
        if min_distance(&self.query(start)) <= gap {
            return Err("B does not start clear of A".into());
        }
        let mut t = 0.0;
        for _ in 0..10_000 {
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
    /// 5 mm more: a separated scene that stops after Stage 1.
    fn clear_of_broad_phase(&mut self, pose: &DPose3, away: DVec3) -> DPose3 {
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

    /// Turns B about its first contact until a second contact reaches `second_gap`.
    fn tilt(&mut self, touched: DPose3, spec: &SettleSpec) -> Result<DPose3, String> {
        let report = self.query(&touched);
        let first = report
            .contacts
            .first()
            .ok_or("no first contact after touching")?;
        let (mut pose, mut pivot) = (touched, first.point_b);
        let step = 0.01;
        let mut angle = 0.0;
        while angle < spec.max_tilt {
            let (next, next_pivot, others) =
                self.resettle(turned(&pose, pivot, spec.tilt_axis, step), pivot, FIRST_GAP);
            angle += step;
            if others <= SECOND_GAP {
                // Bisect the last step on the second contact's distance.
                let (base, base_pivot, axis) = (pose, pivot, spec.tilt_axis);
                let mut at = |x: f64| {
                    self.resettle(turned(&base, base_pivot, axis, x), base_pivot, FIRST_GAP)
                };
                let found = bisect(0.0, step, |x| at(x).2, SECOND_GAP);
                return Ok(at(found).0);
            }
            pose = next;
            pivot = next_pivot;
        }
        Err(format!(
            "{}: no second contact within {} rad",
            spec.pair, spec.max_tilt
        ))
    }
}

fn pose_json(pose: &DPose3) -> Value {
    let t = pose.translation;
    let q = pose.rotation;
    json!({"translation": [t.x, t.y, t.z], "rotation": [q.x, q.y, q.z, q.w]})
}

fn scene_json(spec: &SettleSpec, pose_b: &DPose3, what: &str, options: &ContactOptions) -> String {
    let (name_a, name_b) = if spec.a == spec.b {
        (format!("{}-a", spec.a), format!("{}-b", spec.b))
    } else {
        (spec.a.to_string(), spec.b.to_string())
    };
    let value = json!({
        "note": format!("{} ({what}); {}", crate::paper_objects::GENERATED_NOTE, spec.pair),
        "objects": [
            {"name": name_a, "object": spec.a, "pose": pose_json(&DPose3::IDENTITY)},
            {"name": name_b, "object": spec.b, "pose": pose_json(pose_b)},
        ],
        "options": {"margin": options.margin, "delta1": options.delta1, "delta2": options.delta2,
                    "chordal_tolerance": options.chordal_tolerance},
    });
    let mut text = serde_json::to_string_pretty(&value).unwrap_or_default();
    text.push('\n');
    text
}

/// Every scene file: (file name, contents).
///
/// # Errors
/// A message when a pair cannot be settled.
pub fn generate_scenes(objects: &[ObjectDescription]) -> Result<Vec<(String, String)>, String> {
    let options = ContactOptions::default();
    let find = |name: &str| {
        objects
            .iter()
            .find(|o| o.name == name)
            .ok_or(format!("no object {name}"))
    };
    let mut files = Vec::new();
    for spec in specs() {
        let pipeline = ContactPipeline::new(options).map_err(|e| e.to_string())?;
        let a = pipeline
            .prepare_description(find(spec.a)?)
            .map_err(|e| e.to_string())?;
        let b = pipeline
            .prepare_description(find(spec.b)?)
            .map_err(|e| e.to_string())?;
        let mut settler = Settler {
            pipeline,
            a,
            b,
            scratch: QueryScratch::default(),
        };
        let start = DPose3 {
            rotation: spec.rotation,
            translation: spec.start,
        };
        let touched = settler
            .touch(&start, spec.approach, FIRST_GAP)
            .map_err(|e| format!("{}: {e}", spec.pair))?;
        let two = settler.tilt(touched, &spec)?;
        files.push((
            format!("{}-two-contacts.json", spec.pair),
            scene_json(&spec, &two, "two contacts", &options),
        ));
        files.push((
            format!("{}-one-contact.json", spec.pair),
            scene_json(&spec, &touched, "one contact", &options),
        ));
        let apart = settler.clear_of_broad_phase(&touched, -spec.approach);
        files.push((
            format!("{}-separated.json", spec.pair),
            scene_json(&spec, &apart, "separated", &options),
        ));
        if spec.pair == "pencil-bowl" {
            let into = translated(&touched, spec.approach * 0.5);
            files.push((
                format!("{}-penetrating.json", spec.pair),
                scene_json(&spec, &into, "penetrating", &options),
            ));
        }
    }
    Ok(files)
}
