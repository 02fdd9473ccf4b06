//! The dispatcher's one-shot queries (intersection test, distance, contact, closest points)
//! through parry's `QueryDispatcher` trait, against closed forms: two exact balls, an exact
//! ball with parry's `Ball`, an exact ball on parry's `Cuboid` (face, edge, corner), in both
//! argument orders; penetration depths; what is beyond reach.

use contact_parry::{BeyondReach, DispatcherOptions, ExactDispatcher, ExactShape, exact_ball};
use contact_pipeline::{ContactOptions, ContactPipeline};
use parry3d_f64::math::{Pose, Vector};
use parry3d_f64::query::{ClosestPoints, DefaultQueryDispatcher, QueryDispatcher, Unsupported};
use parry3d_f64::shape::{Ball, Compound, Cuboid, Shape, ShapeType, SharedShape};
use std::sync::Arc;

fn pipeline() -> Arc<ContactPipeline> {
    Arc::new(ContactPipeline::new(ContactOptions::default()).expect("default options"))
}

/// A rotation that mixes every axis, so that frames matter.
fn turn() -> glam::DQuat {
    glam::DQuat::from_euler(glam::EulerRot::XYZ, 0.7, -0.4, 1.9)
}

/// Checks `dispatcher`'s answers for a ball of radius `r1` at the origin (`g1`) and one of
/// radius `r2` (`g2`) placed by `pos12` against the closed forms, for a gap within the band.
fn check_ball_pair(
    dispatcher: &ExactDispatcher,
    g1: &dyn Shape,
    r1: f64,
    g2: &dyn Shape,
    r2: f64,
    pos12: &Pose,
) {
    let c = pos12.translation;
    let gap = c.length() - r1 - r2;
    let n = c.normalize();
    let tol = 1e-8;
    let distance = dispatcher
        .distance(pos12, g1, g2)
        .expect("in the band")
        .distance;
    assert!((distance - gap).abs() < tol, "distance {distance} vs {gap}");
    let contact = dispatcher
        .contact(pos12, g1, g2, 0.1)
        .expect("in the band")
        .expect("within prediction");
    assert!((contact.dist - gap).abs() < tol);
    assert!(contact.point1.distance(r1 * n) < tol, "{}", contact.point1);
    let point2 = pos12.rotation.inverse() * (-r2 * n);
    assert!(contact.point2.distance(point2) < tol, "{}", contact.point2);
    assert!(contact.normal1.distance(n) < tol);
    assert!(contact.normal2.distance(-(pos12.rotation.inverse() * n)) < tol);
    match dispatcher
        .closest_points(pos12, g1, g2, 0.1)
        .expect("in the band")
    {
        ClosestPoints::WithinMargin(p1, p2) => {
            assert!(p1.distance(r1 * n) < tol && p2.distance(point2) < tol);
        }
        other => panic!("expected WithinMargin, got {other:?}"),
    }
    assert_eq!(
        dispatcher.closest_points(pos12, g1, g2, 0.5 * gap),
        Ok(ClosestPoints::Disjoint)
    );
    assert_eq!(dispatcher.contact(pos12, g1, g2, 0.5 * gap), Ok(None));
    let test = dispatcher.intersection_test(pos12, g1, g2).expect("exact");
    assert_eq!(test.intersecting, gap <= 0.0);
}

#[test]
fn two_exact_balls_match_the_closed_form_in_both_orders() {
    let pipeline = pipeline();
    let dispatcher = ExactDispatcher::new(DispatcherOptions::default());
    let (r1, r2) = (10.0, 6.0);
    let a = exact_ball(Arc::clone(&pipeline), r1).expect("ball");
    let b = exact_ball(Arc::clone(&pipeline), r2).expect("ball");
    let dir = Vector::new(1.0, -2.0, 0.5).normalize();
    let pos12 = Pose::from_parts(dir * (r1 + r2 + 0.04), turn());
    check_ball_pair(&dispatcher, &a, r1, &b, r2, &pos12);
    // Swapped: B's frame is the first; A sits at pos12⁻¹.
    check_ball_pair(&dispatcher, &b, r2, &a, r1, &pos12.inverse());
}

