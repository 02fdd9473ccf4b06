//! Stage 2's two triangle paths side by side, measured in one run on the same poses: the
//! paper's proxy-mesh regions (`ConcavePath::ProxyRegions`, the path before issue 15) and the
//! normal-cone patch hierarchy (`ConcavePath::NormalCones`, the default), on every fixture scene
//! and the report's concave scenes. The four timings of a row (each path warm and cold) are
//! interleaved query by query, so that the machine's load falls on all of them alike.

use super::timing::median;
use bvh_hybrid::HybridBvh;
use contact_oracle::{ClosedFormScene, closed_form};
use contact_pipeline::{
    ContactOptions, ContactPipeline, PairReport, PairState, PreparedObject, QueryScratch,
};
use contacts::scene::Scene;
use exact_refine::NewtonRefiner;
use geom_param::{DPose3, DQuat, DVec3, ObjectDescription, ObjectFile, SegmentSpec};
use mesh_narrowphase::{ConcavePath, MeshNarrowphase, MeshNarrowphaseOptions};
use std::path::Path;
use std::time::Instant;

/// One scene measured with both paths.
pub struct ComparisonRow {
    /// Scene name.
    pub scene: String,
    /// Pair state and contact count with the proxy path.
    pub proxy_answer: (PairState, usize),
    /// Pair state and contact count with the normal-cone path.
    pub cones_answer: (PairState, usize),
    /// Whether both paths report the same contacts (distances within 1e-9 mm and points within
    /// 1e-6 mm, in any order).
    pub same_contacts: bool,
    /// Whole-query medians (µs): proxy path and normal cones with a warm scratch (GJK warm
    /// starts; for the cones the previous query's front carried), then both with a fresh
    /// scratch per query.
    pub whole_us: [f64; 4],
    /// Stage 2 medians (µs), likewise.
    pub mesh_us: [f64; 4],
}

/// The pipeline with Stage 2 on `path`.
fn pipeline(options: ContactOptions, path: ConcavePath) -> Result<ContactPipeline, String> {
    ContactPipeline::with_stages(
        HybridBvh::default(),
        MeshNarrowphase {
            options: MeshNarrowphaseOptions {
                concave_path: path,
                ..MeshNarrowphaseOptions::default()
            },
        },
        NewtonRefiner::default(),
        options,
    )
    .map_err(|e| e.to_string())
}

/// A scene to measure: options, both objects and their poses.
struct Case {
    name: String,
    options: ContactOptions,
    a: (ObjectFile, DPose3),
    b: (ObjectFile, DPose3),
}

fn fixture_cases(root: &Path) -> Result<Vec<Case>, String> {
    let dir = root.join("fixtures/scenes");
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .map_err(|e| format!("{}: {e}", dir.display()))?
        .filter_map(Result::ok)
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|x| x == "json"))
        .collect();
    files.sort();
    files
        .iter()
        .map(|path| {
            let scene = Scene::from_file(path).map_err(|e| format!("{}: {e}", path.display()))?;
            let [oa, ob] = scene.objects.as_slice() else {
                return Err(format!("{}: expected two objects", path.display()));
            };
            Ok(Case {
                name: path
                    .file_stem()
                    .map(|s| s.to_string_lossy().into_owned())
                    .unwrap_or_default(),
                options: scene.options,
                a: (oa.description.clone(), oa.pose),
                b: (ob.description.clone(), ob.pose),
            })
        })
        .collect()
}

fn closed_form_case(scene: ClosedFormScene) -> Case {
    Case {
        name: scene.name,
        options: ContactOptions::default(),
        a: (ObjectFile::Revolved(scene.a), scene.pose_a),
        b: (ObjectFile::Revolved(scene.b), scene.pose_b),
    }
}

/// A ball of radius 10 resting 0.03 mm above the bottom of a hemispherical cavity of radius 30
/// in a cup 80 mm wide (`crates/contact-pipeline/tests/pipeline.rs`).
fn ball_in_cavity() -> Case {
    let line = |from: [f64; 2], to: [f64; 2]| SegmentSpec::Line { from, to };
    let cup = ObjectDescription {
        name: "cup".into(),
        note: None,
        profile: vec![
            line([0.0, 0.0], [40.0, 0.0]),
            line([40.0, 0.0], [40.0, 40.0]),
            line([40.0, 40.0], [30.0, 40.0]),
            SegmentSpec::Arc {
                center: [0.0, 40.0],
                from: [30.0, 40.0],
                to: [0.0, 10.0],
                ccw: false,
            },
        ],
    };
    let ball = ObjectDescription {
        name: "ball".into(),
        note: None,
        profile: vec![SegmentSpec::Arc {
            center: [0.0, 0.0],
            from: [0.0, -10.0],
            to: [0.0, 10.0],
            ccw: true,
        }],
    };
    Case {
        name: "ball in a cavity (r 10, R 30, gap 0.03)".into(),
        options: ContactOptions::default(),
        a: (ObjectFile::Revolved(cup), DPose3::IDENTITY),
        b: (
            ObjectFile::Revolved(ball),
            DPose3 {
                rotation: DQuat::IDENTITY,
                translation: DVec3::new(0.0, 0.0, 20.03),
            },
        ),
    }
}

