//! What the pipeline reports for a continuous contact (the paper's section IV): one contact per
//! connected region, flagged continuous, at the exact distance; and for an isolated minimum the
//! extent of its region of near-minimal distance from the gap's curvature, against closed
//! forms.

use contact_pipeline::{ContactOptions, ContactPipeline, PairState, QueryScratch};
use geom_param::{DPose3, DQuat, DVec3, MeshOptions, ObjectModel, Profile, SegmentSpec};

fn model(name: &str, specs: &[SegmentSpec]) -> ObjectModel {
    let profile = Profile::new(specs).expect("valid profile");
    ObjectModel::from_profile(
        name,
        profile,
        &MeshOptions {
            chordal_tolerance: 0.02,
        },
    )
    .expect("model")
}

/// A cylinder of radius `r` from z = 0 to z = `h` (flat disks at both ends).
fn cylinder(r: f64, h: f64) -> ObjectModel {
    model(
        "cylinder",
        &[
            SegmentSpec::Line {
                from: [0.0, 0.0],
                to: [r, 0.0],
            },
            SegmentSpec::Line {
                from: [r, 0.0],
                to: [r, h],
            },
            SegmentSpec::Line {
                from: [r, h],
                to: [0.0, h],
            },
        ],
    )
}

fn sphere(r: f64) -> ObjectModel {
    model(
        "sphere",
        &[SegmentSpec::Arc {
            center: [0.0, 0.0],
            from: [0.0, -r],
            to: [0.0, r],
            ccw: true,
        }],
    )
}

/// A rigid motion applied to both objects, so that nothing is axis-aligned in the world.
fn motion() -> DPose3 {
    DPose3 {
        rotation: DQuat::from_axis_angle(DVec3::new(0.3, -1.0, 0.4).normalize(), 0.9),
        translation: DVec3::new(-12.0, 30.0, 4.0),
    }
}

/// A puck (radius 8, height 5) standing on a wide disk (radius 40, height 10), its bottom
/// 8 mm off the axis and `gap` above the disk's top: the gap is `gap` over the whole puck
/// bottom. One contact, flagged continuous, at the exact distance, its normal the disk's top
/// normal, its points on the two flat faces, its region unbounded by the second-order model.
#[test]
fn a_puck_flat_on_a_disk_is_one_continuous_contact() {
    let pipeline = ContactPipeline::new(ContactOptions::default()).expect("options");
    let a = pipeline.prepare(cylinder(40.0, 10.0));
    let b = pipeline.prepare(cylinder(8.0, 5.0));
    let mut scratch = QueryScratch::default();
    let m = motion();
    for gap in [0.05, 1e-3, 0.0] {
        let pose_b = m * DPose3 {
            rotation: DQuat::from_rotation_z(0.4),
            translation: DVec3::new(8.0, -3.0, 10.0 + gap),
        };
        let report = pipeline
            .query(&a, &m, &b, &pose_b, &mut scratch)
            .expect("query");
        assert_eq!(report.state, PairState::Contact, "gap {gap}");
        assert_eq!(report.contacts.len(), 1, "gap {gap}: {report:?}");
        let c = report.contacts[0];
        assert!(c.is_continuous(), "gap {gap}: {c:?}");
        assert!(
            (c.distance - gap).abs() <= c.diagnostics.error_estimate + 1e-12,
            "{c:?}"
        );
        let up = m.rotation * DVec3::Z;
        assert!(c.normal.distance(up) < 1e-12, "{c:?}");
        let top = m * DVec3::new(0.0, 0.0, 10.0);
        assert!((c.point_a - top).dot(up).abs() < 1e-9, "{c:?}");
        let local = m.inverse() * c.point_a;
        assert!(
            local.truncate().distance(glam::DVec2::new(8.0, -3.0)) <= 8.0 + 1e-9,
            "{c:?}"
        );
        assert_eq!(c.flat_extent(1e-7), f64::INFINITY);
    }
}

/// Two spheres (radii 10 and 5) at gap 0.05: an isolated minimum. A point of A at arc s from
/// the contact is |a − c_b| − 5 from B, with |a − c_b|² = 10² + D² − 2·10·D cos(s / 10),
/// D = 15.05, so the gap's curvature is κ = D / (10 (D − 10)) and the gap stays within τ of
/// its minimum over √(2τ / κ) (up to O(gap x curvature) relative, the two points sliding
/// together rather than A's alone).
#[test]
fn an_isolated_minimum_reports_the_extent_of_its_flat_region() {
    let pipeline = ContactPipeline::new(ContactOptions::default()).expect("options");
    let a = pipeline.prepare(sphere(10.0));
    let b = pipeline.prepare(sphere(5.0));
    let mut scratch = QueryScratch::default();
    let m = motion();
    let gap = 0.05;
    let direction = DVec3::new(1.0, 2.0, -0.5).normalize();
    let pose_b = m * DPose3 {
        rotation: DQuat::IDENTITY,
        translation: direction * (15.0 + gap),
    };
    let report = pipeline
        .query(&a, &m, &b, &pose_b, &mut scratch)
        .expect("query");
    assert_eq!(report.contacts.len(), 1, "{report:?}");
    let c = report.contacts[0];
    assert!(!c.is_continuous(), "{c:?}");
    let centres = 15.0 + gap;
    let kappa = centres / (10.0 * (centres - 10.0));
    assert!(
        (c.diagnostics.gap_curvature - kappa).abs() <= 1e-2 * kappa,
        "{:e} vs {kappa:e}",
        c.diagnostics.gap_curvature
    );
    let tau = 1e-7;
    let extent = (2.0 * tau / kappa).sqrt();
    assert!(
        (c.flat_extent(tau) - extent).abs() <= 1e-2 * extent,
        "{:e} vs {extent:e}",
        c.flat_extent(tau)
    );
    // Bad tolerances give 0, never NaN.
    assert_eq!(c.flat_extent(-1.0), 0.0);
    assert_eq!(c.flat_extent(f64::NAN), 0.0);
}
