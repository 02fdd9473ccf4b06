//! The traversal front carried between queries of one pair (issue 15, part 3): node pairs
//! dropped by their normal cones, and leaf pairs whose triangles a separating axis keeps
//! apart, stay dropped while B moves less than their margin. A query that starts from the
//! carried front must find what a fresh query finds: checked against fresh scratch along
//! random walks of small motions (below and above the margins) of a pencil leaning in a
//! tube's hole, of a pencil lying in (and through) a bowl, and of a pencil whose tip (an apex,
//! traversed from its own front) rests on a bowl's floor. The separating-axis gap is
//! checked against exact triangle distances and intersection tests.

mod common;

use common::*;
use geom_param::{DPose3, DQuat, DVec3};
use mesh_narrowphase::triangles::triangle_distance::{closest_between_triangles, separating_gap};
use mesh_narrowphase::triangles::triangle_intersection::triangles_intersect;
use mesh_narrowphase::{ConcavePath, ContactBand, MeshScratch, MeshStats, MeshVerdict};

/// One component pair's answer: verdict, seeds (A's and B's points), intersecting triangle
/// pairs, and the node pairs examined and leaf pairs left ([`MeshStats`]).
struct Answered {
    verdict: MeshVerdict,
    seeds: Vec<(DVec3, DVec3)>,
    pairs: Vec<(u32, u32)>,
    stats: MeshStats,
}

/// Every component pair's answer.
fn answer(
    a: &Prepared,
    b: &Prepared,
    pose_ab: &DPose3,
    scratch: &mut MeshScratch,
) -> Vec<Answered> {
    let band = ContactBand {
        margin: 1.0,
        delta1: -0.001,
        delta2: 0.1,
    };
    let mut all = Vec::new();
    for ca in &a.object.components {
        for cb in &b.object.components {
            let (verdict, out) = query_path(
                ConcavePath::NormalCones,
                (a, ca.id),
                (b, cb.id),
                pose_ab,
                &band,
                scratch,
            );
            let seeds = out
                .seeds
                .iter()
                .map(|s| (s.a.local_point, s.b.local_point))
                .collect();
            let mut pairs = out.penetrating_pairs.clone();
            pairs.sort_unstable();
            all.push(Answered {
                verdict,
                seeds,
                pairs,
                stats: out.stats,
            });
        }
    }
    all
}

/// Compares at `pose_ab` (step `k`) the answer of the `carried` scratch with a fresh one's: the
/// same verdicts and intersecting triangle pairs, and every seed of either within `near` (mm)
/// of a seed of the other on both objects. Returns how many seeds and pairs it compared.
fn compare(
    k: usize,
    a: &Prepared,
    b: &Prepared,
    pose_ab: &DPose3,
    carried: &mut MeshScratch,
    near: f64,
) -> usize {
    let warm = answer(a, b, pose_ab, carried);
    let fresh = answer(a, b, pose_ab, &mut MeshScratch::default());
    assert_eq!(warm.len(), fresh.len());
    let mut compared = 0;
    for (w, f) in warm.iter().zip(&fresh) {
        let (wv, ws, wp) = (&w.verdict, &w.seeds, &w.pairs);
        let (fv, fs, fp) = (&f.verdict, &f.seeds, &f.pairs);
        assert_eq!(wv, fv, "step {k}: verdicts");
        assert_eq!(wp, fp, "step {k}: intersecting triangle pairs");
        let covered = |from: &[(DVec3, DVec3)], to: &[(DVec3, DVec3)]| {
            from.iter().all(|(pa, pb)| {
                to.iter()
                    .any(|(qa, qb)| pa.distance(*qa) <= near && pb.distance(*qb) <= near)
            })
        };
        assert!(covered(ws, fs), "step {k}: warm seeds {ws:?}, fresh {fs:?}");
        assert!(covered(fs, ws), "step {k}: fresh seeds {fs:?}, warm {ws:?}");
        compared += ws.len() + fs.len() + wp.len();
    }
    compared
}

