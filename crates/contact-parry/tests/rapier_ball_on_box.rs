//! End to end inside rapier (short enough for the debug profile): an exact ball dropped onto a
//! parry `Cuboid` (turned into an exact box by the dispatcher) comes to rest with a
//! penetration (closed form: the ball centre's height minus its radius) and a jitter that stay
//! bounded; and a rolling ball follows, step for step, the trajectory rapier computes with
//! parry's own closed-form ball-cuboid contacts.

use contact_parry::{DispatcherOptions, ExactDispatcher, exact_ball};
use contact_pipeline::{ContactOptions, ContactPipeline};
use parry3d_f64::math::Vector;
use parry3d_f64::shape::SharedShape;
use rapier3d_f64::prelude::{
    ColliderBuilder, NarrowPhase, PhysicsWorld, RigidBodyBuilder, RigidBodyHandle,
};
use std::sync::Arc;

/// The pipeline of the exact runs: prediction 2 mm needs delta2 = 2 mm (and a margin above).
fn pipeline() -> Arc<ContactPipeline> {
    Arc::new(
        ContactPipeline::new(ContactOptions {
            margin: 4.0,
            delta2: 2.0,
            ..ContactOptions::default()
        })
        .expect("options"),
    )
}

/// A millimetre world (gravity 9810 mm/s², prediction 2 mm, no contact recycling, no CCD) with
/// stiff contacts on fixed bodies (8 iterations, 960 Hz, damping ratio 1), a 200 x 200 x 10 mm
/// fixed parry cuboid whose top face is z = 0, and a dynamic ball of radius `r` placed by
/// `start`: with `exact`, an exact ball and the exact dispatcher (which turns the cuboid into
/// an exact box), else a parry ball and parry's dispatcher.
fn world(exact: bool, r: f64, start: RigidBodyBuilder) -> (PhysicsWorld, RigidBodyHandle) {
    let mut world = PhysicsWorld::new();
    world.gravity = Vector::new(0.0, 0.0, -9810.0);
    let p = &mut world.integration_parameters;
    p.length_unit = 1000.0;
    p.normalized_prediction_distance = 0.002;
    p.contact_recycling = false;
    p.max_ccd_substeps = 0;
    p.num_solver_iterations = 8;
    p.static_contact_softness.natural_frequency = 960.0;
    p.static_contact_softness.damping_ratio = 1.0;
    let ball = if exact {
        world.narrow_phase =
            NarrowPhase::with_query_dispatcher(ExactDispatcher::new(DispatcherOptions::default()));
        ColliderBuilder::new(SharedShape::new(
            exact_ball(pipeline(), r).expect("exact ball"),
        ))
    } else {
        ColliderBuilder::ball(r)
    };
    let ground =
        world.insert_body(RigidBodyBuilder::fixed().translation(Vector::new(0.0, 0.0, -5.0)));
    world.insert_collider(
        ColliderBuilder::cuboid(100.0, 100.0, 5.0).build(),
        Some(ground),
    );
    let body = world.insert_body(start.can_sleep(false));
    world.insert_collider(ball.build(), Some(body));
    (world, body)
}

#[test]
fn a_ball_settles_on_a_box_with_exact_contacts() {
    let r = 10.0;
    let (mut world, body) = world(
        true,
        r,
        RigidBodyBuilder::dynamic().translation(Vector::new(1.0, -2.0, r + 0.5)),
    );
    // The same dispatcher again, with a handle on its counters.
    let dispatcher = ExactDispatcher::new(DispatcherOptions::default());
    let counters = dispatcher.counters();
    world.narrow_phase = NarrowPhase::with_query_dispatcher(dispatcher);
    let (mut gaps, mut speeds) = (Vec::new(), Vec::new());
    for _ in 0..60 {
        world.step();
        let b = &world.bodies[body];
        gaps.push(b.translation().z - r);
        speeds.push(b.linvel().length());
    }
    let worst_gap = gaps[40..].iter().fold(0.0_f64, |m, g| m.max(g.abs()));
    let rms = (speeds[40..].iter().map(|v| v * v).sum::<f64>() / 20.0).sqrt();
    println!(
        "last 20 steps: |gap| <= {worst_gap:.2e} mm, rms speed {rms:.2e} mm/s; {:?}",
        counters.snapshot()
    );
    assert!(worst_gap <= 1e-3, "resting penetration {worst_gap} mm");
    assert!(rms <= 1e-3, "jitter {rms} mm/s");
    // Never lost: the ball never fell through (a lost contact lets it fall 2.7 mm in a step).
    assert!(gaps.iter().all(|g| *g > -0.5), "{gaps:?}");
    let counts = counters.snapshot();
    assert_eq!(counts.unsupported, 0);
    assert!(counts.warm >= 30, "{counts:?}");
}

#[test]
fn a_rolling_ball_follows_parrys_closed_form_contacts() {
    let r = 8.0;
    let start = || {
        RigidBodyBuilder::dynamic()
            .translation(Vector::new(0.0, 0.0, r))
            .linvel(Vector::new(30.0, 10.0, 0.0))
            .angvel(Vector::new(0.0, 10.0, 0.0))
            .angular_damping(1.0)
    };
    let (mut ours, a) = world(true, r, start());
    let (mut parrys, b) = world(false, r, start());
    let mut worst = 0.0_f64;
    for _ in 0..120 {
        ours.step();
        parrys.step();
        let (pa, pb) = (ours.bodies[a].translation(), parrys.bodies[b].translation());
        worst = worst.max(pa.distance(pb));
    }
    println!(
        "largest difference {worst:.3e} mm, rolled to {}",
        ours.bodies[a].translation()
    );
    assert!(ours.bodies[a].translation().x > 20.0, "the ball rolled");
    // Stage 3 places an exact touch's point to about 1e-6 mm (at d = 0 Newton converges only
    // linearly), and rapier's iterative solver carries such differences along: 1.2e-4 mm after
    // 68 mm of rolling when written.
    assert!(worst < 1e-3, "the trajectories differ by {worst} mm");
}
