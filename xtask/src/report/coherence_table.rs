//! The report's coherence table (section 6) and `cargo xtask coherence`: per paper scene and
//! kind of motion, the time per frame of coherent queries against cold ones along one
//! trajectory, in the same run.
//!
//! The trajectories are those of `cargo bench -p contact-pipeline --bench coherence`, each of
//! [`FRAMES`] frames about the scene's first contact (point c, normal n, a tangent u):
//! **rolling**, B turned back and forth about the axis n × u through c (amplitude 2e-3 rad,
//! 2.5e-5 rad per frame at most), lifted 2 µm along n so that both contacts stay in the band;
//! **sliding**, B moved back and forth along u (amplitude 0.05 mm, 1e-3 mm per frame at most),
//! lifted 2 µm; **approaching**, B lowered along n from 0.15 mm above the scene's pose (both
//! contacts outside the band) to 2 µm above it (4.6e-4 mm per frame); **leaving**, the same
//! reversed. Three ways along each, each with its own cache and scratch, after one untimed
//! pass: **warm** is `ContactPipeline::query_coherent` with the default options (a full query
//! at least every 64 frames, so its time is the amortised one), **warm-only** the same with
//! the chain never broken by the frame count (only the motion certificate starts a full
//! query), **cold** `ContactPipeline::query_into` with a persistent scratch. Each time is the
//! median over passes of the mean time per frame of a pass (wall clock, µs).

use super::accuracy_scene::PAPER_SCENES;
use contact_pipeline::{
    CoherenceOptions, ContactPipeline, FrameKind, PairCache, PairReport, PreparedObject,
    QueryScratch,
};
use geom_param::{DPose3, DQuat, DVec3};
use std::path::Path;
use std::time::Instant;

/// Frames of one back-and-forth roll.
pub const FRAMES: usize = 320;

/// How B moves along a trajectory (see the module documentation).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Motion {
    /// Turned back and forth about an axis through the first contact.
    Rolling,
    /// Moved back and forth along the contact's tangent plane.
    Sliding,
    /// Lowered along the normal into the band.
    Approaching,
    /// Raised along the normal out of the band.
    Leaving,
}

impl Motion {
    /// Every motion, in table order.
    pub const ALL: [Self; 4] = [
        Self::Rolling,
        Self::Sliding,
        Self::Approaching,
        Self::Leaving,
    ];

    /// Its name in the table.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Rolling => "rolling",
            Self::Sliding => "sliding",
            Self::Approaching => "approaching",
            Self::Leaving => "leaving",
        }
    }

    /// B's pose at frame `k` of [`FRAMES`], from its pose `pose_b` in a scene whose first
    /// contact is at `c` with normal `n` (A's frame, which is the world's here).
    #[must_use]
    pub fn pose(self, k: usize, c: DVec3, n: DVec3, pose_b: DPose3) -> DPose3 {
        let phase = (std::f64::consts::TAU * k as f64 / FRAMES as f64).sin();
        let lowered = |from: f64, to: f64| {
            let lift = from + (to - from) * k as f64 / (FRAMES - 1) as f64;
            DPose3::from_parts(n * lift, DQuat::IDENTITY) * pose_b
        };
        match self {
            Self::Rolling => {
                let axis = n.cross(n.any_orthonormal_vector()).normalize();
                let r = DQuat::from_axis_angle(axis, 2e-3 * phase);
                DPose3::from_parts(c - r * c + n * 0.002, r) * pose_b
            }
            Self::Sliding => {
                let u = n.any_orthonormal_vector();
                DPose3::from_parts(u * (0.05 * phase) + n * 0.002, DQuat::IDENTITY) * pose_b
            }
            Self::Approaching => lowered(0.15, 0.002),
            Self::Leaving => lowered(0.002, 0.15),
        }
    }
}

/// One scene's row.
struct Row {
    name: &'static str,
    motion: Motion,
    contacts_per_frame: f64,
    warm_fraction: f64,
    steps_per_warm_contact: f64,
    warm_us: f64,
    warm_only_us: f64,
    cold_us: f64,
}

/// The markdown table over the paper scenes (`fixtures/scenes/NAME-two-contacts.json` under
/// `root`), each time the median of `passes` passes of [`FRAMES`] frames.
///
/// # Errors
/// A message when a scene does not load or a query fails.
pub fn coherence_table(root: &Path, passes: usize) -> Result<String, String> {
    let passes = passes.max(1);
    // The machine is shared: say how busy it was (the 1-minute load average, where the system
    // reports one) before the table, whose times depend on it.
    let load = std::fs::read_to_string("/proc/loadavg")
        .ok()
        .and_then(|l| l.split_whitespace().next().map(str::to_owned));
    let mut text = match load {
        Some(load) => format!(
            "1-minute load average when the measurement started: {load}, on {} logical cores.\n\n",
            std::thread::available_parallelism().map_or(1, usize::from)
        ),
        None => String::new(),
    };
    text.push_str(
        "| scene | motion | contacts per frame | warm frames | Newton steps per warm contact | warm (µs per frame) | warm, per contact (µs) | warm-only (µs per frame) | cold (µs per frame) | cold / warm |\n|---|---|---|---|---|---|---|---|---|---|\n",
    );
    for name in PAPER_SCENES {
        for motion in Motion::ALL {
            let row = measure(root, name, motion, passes)?;
            let contacts = row.contacts_per_frame.max(1.0);
            text.push_str(&format!(
                "| {} | {} | {:.2} | {:.1} % | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} | {:.1}x |\n",
                row.name,
                row.motion.name(),
                row.contacts_per_frame,
                100.0 * row.warm_fraction,
                row.steps_per_warm_contact,
                row.warm_us,
                row.warm_us / contacts,
                row.warm_only_us,
                row.cold_us,
                row.cold_us / row.warm_us
            ));
        }
    }
    Ok(text)
}

