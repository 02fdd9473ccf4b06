//! Error against run time: every method at every setting on every accuracy scene, with the
//! figures and the ratios the report states.

use super::accuracy_scene::AccuracyScene;
use super::methods::{Measurement, Method, measure};
use super::plot::{FLOOR, Panel, Series, log_log_svg};

/// The settings each method is run at.
pub struct MethodSettings {
    /// Chordal tolerances (mm) of our meshes.
    pub chordal: Vec<f64>,
    /// Newton angle tolerances of our Stage 3.
    pub newton: Vec<f64>,
    /// Triangles per object of the parry baseline.
    pub parry_triangles: Vec<usize>,
    /// Timed repetitions per measurement of our pipeline.
    pub repetitions: usize,
    /// Timed repetitions per measurement of the parry baseline (slower per query).
    pub parry_repetitions: usize,
}

impl MethodSettings {
    /// Every method at every setting, in a fixed order.
    #[must_use]
    pub fn methods(&self) -> Vec<Method> {
        let mut methods = Vec::new();
        for &chordal in &self.chordal {
            for &angle_tolerance in &self.newton {
                methods.push(Method::Exact {
                    chordal,
                    angle_tolerance,
                });
            }
        }
        methods.extend(
            self.chordal
                .iter()
                .map(|&chordal| Method::MeshSeeds { chordal }),
        );
        for warm in [true, false] {
            methods.extend(
                self.parry_triangles
                    .iter()
                    .map(|&triangles| Method::Parry { triangles, warm }),
            );
        }
        methods
    }
}

/// Measures every method on `scene`.
///
/// # Errors
/// A message if a method refuses the scene.
pub fn measure_scene(
    scene: &AccuracyScene,
    settings: &MethodSettings,
) -> Result<Vec<Measurement>, String> {
    settings
        .methods()
        .into_iter()
        .map(|method| {
            let repetitions = match method {
                Method::Parry { .. } => settings.parry_repetitions,
                _ => settings.repetitions,
            };
            measure(scene, method, repetitions)
        })
        .collect()
}

/// The scene's figure: distance error and point error against time per query, log-log, one
/// series per method family.
///
/// # Errors
/// A message if plotting fails.
pub fn figure(scene: &AccuracyScene, measurements: &[Measurement]) -> Result<String, String> {
    let mut families: Vec<&'static str> = Vec::new();
    for m in measurements {
        if !families.contains(&m.method.family()) {
            families.push(m.method.family());
        }
    }
    let series = |error: fn(&Measurement) -> f64| {
        families
            .iter()
            .map(|family| Series {
                name: (*family).to_string(),
                points: measurements
                    .iter()
                    .filter(|m| m.method.family() == *family && m.missed == 0)
                    .map(|m| (m.time_us, error(m)))
                    .collect(),
            })
            .collect()
    };
    log_log_svg(&[
        Panel {
            title: format!("{}: contact distance", scene.name),
            x_label: "time per query (µs)".into(),
            y_label: "|distance error| (mm)".into(),
            series: series(|m| m.distance_error),
        },
        Panel {
            title: format!("{}: contact points", scene.name),
            x_label: "time per query (µs)".into(),
            y_label: "point error (mm)".into(),
            series: series(|m| m.point_error),
        },
    ])
}

/// Our default setting (the one the other tables use) among `measurements`.
#[must_use]
pub fn default_exact(measurements: &[Measurement]) -> Option<&Measurement> {
    let defaults = contact_pipeline::ContactOptions::default();
    let newton = exact_refine::NewtonOptions::default();
    measurements
        .iter()
        .find(|m| {
            m.method
                == Method::Exact {
                    chordal: defaults.chordal_tolerance,
                    angle_tolerance: newton.angle_tolerance,
                }
        })
        .or_else(|| {
            measurements
                .iter()
                .find(|m| matches!(m.method, Method::Exact { .. }))
        })
}

/// The ratios the report states for one scene against one baseline measurement.
pub struct Ratio {
    /// The baseline's setting.
    pub baseline: String,
    /// Baseline time / our default time: how many times faster we are.
    pub speedup: f64,
    /// Baseline distance error / ours (errors floored at [`FLOOR`]).
    pub distance_gain: f64,
    /// Baseline point error / ours (floored likewise).
    pub point_gain: f64,
    /// Our fastest setting whose distance and point errors are both at most the baseline's:
    /// baseline time / its time ("at equal accuracy"), if any setting qualifies.
    pub speedup_at_equal_accuracy: Option<f64>,
}

/// Ratios of our pipeline against each parry setting (warm) that found every true contact.
#[must_use]
pub fn ratios(measurements: &[Measurement]) -> Vec<Ratio> {
    let Some(ours) = default_exact(measurements) else {
        return Vec::new();
    };
    let exact: Vec<&Measurement> = measurements
        .iter()
        .filter(|m| matches!(m.method, Method::Exact { .. }) && m.missed == 0)
        .collect();
    measurements
        .iter()
        .filter(|m| matches!(m.method, Method::Parry { warm: true, .. }) && m.missed == 0)
        .map(|p| {
            let at_equal = exact
                .iter()
                .filter(|e| e.distance_error <= p.distance_error && e.point_error <= p.point_error)
                .map(|e| e.time_us)
                .min_by(f64::total_cmp)
                .map(|t| p.time_us / t);
            Ratio {
                baseline: p.method.setting(),
                speedup: p.time_us / ours.time_us,
                distance_gain: p.distance_error.max(FLOOR) / ours.distance_error.max(FLOOR),
                point_gain: p.point_error.max(FLOOR) / ours.point_error.max(FLOOR),
                speedup_at_equal_accuracy: at_equal,
            }
        })
        .collect()
}
