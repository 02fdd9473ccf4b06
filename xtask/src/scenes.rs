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

use crate::settle::{Settler, TiltSpec, translated};
use contact_pipeline::{ContactOptions, ContactPipeline};
use geom_param::{DPose3, DQuat, DVec3, MeshOptions, ObjectFile};
use serde_json::{Value, json};

/// Gaps of the first and second contact (mm), inside the default band [-0.001, 0.1].
const FIRST_GAP: f64 = 0.02;
const SECOND_GAP: f64 = 0.05;
/// Longest approach tried (mm).
const MAX_TRAVEL: f64 = 5000.0;

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
        // General solids. The pencil at 45° lowered eraser first onto the rounded box's top
        // face, then leaning over onto the box's rounded edge (a fillet cylinder).
        SettleSpec {
            pair: "pencil-rounded-box",
            a: "rounded-box",
            b: "pencil",
            rotation: DQuat::from_rotation_y(0.25 * std::f64::consts::PI),
            start: DVec3::new(10.0, 3.0, 40.0),
            approach: DVec3::NEG_Z,
            tilt_axis: DVec3::Y,
            max_tilt: 1.2,
        },
        // The pencil slightly slanted through the tube's bore: against one rim of the bore,
        // then tipping against the opposite wall at the other end (concave bore, trimmed caps).
        SettleSpec {
            pair: "pencil-tube",
            a: "tube",
            b: "pencil",
            rotation: DQuat::from_rotation_y(0.02),
            start: DVec3::new(-1.6, 0.0, -50.0),
            approach: DVec3::X,
            tilt_axis: DVec3::Y,
            max_tilt: 0.3,
        },
        // The paperweight upside down, its ball against the bracket's vertical leg, then
        // turning about that contact into the corner onto the horizontal leg.
        SettleSpec {
            pair: "paperweight-bracket",
            a: "bracket",
            b: "paperweight",
            rotation: DQuat::from_rotation_x(std::f64::consts::PI),
            start: DVec3::new(40.0, 42.0, 51.1245154965971),
            approach: DVec3::new(-1.0, -1.0, 0.0).normalize(),
            tilt_axis: DVec3::NEG_Z,
            max_tilt: 1.2,
        },
    ]
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
pub fn generate_scenes(objects: &[ObjectFile]) -> Result<Vec<(String, String)>, String> {
    let options = ContactOptions::default();
    let mesh = MeshOptions {
        chordal_tolerance: options.chordal_tolerance,
    };
    let find = |name: &str| {
        objects
            .iter()
            .find(|o| o.name() == name)
            .ok_or(format!("no object {name}"))?
            .build(&mesh)
            .map_err(|e| format!("{name}: {e}"))
    };
    let mut files = Vec::new();
    for spec in specs() {
        let pipeline = ContactPipeline::new(options).map_err(|e| e.to_string())?;
        let a = pipeline.prepare(find(spec.a)?);
        let b = pipeline.prepare(find(spec.b)?);
        let mut settler = Settler::new(&pipeline, &a, &b);
        let start = DPose3 {
            rotation: spec.rotation,
            translation: spec.start,
        };
        let touched = settler
            .touch(&start, spec.approach, FIRST_GAP, MAX_TRAVEL)
            .map_err(|e| format!("{}: {e}", spec.pair))?;
        let tilt = TiltSpec {
            axis: spec.tilt_axis,
            max_angle: spec.max_tilt,
            first_gap: FIRST_GAP,
            second_gap: SECOND_GAP,
        };
        let two = settler
            .tilt(touched, &tilt)
            .map_err(|e| format!("{}: {e}", spec.pair))?;
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
