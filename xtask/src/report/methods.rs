//! The ways of answering a contact query that the report compares, each at several settings.

use super::accuracy_scene::{AccuracyScene, TrueContact};
use super::mesh_seed_refiner::MeshSeedRefiner;
use super::timing::median_us;
use bvh_hybrid::HybridBvh;
use contact_pipeline::{ContactOptions, ContactPipeline, QueryScratch};
use exact_refine::{NewtonOptions, NewtonRefiner};
use mesh_baseline::{BaselineMesh, MeshOnlyBaseline};
use mesh_narrowphase::MeshNarrowphase;

/// One method at one setting.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Method {
    /// Our three stages, meshes at `chordal` mm, Newton to `angle_tolerance`.
    Exact {
        /// Chordal tolerance of the component meshes (mm).
        chordal: f64,
        /// NewtonOptions::angle_tolerance.
        angle_tolerance: f64,
    },
    /// Our Stages 1-2 alone: the mesh phase's seeds, unrefined.
    MeshSeeds {
        /// Chordal tolerance of the component meshes (mm).
        chordal: f64,
    },
    /// parry3d-f64 contact manifolds between whole-object triangle meshes.
    Parry {
        /// Requested triangles per object.
        triangles: usize,
        /// Manifolds and workspace kept across queries (false: fresh each query).
        warm: bool,
    },
}

impl Method {
    /// The family, used for series in figures and columns in tables.
    #[must_use]
    pub fn family(&self) -> &'static str {
        match self {
            Self::Exact { .. } => "exact (ours, 3 stages)",
            Self::MeshSeeds { .. } => "mesh seeds (ours, stages 1-2)",
            Self::Parry { warm: true, .. } => "parry mesh-only, warm",
            Self::Parry { warm: false, .. } => "parry mesh-only, cold",
        }
    }

    /// The setting, in words.
    #[must_use]
    pub fn setting(&self) -> String {
        match self {
            Self::Exact {
                chordal,
                angle_tolerance,
            } => format!("chordal {chordal} mm, Newton {angle_tolerance:.0e}"),
            Self::MeshSeeds { chordal } => format!("chordal {chordal} mm"),
            Self::Parry { triangles, .. } => format!("{}k triangles", triangles / 1000),
        }
    }
}

/// One point of the error-against-time figure.
#[derive(Clone, Debug)]
pub struct Measurement {
    /// Scene name.
    pub scene: String,
    /// Method and setting.
    pub method: Method,
    /// Median wall time per query (µs).
    pub time_us: f64,
    /// Worst |d − d_true| over the true contacts (mm), of the nearest reported contact.
    pub distance_error: f64,
    /// Worst distance of the nearest reported contact's points from the true points (mm).
    pub point_error: f64,
    /// True contacts with no reported contact within [`MATCH_RADIUS`].
    pub missed: usize,
    /// Reported contacts farther than [`MATCH_RADIUS`] from every true contact.
    pub extra: usize,
    /// Triangles per object (both objects' meshes, mean).
    pub triangles: usize,
}

/// A reported contact counts as an answer to a true contact when both its points lie within
/// this distance (mm) of the true points: far enough for a 1k-triangle mesh, near enough that
/// the two contacts of a paper scene (tens of mm apart) are not confused.
pub const MATCH_RADIUS: f64 = 2.0;

/// The reported contacts, world frame: (point_a, point_b, signed distance).
type Reported = Vec<(geom_param::DVec3, geom_param::DVec3, f64)>;

fn score(
    scene: &AccuracyScene,
    method: Method,
    time_us: f64,
    triangles: usize,
    reported: &Reported,
) -> Measurement {
    let separation = |t: &TrueContact, r: &(geom_param::DVec3, geom_param::DVec3, f64)| {
        t.point_a.distance(r.0).max(t.point_b.distance(r.1))
    };
    let (mut distance_error, mut point_error, mut missed) = (0.0_f64, 0.0_f64, 0);
    for t in &scene.truth {
        let nearest = reported
            .iter()
            .min_by(|x, y| separation(t, x).total_cmp(&separation(t, y)));
        match nearest {
            Some(r) if separation(t, r) <= MATCH_RADIUS => {
                distance_error = distance_error.max((r.2 - t.distance).abs());
                point_error = point_error.max(separation(t, r));
            }
            _ => missed += 1,
        }
    }
    let extra = reported
        .iter()
        .filter(|r| scene.truth.iter().all(|t| separation(t, r) > MATCH_RADIUS))
        .count();
    Measurement {
        scene: scene.name.clone(),
        method,
        time_us,
        distance_error,
        point_error,
        missed,
        extra,
        triangles,
    }
}

