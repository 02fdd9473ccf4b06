//! The JSON form of a planar NURBS curve ([`NurbsCurve2`]), for profile segments:
//! `{"degree": 2, "knots": [...], "points": [[x, y], ...], "weights": [...], "periodic": false}`
//! (mm; `weights` may be left out for a non-rational curve, `periodic` defaults to false).
//! Reading validates the curve as [`NurbsCurve2::new`] does and reports its error.

use crate::curves::nurbs_curve2::NurbsCurve2;
use glam::DVec2;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// The fields of the JSON form.
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct NurbsCurve2Form {
    degree: usize,
    knots: Vec<f64>,
    points: Vec<DVec2>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    weights: Option<Vec<f64>>,
    #[serde(default)]
    periodic: bool,
}

/// Writes `curve` in the JSON form (every field, weights included).
pub(crate) fn serialize<S: Serializer>(
    curve: &NurbsCurve2,
    serializer: S,
) -> Result<S::Ok, S::Error> {
    NurbsCurve2Form {
        degree: curve.basis().degree(),
        knots: curve.basis().knots().to_vec(),
        points: curve.control_points().to_vec(),
        weights: Some(curve.weights().to_vec()),
        periodic: curve.is_periodic(),
    }
    .serialize(serializer)
}

/// Reads the JSON form and builds the curve; missing weights are all 1.
pub(crate) fn deserialize<'de, D: Deserializer<'de>>(
    deserializer: D,
) -> Result<NurbsCurve2, D::Error> {
    let form = NurbsCurve2Form::deserialize(deserializer)?;
    let weights = form.weights.unwrap_or_else(|| vec![1.0; form.points.len()]);
    NurbsCurve2::new(form.degree, form.knots, form.points, weights, form.periodic)
        .map_err(serde::de::Error::custom)
}
