//! The paper's measurements repeated here: Table 1 (tree check against colliding leaf pairs),
//! Fig. 2 (total time against the number of feature pairs), Table 2 (Newton time per feature
//! pair kind) and Table 3 (total time per scene). The paper's figures were measured on a
//! 2.8 GHz Pentium (C++); ours on the machine named in the report.

use super::stage_times::StageTimes;
use super::timing::{median, median_us};
use crate::rng::SplitMix64;
use crate::soak::pose_generator::PoseGenerator;
use bvh_hybrid::{BroadPhase, HybridBvh, TraversalScratch};
use contact_pipeline::{ContactOptions, ContactPipeline, PairState, PreparedObject, QueryScratch};
use contacts::builtin_objects::builtin_object;
use contacts::scene::Scene;
use geom_param::{DPose3, FeatureLocation, MeshOptions, ObjectDescription, ObjectModel};
use std::collections::BTreeMap;
use std::path::Path;

/// Table 1 of the paper (µs) for 0..=6 colliding leaf pairs.
pub const PAPER_TABLE1_US: [f64; 7] = [10.0, 150.0, 300.0, 330.0, 420.0, 460.0, 510.0];
/// Table 2 of the paper (µs): Newton time per feature pair kind.
pub const PAPER_TABLE2_US: [(&str, f64); 4] = [
    ("point-curve", 170.0),
    ("curve-curve", 320.0),
    ("curve-surface", 620.0),
    ("surface-surface", 950.0),
];
/// Table 3 of the paper (µs): total time of the two-contact scenes.
pub const PAPER_TABLE3_US: [(&str, f64); 4] = [
    ("pencil-paperweight", 2680.0),
    ("paperweight-goblet", 3130.0),
    ("pencil-bowl", 2950.0),
    ("vase-vase", 4870.0),
];
/// Fig. 2 of the paper: "the average running time ranges from 1.4 to 1.8 millisecond".
pub const PAPER_FIG2_RANGE_US: (f64, f64) = (1400.0, 1800.0);

/// How much work the tables do.
#[derive(Clone, Copy, Debug)]
pub struct TableSettings {
    /// Poses per Table 1 group.
    pub poses_per_group: usize,
    /// Random near-contact queries for Fig. 2 and Table 2.
    pub random_queries: usize,
    /// Timed repetitions per measured query.
    pub repetitions: usize,
}

/// A paper object built at `chordal` mm.
///
/// # Errors
/// A message if the built-in object does not build.
pub fn paper_object(name: &str, chordal: f64) -> Result<ObjectModel, String> {
    let text = builtin_object(name).ok_or_else(|| format!("no built-in object {name}"))?;
    ObjectDescription::from_json(text)
        .map_err(|e| format!("{name}: {e}"))?
        .build(&MeshOptions {
            chordal_tolerance: chordal,
        })
        .map_err(|e| format!("{name}: {e}"))
}

/// One row of Table 1.
pub struct Table1Row {
    /// Colliding leaf pairs.
    pub pairs: usize,
    /// Poses timed in this group.
    pub poses: usize,
    /// Median µs of the whole tree-vs-tree check.
    pub ours_us: f64,
}