/// Runs `method` on `scene`: prepares it (not timed), times `repetitions` queries and scores
/// the last answer against the scene's truth.
///
/// # Errors
/// A message if the method refuses the scene.
pub fn measure(
    scene: &AccuracyScene,
    method: Method,
    repetitions: usize,
) -> Result<Measurement, String> {
    let fail = |e: &dyn std::fmt::Display| format!("{} / {}: {e}", scene.name, method.setting());
    match method {
        Method::Exact {
            chordal,
            angle_tolerance,
        } => {
            let refiner = NewtonRefiner {
                options: NewtonOptions {
                    angle_tolerance,
                    ..NewtonOptions::default()
                },
            };
            let options = ContactOptions {
                chordal_tolerance: chordal,
                ..ContactOptions::default()
            };
            let pipeline = ContactPipeline::with_stages(
                HybridBvh::default(),
                MeshNarrowphase::default(),
                refiner,
                options,
            )
            .map_err(|e| fail(&e))?;
            run_pipeline(scene, method, &pipeline, repetitions)
        }
        Method::MeshSeeds { chordal } => {
            // Every seed is kept: the band is widened to the margin so that a seed whose mesh
            // distance is off by the chordal error is still reported, and scored.
            let defaults = ContactOptions::default();
            let options = ContactOptions {
                chordal_tolerance: chordal,
                delta1: -defaults.margin,
                delta2: defaults.margin,
                ..defaults
            };
            let pipeline = ContactPipeline::with_stages(
                HybridBvh::default(),
                MeshNarrowphase::default(),
                MeshSeedRefiner,
                options,
            )
            .map_err(|e| fail(&e))?;
            run_pipeline(scene, method, &pipeline, repetitions)
        }
        Method::Parry { triangles, warm } => {
            let a = BaselineMesh::from_description(&scene.a, triangles).map_err(|e| fail(&e))?;
            let b = BaselineMesh::from_description(&scene.b, triangles).map_err(|e| fail(&e))?;
            let prediction = ContactOptions::default().delta2;
            let mut baseline = MeshOnlyBaseline::default();
            let query = |baseline: &mut MeshOnlyBaseline| {
                if warm {
                    baseline.contacts(&a, &scene.pose_a, &b, &scene.pose_b, prediction)
                } else {
                    baseline.contacts_cold(&a, &scene.pose_a, &b, &scene.pose_b, prediction)
                }
            };
            let reported: Reported = query(&mut baseline)
                .map_err(|e| fail(&e))?
                .iter()
                .map(|c| (c.point_a, c.point_b, c.distance))
                .collect();
            // Errors cannot appear on a repeat of the same query: the first call checked it.
            let (time_us, _) = median_us(repetitions, || query(&mut baseline).map(|c| c.len()));
            let mean_triangles = (a.triangle_count() + b.triangle_count()) / 2;
            Ok(score(scene, method, time_us, mean_triangles, &reported))
        }
    }
}

fn run_pipeline<R: exact_refine::Refiner>(
    scene: &AccuracyScene,
    method: Method,
    pipeline: &ContactPipeline<HybridBvh, MeshNarrowphase, R>,
    repetitions: usize,
) -> Result<Measurement, String> {
    let fail = |e: &dyn std::fmt::Display| format!("{} / {}: {e}", scene.name, method.setting());
    let a = pipeline
        .prepare_description(&scene.a)
        .map_err(|e| fail(&e))?;
    let b = pipeline
        .prepare_description(&scene.b)
        .map_err(|e| fail(&e))?;
    let mut scratch = QueryScratch::default();
    let mut report = contact_pipeline::PairReport::default();
    let mut failure = None;
    let (time_us, _) = median_us(repetitions, || {
        if let Err(e) = pipeline.query_into(
            &a,
            &scene.pose_a,
            &b,
            &scene.pose_b,
            &mut scratch,
            &mut report,
        ) {
            failure = Some(e);
        }
    });
    if let Some(e) = failure {
        return Err(fail(&e));
    }
    let reported: Reported = report
        .contacts
        .iter()
        .map(|c| (c.point_a, c.point_b, c.distance))
        .collect();
    let triangles = [&a, &b]
        .iter()
        .map(|o| {
            o.model
                .meshes
                .iter()
                .map(|m| m.triangles.len())
                .sum::<usize>()
        })
        .sum::<usize>()
        / 2;
    Ok(score(scene, method, time_us, triangles, &reported))
}
