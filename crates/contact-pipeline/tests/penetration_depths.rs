//! Penetration depths against closed forms: every penetration region is reported as a contact
//! with negative distance, the exact witness: a point of one solid inside the other and its
//! nearest boundary point (sphere
//! into sphere, a ball into a plane, a ball into a tube's bore wall, two crossed cylinders, a
//! tilted torus into a plane), in both orders, with the contact invariants:
//! point_b = point_a + distance * normal, the normal A's outward normal at point_a.

use contact_pipeline::{
    Contact, ContactOptions, ContactPipeline, PairReport, PairState, QueryScratch,
};
use geom_param::{
    DPose3, DQuat, DVec3, MeshOptions, ObjectModel, Profile, SegmentSpec, Solid, tube,
};
use std::f64::consts::FRAC_PI_2;

const OPTIONS: MeshOptions = MeshOptions {
    chordal_tolerance: 0.02,
};

fn revolved(name: &str, specs: &[SegmentSpec]) -> ObjectModel {
    let profile = Profile::new(specs).expect("valid profile");
    ObjectModel::from_profile(name, profile, &OPTIONS).expect("model")
}

fn ball(r: f64) -> ObjectModel {
    revolved(
        "ball",
        &[SegmentSpec::Arc {
            center: [0.0, 0.0],
            from: [0.0, -r],
            to: [0.0, r],
            ccw: true,
        }],
    )
}

