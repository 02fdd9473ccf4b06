//! The work behind each subcommand.

use crate::output::{pair_json, state_name};
use crate::scene::{Scene, SceneError};
use contact_pipeline::{ContactPipeline, PairReport, PreparedObject, QueryScratch};
use serde_json::{Value, json};
use std::path::Path;
use std::time::Instant;

/// A scene with its pipeline and prepared objects.
pub struct PreparedScene {
    /// The scene as read.
    pub scene: Scene,
    /// The pipeline built from the scene's options.
    pub pipeline: ContactPipeline,
    /// Prepared objects, in scene order.
    pub objects: Vec<PreparedObject>,
}

/// Reads and prepares a scene.
///
/// # Errors
/// A [`SceneError`] for unreadable or invalid input.
pub fn prepare_scene(path: &Path) -> Result<PreparedScene, SceneError> {
    let scene = Scene::from_file(path)?;
    let pipeline = ContactPipeline::new(scene.options)?;
    let objects = scene
        .objects
        .iter()
        .enumerate()
        .map(|(i, o)| {
            pipeline
                .prepare_description(&o.description)
                .map_err(|source| SceneError::Object { at: format!("objects[{i}] ({})", o.name), source })
        })
        .collect::<Result<Vec<_>, _>>()?;
    Ok(PreparedScene { scene, pipeline, objects })
}

impl PreparedScene {
    /// Index pairs (i, j), i < j, of every pair of objects.
    #[must_use]
    pub fn pairs(&self) -> Vec<(usize, usize)> {
        let n = self.objects.len();
        (0..n).flat_map(|i| (i + 1..n).map(move |j| (i, j))).collect()
    }

    /// Queries pair (i, j) once.
    #[must_use]
    pub fn query(&self, (i, j): (usize, usize), scratch: &mut QueryScratch) -> PairReport {
        let (a, b) = (&self.scene.objects[i], &self.scene.objects[j]);
        self.pipeline.query(&self.objects[i], &a.pose, &self.objects[j], &b.pose, scratch)
    }

    /// `contacts query`: every pair's result.
    #[must_use]
    pub fn query_json(&self) -> Value {
        let mut scratch = QueryScratch::default();
        let pairs: Vec<Value> = self
            .pairs()
            .into_iter()
            .map(|(i, j)| {
                let report = self.query((i, j), &mut scratch);
                pair_json(&self.scene.objects[i].name, &self.scene.objects[j].name, &report)
            })
            .collect();
        json!({ "pairs": pairs })
    }

    /// Median and minimum wall time (µs) of `iterations` queries of pair (i, j), after as many
    /// warm-up queries, and the last report.
    #[must_use]
    pub fn time_pair(&self, pair: (usize, usize), iterations: usize) -> (f64, f64, PairReport) {
        let mut scratch = QueryScratch::default();
        let mut report = self.query(pair, &mut scratch);
        for _ in 0..iterations {
            report = self.query(pair, &mut scratch);
        }
        let mut times: Vec<f64> = (0..iterations.max(1))
            .map(|_| {
                let start = Instant::now();
                report = self.query(pair, &mut scratch);
                start.elapsed().as_secs_f64() * 1e6
            })
            .collect();
        times.sort_by(f64::total_cmp);
        (times[times.len() / 2], times[0], report)
    }

    /// `contacts bench`: median and minimum µs per query for each pair.
    #[must_use]
    pub fn bench_json(&self, iterations: usize) -> Value {
        let pairs: Vec<Value> = self
            .pairs()
            .into_iter()
            .map(|(i, j)| {
                let (median, min, report) = self.time_pair((i, j), iterations);
                json!({
                    "a": self.scene.objects[i].name,
                    "b": self.scene.objects[j].name,
                    "state": state_name(report.state),
                    "contacts": report.contacts.len(),
                    "iterations": iterations,
                    "median_us": median,
                    "min_us": min,
                })
            })
            .collect();
        json!({ "pairs": pairs })
    }
}
