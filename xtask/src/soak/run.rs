//! The soak driver: poses for each ordered pair, the pipeline's answer for each, the properties
//! and the oracle comparison, tallied per pair.

use crate::fixture_objects;
use crate::paper_objects::paper_objects;
use crate::rng::SplitMix64;
use crate::soak::oracle_check::{compare, oracle_report};
use crate::soak::pose_generator::{GapKind, PoseGenerator, SoakPose};
use crate::soak::properties::{Property, PropertyChecker, PropertyFailure};
use contact_pipeline::{ContactOptions, ContactPipeline, PairState, PreparedObject};
use geom_param::MeshOptions;
use std::collections::BTreeMap;

/// What to run.
#[derive(Clone, Debug, PartialEq)]
pub struct SoakConfig {
    /// Total number of poses, spread evenly over the pairs (the first pairs get one more when
    /// it does not divide).
    pub poses: usize,
    /// Base seed: pose k of pair p has seed [`pose_seed`]`(seed, p, k)`.
    pub seed: u64,
    /// Ordered pairs (A, B) by object name; empty for all pairs of the object set.
    pub pairs: Vec<(String, String)>,
    /// Also the general fixture objects (rounded box, tube, bracket, loft), not only the six
    /// paper objects.
    pub general: bool,
}

/// The seed of pose `k` of the pair at index `pair` (0..36 in the order of
/// [`all_pairs`]) under base seed `base`.
#[must_use]
pub fn pose_seed(base: u64, pair: usize, k: usize) -> u64 {
    // The base is mixed first, so that runs with nearby base seeds share no poses.
    let mixed = SplitMix64::new(base).next_u64();
    SplitMix64::new(mixed ^ ((pair as u64) << 40) ^ k as u64).next_u64()
}

/// Every ordered pair of the six paper objects, A first; with `general`, followed by every
/// other ordered pair of all fixture objects (so that a paper pair keeps its index, and its
/// poses their seeds).
#[must_use]
pub fn all_pairs(general: bool) -> Vec<(String, String)> {
    let paper: Vec<String> = paper_objects().into_iter().map(|o| o.name).collect();
    let square = |names: &[String]| -> Vec<(String, String)> {
        names
            .iter()
            .flat_map(|a| names.iter().map(move |b| (a.clone(), b.clone())))
            .collect()
    };
    let mut pairs = square(&paper);
    if general {
        let all: Vec<String> = fixture_objects()
            .iter()
            .map(|o| o.name().to_string())
            .collect();
        let more: Vec<_> = square(&all)
            .into_iter()
            .filter(|p| !pairs.contains(p))
            .collect();
        pairs.extend(more);
    }
    pairs
}

/// A worst error and the pose it came from.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Worst {
    /// The error (mm).
    pub value: f64,
    /// Seed of the pose.
    pub seed: u64,
}

impl Worst {
    pub(crate) fn update(&mut self, value: f64, seed: u64) {
        if value > self.value {
            *self = Self { value, seed };
        }
    }
}

/// One failure, reproducible from its pair and seed.
#[derive(Clone, Debug, PartialEq)]
pub struct FailureRecord {
    /// Seed of the pose.
    pub seed: u64,
    /// The pose.
    pub pose: Option<SoakPose>,
    /// What failed: "missed", "false", "state", "depth", a property name or "generator".
    pub what: String,
    /// Details.
    pub detail: String,
}

