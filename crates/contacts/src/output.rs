//! JSON output of query results (world frame, mm).

use contact_pipeline::{Contact, PairReport, PairState};
use geom_param::FeatureLocation;
use glam::DVec3;
use serde_json::{Value, json};

fn vector(v: DVec3) -> Value {
    json!([v.x, v.y, v.z])
}

fn feature(location: &FeatureLocation) -> Value {
    match *location {
        FeatureLocation::Face { id, u, v } => json!({"kind": "face", "id": id.0, "params": [u, v]}),
        FeatureLocation::Edge { id, t } => json!({"kind": "edge", "id": id.0, "params": [t]}),
        FeatureLocation::Vertex { id } => json!({"kind": "vertex", "id": id.0, "params": []}),
    }
}

/// A finite number, or null (JSON has no NaN or infinity).
fn number(x: f64) -> Value {
    if x.is_finite() { json!(x) } else { Value::Null }
}

/// Lower-case name of a state, as written in the output.
#[must_use]
pub fn state_name(state: PairState) -> &'static str {
    match state {
        PairState::Separated => "separated",
        PairState::Contact => "contact",
        PairState::Penetration => "penetration",
    }
}

fn contact(c: &Contact) -> Value {
    let d = &c.diagnostics;
    json!({
        "point_a": vector(c.point_a),
        "point_b": vector(c.point_b),
        "distance": c.distance,
        "normal": vector(c.normal),
        "feature_a": feature(&c.location_a),
        "feature_b": feature(&c.location_b),
        "converged": d.converged,
        "local_minimum": d.is_local_minimum,
        "status": format!("{:?}", d.status),
        "iterations": d.iterations,
        "gradient_norm": number(d.gradient_norm),
        "condition": number(d.condition),
        "error_estimate": number(d.error_estimate),
        "point_error_estimate": number(d.point_error_estimate),
    })
}

/// One pair's result as JSON.
#[must_use]
pub fn pair_json(a: &str, b: &str, report: &PairReport) -> Value {
    let s = &report.stats;
    json!({
        "a": a,
        "b": b,
        "state": state_name(report.state),
        "contacts": report.contacts.iter().map(contact).collect::<Vec<_>>(),
        "penetration_witnesses": report.penetration_witnesses.iter().map(|p| vector(*p)).collect::<Vec<_>>(),
        "stages_ran": {"broad": s.broad_ran, "mesh": s.mesh_ran, "refine": s.refine_ran},
        "counts": {"component_pairs": s.component_pairs, "seeds": s.seeds, "refined": s.refined, "merged": s.merged},
        "stages_us": {"broad": s.broad_us, "mesh": s.mesh_us, "refine": s.refine_us},
        "total_us": s.total_us(),
    })
}