/// Table 1: the paperweight's tree against the goblet's (default margin and tolerance), random
/// near-contact poses grouped by the number of colliding leaf pairs.
///
/// # Errors
/// A message if an object does not build.
pub fn table1(settings: &TableSettings) -> Result<Vec<Table1Row>, String> {
    let options = ContactOptions::default();
    let paperweight = paper_object("paperweight", options.chordal_tolerance)?;
    let goblet = paper_object("goblet", options.chordal_tolerance)?;
    let phase = HybridBvh::default();
    let (a, b) = (
        phase.build(&paperweight, options.margin),
        phase.build(&goblet, options.margin),
    );
    let mut scratch = TraversalScratch::default();
    let mut out = Vec::new();
    let mut groups: [Vec<DPose3>; 7] = Default::default();
    let mut rng = SplitMix64::new(0x7ab1e1);
    for _ in 0..200_000 {
        if groups.iter().all(|g| g.len() >= settings.poses_per_group) {
            break;
        }
        let spread = rng.uniform(0.1, 30.0);
        let pose = near_contact_pose(&mut rng, &paperweight, &goblet, spread);
        phase.overlapping_components(&a, &b, &pose, &mut scratch, &mut out);
        if let Some(group) = groups.get_mut(out.len()) {
            if group.len() < settings.poses_per_group {
                group.push(pose);
            }
        }
    }
    Ok(groups
        .iter()
        .enumerate()
        .filter(|(_, poses)| !poses.is_empty())
        .map(|(pairs, poses)| {
            let mut i = 0;
            let (ours_us, _) = median_us(settings.repetitions * poses.len(), || {
                i = (i + 1) % poses.len();
                phase.overlapping_components(&a, &b, &poses[i], &mut scratch, &mut out);
                out.len()
            });
            Table1Row {
                pairs,
                poses: poses.len(),
                ours_us,
            }
        })
        .collect())
}

/// A pose of B in A's frame that brings a random mesh vertex of B near a random mesh vertex of
/// A: B's point lands on A's point moved along A's outward normal by a uniform amount in
/// [−spread, 2·spread] (mm) plus a sideways jitter of up to `spread`, under a uniformly random
/// rotation. Spreads up to tens of mm give every number of colliding leaf pairs.
fn near_contact_pose(
    rng: &mut SplitMix64,
    a: &ObjectModel,
    b: &ObjectModel,
    spread: f64,
) -> DPose3 {
    let mut surface_point = |object: &ObjectModel| {
        let mesh = &object.meshes[rng.index(object.meshes.len())];
        let k = rng.index(mesh.positions.len());
        (mesh.positions[k], mesh.normals[k])
    };
    let (pa, na) = surface_point(a);
    let (pb, _) = surface_point(b);
    let rotation = rng.rotation();
    let target =
        pa + na * rng.uniform(-spread, 2.0 * spread) + rng.direction() * rng.uniform(0.0, spread);
    DPose3::from_parts(target - rotation * pb, rotation)
}

/// The paper's name for a feature kind: vertex = point, edge = curve, face = surface.
fn kind(location: &FeatureLocation) -> &'static str {
    match location {
        FeatureLocation::Vertex { .. } => "point",
        FeatureLocation::Edge { .. } => "curve",
        FeatureLocation::Face { .. } => "surface",
    }
}

/// A feature pair kind in the paper's order (point < curve < surface), e.g. "curve-surface".
fn pair_kind(a: &FeatureLocation, b: &FeatureLocation) -> String {
    let rank = |k: &str| match k {
        "point" => 0,
        "curve" => 1,
        _ => 2,
    };
    let (ka, kb) = (kind(a), kind(b));
    if rank(ka) <= rank(kb) {
        format!("{ka}-{kb}")
    } else {
        format!("{kb}-{ka}")
    }
}

/// Fig. 2 and Table 2 from one set of random near-contact queries of the paper's four pairs.
pub struct RandomQueryTables {
    /// Fig. 2: feature pairs refined → (queries, median total µs).
    pub by_feature_pairs: BTreeMap<usize, (usize, f64)>,
    /// Table 2: feature pair kind → (solves, median µs per Stage 3 solve), from queries with
    /// one refined pair that ended as one contact.
    pub by_kind: BTreeMap<String, (usize, f64)>,
    /// Queries timed (those in a contact state).
    pub queries: usize,
}