/// Every case: the fixture scenes, then the report's concave scenes.
fn cases(root: &Path) -> Result<Vec<Case>, String> {
    let mut all = fixture_cases(root)?;
    all.push(closed_form_case(closed_form::sphere_in_bowl(
        8.0,
        20.0,
        0.02,
        0.3,
        1.1,
        DQuat::from_rotation_z(0.5),
    )));
    all.push(ball_in_cavity());
    Ok(all)
}

fn same_contacts(x: &PairReport, y: &PairReport) -> bool {
    x.state == y.state
        && x.contacts.len() == y.contacts.len()
        && x.contacts.iter().all(|c| {
            y.contacts.iter().any(|d| {
                (c.distance - d.distance).abs() <= 1e-9
                    && c.point_a.distance(d.point_a) <= 1e-6
                    && c.point_b.distance(d.point_b) <= 1e-6
            })
        })
}

/// Measures every case `repetitions` times with each path (after one untimed query each, which
/// builds the lazily prepared structures).
///
/// # Errors
/// A message if a scene does not load or a query fails.
pub fn measure(root: &Path, repetitions: usize) -> Result<Vec<ComparisonRow>, String> {
    cases(root)?
        .into_iter()
        .map(|case| measure_case(&case, repetitions))
        .collect()
}

fn measure_case(case: &Case, repetitions: usize) -> Result<ComparisonRow, String> {
    let proxy = pipeline(case.options, ConcavePath::ProxyRegions)?;
    let cones = pipeline(case.options, ConcavePath::NormalCones)?;
    let mesh = geom_param::MeshOptions {
        chordal_tolerance: case.options.chordal_tolerance,
    };
    let prepare = |d: &ObjectFile| -> Result<PreparedObject, String> {
        d.build(&mesh)
            .map(|model| cones.prepare(model))
            .map_err(|e| format!("{}: {}: {e}", case.name, d.name()))
    };
    let (a, b) = (prepare(&case.a.0)?, prepare(&case.b.0)?);
    let (pose_a, pose_b) = (&case.a.1, &case.b.1);
    let query =
        |p: &ContactPipeline, scratch: &mut QueryScratch| -> Result<(PairReport, f64), String> {
            let start = Instant::now();
            let report = p
                .query(&a, pose_a, &b, pose_b, scratch)
                .map_err(|e| format!("{}: {e}", case.name))?;
            Ok((report, start.elapsed().as_secs_f64() * 1e6))
        };
    let (mut proxy_scratch, mut warm_scratch) = (QueryScratch::default(), QueryScratch::default());
    let (proxy_report, _) = query(&proxy, &mut proxy_scratch)?;
    let (cones_report, _) = query(&cones, &mut warm_scratch)?;
    let n = repetitions.max(1);
    let mut whole: [Vec<f64>; 4] = Default::default();
    let mut mesh: [Vec<f64>; 4] = Default::default();
    for _ in 0..n {
        let (r, t) = query(&proxy, &mut proxy_scratch)?;
        whole[0].push(t);
        mesh[0].push(r.stats.mesh_us);
        let (r, t) = query(&cones, &mut warm_scratch)?;
        whole[1].push(t);
        mesh[1].push(r.stats.mesh_us);
        let (r, t) = query(&proxy, &mut QueryScratch::default())?;
        whole[2].push(t);
        mesh[2].push(r.stats.mesh_us);
        let (r, t) = query(&cones, &mut QueryScratch::default())?;
        whole[3].push(t);
        mesh[3].push(r.stats.mesh_us);
    }
    Ok(ComparisonRow {
        scene: case.name.clone(),
        proxy_answer: (proxy_report.state, proxy_report.contacts.len()),
        cones_answer: (cones_report.state, cones_report.contacts.len()),
        same_contacts: same_contacts(&proxy_report, &cones_report),
        whole_us: whole.each_mut().map(|v| median(v)),
        mesh_us: mesh.each_mut().map(|v| median(v)),
    })
}
