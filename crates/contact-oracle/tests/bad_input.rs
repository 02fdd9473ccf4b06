//! Bad input gives a typed error, never a panic.

use contact_oracle::closed_form::sphere_on_sphere;
use contact_oracle::{OracleError, OracleOptions, find_contacts};
use geom_param::{DPose3, DQuat, DVec3, Solid};

fn spheres() -> (Solid, Solid, DPose3, DPose3) {
    let scene = sphere_on_sphere(1.0, 1.0, 0.1, DVec3::X, [DQuat::IDENTITY; 2]);
    let (a, b) = scene.solids().expect("valid");
    (a, b, scene.pose_a, scene.pose_b)
}

#[test]
fn non_finite_or_non_unit_poses_are_refused() {
    let (a, b, pa, pb) = spheres();
    let options = OracleOptions::for_solids(&a, &b, 0.5);
    for bad in [
        DPose3 {
            rotation: DQuat::from_xyzw(f64::NAN, 0.0, 0.0, 1.0),
            translation: DVec3::ZERO,
        },
        DPose3 {
            rotation: DQuat::IDENTITY,
            translation: DVec3::new(f64::INFINITY, 0.0, 0.0),
        },
        DPose3 {
            rotation: DQuat::from_xyzw(0.0, 0.0, 0.0, 2.0),
            translation: DVec3::ZERO,
        },
    ] {
        assert_eq!(
            find_contacts(&a, &bad, &b, &pb, &options),
            Err(OracleError::BadPose { which: "a" })
        );
        assert_eq!(
            find_contacts(&a, &pa, &b, &bad, &options),
            Err(OracleError::BadPose { which: "b" })
        );
    }
}

#[test]
fn unusable_options_are_refused() {
    let (a, b, pa, pb) = spheres();
    let good = OracleOptions::for_solids(&a, &b, 0.5);
    for options in [
        OracleOptions {
            spacing: 0.0,
            ..good
        },
        OracleOptions {
            spacing: f64::NAN,
            ..good
        },
        OracleOptions {
            spacing: -1.0,
            ..good
        },
        OracleOptions {
            reach: -0.1,
            ..good
        },
        OracleOptions {
            reach: f64::INFINITY,
            ..good
        },
        OracleOptions {
            tolerance: 0.0,
            ..good
        },
        OracleOptions {
            tolerance: f64::NAN,
            ..good
        },
    ] {
        assert!(
            matches!(
                find_contacts(&a, &pa, &b, &pb, &options),
                Err(OracleError::BadOptions { .. })
            ),
            "{options:?}"
        );
    }
}

#[test]
fn a_spacing_beyond_the_sample_budget_is_refused() {
    let (a, b, pa, pb) = spheres();
    let options = OracleOptions {
        spacing: 1e-5,
        ..OracleOptions::for_solids(&a, &b, 0.5)
    };
    assert!(matches!(
        find_contacts(&a, &pa, &b, &pb, &options),
        Err(OracleError::TooManySamples { .. })
    ));
}

#[test]
fn an_empty_solid_is_refused() {
    let (a, b, pa, pb) = spheres();
    let options = OracleOptions::for_solids(&a, &b, 0.5);
    let empty = Solid::default();
    assert_eq!(
        find_contacts(&empty, &pa, &b, &pb, &options),
        Err(OracleError::BadSolid { which: "a" })
    );
    assert_eq!(
        find_contacts(&a, &pa, &empty, &pb, &options),
        Err(OracleError::BadSolid { which: "b" })
    );
}

/// Far apart (beyond reach): nothing reported, separated.
#[test]
fn far_apart_reports_nothing() {
    let scene = sphere_on_sphere(1.0, 1.0, 5.0, DVec3::X, [DQuat::IDENTITY; 2]);
    let (a, b) = scene.solids().expect("valid");
    let options = OracleOptions::for_solids(&a, &b, 0.5);
    let report = find_contacts(&a, &scene.pose_a, &b, &scene.pose_b, &options).expect("runs");
    assert!(report.contacts.is_empty());
    assert_eq!(report.min_distance, f64::INFINITY);
    assert_eq!(
        report.state(-0.001, 0.1),
        contact_oracle::OracleState::Separated
    );
}