/// Walks B from `start` by random steps (translations and turns of the sizes in `steps`,
/// cycled) and compares, at every pose, the answer of a scratch carried along the walk with a
/// fresh one's ([`compare`], `near` a leaf's size: the seeds of one minimum may come from
/// neighbouring leaf pairs).
fn walk(a: &Prepared, b: &Prepared, start: DPose3, steps: &[(f64, f64)], near: f64) {
    let mut rng = Rng(0x5eed_1234_abcd_0001);
    let mut carried = MeshScratch::default();
    let mut pose_ab = start;
    let mut compared = 0;
    for k in 0..40 {
        let (shift, turn) = steps[k % steps.len()];
        let direction = DVec3::new(
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
        )
        .normalize();
        let axis = DVec3::new(
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
        )
        .normalize();
        pose_ab = pose(
            (DQuat::from_axis_angle(axis, turn) * pose_ab.rotation).normalize(),
            pose_ab.translation + direction * shift,
        );
        compared += compare(k, a, b, &pose_ab, &mut carried, near);
    }
    assert!(compared > 0, "the walk found nothing to compare");
}

/// Steps (mm, rad) below the carried margins (a hundredth of a leaf's ball, about 0.005 mm,
/// and a sixteenth of that for a nearly critical cone drop, `NEAR_CRITICAL_CARRY`), about
/// them, and far above.
const STEPS: [(f64, f64); 5] = [
    (1e-4, 1e-7),
    (1e-3, 1e-6),
    (5e-3, 2e-5),
    (2e-4, 0.0),
    (0.05, 3e-4),
];

#[test]
fn a_carried_front_answers_like_a_fresh_one_for_a_pencil_in_a_tube() {
    let tube = Prepared::new(fixture_object("tube", 0.05));
    let pencil = Prepared::new(fixture_object("pencil", 0.05));
    let start = pose(
        DQuat::from_array([0.0, 0.024325244977882785, 0.0, 0.9997040974492232]),
        DVec3::new(-3.87032714844386, 0.0, -49.79149919838436),
    );
    walk(&tube, &pencil, start, &STEPS, 2.5);
}

#[test]
fn a_carried_front_answers_like_a_fresh_one_for_a_pencil_through_a_bowl() {
    let bowl = Prepared::new(fixture_object("bowl", 0.05));
    let pencil = Prepared::new(fixture_object("pencil", 0.05));
    let start = pose(
        DQuat::from_array([0.0, 0.9238795325112867, 0.0, 0.38268343236508984]),
        DVec3::new(-115.5, 0.0, 131.0314536606893),
    );
    walk(&bowl, &pencil, start, &STEPS, 2.5);
}

/// The pencil's pose in the bowl of the two-contact fixture scene: its tip on the floor, its
/// side on the rim.
fn pencil_resting_in_a_bowl() -> DPose3 {
    pose(
        DQuat::from_array([0.0, 0.8977059759571835, 0.0, 0.44059503030647196]),
        DVec3::new(-130.3998473869082, 0.0, 114.60598684057987),
    )
}

#[test]
fn a_carried_front_answers_like_a_fresh_one_for_a_pencil_tip_on_a_bowl() {
    let bowl = Prepared::new(fixture_object("bowl", 0.05));
    let pencil = Prepared::new(fixture_object("pencil", 0.05));
    let start = pencil_resting_in_a_bowl();
    walk(&bowl, &pencil, start, &STEPS, 2.5);
}

/// An apex's front follows the apex: a pencil whose tip rests on a bowl's floor slides 4 mm
/// across it in steps of 0.05 mm (far beyond the leaves the tip reached at first, each step
/// beyond the margin of a kept leaf, a tenth of its ball), with its warm answers checked against
/// fresh ones at every step ([`compare`]).
#[test]
fn an_apex_front_follows_the_apex_across_a_face() {
    let bowl = Prepared::new(fixture_object("bowl", 0.05));
    let pencil = Prepared::new(fixture_object("pencil", 0.05));
    let start = pencil_resting_in_a_bowl();
    let mut carried = MeshScratch::default();
    let mut compared = 0;
    for k in 0..80 {
        let at = pose(
            start.rotation,
            start.translation + DVec3::Y * (0.05 * k as f64),
        );
        compared += compare(k, &bowl, &pencil, &at, &mut carried, 2.5);
    }
    assert!(compared > 80, "{compared} seeds compared");
}