/// Tallies of one ordered pair.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PairStats {
    /// Poses run.
    pub poses: usize,
    /// Pipeline states: separated, contact, penetration.
    pub states: [usize; 3],
    /// Poses by the gap kind the generator aimed at.
    pub kinds: BTreeMap<GapKind, usize>,
    /// Oracle contacts in the band with no pipeline contact.
    pub missed: usize,
    /// Pipeline contacts with no oracle contact.
    pub false_contacts: usize,
    /// States that differ from the oracle's away from the band edges.
    pub state_mismatches: usize,
    /// Poses with the oracle's minimum or some contact within the ambiguity tolerance of a band
    /// edge (not counted as failures).
    pub borderline: usize,
    /// Property failures by property.
    pub property_failures: BTreeMap<Property, usize>,
    /// Largest |distance difference| of matched contacts (mm).
    pub worst_distance: Worst,
    /// Largest point difference of matched contacts (mm).
    pub worst_point: Worst,
    /// Penetration depths that disagree with the oracle's witnesses.
    pub depth_mismatches: usize,
    /// Largest |depth difference| of matched penetration witnesses (mm).
    pub worst_depth: Worst,
    /// Poses whose oracle runs at its two spacings disagree (unmatched contacts).
    pub cross_check: usize,
    /// Disagreements explained by the oracle's documented limits (not failures).
    pub oracle_limits: usize,
    /// Seeds the generator could not place.
    pub generator_failures: usize,
    /// Every failure, and every oracle-limit note, for reproduction.
    pub failures: Vec<FailureRecord>,
}

impl PairStats {
    /// Missed + false + state mismatches + depth mismatches + property failures + generator
    /// failures.
    #[must_use]
    pub fn failure_count(&self) -> usize {
        self.missed
            + self.false_contacts
            + self.state_mismatches
            + self.depth_mismatches
            + self.property_failures.values().sum::<usize>()
            + self.generator_failures
    }

    fn add_properties(&mut self, seed: u64, pose: &SoakPose, failures: Vec<PropertyFailure>) {
        for f in failures {
            *self.property_failures.entry(f.property).or_default() += 1;
            self.failures.push(FailureRecord {
                seed,
                pose: Some(*pose),
                what: f.property.name().into(),
                detail: f.detail,
            });
        }
    }
}

/// The whole run: per-pair tallies, in pair order.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SoakSummary {
    /// (A, B) and its tallies.
    pub pairs: Vec<((String, String), PairStats)>,
}

/// Every fixture object (paper and general) prepared for `pipeline`, by name.
///
/// # Errors
/// A message if an object fails to build.
pub fn prepare_objects(
    pipeline: &ContactPipeline,
) -> Result<BTreeMap<String, PreparedObject>, String> {
    let mesh = MeshOptions {
        chordal_tolerance: pipeline.options().chordal_tolerance,
    };
    fixture_objects()
        .iter()
        .map(|d| {
            d.build(&mesh)
                .map(|model| (d.name().to_string(), pipeline.prepare(model)))
                .map_err(|e| format!("{}: {e}", d.name()))
        })
        .collect()
}