/// A closed cylinder of radius `r` about the z axis, 0 <= z <= `h`.
fn cylinder(r: f64, h: f64) -> ObjectModel {
    revolved(
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

/// A torus about the z axis: centre circle of radius `rc`, tube radius `a`.
fn torus(rc: f64, a: f64) -> ObjectModel {
    revolved(
        "torus",
        &[
            SegmentSpec::Arc {
                center: [rc, 0.0],
                from: [rc + a, 0.0],
                to: [rc - a, 0.0],
                ccw: true,
            },
            SegmentSpec::Arc {
                center: [rc, 0.0],
                from: [rc - a, 0.0],
                to: [rc + a, 0.0],
                ccw: true,
            },
        ],
    )
}

fn general(name: &str, solid: Solid) -> ObjectModel {
    ObjectModel::from_solid(name, solid, &OPTIONS).expect("general solid meshes")
}

fn pipeline() -> ContactPipeline {
    ContactPipeline::new(ContactOptions {
        chordal_tolerance: OPTIONS.chordal_tolerance,
        ..ContactOptions::default()
    })
    .expect("options")
}

/// The expected witness: A's point, B's point (world), the depth (> 0).
struct Witness {
    point_a: DVec3,
    point_b: DVec3,
    depth: f64,
}

/// Queries (a, pose_a) against (b, pose_b) in both orders and checks that each report is a
/// penetration with exactly one penetration contact, the closed-form `expected` one.
fn check_both_orders(
    (a, pose_a): (ObjectModel, DPose3),
    (b, pose_b): (ObjectModel, DPose3),
    expected: &Witness,
    what: &str,
) {
    let pipeline = pipeline();
    let (a, b) = (pipeline.prepare(a), pipeline.prepare(b));
    let mut scratch = QueryScratch::default();
    let ab = pipeline
        .query(&a, &pose_a, &b, &pose_b, &mut scratch)
        .expect("query");
    let ba = pipeline
        .query(&b, &pose_b, &a, &pose_a, &mut scratch)
        .expect("query");
    let delta1 = pipeline.options().delta1;
    check(&ab, delta1, expected, &format!("{what} (a, b)"));
    let swapped = Witness {
        point_a: expected.point_b,
        point_b: expected.point_a,
        depth: expected.depth,
    };
    check(&ba, delta1, &swapped, &format!("{what} (b, a)"));
}

fn check(report: &PairReport, delta1: f64, expected: &Witness, what: &str) {
    assert_eq!(report.state, PairState::Penetration, "{what}: {report:?}");
    let deep: Vec<&Contact> = report
        .contacts
        .iter()
        .filter(|c| c.distance < delta1)
        .collect();
    assert_eq!(deep.len(), 1, "{what}: {:?}", report.contacts);
    let c = deep[0];
    assert!(
        (c.distance + expected.depth).abs() < 1e-9,
        "{what}: distance {} vs closed form {}",
        c.distance,
        -expected.depth
    );
    assert!(
        c.point_a.distance(expected.point_a) < 1e-6 && c.point_b.distance(expected.point_b) < 1e-6,
        "{what}: points {} / {} vs {} / {}",
        c.point_a,
        c.point_b,
        expected.point_a,
        expected.point_b
    );
    let along = (expected.point_a - expected.point_b) / expected.depth;
    assert!(
        c.normal.distance(along) < 1e-9,
        "{what}: normal {} vs A's outward normal {along}",
        c.normal
    );
    assert!(
        (c.point_b - c.point_a - c.distance * c.normal).length() < 1e-9,
        "{what}: point_b != point_a + distance * normal"
    );
    assert!(
        c.diagnostics.is_local_minimum,
        "{what}: {:?}",
        c.diagnostics
    );
    assert!(
        c.diagnostics.error_estimate < 1e-9,
        "{what}: {:?}",
        c.diagnostics
    );
}

fn at(p: DVec3) -> DPose3 {
    DPose3::from_translation(p)
}

#[test]
fn sphere_into_sphere() {
    let direction = DVec3::new(1.0, 2.0, -0.5).normalize();
    let base = DVec3::new(3.0, -7.0, 11.0);
    for depth in [0.01, 0.3, 2.0, 6.0] {
        let centre_b = base + direction * (10.0 + 5.0 - depth);
        check_both_orders(
            (ball(10.0), at(base)),
            (
                ball(5.0),
                DPose3 {
                    rotation: DQuat::from_rotation_x(0.4),
                    translation: centre_b,
                },
            ),
            &Witness {
                point_a: base + direction * 10.0,
                point_b: centre_b - direction * 5.0,
                depth,
            },
            &format!("depth {depth}"),
        );
    }
}

/// A slab: a closed cylinder of radius 40 whose top face z = 10 is the plane of the tests.
/// (Not the rounded box: its convex component's patch tree, built on the first query whose
/// hulls overlap, takes minutes: see the session report.)
fn slab() -> ObjectModel {
    cylinder(40.0, 10.0)
}

#[test]
fn ball_into_a_plane() {
    // The slab's top face z = 10: a plane.
    for depth in [0.05, 1.0, 4.0] {
        let centre = DVec3::new(4.0, -3.0, 15.0 - depth);
        check_both_orders(
            (slab(), DPose3::IDENTITY),
            (ball(5.0), at(centre)),
            &Witness {
                point_a: DVec3::new(4.0, -3.0, 10.0),
                point_b: DVec3::new(4.0, -3.0, 10.0 - depth),
                depth,
            },
            &format!("depth {depth}"),
        );
    }
}

#[test]
fn ball_into_a_tube_bore_wall() {
    // Bore radius 8, wall 4 mm thick: the ball (r = 3) off the axis by 5 + depth pokes
    // into the concave inner wall.
    for depth in [0.05, 0.5, 1.5] {
        let off = 8.0 - 3.0 + depth;
        check_both_orders(
            (
                general("tube", tube(12.0, 8.0, 30.0).expect("tube")),
                DPose3::IDENTITY,
            ),
            (ball(3.0), at(DVec3::new(0.0, off, 15.0))),
            &Witness {
                point_a: DVec3::new(0.0, 8.0, 15.0),
                point_b: DVec3::new(0.0, off + 3.0, 15.0),
                depth,
            },
            &format!("depth {depth}"),
        );
    }
}

#[test]
fn crossed_cylinders() {
    // A: radius 4 about the z axis (0 <= z <= 40). B: radius 3, its axis turned onto +x and
    // placed along y = 7 - depth, z = 20 (x from -20 to 20): the common perpendicular is the
    // y axis at z = 20.
    for depth in [0.02, 0.4, 1.5] {
        let pose_b = DPose3 {
            rotation: DQuat::from_rotation_y(FRAC_PI_2),
            translation: DVec3::new(-20.0, 7.0 - depth, 20.0),
        };
        check_both_orders(
            (cylinder(4.0, 40.0), DPose3::IDENTITY),
            (cylinder(3.0, 40.0), pose_b),
            &Witness {
                point_a: DVec3::new(0.0, 4.0, 20.0),
                point_b: DVec3::new(0.0, 4.0 - depth, 20.0),
                depth,
            },
            &format!("depth {depth}"),
        );
    }
}

#[test]
fn tilted_torus_into_a_face() {
    // Torus (rc = 10, a = 3) tilted by alpha about x: its lowest point is its centre plus
    // (0, -rc cos alpha, -rc sin alpha - a), set depth below the slab's top face z = 10.
    let (rc, a, alpha) = (10.0, 3.0, 0.3_f64);
    for depth in [0.05, 0.8] {
        let lowest = DVec3::new(1.0, -2.0, 10.0 - depth);
        let centre = lowest - DVec3::new(0.0, -rc * alpha.cos(), -rc * alpha.sin() - a);
        let pose_b = DPose3 {
            rotation: DQuat::from_rotation_x(alpha),
            translation: centre,
        };
        check_both_orders(
            (slab(), DPose3::IDENTITY),
            (torus(rc, a), pose_b),
            &Witness {
                point_a: DVec3::new(lowest.x, lowest.y, 10.0),
                point_b: lowest,
                depth,
            },
            &format!("depth {depth}"),
        );
    }
}