#[test]
fn an_exact_ball_with_parry_balls_matches_parry_and_the_closed_form() {
    let pipeline = pipeline();
    let dispatcher = ExactDispatcher::new(DispatcherOptions::default());
    let (r1, r2) = (10.0, 6.0);
    let exact = exact_ball(Arc::clone(&pipeline), r1).expect("ball");
    let parry_ball = Ball::new(r2);
    let dir = Vector::new(-0.3, 0.2, 1.0).normalize();
    let pos12 = Pose::from_parts(dir * (r1 + r2 + 0.07), turn());
    check_ball_pair(&dispatcher, &exact, r1, &parry_ball, r2, &pos12);
    check_ball_pair(&dispatcher, &parry_ball, r2, &exact, r1, &pos12.inverse());
    // Parry's own closed form for two parry balls agrees with ours.
    let parry = DefaultQueryDispatcher
        .contact(&pos12, &Ball::new(r1), &parry_ball, 0.1)
        .expect("supported")
        .expect("close");
    let ours = dispatcher
        .contact(&pos12, &exact, &parry_ball, 0.1)
        .expect("exact")
        .expect("close");
    assert!((parry.dist - ours.dist).abs() < 1e-8);
    assert!(parry.point1.distance(ours.point1) < 1e-8);
    assert!(parry.point2.distance(ours.point2) < 1e-8);
}

#[test]
fn an_exact_ball_on_a_parry_cuboid_face_edge_and_corner() {
    let pipeline = pipeline();
    let dispatcher = ExactDispatcher::new(DispatcherOptions::default());
    let r = 5.0;
    let ball = exact_ball(Arc::clone(&pipeline), r).expect("ball");
    let h = Vector::new(40.0, 30.0, 10.0);
    let cuboid = Cuboid::new(h);
    let gap = 0.03;
    // (ball centre in the cuboid's frame, nearest point of the cuboid)
    let face = Vector::new(3.0, -7.0, h.z + r + gap);
    let edge_dir = Vector::new(1.0, 0.0, 1.0).normalize();
    let edge = Vector::new(h.x, 5.0, h.z) + (r + gap) * edge_dir;
    let corner_dir = Vector::new(-1.0, 1.0, 1.0).normalize();
    let corner = Vector::new(-h.x, h.y, h.z) + (r + gap) * corner_dir;
    for (centre, nearest) in [
        (face, Vector::new(3.0, -7.0, h.z)),
        (edge, Vector::new(h.x, 5.0, h.z)),
        (corner, Vector::new(-h.x, h.y, h.z)),
    ] {
        let pos_ball = Pose::from_parts(centre, turn());
        // Cuboid first.
        let c = dispatcher
            .contact(&pos_ball, &cuboid, &ball, 0.1)
            .expect("exact")
            .expect("close");
        assert!((c.dist - gap).abs() < 1e-8, "{} vs {gap}", c.dist);
        assert!(
            c.point1.distance(nearest) < 1e-7,
            "{} vs {nearest}",
            c.point1
        );
        let n = (centre - nearest).normalize();
        assert!(c.normal1.distance(n) < 1e-7);
        assert!(c.point2.distance(pos_ball.rotation.inverse() * (-r * n)) < 1e-7);
        // Ball first: normals flipped, points swapped.
        let pos_cuboid = pos_ball.inverse();
        let f = dispatcher
            .contact(&pos_cuboid, &ball, &cuboid, 0.1)
            .expect("exact")
            .expect("close");
        assert!((f.dist - gap).abs() < 1e-8);
        assert!(f.point1.distance(c.point2) < 1e-7 && f.point2.distance(c.point1) < 1e-7);
        assert!(f.normal1.distance(c.normal2) < 1e-7 && f.normal2.distance(c.normal1) < 1e-7);
    }
}

