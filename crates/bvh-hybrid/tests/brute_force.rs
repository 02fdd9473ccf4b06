//! Brute force over random relative poses for every ordered pair of the six paper objects:
//! every component pair whose exact distance is below the margin must be reported. The exact
//! distance is computed independently of the volumes: the smallest triangle-triangle distance
//! (parry's GJK) between fine meshes (0.02 mm chordal tolerance) of the two components, over
//! the triangle pairs whose boxes come within a cutoff (parry's triangle BVHs), bracketed by
//! their chordal errors (d_exact lies within d_fine -+ (c_a + c_b)). The trees are built on
//! coarse meshes (0.1 mm).
//! Also compares the culling of bevelled and plain-box leaves on the same poses.

mod support;

use bvh_hybrid::{BroadPhase, HybridBvh, LeafShape, TraversalScratch, TreeOptions};
use geom_param::{ComponentId, DPose3, ObjectModel};
use parry3d_f64::bounding_volume::{Aabb, BoundingVolume};
use parry3d_f64::shape::{TriMesh, Triangle};
use support::{NAMES, Rng, near_contact_pose, paper};

const MARGIN: f64 = 0.5;
const TREE_TOLERANCE: f64 = 0.1;
const TRUTH_TOLERANCE: f64 = 0.02;
const POSES_PER_PAIR: usize = 24;

/// Fine component meshes as parry shapes, with their chordal errors.
struct Truth {
    meshes: Vec<TriMesh>,
    chordal: Vec<f64>,
}

impl Truth {
    fn of(object: &ObjectModel) -> Self {
        let meshes = object
            .meshes
            .iter()
            .map(|m| TriMesh::new(m.positions.clone(), m.triangles.clone()).expect("mesh"))
            .collect();
        Truth {
            meshes,
            chordal: object.meshes.iter().map(|m| m.chordal_error).collect(),
        }
    }
}

#[derive(Default, Debug)]
struct Counts {
    /// Component pairs with d_fine + c_a + c_b < margin (certainly within the margin).
    close: usize,
    /// Pairs with d_fine - c_a - c_b > margin (certainly beyond it).
    far: usize,
    /// Pairs in between (undecided by the bracket).
    band: usize,
    missed: [usize; 2],
    far_reported: [usize; 2],
    reported: [usize; 2],
}

#[test]
fn no_pair_within_the_margin_is_missed() {
    let coarse: Vec<ObjectModel> = NAMES.iter().map(|n| paper(n, TREE_TOLERANCE)).collect();
    let fine: Vec<Truth> = NAMES
        .iter()
        .map(|n| Truth::of(&paper(n, TRUTH_TOLERANCE)))
        .collect();
    let phases = [LeafShape::Bevelled, LeafShape::Box].map(|leaf_shape| HybridBvh {
        options: TreeOptions { leaf_shape },
    });
    let trees: Vec<[_; 2]> = coarse
        .iter()
        .map(|o| phases.map(|p| p.build(o, MARGIN)))
        .collect();

    let mut rng = Rng(0x5eed_b0c5);
    let mut scratch = TraversalScratch::default();
    let mut found: [Vec<(ComponentId, ComponentId)>; 2] = Default::default();
    let mut counts = Counts::default();
    for a in 0..NAMES.len() {
        for b in 0..NAMES.len() {
            for _ in 0..POSES_PER_PAIR {
                let pose = near_contact_pose(&mut rng, &coarse[a], &coarse[b], 2.0 * MARGIN);
                for k in 0..2 {
                    phases[k].overlapping_components(
                        &trees[a][k],
                        &trees[b][k],
                        &pose,
                        &mut scratch,
                        &mut found[k],
                    );
                    counts.reported[k] += found[k].len();
                }
                // A bevelled leaf lies inside the plain box fitted on the same points.
                for pair in &found[0] {
                    assert!(
                        found[1].contains(pair),
                        "{} {}: bevelled-only {pair:?}",
                        NAMES[a],
                        NAMES[b]
                    );
                }
                check_pose(&fine[a], &fine[b], &pose, &found, &mut counts, (a, b));
            }
        }
    }
    let pairs = counts.close + counts.far + counts.band;
    let cull = |k: usize| 1.0 - counts.far_reported[k] as f64 / counts.far as f64;
    println!(
        "component pairs checked {pairs}: within margin {}, beyond {}, undecided {}",
        counts.close, counts.far, counts.band
    );
    for (k, name) in ["bevelled", "box"].iter().enumerate() {
        println!(
            "{name:>8} leaves: reported {}, missed {}, reported beyond margin {} \
             (culling rate of far pairs {:.3}; false positives {:.3} of reported)",
            counts.reported[k],
            counts.missed[k],
            counts.far_reported[k],
            cull(k),
            counts.far_reported[k] as f64 / counts.reported[k] as f64,
        );
    }
    assert_eq!(counts.missed, [0, 0]);
    assert!(
        counts.close >= 300,
        "too few close pairs to mean anything: {counts:?}"
    );
    assert!(counts.far_reported[0] <= counts.far_reported[1]);
}

