//! Prints, for the paper's four two-contact scenes, the exact pipeline's contacts beside the
//! mesh-only baseline's (parry contact manifolds between whole-object meshes of 1k, 5k, 20k
//! and 80k triangles, prediction = the scene's delta2): counts, distances, the baseline
//! contact nearest each exact contact, and median warm and cold query times.
//!
//! `cargo run --release -p contacts --example baseline_report`

use contact_pipeline::{Contact, QueryScratch};
use contacts::run::prepare_scene;
use mesh_baseline::{BaselineContact, BaselineMesh, MeshOnlyBaseline, nearest_to};
use std::path::Path;
use std::time::Instant;

const SCENES: [&str; 4] = [
    "pencil-paperweight-two-contacts",
    "paperweight-goblet-two-contacts",
    "pencil-bowl-two-contacts",
    "vase-vase-two-contacts",
];
const TARGETS: [usize; 4] = [1_000, 5_000, 20_000, 80_000];
const RUNS: usize = 31;
/// Baseline contacts whose midpoints are this close (mm) count as one cluster.
const CLUSTER_RADIUS: f64 = 2.0;

/// Median wall time (µs) of `RUNS` calls after one warm-up call.
fn median_us(mut f: impl FnMut()) -> f64 {
    f();
    let mut times: Vec<f64> = (0..RUNS)
        .map(|_| {
            let start = Instant::now();
            f();
            start.elapsed().as_secs_f64() * 1e6
        })
        .collect();
    times.sort_by(f64::total_cmp);
    times[RUNS / 2]
}

/// Number of groups of contacts linked by midpoints within [`CLUSTER_RADIUS`].
fn clusters(contacts: &[BaselineContact]) -> usize {
    let mut parent: Vec<usize> = (0..contacts.len()).collect();
    fn root(parent: &mut [usize], mut i: usize) -> usize {
        while parent[i] != i {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        i
    }
    for i in 0..contacts.len() {
        for j in i + 1..contacts.len() {
            if contacts[i].midpoint().distance(contacts[j].midpoint()) <= CLUSTER_RADIUS {
                let (a, b) = (root(&mut parent, i), root(&mut parent, j));
                parent[a] = b;
            }
        }
    }
    (0..contacts.len())
        .filter(|&i| root(&mut parent, i) == i)
        .count()
}

fn describe(truth: &Contact, contacts: &[BaselineContact]) -> String {
    let mid = 0.5 * (truth.point_a + truth.point_b);
    let Some((i, separation)) = nearest_to(contacts, mid) else {
        return "no baseline contact".into();
    };
    let c = &contacts[i];
    // The deepest baseline contact near this exact contact.
    let local_min = contacts
        .iter()
        .filter(|c| c.midpoint().distance(mid) <= CLUSTER_RADIUS)
        .map(|c| c.distance)
        .fold(f64::INFINITY, f64::min);
    format!(
        "nearest at {separation:.3} mm: distance {:.4} (error {:+.4}), normal off {:.2} deg; min distance within {CLUSTER_RADIUS} mm {:.4}",
        c.distance,
        c.distance - truth.distance,
        c.normal.angle_between(truth.normal).to_degrees(),
        local_min
    )
}

fn main() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/scenes");
    for name in SCENES {
        let prepared = prepare_scene(&dir.join(format!("{name}.json"))).expect("scene loads");
        let objects = &prepared.scene.objects;
        let (pose_a, pose_b) = (&objects[0].pose, &objects[1].pose);
        let prediction = prepared.scene.options.delta2;
        let mut scratch = QueryScratch::default();
        let report = prepared.query((0, 1), &mut scratch).expect("query");
        let ours = median_us(|| {
            prepared.query((0, 1), &mut scratch).expect("query");
        });
        println!("== {name} (prediction = delta2 = {prediction} mm)");
        println!(
            "exact pipeline: {} contacts, distances [{}], median {ours:.1} us",
            report.contacts.len(),
            report
                .contacts
                .iter()
                .map(|c| format!("{:.6}", c.distance))
                .collect::<Vec<_>>()
                .join(", ")
        );
        for target in TARGETS {
            let mesh = |i: usize| {
                BaselineMesh::new(&prepared.objects[i].model.solid, target).expect("meshes")
            };
            let (a, b) = (mesh(0), mesh(1));
            let mut baseline = MeshOnlyBaseline::new();
            let contacts = baseline
                .contacts_cold(&a, pose_a, &b, pose_b, prediction)
                .expect("query");
            let warm = median_us(|| {
                baseline
                    .contacts(&a, pose_a, &b, pose_b, prediction)
                    .expect("query");
            });
            let cold = median_us(|| {
                baseline
                    .contacts_cold(&a, pose_a, &b, pose_b, prediction)
                    .expect("query");
            });
            let (lo, hi) = contacts
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |m, c| {
                    (m.0.min(c.distance), m.1.max(c.distance))
                });
            println!(
                "  parry {target:>6} (A {} tris, e {:.3} mm; B {} tris, e {:.3} mm): {} points in {} clusters, distances [{lo:.4}, {hi:.4}], warm {warm:.0} us, cold {cold:.0} us",
                a.triangle_count(),
                a.chordal_error(),
                b.triangle_count(),
                b.chordal_error(),
                contacts.len(),
                clusters(&contacts),
            );
            for (k, truth) in report.contacts.iter().enumerate() {
                println!(
                    "    exact contact {k} ({:.6} mm): {}",
                    truth.distance,
                    describe(truth, &contacts)
                );
            }
        }
    }
}