/// Runs one pose: generates it, queries, checks the properties (and the oracle), and tallies.
/// Returns the pose (`None` when the generator failed).
fn run_pose(
    pipeline: &ContactPipeline,
    a: &PreparedObject,
    b: &PreparedObject,
    seed: u64,
    stats: &mut PairStats,
) -> Result<Option<SoakPose>, String> {
    stats.poses += 1;
    let mut generator = PoseGenerator::new(pipeline, a, b);
    let pose = match generator.generate(seed) {
        Ok(pose) => pose,
        Err(e) => {
            stats.generator_failures += 1;
            stats.failures.push(FailureRecord {
                seed,
                pose: None,
                what: "generator".into(),
                detail: e,
            });
            return Ok(None);
        }
    };
    *stats.kinds.entry(pose.kind).or_default() += 1;
    let mut scratch = Default::default();
    let report = pipeline
        .query(
            a,
            &geom_param::DPose3::IDENTITY,
            b,
            &pose.pose_b,
            &mut scratch,
        )
        .map_err(|e| e.to_string())?;
    stats.states[match report.state {
        PairState::Separated => 0,
        PairState::Contact => 1,
        PairState::Penetration => 2,
    }] += 1;
    let mut rng = SplitMix64::new(seed ^ 0x005E_ED0F_5A4E);
    let failures = PropertyChecker::new(pipeline, a, b).check(&pose.pose_b, &report, &mut rng)?;
    stats.add_properties(seed, &pose, failures);
    let options = pipeline.options();
    let size = a.model.scale.max(b.model.scale);
    let oracle = oracle_report(&a.model.solid, &b.model.solid, &pose.pose_b, options)?;
    let verdict = compare(&report, &oracle, options, size, pose.target_gap);
    let mut record = |what: &str, detail: String| {
        stats.failures.push(FailureRecord {
            seed,
            pose: Some(pose),
            what: what.into(),
            detail,
        });
    };
    if let Some(detail) = verdict.state_mismatch {
        record("state", detail);
        stats.state_mismatches += 1;
    }
    stats.missed += verdict.missed.len();
    for detail in verdict.missed {
        record("missed", detail);
    }
    stats.false_contacts += verdict.false_contacts.len();
    for detail in verdict.false_contacts {
        record("false", detail);
    }
    stats.depth_mismatches += verdict.depth_mismatches.len();
    for detail in verdict.depth_mismatches {
        record("depth", detail);
    }
    stats.worst_depth.update(verdict.worst_depth, seed);
    stats.oracle_limits += verdict.oracle_limits.len();
    for detail in verdict.oracle_limits {
        record("oracle-limit", detail);
    }
    stats.borderline += usize::from(verdict.borderline);
    stats.cross_check += usize::from(verdict.cross_check_disagrees);
    stats.worst_distance.update(verdict.worst_distance, seed);
    stats.worst_point.update(verdict.worst_point, seed);
    Ok(Some(pose))
}

/// Runs the soak. `progress` is called after each pair with its tallies.
///
/// # Errors
/// A message for an unknown object name or a pipeline that refuses a pose.
pub fn run_soak(
    config: &SoakConfig,
    mut progress: impl FnMut(&(String, String), &PairStats),
) -> Result<SoakSummary, String> {
    let pipeline = ContactPipeline::new(ContactOptions::default()).map_err(|e| e.to_string())?;
    let objects = prepare_objects(&pipeline)?;
    let all = all_pairs(config.general);
    let chosen: Vec<usize> = if config.pairs.is_empty() {
        (0..all.len()).collect()
    } else {
        config
            .pairs
            .iter()
            .map(|p| {
                all.iter()
                    .position(|q| q == p)
                    .ok_or(format!("unknown pair {}-{}", p.0, p.1))
            })
            .collect::<Result<_, _>>()?
    };
    let mut summary = SoakSummary::default();
    let per_pair = config.poses / chosen.len().max(1);
    let extra = config.poses % chosen.len().max(1);
    for (rank, &index) in chosen.iter().enumerate() {
        let pair = &all[index];
        let (a, b) = (&objects[&pair.0], &objects[&pair.1]);
        let mut stats = PairStats::default();
        let count = per_pair + usize::from(rank < extra);
        for k in 0..count {
            run_pose(
                &pipeline,
                a,
                b,
                pose_seed(config.seed, index, k),
                &mut stats,
            )?;
        }
        progress(pair, &stats);
        summary.pairs.push((pair.clone(), stats));
    }
    Ok(summary)
}

/// Runs the single pose `seed` of pair (a, b), to reproduce a failure: the pose (`None` if the
/// generator failed) and its tallies.
///
/// # Errors
/// As [`run_soak`].
pub fn replay(a: &str, b: &str, seed: u64) -> Result<(Option<SoakPose>, PairStats), String> {
    let pipeline = ContactPipeline::new(ContactOptions::default()).map_err(|e| e.to_string())?;
    let objects = prepare_objects(&pipeline)?;
    let get = |n: &str| objects.get(n).ok_or(format!("unknown object {n}"));
    let mut stats = PairStats::default();
    let pose = run_pose(&pipeline, get(a)?, get(b)?, seed, &mut stats)?;
    Ok((pose, stats))
}