/// Runs Fig. 2 and Table 2 on the soak's random near-contact poses (B set at a random gap
/// across and around the band, some tilted onto a second contact), keeping those that end in a
/// contact state.
///
/// # Errors
/// A message if an object does not build or a query fails.
pub fn random_query_tables(settings: &TableSettings) -> Result<RandomQueryTables, String> {
    let pipeline = ContactPipeline::new(ContactOptions::default()).map_err(|e| e.to_string())?;
    let pairs = [
        ("pencil", "paperweight"),
        ("paperweight", "goblet"),
        ("pencil", "bowl"),
        ("vase", "vase"),
    ];
    let chordal = pipeline.options().chordal_tolerance;
    let prepared: Vec<(PreparedObject, PreparedObject)> = pairs
        .iter()
        .map(|(a, b)| {
            Ok((
                pipeline.prepare(paper_object(a, chordal)?),
                pipeline.prepare(paper_object(b, chordal)?),
            ))
        })
        .collect::<Result<_, String>>()?;
    let mut totals: BTreeMap<usize, Vec<f64>> = BTreeMap::new();
    let mut kinds: BTreeMap<String, Vec<f64>> = BTreeMap::new();
    let mut generators: Vec<PoseGenerator<'_>> = prepared
        .iter()
        .map(|(a, b)| PoseGenerator::new(&pipeline, a, b))
        .collect();
    let mut scratch = QueryScratch::default();
    let mut queries = 0;
    for q in 0..settings.random_queries {
        let (a, b) = &prepared[q % prepared.len()];
        let pose_b = generators[q % prepared.len()]
            .generate(0xf162_0000 + q as u64)?
            .pose_b;
        let probe = pipeline
            .query(a, &DPose3::IDENTITY, b, &pose_b, &mut scratch)
            .map_err(|e| e.to_string())?;
        // The paper's Fig. 2 and Table 2 are about contact states: penetrating and separated
        // poses are not timed.
        if probe.state != PairState::Contact {
            continue;
        }
        let times = StageTimes::measure(
            &pipeline,
            a,
            &DPose3::IDENTITY,
            b,
            &pose_b,
            settings.repetitions,
        )?;
        queries += 1;
        totals
            .entry(times.report.stats.refined)
            .or_default()
            .push(times.total_us);
        if let [contact] = times.report.contacts.as_slice() {
            if times.report.stats.refined == 1 {
                kinds
                    .entry(pair_kind(&contact.location_a, &contact.location_b))
                    .or_default()
                    .push(times.refine_us);
            }
        }
    }
    Ok(RandomQueryTables {
        by_feature_pairs: summarise(totals),
        by_kind: summarise(kinds),
        queries,
    })
}

/// Each key's count and median.
fn summarise<K: Ord>(groups: BTreeMap<K, Vec<f64>>) -> BTreeMap<K, (usize, f64)> {
    groups
        .into_iter()
        .map(|(k, mut v)| {
            let n = v.len();
            (k, (n, median(&mut v)))
        })
        .collect()
}

/// One row of Table 3 / the per-stage share.
pub struct SceneTimes {
    /// Scene name.
    pub name: String,
    /// Stage medians and the answer.
    pub times: StageTimes,
}

/// Table 3: each paper scene's two-contact pose (fixtures/scenes), default pipeline.
///
/// # Errors
/// A message if a scene does not load or a query fails.
pub fn table3(root: &Path, repetitions: usize) -> Result<Vec<SceneTimes>, String> {
    PAPER_TABLE3_US
        .iter()
        .map(|(name, _)| {
            let path = root.join(format!("fixtures/scenes/{name}-two-contacts.json"));
            let scene = Scene::from_file(&path).map_err(|e| format!("{name}: {e}"))?;
            let pipeline = ContactPipeline::new(scene.options).map_err(|e| e.to_string())?;
            let [oa, ob] = scene.objects.as_slice() else {
                return Err(format!("{name}: expected two objects"));
            };
            let mesh = geom_param::MeshOptions {
                chordal_tolerance: scene.options.chordal_tolerance,
            };
            let prepare = |file: &geom_param::ObjectFile| {
                file.build(&mesh)
                    .map(|model| pipeline.prepare(model))
                    .map_err(|e| e.to_string())
            };
            let (a, b) = (prepare(&oa.description)?, prepare(&ob.description)?);
            let times = StageTimes::measure(&pipeline, &a, &oa.pose, &b, &ob.pose, repetitions)?;
            Ok(SceneTimes {
                name: (*name).to_string(),
                times,
            })
        })
        .collect()
}
