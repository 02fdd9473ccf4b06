//! Two local minima of distance close together: the normal-cone path seeds each of them.
//!
//! The pose is the soak's bowl-paperweight 5618258536318199318 (`cargo xtask soak 1000
//! --seed 11`, kept in `xtask/tests/soak_regressions.rs`): the bowl's face 4 against the
//! paperweight's face 1 at 0.03326 mm and, 4.6 mm away, against its face 3 at 0.07308 mm. The
//! proxy path found both in one collision region of radius 4.3 mm, whose centre seed converged
//! to the first; only a probe at the region's far end (refined by the pipeline) reached the
//! second. The minima are the independent oracle's (`contact-oracle`: dense sampling of the
//! exact surfaces and Newton polishing); the regression test checks the second one's Hessian.

mod common;

use common::*;
use geom_param::{DQuat, DVec3, Seed};
use mesh_narrowphase::{ConcavePath, ContactBand, MeshScratch};

/// The two minima on the bowl (A's frame, mm).
const MINIMA: [[f64; 3]; 2] = [
    [-28.85065080120365, -30.614923724414673, 41.76904940021897],
    [-33.28678828500792, -25.838393333200578, 41.804827385957026],
];

/// The seeds of every component pair of the two objects at the pose.
fn all_seeds(path: ConcavePath, bowl: &Prepared, paperweight: &Prepared) -> Vec<Seed> {
    let pose_b = pose(
        DQuat::from_array([
            -0.25871576848907074,
            -0.5949659295245138,
            -0.08637166352349065,
            0.7560566311992282,
        ]),
        DVec3::new(-14.13872657433006, -20.735789749114346, 72.12623322873607),
    );
    let band = ContactBand {
        margin: 1.0,
        delta1: -0.001,
        delta2: 0.1,
    };
    let mut scratch = MeshScratch::default();
    let mut seeds = Vec::new();
    for ca in &bowl.object.components {
        for cb in &paperweight.object.components {
            let (_, out) = query_path(
                path,
                (bowl, ca.id),
                (paperweight, cb.id),
                &pose_b,
                &band,
                &mut scratch,
            );
            seeds.extend(out.seeds);
        }
    }
    seeds
}

#[test]
fn two_minima_4_6_mm_apart_get_a_seed_each() {
    let bowl = Prepared::new(paper_object("bowl", 0.05));
    let paperweight = Prepared::new(paper_object("paperweight", 0.05));
    let seeds = all_seeds(ConcavePath::NormalCones, &bowl, &paperweight);
    // A third of the minima's separation: a seed this close to one is farther from the other.
    let tolerance = DVec3::from(MINIMA[0]).distance(DVec3::from(MINIMA[1])) / 3.0;
    let nearest: Vec<(usize, f64)> = MINIMA
        .iter()
        .map(|m| {
            seeds
                .iter()
                .enumerate()
                .map(|(i, s)| (i, s.a.local_point.distance(DVec3::from(*m))))
                .min_by(|x, y| x.1.total_cmp(&y.1))
                .expect("some seed")
        })
        .collect();
    println!(
        "{} seeds; nearest to each minimum: {nearest:?}",
        seeds.len()
    );
    for ((_, d), m) in nearest.iter().zip(MINIMA) {
        assert!(
            *d <= tolerance,
            "no seed within {tolerance} mm of the minimum at {m:?}: {seeds:?}"
        );
    }
    assert_ne!(nearest[0].0, nearest[1].0);
}
