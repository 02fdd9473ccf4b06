//! Convex-convex GJK on the paper objects' convex components near contact: cold (no warm start)
//! and warm (warm start carried across a slowly moving sequence of poses), against parry's
//! `ConvexPolyhedron` (which scans every vertex per support call), and the full query.

use criterion::Criterion;
use geom_param::{
    ComponentId, ConvexHull, DPose3, DQuat, DVec3, MeshOptions, ObjectDescription, ObjectModel,
};
use mesh_narrowphase::convex::convex_pair::{GjkScratch, HullProximity, WarmStart, hull_proximity};
use mesh_narrowphase::{
    ComponentRef, ContactBand, MeshNarrowphase, MeshOutput, MeshPhase, MeshScratch,
};
use parry3d_f64::query;
use parry3d_f64::shape::ConvexPolyhedron;
use std::hint::black_box;

fn load(name: &str) -> ObjectModel {
    let path = format!(
        "{}/../../fixtures/objects/{name}.json",
        env!("CARGO_MANIFEST_DIR")
    );
    let text = std::fs::read_to_string(path).expect("fixture");
    ObjectDescription::from_json(&text)
        .expect("valid")
        .build(&MeshOptions {
            chordal_tolerance: 0.05,
        })
        .expect("built")
}

fn largest_hull(object: &ObjectModel) -> (ComponentId, &ConvexHull) {
    object
        .hulls
        .iter()
        .enumerate()
        .filter_map(|(i, h)| h.as_ref().map(|h| (ComponentId(i as u32), h)))
        .max_by_key(|(_, h)| h.points.len())
        .expect("a convex component")
}

/// 64 poses of B along a slow path, each with the hulls about 0.1 mm apart (B's hull centroid
/// moved away from A's along a slowly turning direction).
fn near_contact_path(a: &ConvexHull, b: &ConvexHull) -> Vec<DPose3> {
    let centroid = |h: &ConvexHull| h.points.iter().sum::<DVec3>() / h.points.len() as f64;
    let (ca, cb) = (centroid(a), centroid(b));
    let mut scratch = GjkScratch::default();
    let mut poses = Vec::new();
    for k in 0..64 {
        let angle = 0.002 * k as f64;
        let rotation = DQuat::from_rotation_z(angle) * DQuat::from_rotation_x(0.3);
        let dir = DVec3::new(1.0, 0.2 * angle.sin(), 0.1).normalize();
        // Bisect the distance along `dir` at which the hull distance is 0.1 mm.
        let (mut lo, mut hi) = (0.0, 500.0);
        for _ in 0..60 {
            let t = 0.5 * (lo + hi);
            let pose = DPose3 {
                rotation,
                translation: ca - rotation * cb + dir * t,
            };
            let (got, _) = hull_proximity(
                a,
                b,
                &pose,
                1e4,
                1e-9,
                &mut WarmStart::default(),
                &mut scratch,
            );
            match got {
                HullProximity::Close { p1, p2 } if p1.distance(p2) > 0.1 => hi = t,
                HullProximity::Separated => hi = t,
                _ => lo = t,
            }
        }
        poses.push(DPose3 {
            rotation,
            translation: ca - rotation * cb + dir * hi,
        });
    }
    poses
}

fn bench(c: &mut Criterion) {
    let pairs = [
        ("paperweight", "goblet"),
        ("pencil", "paperweight"),
        ("vase", "vase"),
        ("jar", "pencil"),
    ];
    let mut group = c.benchmark_group("convex_gjk");
    for (na, nb) in pairs {
        let (a, b) = (load(na), load(nb));
        let ((ca, ha), (cb, hb)) = (largest_hull(&a), largest_hull(&b));
        let poses = near_contact_path(ha, hb);
        let label = format!("{na}({})-{nb}({})", ha.points.len(), hb.points.len());
        let mut scratch = GjkScratch::default();
        let mut k = 0;
        group.bench_function(format!("cold/{label}"), |bench| {
            bench.iter(|| {
                k = (k + 1) % poses.len();
                let mut warm = WarmStart::default();
                black_box(hull_proximity(
                    ha,
                    hb,
                    &poses[k],
                    0.5,
                    1e-5,
                    &mut warm,
                    &mut scratch,
                ))
            })
        });
        let mut warm = WarmStart::default();
        group.bench_function(format!("warm/{label}"), |bench| {
            bench.iter(|| {
                k = (k + 1) % poses.len();
                black_box(hull_proximity(
                    ha,
                    hb,
                    &poses[k],
                    0.5,
                    1e-5,
                    &mut warm,
                    &mut scratch,
                ))
            })
        });
        let phase = MeshNarrowphase::default();
        let (pa, pb) = (phase.prepare(&a), phase.prepare(&b));
        let band = ContactBand {
            margin: 0.5,
            delta1: -0.05,
            delta2: 0.3,
        };
        let mut scratch = MeshScratch::default();
        let mut out = MeshOutput::default();
        group.bench_function(format!("query_warm/{label}"), |bench| {
            bench.iter(|| {
                k = (k + 1) % poses.len();
                black_box(phase.query(
                    ComponentRef {
                        object: &a,
                        prepared: &pa,
                        component: ca,
                    },
                    ComponentRef {
                        object: &b,
                        prepared: &pb,
                        component: cb,
                    },
                    &poses[k],
                    &band,
                    &mut scratch,
                    &mut out,
                ))
            })
        });
        let (qa, qb) = (
            ConvexPolyhedron::from_convex_hull(&ha.points).expect("hull"),
            ConvexPolyhedron::from_convex_hull(&hb.points).expect("hull"),
        );
        let identity = DPose3 {
            rotation: DQuat::IDENTITY,
            translation: DVec3::ZERO,
        };
        group.bench_function(format!("parry_convex_polyhedron/{label}"), |bench| {
            bench.iter(|| {
                k = (k + 1) % poses.len();
                black_box(query::distance(&identity, &qa, &poses[k], &qb))
            })
        });
    }
    group.finish();
}

// What `criterion_group!` / `criterion_main!` expand to, written out so that no undocumented
// public function is generated.
fn main() {
    let mut c = Criterion::default().configure_from_args();
    bench(&mut c);
    c.final_summary();
}