/// Queries `b` against `a` at `pose_ab`, then again at the same pose (twice) and after a nudge
/// of 2.4e-4 mm, with one scratch: each repeated query examines fewer node pairs than it has
/// leaf pairs (the front kept them, untested), keeps at least the fresh query's leaf pairs and
/// finds the fresh query's intersecting triangle pairs, and at the same pose gives the fresh
/// query's seeds. Returns the first query's leaf pairs.
fn kept_leaves(a: &Prepared, b: &Prepared, pose_ab: DPose3) -> u32 {
    let mut carried = MeshScratch::default();
    let first = answer(a, b, &pose_ab, &mut carried);
    let nudged = pose(
        pose_ab.rotation,
        pose_ab.translation + DVec3::new(1e-4, -2e-4, 1e-4),
    );
    for at in [pose_ab, pose_ab, nudged] {
        let warm = answer(a, b, &at, &mut carried);
        let fresh = answer(a, b, &at, &mut MeshScratch::default());
        for (w, f) in warm.iter().zip(&fresh) {
            let (visited, leaf_pairs) = (w.stats.node_pairs_visited, w.stats.leaf_pairs);
            assert!(
                visited < leaf_pairs || leaf_pairs == 0,
                "{visited} node pairs examined for {leaf_pairs} leaf pairs"
            );
            assert!(
                leaf_pairs >= f.stats.leaf_pairs,
                "{leaf_pairs} kept against {} fresh",
                f.stats.leaf_pairs
            );
            assert_eq!(w.pairs, f.pairs);
            if at == pose_ab {
                assert_eq!(w.seeds, f.seeds);
            }
        }
    }
    first.iter().map(|s| s.stats.leaf_pairs).sum()
}

/// Meshes apart need no exact triangle test: a leaf pair whose triangles a separating axis
/// keeps apart is not a candidate for one, also where the pieces' balls overlap (a pencil
/// leaning on a tube's rim: balls spanning a triangle each, gaps of hundredths of a
/// millimetre), and a carried leaf pair keeps its gap less B's motion. Fresh and warm (the
/// same pose again, then nudged by 2.4e-4 mm), every component pair without intersecting
/// triangles tests none.
#[test]
fn triangles_apart_are_not_tested_for_intersection() {
    let tube = Prepared::new(fixture_object("tube", 0.05));
    let pencil = Prepared::new(fixture_object("pencil", 0.05));
    let start = pose(
        DQuat::from_array([0.0, 0.024325244977882785, 0.0, 0.9997040974492232]),
        DVec3::new(-3.87032714844386, 0.0, -49.79149919838436),
    );
    let nudged = pose(
        start.rotation,
        start.translation + DVec3::new(1e-4, -2e-4, 1e-4),
    );
    let mut carried = MeshScratch::default();
    let mut leaf_pairs = 0;
    for at in [start, start, nudged] {
        let warm = answer(&tube, &pencil, &at, &mut carried);
        let fresh = answer(&tube, &pencil, &at, &mut MeshScratch::default());
        for answered in warm.iter().chain(&fresh) {
            assert!(answered.pairs.is_empty(), "the meshes are apart");
            assert_eq!(answered.stats.triangle_pairs_tested, 0);
            leaf_pairs += answered.stats.leaf_pairs;
        }
    }
    assert!(leaf_pairs > 100, "{leaf_pairs} leaf pairs in six queries");
}

/// Certified pairs are kept by the front as well, under small motions, while they stay
/// certified at the query's rotation (without a new test for those certified for the turn
/// that the motion allows, `turned_certificates.rs`): a pencil lying in a bowl (the two-contact fixture
/// scene's pose, meshed at 0.02 mm), whose contacts the traversal answers with 45 certified
/// pairs (at the fixture's 0.05 mm the certificate's tilt allowance leaves 8, the rest leaf
/// pairs). Queried again at the same pose, nudged by 2.4e-4 mm, and turned by 1e-6 rad, each
/// warm query examines less than a hundredth of the fresh query's 2260 node pairs (1 to 7: the
/// front's pairs whose margins the motion used up, and the nodes that the cones dropped from
/// the pencil tip's traversal, which its own front tests again every query; 94 to 102 while
/// the tip was traversed from the root every query), and gives the fresh query's certified
/// pairs at the same pose and its seeds (within a leaf's size) at every pose.
#[test]
fn certified_pairs_are_not_tested_again_under_small_motions() {
    let bowl = Prepared::new(fixture_object("bowl", 0.02));
    let pencil = Prepared::new(fixture_object("pencil", 0.02));
    let start = pencil_resting_in_a_bowl();
    let nudged = pose(
        start.rotation,
        start.translation + DVec3::new(1e-4, -2e-4, 1e-4),
    );
    let turned = pose(
        (DQuat::from_rotation_x(1e-6) * start.rotation).normalize(),
        start.translation,
    );
    let mut carried = MeshScratch::default();
    let first = answer(&bowl, &pencil, &start, &mut carried);
    let certified: u32 = first.iter().map(|s| s.stats.certified_pairs).sum();
    assert!(certified > 10, "{certified} certified pairs");
    for at in [start, nudged, turned] {
        let warm = answer(&bowl, &pencil, &at, &mut carried);
        let fresh = answer(&bowl, &pencil, &at, &mut MeshScratch::default());
        for (w, f) in warm.iter().zip(&fresh) {
            let (visited, kept) = (w.stats.node_pairs_visited, w.stats.certified_pairs);
            assert!(
                100 * visited < f.stats.node_pairs_visited || kept == 0,
                "{visited} node pairs examined for {kept} certified pairs (fresh: {})",
                f.stats.node_pairs_visited
            );
            if at == start {
                assert_eq!(kept, f.stats.certified_pairs);
            }
            assert_eq!(w.verdict, f.verdict);
            for (pa, pb) in &f.seeds {
                assert!(
                    w.seeds
                        .iter()
                        .any(|(qa, qb)| pa.distance(*qa) <= 2.5 && pb.distance(*qb) <= 2.5),
                    "fresh seed {pa:?} {pb:?} not among the warm ones {:?}",
                    w.seeds
                );
            }
        }
    }
}