fn check_pose(
    a: &Truth,
    b: &Truth,
    pose: &DPose3,
    found: &[Vec<(ComponentId, ComponentId)>; 2],
    counts: &mut Counts,
    names: (usize, usize),
) {
    for (i, mesh_a) in a.meshes.iter().enumerate() {
        for (j, mesh_b) in b.meshes.iter().enumerate() {
            let bracket = a.chordal[i] + b.chordal[j];
            // Only whether d is below margin + bracket matters; above it, d = cutoff.
            let d = mesh_distance_below(mesh_a, mesh_b, pose, MARGIN + 2.0 * bracket);
            let pair = (ComponentId(i as u32), ComponentId(j as u32));
            let reported = [found[0].contains(&pair), found[1].contains(&pair)];
            if d + bracket < MARGIN {
                counts.close += 1;
                for (k, &hit) in reported.iter().enumerate() {
                    if !hit {
                        counts.missed[k] += 1;
                        eprintln!(
                            "MISS ({}) {} {} pair {pair:?} d_fine {d} pose {pose:?}",
                            k, NAMES[names.0], NAMES[names.1]
                        );
                    }
                }
            } else if d - bracket > MARGIN {
                counts.far += 1;
                for (count, &hit) in counts.far_reported.iter_mut().zip(&reported) {
                    *count += usize::from(hit);
                }
            } else {
                counts.band += 1;
            }
        }
    }
}

/// The distance between the two triangle meshes (`b` posed in `a`'s frame) if it is below
/// `cutoff`, else `cutoff`: every pair of triangles whose boxes come within `cutoff`, and the
/// current best, is measured exactly (GJK between triangles).
fn mesh_distance_below(a: &TriMesh, b: &TriMesh, pose: &DPose3, cutoff: f64) -> f64 {
    let a_box = a.local_aabb();
    if !a_box.intersects(&b.local_aabb().transform_by(pose).loosened(cutoff)) {
        return cutoff;
    }
    let a_box_in_b = a_box.transform_by(&pose.inverse()).loosened(cutoff);
    let mut best = cutoff;
    for tb in b.bvh().intersect_aabb(&a_box_in_b) {
        let t = b.triangle(tb);
        let tri_b = Triangle::new(pose * t.a, pose * t.b, pose * t.c);
        let reach = Aabb::from_points([tri_b.a, tri_b.b, tri_b.c]).loosened(best);
        for ta in a.bvh().intersect_aabb(&reach) {
            let d = parry3d_f64::query::distance(
                &DPose3::IDENTITY,
                &a.triangle(ta),
                &DPose3::IDENTITY,
                &tri_b,
            )
            .expect("triangle-triangle distance is supported")
            .distance;
            best = best.min(d);
        }
    }
    best
}
