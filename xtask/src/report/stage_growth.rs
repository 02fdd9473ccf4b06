//! How each stage's cost grows with the mesh resolution and with the number of components.

use super::stage_times::StageTimes;
use bvh_hybrid::HybridBvh;
use contact_pipeline::{ContactOptions, ContactPipeline};
use contacts::scene::Scene;
use exact_refine::NewtonRefiner;
use geom_param::{DPose3, DQuat, DVec3, ObjectDescription, SegmentSpec};
use mesh_narrowphase::{ConcavePath, MeshNarrowphase, MeshNarrowphaseOptions};
use std::path::Path;

/// One measured configuration.
pub struct GrowthRow {
    /// What varies: the chordal tolerance (mm) or the number of components.
    pub parameter: f64,
    /// Triangles of both objects' component meshes together.
    pub triangles: usize,
    /// Components of both objects together.
    pub components: usize,
    /// Stage medians (Stage 2 on the default path, the normal-cone patch hierarchy).
    pub times: StageTimes,
    /// Stage 2 median (µs) of the same queries with Stage 2 on the proxy-mesh path
    /// (`ConcavePath::ProxyRegions`), measured in the same run.
    pub mesh_proxy_us: f64,
}

/// A paper scene (two-contact pose) at each chordal tolerance.
///
/// # Errors
/// A message if the scene does not load or a query fails.
pub fn with_resolution(
    root: &Path,
    scene_name: &str,
    tolerances: &[f64],
    repetitions: usize,
) -> Result<Vec<GrowthRow>, String> {
    let path = root.join(format!("fixtures/scenes/{scene_name}-two-contacts.json"));
    let scene = Scene::from_file(&path).map_err(|e| format!("{scene_name}: {e}"))?;
    let [oa, ob] = scene.objects.as_slice() else {
        return Err(format!("{scene_name}: expected two objects"));
    };
    let revolved = |file: &geom_param::ObjectFile| match file {
        geom_param::ObjectFile::Revolved(d) => Ok(d.clone()),
        geom_param::ObjectFile::General(d) => Err(format!(
            "{scene_name}: {} is not a solid of revolution",
            d.name
        )),
    };
    let (da, db) = (revolved(&oa.description)?, revolved(&ob.description)?);
    tolerances
        .iter()
        .map(|&chordal| {
            let options = ContactOptions {
                chordal_tolerance: chordal,
                ..scene.options
            };
            measure_pair(
                options,
                (&da, &oa.pose),
                (&db, &ob.pose),
                chordal,
                repetitions,
            )
        })
        .collect()
}

/// A column of `n` bumps (one convex component each, concave edges between) against a ball
/// of radius 3 resting 0.02 mm off the middle bump, for each n.
///
/// # Errors
/// A message if a query fails.
pub fn with_components(counts: &[usize], repetitions: usize) -> Result<Vec<GrowthRow>, String> {
    let ball = ObjectDescription {
        name: "ball".into(),
        note: None,
        profile: vec![SegmentSpec::Arc {
            center: [0.0, 0.0],
            from: [0.0, -3.0],
            to: [0.0, 3.0],
            ccw: true,
        }],
    };
    counts
        .iter()
        .map(|&n| {
            let (column, bump_z, bump_r) = bumpy_column(n);
            let gap = 0.02;
            let ball_pose = DPose3::from_parts(
                DVec3::new(bump_r + 3.0 + gap, 0.0, bump_z),
                DQuat::from_rotation_z(0.3),
            );
            #[allow(clippy::cast_precision_loss)]
            let parameter = n as f64;
            measure_pair(
                ContactOptions::default(),
                (&column, &DPose3::IDENTITY),
                (&ball, &ball_pose),
                parameter,
                repetitions,
            )
        })
        .collect()
}

fn measure_pair(
    options: ContactOptions,
    (da, pose_a): (&ObjectDescription, &DPose3),
    (db, pose_b): (&ObjectDescription, &DPose3),
    parameter: f64,
    repetitions: usize,
) -> Result<GrowthRow, String> {
    let pipeline = ContactPipeline::new(options).map_err(|e| e.to_string())?;
    let proxy = ContactPipeline::with_stages(
        HybridBvh::default(),
        MeshNarrowphase {
            options: MeshNarrowphaseOptions {
                concave_path: ConcavePath::ProxyRegions,
                ..MeshNarrowphaseOptions::default()
            },
        },
        NewtonRefiner::default(),
        options,
    )
    .map_err(|e| e.to_string())?;
    let a = pipeline
        .prepare_description(da)
        .map_err(|e| format!("{}: {e}", da.name))?;
    let b = pipeline
        .prepare_description(db)
        .map_err(|e| format!("{}: {e}", db.name))?;
    let triangles = [&a, &b]
        .iter()
        .flat_map(|o| o.model.meshes.iter())
        .map(|m| m.triangles.len())
        .sum();
    let components = a.model.meshes.len() + b.model.meshes.len();
    let times = StageTimes::measure(&pipeline, &a, pose_a, &b, pose_b, repetitions)?;
    let old = StageTimes::measure(&proxy, &a, pose_a, &b, pose_b, repetitions)?;
    Ok(GrowthRow {
        parameter,
        triangles,
        components,
        times,
        mesh_proxy_us: old.mesh_us,
    })
}

/// A column of `n` circular bumps of radius 1 (30° either side of the outward direction),
/// consecutive bumps meeting at concave edges, closed by flat disks: `n` convex components
/// plus the caps. Returns the description, the middle bump's height and its outer radius (mm).
fn bumpy_column(n: usize) -> (ObjectDescription, f64, f64) {
    let (r0, a, half) = (5.0, 1.0, 30f64.to_radians());
    let (dr, dz) = (a * half.cos(), a * half.sin());
    let pitch = 2.0 * dz;
    let mut profile = Vec::with_capacity(n + 2);
    profile.push(SegmentSpec::Line {
        from: [0.0, -dz],
        to: [r0 + dr, -dz],
    });
    #[allow(clippy::cast_precision_loss)]
    let height = |i: usize| pitch * i as f64;
    for i in 0..n {
        let z = height(i);
        profile.push(SegmentSpec::Arc {
            center: [r0, z],
            from: [r0 + dr, z - dz],
            to: [r0 + dr, z + dz],
            ccw: true,
        });
    }
    let top = height(n.saturating_sub(1)) + dz;
    profile.push(SegmentSpec::Line {
        from: [r0 + dr, top],
        to: [0.0, top],
    });
    let description = ObjectDescription {
        name: format!("column of {n} bumps"),
        note: None,
        profile,
    };
    (description, height(n / 2), r0 + a)
}