fn measure(root: &Path, name: &'static str, motion: Motion, passes: usize) -> Result<Row, String> {
    let path = root.join(format!("fixtures/scenes/{name}-two-contacts.json"));
    let scene = contacts::run::prepare_scene(&path).map_err(|e| format!("{name}: {e}"))?;
    let (objects, placed) = (&scene.objects, &scene.scene.objects);
    if objects.len() != 2 || placed.len() != 2 {
        return Err(format!("{name}: expected two objects"));
    }
    let (a, b) = (objects[0].as_ref(), objects[1].as_ref());
    let (oa, ob) = (&placed[0], &placed[1]);
    let pipeline = &scene.pipeline;
    let (pose_a, pose_b) = (oa.pose, ob.pose);
    let start = pipeline
        .query(a, &pose_a, b, &pose_b, &mut QueryScratch::default())
        .map_err(|e| format!("{name}: {e}"))?;
    let first = start
        .contacts
        .first()
        .ok_or(format!("{name}: no contact at the scene's pose"))?;
    let (c, n) = (first.point_a, first.normal);
    let trajectory: Vec<DPose3> = (0..FRAMES).map(|k| motion.pose(k, c, n, pose_b)).collect();
    let ways = Ways {
        pipeline,
        a,
        b,
        pose_a,
        trajectory: &trajectory,
        passes,
    };
    let (warm_us, census) = ways.coherent(64).map_err(|e| format!("{name}: {e}"))?;
    let (warm_only_us, _) = ways
        .coherent(u32::MAX)
        .map_err(|e| format!("{name}: {e}"))?;
    let cold_us = ways.cold().map_err(|e| format!("{name}: {e}"))?;
    Ok(Row {
        name,
        motion,
        contacts_per_frame: census.contacts as f64 / census.frames.max(1) as f64,
        warm_fraction: census.warm_frames as f64 / census.frames.max(1) as f64,
        steps_per_warm_contact: census.warm_steps as f64 / census.warm_contacts.max(1) as f64,
        warm_us,
        warm_only_us,
        cold_us,
    })
}

/// What the timed passes of the warm way did.
#[derive(Default)]
struct Census {
    frames: usize,
    contacts: usize,
    warm_frames: usize,
    warm_contacts: usize,
    warm_steps: u64,
}

/// One scene's trajectory and the ways along it.
struct Ways<'s> {
    pipeline: &'s ContactPipeline,
    a: &'s PreparedObject,
    b: &'s PreparedObject,
    pose_a: DPose3,
    trajectory: &'s [DPose3],
    passes: usize,
}

impl Ways<'_> {
    /// Coherent queries with this `max_warm_frames`: the median time per frame (µs) and the
    /// census of the timed passes.
    fn coherent(&self, max_warm_frames: u32) -> Result<(f64, Census), String> {
        let options = CoherenceOptions {
            max_warm_frames,
            ..CoherenceOptions::default()
        };
        let (mut cache, mut scratch, mut report) = (
            PairCache::new(),
            QueryScratch::default(),
            PairReport::default(),
        );
        let mut census = Census::default();
        let mut per_frame = Vec::with_capacity(self.passes);
        for pass in 0..=self.passes {
            let start = Instant::now();
            for pose in self.trajectory {
                let kind = self
                    .pipeline
                    .query_coherent(
                        self.a,
                        &self.pose_a,
                        self.b,
                        pose,
                        &options,
                        &mut cache,
                        &mut scratch,
                        &mut report,
                    )
                    .map_err(|e| e.to_string())?;
                if pass > 0 {
                    census.frames += 1;
                    census.contacts += report.contacts.len();
                    if kind == FrameKind::Warm {
                        census.warm_frames += 1;
                        census.warm_contacts += report.contacts.len();
                        census.warm_steps += report
                            .contacts
                            .iter()
                            .map(|c| u64::from(c.diagnostics.iterations))
                            .sum::<u64>();
                    }
                }
            }
            // The first pass builds the cache and warms the scratch: not timed.
            if pass > 0 {
                per_frame.push(start.elapsed().as_secs_f64() * 1e6 / self.trajectory.len() as f64);
            }
        }
        Ok((median(per_frame), census))
    }

    /// Cold queries with a persistent scratch: the median time per frame (µs).
    fn cold(&self) -> Result<f64, String> {
        let (mut scratch, mut report) = (QueryScratch::default(), PairReport::default());
        let mut per_frame = Vec::with_capacity(self.passes);
        for pass in 0..=self.passes {
            let start = Instant::now();
            for pose in self.trajectory {
                self.pipeline
                    .query_into(
                        self.a,
                        &self.pose_a,
                        self.b,
                        pose,
                        &mut scratch,
                        &mut report,
                    )
                    .map_err(|e| e.to_string())?;
            }
            if pass > 0 {
                per_frame.push(start.elapsed().as_secs_f64() * 1e6 / self.trajectory.len() as f64);
            }
        }
        Ok(median(per_frame))
    }
}

fn median(mut values: Vec<f64>) -> f64 {
    values.sort_by(f64::total_cmp);
    values.get(values.len() / 2).copied().unwrap_or(f64::NAN)
}