#[test]
fn penetration_depths_are_exact_and_signed() {
    let pipeline = pipeline();
    let dispatcher = ExactDispatcher::new(DispatcherOptions::default());
    let (r1, r2) = (10.0, 6.0);
    let a = exact_ball(Arc::clone(&pipeline), r1).expect("ball");
    let b = exact_ball(Arc::clone(&pipeline), r2).expect("ball");
    let depth = 0.2;
    let dir = Vector::new(0.0, 0.6, 0.8);
    let pos12 = Pose::from_parts(dir * (r1 + r2 - depth), turn());
    let c = dispatcher
        .contact(&pos12, &a, &b, 0.0)
        .expect("certified depth")
        .expect("penetrating");
    assert!((c.dist + depth).abs() < 1e-8, "{}", c.dist);
    assert!(c.point1.distance(r1 * dir) < 1e-7);
    assert!(c.normal1.distance(dir) < 1e-7);
    assert!(
        dispatcher
            .intersection_test(&pos12, &a, &b)
            .expect("exact")
            .intersecting
    );
    assert_eq!(
        dispatcher.distance(&pos12, &a, &b).map(|d| d.distance),
        Ok(0.0)
    );
    assert_eq!(
        dispatcher.closest_points(&pos12, &a, &b, 1.0),
        Ok(ClosestPoints::Intersecting)
    );
}

#[test]
fn beyond_the_band_is_unsupported_or_a_stated_mesh_approximation() {
    let pipeline = pipeline();
    let (r1, r2) = (10.0, 6.0);
    let a = exact_ball(Arc::clone(&pipeline), r1).expect("ball");
    let b = exact_ball(Arc::clone(&pipeline), r2).expect("ball");
    let gap = 3.0;
    let pos12 = Pose::translation(r1 + r2 + gap, 0.0, 0.0);
    let strict = ExactDispatcher::new(DispatcherOptions::default());
    assert_eq!(strict.distance(&pos12, &a, &b), Err(Unsupported));
    assert_eq!(strict.contact(&pos12, &a, &b, 5.0), Err(Unsupported));
    assert_eq!(strict.closest_points(&pos12, &a, &b, 5.0), Err(Unsupported));
    // What is known exactly stays exact: no contact within the band, no intersection.
    assert_eq!(strict.contact(&pos12, &a, &b, 0.1), Ok(None));
    assert_eq!(
        strict.closest_points(&pos12, &a, &b, 0.1),
        Ok(ClosestPoints::Disjoint)
    );
    assert!(
        !strict
            .intersection_test(&pos12, &a, &b)
            .expect("exact")
            .intersecting
    );
    let meshy = ExactDispatcher::new(DispatcherOptions {
        beyond_reach: BeyondReach::MeshApproximation,
        ..DispatcherOptions::default()
    });
    let d = meshy.distance(&pos12, &a, &b).expect("mesh").distance;
    let e = a.closed_mesh().chordal_error + b.closed_mesh().chordal_error;
    assert!(
        (d - gap).abs() <= e,
        "mesh distance {d} vs {gap} (errors {e})"
    );
    assert_eq!(strict.counters().snapshot().unsupported, 3);
    assert_eq!(meshy.counters().snapshot().mesh, 1);
}

