//! The work behind each subcommand.

use crate::output::{pair_json, state_name};
use crate::scene::{Scene, SceneError};
use contact_pipeline::{
    ContactPipeline, Groups, PairReport, PreparedObject, QueryError, QueryScratch, World,
    WorldError,
};
use geom_param::MeshOptions;
use serde_json::{Value, json};
use std::path::Path;
use std::sync::Arc;
use std::time::Instant;

/// Scenes with more objects than this are queried through a [`World`] (broad phase across
/// objects): only pairs whose inflated boxes overlap are listed, in the same order and format.
pub const WORLD_OBJECTS: usize = 16;

/// A scene with its pipeline and prepared objects.
pub struct PreparedScene {
    /// The scene as read.
    pub scene: Scene,
    /// The pipeline built from the scene's options.
    pub pipeline: ContactPipeline,
    /// Prepared objects, in scene order; objects with equal descriptions share one.
    pub objects: Vec<Arc<PreparedObject>>,
}

/// Reads and prepares a scene.
///
/// # Errors
/// A [`SceneError`] for unreadable or invalid input.
pub fn prepare_scene(path: &Path) -> Result<PreparedScene, SceneError> {
    prepare(Scene::from_file(path)?)
}

/// Reads and prepares a scene given as text whose objects are all built-in or inline.
///
/// # Errors
/// A [`SceneError`] for invalid input.
pub fn prepare_scene_text(text: &str) -> Result<PreparedScene, SceneError> {
    prepare(Scene::from_json(
        text,
        Path::new("<built-in scene>"),
        Path::new("."),
    )?)
}

fn prepare(scene: Scene) -> Result<PreparedScene, SceneError> {
    let pipeline = ContactPipeline::new(scene.options)?;
    let mut objects: Vec<Arc<PreparedObject>> = Vec::with_capacity(scene.objects.len());
    for (i, o) in scene.objects.iter().enumerate() {
        // Instances of one description share its preparation.
        if let Some(k) = scene.objects[..i]
            .iter()
            .position(|p| p.description == o.description)
        {
            objects.push(Arc::clone(&objects[k]));
            continue;
        }
        let prepared = o
            .description
            .build(&MeshOptions {
                chordal_tolerance: pipeline.options().chordal_tolerance,
            })
            .map(|model| pipeline.prepare(model))
            .map_err(|source| SceneError::Object {
                at: format!("objects[{i}] ({})", o.name),
                source,
            })?;
        objects.push(Arc::new(prepared));
    }
    Ok(PreparedScene {
        scene,
        pipeline,
        objects,
    })
}

impl PreparedScene {
    /// Index pairs (i, j), i < j, of every pair of objects.
    #[must_use]
    pub fn pairs(&self) -> Vec<(usize, usize)> {
        let n = self.objects.len();
        (0..n)
            .flat_map(|i| (i + 1..n).map(move |j| (i, j)))
            .collect()
    }

    /// Queries pair (i, j) once.
    ///
    /// # Errors
    /// [`QueryError`] if a stage refuses the pair.
    pub fn query(
        &self,
        (i, j): (usize, usize),
        scratch: &mut QueryScratch,
    ) -> Result<PairReport, QueryError> {
        let (a, b) = (&self.scene.objects[i], &self.scene.objects[j]);
        self.pipeline.query(
            &self.objects[i],
            &a.pose,
            &self.objects[j],
            &b.pose,
            scratch,
        )
    }

    /// `contacts query`: every pair's result; for scenes of more than [`WORLD_OBJECTS`]
    /// objects, every pair in range of the world's broad phase (the others are separated).
    ///
    /// # Errors
    /// [`QueryError`] if a stage refuses a pair.
    pub fn query_json(&self) -> Result<Value, QueryError> {
        if self.objects.len() > WORLD_OBJECTS {
            return self.query_world_json();
        }
        let mut scratch = QueryScratch::default();
        let pairs = self
            .pairs()
            .into_iter()
            .map(|(i, j)| {
                let report = self.query((i, j), &mut scratch)?;
                Ok(pair_json(
                    &self.scene.objects[i].name,
                    &self.scene.objects[j].name,
                    &report,
                ))
            })
            .collect::<Result<Vec<Value>, QueryError>>()?;
        Ok(json!({ "pairs": pairs }))
    }

    /// `contacts query` through a [`World`]: one step, pairs in range in scene order.
    fn query_world_json(&self) -> Result<Value, QueryError> {
        let pipeline = ContactPipeline::new(*self.pipeline.options()).map_err(|e| {
            QueryError::MeshPhase(format!("options accepted once are refused now: {e}"))
        })?;
        let mut world = World::new(pipeline, None);
        let world_error = |e: WorldError| match e {
            WorldError::BadPose { source, .. } | WorldError::Query { source, .. } => source,
            other => QueryError::MeshPhase(other.to_string()),
        };
        for (prepared, o) in self.objects.iter().zip(&self.scene.objects) {
            world
                .insert(Arc::clone(prepared), o.pose, Groups::default())
                .map_err(world_error)?;
        }
        world.step_parallel().map_err(world_error)?;
        // Inserted in scene order into an empty world: slot index = scene index.
        let pairs = world
            .all_pairs()
            .map(|p| {
                let (i, j) = (p.a.index as usize, p.b.index as usize);
                pair_json(
                    &self.scene.objects[i].name,
                    &self.scene.objects[j].name,
                    p.report,
                )
            })
            .collect::<Vec<Value>>();
        Ok(json!({ "pairs": pairs }))
    }

    /// Median and minimum wall time (µs) of `iterations` queries of pair (i, j), after as many
    /// warm-up queries, and the last report.
    ///
    /// # Errors
    /// [`QueryError`] if a stage refuses the pair.
    pub fn time_pair(
        &self,
        pair: (usize, usize),
        iterations: usize,
    ) -> Result<(f64, f64, PairReport), QueryError> {
        let mut scratch = QueryScratch::default();
        let mut report = PairReport::default();
        let (a, b) = (&self.objects[pair.0], &self.objects[pair.1]);
        let (pose_a, pose_b) = (
            &self.scene.objects[pair.0].pose,
            &self.scene.objects[pair.1].pose,
        );
        let mut query = |report: &mut PairReport| {
            self.pipeline
                .query_into(a, pose_a, b, pose_b, &mut scratch, report)
        };
        for _ in 0..iterations {
            query(&mut report)?;
        }
        let mut times = Vec::with_capacity(iterations.max(1));
        for _ in 0..iterations.max(1) {
            let start = Instant::now();
            query(&mut report)?;
            times.push(start.elapsed().as_secs_f64() * 1e6);
        }
        times.sort_by(f64::total_cmp);
        Ok((times[times.len() / 2], times[0], report))
    }

    /// `contacts bench`: median and minimum µs per query for each pair.
    ///
    /// # Errors
    /// [`QueryError`] if a stage refuses a pair.
    pub fn bench_json(&self, iterations: usize) -> Result<Value, QueryError> {
        let pairs = self
            .pairs()
            .into_iter()
            .map(|(i, j)| {
                let (median, min, report) = self.time_pair((i, j), iterations)?;
                Ok(json!({
                    "a": self.scene.objects[i].name,
                    "b": self.scene.objects[j].name,
                    "state": state_name(report.state),
                    "contacts": report.contacts.len(),
                    "iterations": iterations,
                    "median_us": median,
                    "min_us": min,
                }))
            })
            .collect::<Result<Vec<Value>, QueryError>>()?;
        Ok(json!({ "pairs": pairs }))
    }
}
