//! The shape's contract: bounding volumes that hold the exact surface, mass properties within
//! the stated error of the closed forms, the CCD thickness of known walls, welded meshes of
//! every fixture object closed.

mod support;

use contact_parry::{ExactShape, exact_ball, exact_cuboid};
use contact_pipeline::{ContactOptions, ContactPipeline};
use geom_param::{MeshOptions, ObjectModel, tube};
use glam::DVec3;
use parry3d_f64::shape::{Shape, ShapeType};
use std::f64::consts::PI;
use std::sync::Arc;

fn pipeline() -> Arc<ContactPipeline> {
    Arc::new(ContactPipeline::new(ContactOptions::default()).expect("default options"))
}

#[test]
fn a_ball_weighs_and_turns_as_the_exact_sphere_within_the_stated_bound() {
    let r = 10.0;
    let ball = exact_ball(pipeline(), r).expect("ball");
    let volume = 4.0 / 3.0 * PI * r.powi(3);
    let density = 0.0078; // g/mm³ (steel), any value
    let mp = ball.mass_properties(density);
    let bound = ball.volume_error_bound();
    let error = (mp.mass() / density - volume).abs();
    println!(
        "ball r = {r}: mesh volume error {error:.3} mm³ ({:.3} %), bound {bound:.3} mm³",
        100.0 * error / volume
    );
    assert!(error <= bound, "{error} > {bound}");
    // The centre moves by at most the misplaced volume times its lever arm, over the volume.
    let com_bound = 2.0 * bound * r / volume;
    println!(
        "centre of mass off by {:.2e} mm (bound {com_bound:.2e})",
        mp.local_com.length()
    );
    assert!(mp.local_com.length() <= com_bound);
    // Inertia 2/5 m r² about every axis (to first order in the chordal error).
    let exact = 0.4 * density * volume * r * r;
    for i in mp.principal_inertia().to_array() {
        assert!(
            (i - exact).abs() <= 5.0 * bound / volume * exact,
            "{i} vs {exact}"
        );
    }
    assert_eq!(ball.shape_type(), ShapeType::Custom);
}

#[test]
fn a_cuboid_weighs_exactly_its_closed_form() {
    let h = DVec3::new(30.0, 20.0, 5.0);
    let cuboid = exact_cuboid(pipeline(), h).expect("cuboid");
    // Planes mesh exactly: no chordal error beyond rounding.
    assert!(cuboid.volume_error_bound() < 1e-6);
    let mass = cuboid.mass_properties(1.0);
    let m = 8.0 * h.x * h.y * h.z;
    assert!((mass.mass() - m).abs() < 1e-9 * m);
    let mut inertia = mass.principal_inertia().to_array();
    inertia.sort_by(f64::total_cmp);
    let mut exact = [
        m / 3.0 * (h.y * h.y + h.z * h.z),
        m / 3.0 * (h.x * h.x + h.z * h.z),
        m / 3.0 * (h.x * h.x + h.y * h.y),
    ];
    exact.sort_by(f64::total_cmp);
    for (i, e) in inertia.iter().zip(exact) {
        assert!((i - e).abs() < 1e-9 * e, "{i} vs {e}");
    }
    assert!(
        (cuboid.ccd_thickness() - h.z).abs() < 1e-9,
        "{}",
        cuboid.ccd_thickness()
    );
}

#[test]
fn bounding_volumes_hold_the_exact_surface() {
    let r = 7.0;
    let ball = exact_ball(pipeline(), r).expect("ball");
    let aabb = ball.compute_local_aabb();
    assert!(aabb.mins.max_element() <= -r && aabb.maxs.min_element() >= r);
    let sphere = ball.compute_local_bounding_sphere();
    assert!(sphere.center.length() + r <= sphere.radius + 1e-12);
    // And not much more: within the chordal error plus the mesh's vertex spread.
    let e = ball.closed_mesh().chordal_error;
    assert!(aabb.maxs.max_element() <= r + 2.0 * e);
}

#[test]
fn the_ccd_thickness_is_half_the_thinnest_wall() {
    let pipeline = pipeline();
    // A tube 18 mm across with a 10 mm bore: walls 4 mm thick.
    let mesh = MeshOptions {
        chordal_tolerance: pipeline.options().chordal_tolerance,
    };
    let model =
        ObjectModel::from_solid("tube", tube(9.0, 5.0, 40.0).expect("tube"), &mesh).expect("model");
    let shape = ExactShape::from_model(Arc::clone(&pipeline), model).expect("shape");
    let e = shape.closed_mesh().chordal_error;
    assert!(
        (shape.ccd_thickness() - 2.0).abs() <= e,
        "{}",
        shape.ccd_thickness()
    );
    let ball = exact_ball(pipeline, 6.0).expect("ball");
    let e = ball.closed_mesh().chordal_error;
    assert!(
        (ball.ccd_thickness() - 6.0).abs() <= e,
        "{}",
        ball.ccd_thickness()
    );
}

#[test]
fn every_fixture_object_welds_into_a_closed_outward_mesh() {
    let pipeline = pipeline();
    for name in [
        "bowl",
        "bracket",
        "goblet",
        "jar",
        "loft",
        "paperweight",
        "pencil",
        "rounded-box",
        "tube",
        "vase",
    ] {
        let shape = support::fixtures::object(&pipeline, name);
        let mesh = shape.closed_mesh();
        let mass = shape.mass_properties(1.0);
        assert!(mesh.volume > 0.0 && (mass.mass() - mesh.volume).abs() < 1e-9 * mesh.volume);
        // Every mesh vertex lies inside the bounding ball.
        let ball = shape.compute_local_bounding_sphere();
        assert!(
            mesh.trimesh
                .vertices()
                .iter()
                .all(|v| v.distance(ball.center) <= ball.radius),
            "{name}"
        );
    }
}
