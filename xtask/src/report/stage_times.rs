//! Per-stage wall times of repeated queries of one pair, as medians.

use super::timing::median;
use contact_pipeline::{ContactPipeline, PairReport, PreparedObject, QueryScratch};
use geom_param::DPose3;
use std::time::Instant;

/// Medians over repeated queries of one pair (µs), with the last report.
pub struct StageTimes {
    /// Stage 1 (broad phase).
    pub broad_us: f64,
    /// Stage 2 (mesh phase).
    pub mesh_us: f64,
    /// Stage 3 (exact refinement).
    pub refine_us: f64,
    /// The whole query, timed outside the pipeline (includes pose checks and merging).
    pub total_us: f64,
    /// The answer of the last query.
    pub report: PairReport,
}

impl StageTimes {
    /// Times `repetitions` queries (after one untimed warm-up query, which builds lazily
    /// prepared proxies) and takes the median of each stage and of the whole.
    ///
    /// # Errors
    /// A message if the pipeline refuses the pair.
    pub fn measure(
        pipeline: &ContactPipeline,
        a: &PreparedObject,
        pose_a: &DPose3,
        b: &PreparedObject,
        pose_b: &DPose3,
        repetitions: usize,
    ) -> Result<Self, String> {
        let mut scratch = QueryScratch::default();
        let mut report = PairReport::default();
        pipeline
            .query_into(a, pose_a, b, pose_b, &mut scratch, &mut report)
            .map_err(|e| e.to_string())?;
        let n = repetitions.max(1);
        let (mut broad, mut mesh, mut refine, mut total) = (
            Vec::with_capacity(n),
            Vec::with_capacity(n),
            Vec::with_capacity(n),
            Vec::with_capacity(n),
        );
        for _ in 0..n {
            let start = Instant::now();
            pipeline
                .query_into(a, pose_a, b, pose_b, &mut scratch, &mut report)
                .map_err(|e| e.to_string())?;
            total.push(start.elapsed().as_secs_f64() * 1e6);
            broad.push(report.stats.broad_us);
            mesh.push(report.stats.mesh_us);
            refine.push(report.stats.refine_us);
        }
        Ok(Self {
            broad_us: median(&mut broad),
            mesh_us: median(&mut mesh),
            refine_us: median(&mut refine),
            total_us: median(&mut total),
            report,
        })
    }
}
