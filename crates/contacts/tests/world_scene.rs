//! `contacts query` on the 300-object scene (fixtures/worlds/world-300.json), answered through
//! a `World`, against brute force: every pair of the scene queried on its own. The pairs the
//! world lists are those in range, in scene order, each with the state and contacts of its
//! own query; every pair it leaves out is separated.

use contact_pipeline::{PairState, QueryScratch};
use contacts::run::{WORLD_OBJECTS, prepare_scene};
use std::path::Path;

#[test]
fn the_world_scene_equals_all_pairs_queried_alone() {
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/worlds/world-300.json");
    let scene = prepare_scene(&file).expect("the world scene loads");
    assert!(scene.objects.len() > WORLD_OBJECTS);
    let result = scene.query_json().expect("queries run");
    let listed = result["pairs"].as_array().expect("pairs");
    let name = |i: usize| scene.scene.objects[i].name.as_str();
    let mut scratch = QueryScratch::default();
    let (mut next, mut contacts) = (0, 0);
    for (i, j) in scene.pairs() {
        let report = scene.query((i, j), &mut scratch).expect("query");
        let entry = listed
            .get(next)
            .filter(|p| p["a"] == name(i) && p["b"] == name(j));
        match entry {
            Some(p) => {
                next += 1;
                let state = contacts::output::state_name(report.state);
                assert_eq!(p["state"], state, "{} {}", name(i), name(j));
                let found = p["contacts"].as_array().expect("contacts");
                assert_eq!(
                    found.len(),
                    report.contacts.len(),
                    "{} {}",
                    name(i),
                    name(j)
                );
                for (f, c) in found.iter().zip(&report.contacts) {
                    let d = f["distance"].as_f64().expect("distance");
                    assert!((d - c.distance).abs() < 1e-9, "{} {}", name(i), name(j));
                }
                contacts += report.contacts.len();
            }
            None => assert_eq!(
                report.state,
                PairState::Separated,
                "{} {} is left out but not separated",
                name(i),
                name(j)
            ),
        }
    }
    assert_eq!(
        next,
        listed.len(),
        "every listed pair is a pair of the scene, in order"
    );
    assert!(
        contacts > 100,
        "the grid holds near contacts, found {contacts}"
    );
}