#[test]
fn shapes_it_cannot_represent_are_never_answered_wrongly() {
    let pipeline = pipeline();
    let dispatcher = ExactDispatcher::new(DispatcherOptions::default());
    let ball = exact_ball(Arc::clone(&pipeline), 5.0).expect("ball");
    let mesh = ball.closed_mesh().trimesh.clone();
    let pos12 = Pose::translation(10.02, 0.0, 0.0);
    assert_eq!(dispatcher.distance(&pos12, &ball, &mesh), Err(Unsupported));
    assert_eq!(
        dispatcher.contact(&pos12, &mesh, &ball, 0.1),
        Err(Unsupported)
    );
    // An exact shape inside a compound: parry's compound code would ask parry about the part.
    let compound = Compound::new(vec![(Pose::IDENTITY, SharedShape::new(ball.clone()))]);
    let other = Ball::new(5.0);
    assert_eq!(
        dispatcher.contact(&pos12, &compound, &other, 0.1),
        Err(Unsupported)
    );
    // Two exact shapes of different pipelines.
    let other_pipeline = exact_ball(self::pipeline(), 5.0).expect("ball");
    assert_eq!(
        dispatcher.distance(&pos12, &ball, &other_pipeline),
        Err(Unsupported)
    );
    // Parry's default dispatcher does not know the shape: unsupported, not wrong.
    assert_eq!(ball.shape_type(), ShapeType::Custom);
    assert_eq!(
        DefaultQueryDispatcher.distance(&pos12, &ball, &Cuboid::new(Vector::splat(5.0))),
        Err(Unsupported)
    );
    // Pairs without an exact shape are parry's answers.
    let (b1, b2) = (Ball::new(1.0), Ball::new(2.0));
    let far = Pose::translation(5.0, 0.0, 0.0);
    assert_eq!(
        dispatcher.distance(&far, &b1, &b2).map(|d| d.distance),
        Ok(2.0)
    );
    let _: &dyn Shape = &ExactShape::clone(&ball);
}

/// A ball resting on a box face, touching (gap 0 or ±1e-9 mm) at points 1e-4 to 1e-2 rad from
/// the pole of a sphere revolved about z: Stage 3 reaches its iteration limit there and the
/// contact is lost (FIXME: exact-refine, Newton next to a pole of a revolved face). The
/// dispatcher's balls put their poles along `BALL_AXIS`, so the same touches along z are found.
#[test]
fn touches_near_a_sphere_pole() {
    use contact_parry::{BALL_AXIS, exact_cuboid};
    use contact_pipeline::QueryScratch;
    use geom_param::{ObjectModel, Profile, SegmentSpec};
    let pipeline = pipeline();
    let r = 10.0;
    let profile = Profile::new(&[SegmentSpec::Arc {
        center: [0.0, 0.0],
        from: [0.0, -r],
        to: [0.0, r],
        ccw: true,
    }])
    .expect("half circle");
    let model = ObjectModel::from_profile(
        "z-ball",
        profile,
        &geom_param::MeshOptions {
            chordal_tolerance: 0.05,
        },
    )
    .expect("model");
    let z_ball = ExactShape::from_model(Arc::clone(&pipeline), model).expect("shape");
    let placed = exact_ball(Arc::clone(&pipeline), r).expect("ball");
    assert!((placed.placement().rotation * Vector::Z).distance(BALL_AXIS.normalize()) < 1e-12);
    let cuboid = exact_cuboid(Arc::clone(&pipeline), Vector::new(100.0, 100.0, 5.0)).expect("box");
    let mut scratch = QueryScratch::default();
    let (mut lost_z, mut lost_placed, mut total) = (0, 0, 0);
    for k in 0..30 {
        let theta = 1e-4 * 10f64.powf(2.0 * f64::from(k) / 29.0);
        let rot =
            glam::DQuat::from_rotation_z(0.7 * f64::from(k)) * glam::DQuat::from_rotation_y(theta);
        for gap in [0.0, 1e-9, -1e-9] {
            total += 1;
            for (shape, lost) in [(&z_ball, &mut lost_z), (&placed, &mut lost_placed)] {
                // The shape frame turned by `rot`: the object frame is that times the placement.
                let pose = Pose::from_parts(
                    Vector::new(1.0, -2.0, r + gap),
                    rot * shape.placement().rotation,
                );
                let report = pipeline
                    .query(
                        cuboid.object(),
                        &Pose::translation(0.0, 0.0, -5.0),
                        shape.object(),
                        &pose,
                        &mut scratch,
                    )
                    .expect("query");
                if report.contacts.is_empty() {
                    *lost += 1;
                } else {
                    assert!(report.contacts[0].distance.abs() < 1e-6);
                }
            }
        }
    }
    println!("touches lost: {lost_z} of {total} about z, {lost_placed} placed");
    assert!(
        lost_z > 0,
        "FIXME fixed? near-pole touches are found now: drop the placement"
    );
    assert_eq!(lost_placed, 0);
}
