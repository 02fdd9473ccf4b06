//! The README's "Inside rapier" example, as a test: a parry ball dropped into the exact bowl
//! settles on the bowl's flat inner bottom (z = 6), with exact contacts from the dispatcher.

use contact_parry::{DispatcherOptions, ExactDispatcher, ExactShape};
use contact_pipeline::{ContactOptions, ContactPipeline};
use geom_param::ObjectDescription;
use rapier3d_f64::prelude::*;
use std::sync::Arc;

#[test]
fn a_ball_settles_in_the_exact_bowl() -> Result<(), Box<dyn std::error::Error>> {
    let fixtures = concat!(env!("CARGO_MANIFEST_DIR"), "/../../fixtures");
    std::env::set_current_dir(format!("{fixtures}/.."))?;
    // --- README example starts here ---
    // Millimetres; the band reaches rapier's prediction distance (2 mm below).
    let options = ContactOptions {
        margin: 4.0,
        delta2: 2.0,
        ..ContactOptions::default()
    };
    let pipeline = Arc::new(ContactPipeline::new(options)?);
    let bowl =
        ObjectDescription::from_json(&std::fs::read_to_string("fixtures/objects/bowl.json")?)?;
    let bowl = ExactShape::new(
        Arc::clone(&pipeline),
        Arc::new(pipeline.prepare_description(&bowl)?),
    )?;

    let mut world = PhysicsWorld::new();
    world.gravity = Vector::new(0.0, 0.0, -9810.0); // mm/s²
    world.integration_parameters.length_unit = 1000.0; // 1000 mm = 1 m
    world.integration_parameters.normalized_prediction_distance = 0.002; // 2 mm
    world.narrow_phase =
        NarrowPhase::with_query_dispatcher(ExactDispatcher::new(DispatcherOptions::default()));
    let fixed = world.insert_body(RigidBodyBuilder::fixed());
    world.insert_collider(
        ColliderBuilder::new(SharedShape::new(bowl)).build(),
        Some(fixed),
    );
    let ball =
        world.insert_body(RigidBodyBuilder::dynamic().translation(Vector::new(5.0, 0.0, 20.0)));
    world.insert_collider(ColliderBuilder::ball(6.0).build(), Some(ball)); // exact against the bowl
    for _ in 0..120 {
        world.step();
    }
    println!("ball at {}", world.bodies[ball].translation());
    // --- README example ends here ---
    let b = &world.bodies[ball];
    // Resting on the flat bottom z = 6: its centre 6 mm above, less rapier's soft-contact
    // settling (about 0.07 mm with the default solver parameters).
    let z = b.translation().z;
    assert!((z - 12.0).abs() < 0.2, "ball centre at z = {z}");
    assert!(
        b.linvel().length() < 1.0,
        "still moving at {} mm/s",
        b.linvel().length()
    );
    Ok(())
}