/// Leaf pairs with a possible critical pair are kept by the front without being tested again
/// while B moves less than a tenth of their smaller ball (`LEAF_CARRY`): a pencil leaning on
/// a tube's rim.
#[test]
fn kept_leaf_pairs_are_not_tested_again_under_small_motions() {
    let tube = Prepared::new(fixture_object("tube", 0.05));
    let pencil = Prepared::new(fixture_object("pencil", 0.05));
    let start = pose(
        DQuat::from_array([0.0, 0.024325244977882785, 0.0, 0.9997040974492232]),
        DVec3::new(-3.87032714844386, 0.0, -49.79149919838436),
    );
    let leaves = kept_leaves(&tube, &pencil, start);
    assert!(leaves > 50, "the pose has {leaves} leaf pairs");
}

/// Leaf pairs whose meshes may meet and whose cones rule out a critical pair for a motion of a
/// hundredth of their smaller ball (`CONE_CARRY`) are kept as well, for their exact
/// intersection tests: a pencil through a bowl's wall.
#[test]
fn intersecting_leaf_pairs_are_kept_under_small_motions() {
    let bowl = Prepared::new(fixture_object("bowl", 0.05));
    let pencil = Prepared::new(fixture_object("pencil", 0.05));
    let start = pose(
        DQuat::from_array([0.0, 0.9238795325112867, 0.0, 0.38268343236508984]),
        DVec3::new(-115.5, 0.0, 131.0314536606893),
    );
    let leaves = kept_leaves(&bowl, &pencil, start);
    assert!(leaves > 20, "the pose has {leaves} leaf pairs");
}

/// The separating-axis gap of random triangle pairs (apart, touching, crossing, at scales from
/// 1e-3 to 1e2 mm) is at most their exact distance (Ericson's closest points, exact for
/// disjoint triangles), at most 0 for intersecting ones, and positive for disjoint ones
/// farther apart than rounding.
#[test]
fn the_separating_gap_bounds_the_triangle_distance_from_below() {
    let mut rng = Rng(0x7a1e_9bb1_0000_0042);
    let (mut apart, mut crossing) = (0, 0);
    for _ in 0..20_000 {
        let scale = 10f64.powf(rng.range(-3.0, 2.0));
        let corner = |rng: &mut Rng, centre: DVec3| {
            centre
                + DVec3::new(
                    rng.range(-1.0, 1.0),
                    rng.range(-1.0, 1.0),
                    rng.range(-1.0, 1.0),
                ) * scale
        };
        let t1 = [DVec3::ZERO; 3].map(|c| corner(&mut rng, c));
        let offset = DVec3::new(rng.range(-2.0, 2.0), rng.range(-2.0, 2.0), 0.0) * scale;
        let t2 = [offset; 3].map(|c| corner(&mut rng, c));
        let gap = separating_gap(&t1, &t2);
        let rounding = 1e-12 * scale;
        if triangles_intersect(&t1, &t2) {
            assert!(gap <= rounding, "{t1:?} {t2:?} intersect, gap {gap}");
            crossing += 1;
        } else {
            let distance = closest_between_triangles(&t1, &t2).distance;
            assert!(
                gap <= distance + rounding,
                "gap {gap} > distance {distance}"
            );
            if distance > 1e-9 * scale {
                assert!(gap > 0.0, "{t1:?} {t2:?} apart by {distance}, gap {gap}");
                apart += 1;
            }
        }
    }
    assert!(
        apart > 1000 && crossing > 500,
        "{apart} apart, {crossing} crossing"
    );
}
