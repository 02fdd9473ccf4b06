//! A world of fixture objects in a grid with near contacts against brute force: after every
//! step (objects moving a little between steps) the pairs the world reports are exactly the
//! pairs whose independent cold query (fresh scratch, all pairs, no broad phase across objects)
//! is not separated, with the same states and contacts (distances within 1e-9 mm, points within
//! 1e-6 mm). Also: removal, groups and the caller's filter; and, with the `parallel` feature,
//! the same answers in the same order on 1 and 2 threads.

#[path = "support/grid.rs"]
mod grid;

use contact_pipeline::{Groups, ObjectKey, PairReport, PairState, QueryScratch, World, WorldError};
use exact_refine::RefineStatus;
use geom_param::{DPose3, DQuat, DVec3};

/// Same state and contacts; the points of a continuous contact (parallel cylinders, flat on
/// flat) are any pair of the degenerate set (see `RefineStatus::ContinuousContact`), so where
/// either side calls it continuous only the distance is compared (the grid's upright cylinders
/// side by side, turned by 1e-4 rad, are such sets up to rounding).
fn assert_same(world: &PairReport, cold: &PairReport, what: &str) {
    assert_eq!(world.state, cold.state, "{what}: state");
    assert_eq!(
        world.contacts.len(),
        cold.contacts.len(),
        "{what}: contacts"
    );
    for w in &world.contacts {
        let continuous =
            |c: &contact_pipeline::Contact| c.diagnostics.status == RefineStatus::ContinuousContact;
        assert!(
            cold.contacts
                .iter()
                .any(|c| (c.distance - w.distance).abs() <= 1e-9
                    && if continuous(w) || continuous(c) {
                        true
                    } else {
                        c.point_a.distance(w.point_a) <= 1e-6
                            && c.point_b.distance(w.point_b) <= 1e-6
                    }),
            "{what}: {w:?} not in {cold:?}"
        );
    }
}

/// Checks the world's last step against cold queries of every pair of `keys`.
fn check_against_brute_force(world: &World, keys: &[ObjectKey], what: &str) -> usize {
    let mut touching = 0;
    let mut contacts = 0;
    let pipeline = world.pipeline();
    let listed: Vec<_> = world.pairs().collect();
    for (i, &ka) in keys.iter().enumerate() {
        for &kb in &keys[i + 1..] {
            let (a, b) = if ka.index < kb.index {
                (ka, kb)
            } else {
                (kb, ka)
            };
            let object = |k: ObjectKey| world.object(k).expect("object");
            let cold = pipeline
                .query(
                    &object(a),
                    &world.pose(a).expect("pose"),
                    &object(b),
                    &world.pose(b).expect("pose"),
                    &mut QueryScratch::default(),
                )
                .expect("query");
            let found = listed.iter().find(|p| p.a == a && p.b == b);
            match (cold.state, found) {
                (PairState::Separated, None) => {}
                (_, Some(p)) => {
                    assert_same(p.report, &cold, &format!("{what} {a:?}-{b:?}"));
                    touching += 1;
                    contacts += cold.contacts.len();
                }
                (state, None) => panic!("{what}: pair {a:?}-{b:?} is {state:?} but not listed"),
            }
        }
    }
    assert_eq!(listed.len(), touching, "{what}: no extra pairs");
    contacts
}

#[test]
fn world_answers_equal_brute_force_pairs() -> Result<(), WorldError> {
    let (mut world, _models, keys) = grid::world(27, 4);
    let mut contacts = 0;
    for step in 0..4 {
        let stats = world.step()?;
        assert!(stats.pairs_queried < keys.len() * (keys.len() - 1) / 2);
        contacts += check_against_brute_force(&world, &keys, &format!("step {step}"));
        // Every third object turns and shifts by a few micrometres.
        for (n, &k) in keys.iter().enumerate().step_by(3) {
            let pose = world.pose(k)?;
            let turn = DQuat::from_axis_angle(DVec3::new(0.3, 1.0, 0.2).normalize(), 1e-4);
            let shift = DVec3::new(0.002, -0.001, 0.001) * ((n % 5) as f64 - 2.0);
            world.set_pose(
                k,
                DPose3::from_parts(pose.translation + shift, turn * pose.rotation),
            )?;
        }
    }
    assert!(
        contacts > 20,
        "the grid should hold contacts, found {contacts}"
    );
    Ok(())
}

#[test]
fn removal_groups_and_filters_drop_pairs() -> Result<(), WorldError> {
    let (mut world, _models, _keys) = grid::world(8, 2);
    world.step()?;
    let before = world.pairs().count();
    assert!(before > 0, "the grid should touch");
    let victim = world.pairs().next().map(|p| p.a).expect("a pair");
    let object = world.remove(victim)?;
    assert!(matches!(
        world.set_pose(victim, DPose3::IDENTITY),
        Err(WorldError::UnknownObject(_))
    ));
    world.step()?;
    assert!(world.all_pairs().all(|p| p.a != victim && p.b != victim));
    // Back in, in a group that accepts nothing: still no pair with it.
    let lonely = world.insert(
        object,
        grid::grid(&grid::models(2).1, 8)[victim.index as usize].1,
        Groups {
            memberships: 0b10,
            filter: 0,
        },
    )?;
    assert_ne!(lonely, victim, "a new key for the reused slot");
    world.step()?;
    assert!(world.all_pairs().all(|p| p.a != lonely && p.b != lonely));
    // The caller's predicate removes every pair.
    world.set_filter(Some(Box::new(|_, _| false)));
    let stats = world.step()?;
    assert_eq!(stats.pairs_queried, 0);
    assert!(stats.pairs_in_range > 0);
    assert_eq!(world.all_pairs().count(), 0);
    Ok(())
}

#[cfg(feature = "parallel")]
#[test]
fn one_and_two_threads_give_the_same_answers_in_the_same_order() -> Result<(), WorldError> {
    type Answer = Vec<(
        ObjectKey,
        ObjectKey,
        PairReport,
        Vec<contact_pipeline::ContactId>,
    )>;
    let answers = |world: &World| -> Answer {
        world
            .all_pairs()
            .map(|p| {
                let mut report = p.report.clone();
                report.stats = Default::default();
                (p.a, p.b, report, p.ids.to_vec())
            })
            .collect()
    };
    let mut runs: Vec<Vec<Answer>> = Vec::new();
    for threads in [1, 2] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("pool");
        let (mut world, _models, keys) = grid::world(27, 4);
        let mut steps = Vec::new();
        for step in 0..3 {
            pool.install(|| world.step_parallel())?;
            steps.push(answers(&world));
            for &k in keys.iter().step_by(4) {
                let pose = world.pose(k)?;
                world.set_pose(
                    k,
                    DPose3::from_parts(
                        pose.translation + DVec3::new(0.001, 0.0, 0.0) * step as f64,
                        pose.rotation,
                    ),
                )?;
            }
        }
        runs.push(steps);
    }
    assert_eq!(runs[0], runs[1]);
    assert!(runs[0].iter().all(|s| !s.is_empty()));
    Ok(())
}
