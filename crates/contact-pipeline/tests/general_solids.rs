//! The whole pipeline on general solids (built in code, not revolved) against closed forms:
//! a ball above a rounded box's flat face, over one of its fillet cylinders, over a corner
//! sphere; a ball inside a tube's bore and on its annular cap; a ball on an extruded
//! L-bracket's flat face, against the concave fillet of its inner corner and inside its hole.
//! Every contact's connecting vector is checked to be normal to both surfaces.

use contact_pipeline::{ContactOptions, ContactPipeline, PairReport, PairState, QueryScratch};
use geom_param::{
    DPose3, DVec2, DVec3, FeatureLocation, MeshOptions, ObjectModel, PlanarProfile, PlanarSegment,
    Profile, SegmentSpec, Solid, extrude, rounded_box, tube,
};

const OPTIONS: MeshOptions = MeshOptions {
    chordal_tolerance: 0.02,
};

fn ball(r: f64) -> ObjectModel {
    let profile = Profile::new(&[SegmentSpec::Arc {
        center: [0.0, 0.0],
        from: [0.0, -r],
        to: [0.0, r],
        ccw: true,
    }])
    .expect("valid profile");
    ObjectModel::from_profile("ball", profile, &OPTIONS).expect("model")
}

fn model(name: &str, solid: Solid) -> ObjectModel {
    ObjectModel::from_solid(name, solid, &OPTIONS).expect("general solid meshes")
}

fn at(p: DVec3) -> DPose3 {
    DPose3::from_translation(p)
}

/// Queries `a` at the identity against balls of radius r centred at each `centre`.
fn queries(a: ObjectModel, balls: &[(f64, DVec3)]) -> Vec<PairReport> {
    let pipeline = ContactPipeline::new(ContactOptions {
        chordal_tolerance: OPTIONS.chordal_tolerance,
        ..ContactOptions::default()
    })
    .expect("options");
    let a = pipeline.prepare(a);
    let mut scratch = QueryScratch::default();
    balls
        .iter()
        .map(|&(r, centre)| {
            let b = pipeline.prepare(ball(r));
            pipeline
                .query(&a, &DPose3::IDENTITY, &b, &at(centre), &mut scratch)
                .expect("query")
        })
        .collect()
}

fn box_solid() -> Solid {
    rounded_box(DVec3::new(20.0, 15.0, 10.0), 3.0).expect("rounded box")
}

fn tube_solid() -> Solid {
    tube(12.0, 8.0, 30.0).expect("tube")
}

/// An L-bracket 40 x 40 mm, 8 mm thick legs, with a concave fillet of radius 5 in its inner
/// corner and a hole of radius 4 through the long leg, extruded 20 mm in z.
fn bracket_solid() -> Solid {
    let p = |x: f64, y: f64| DVec2::new(x, y);
    let outer = vec![
        PlanarSegment::Line {
            from: p(0.0, 0.0),
            to: p(40.0, 0.0),
        },
        PlanarSegment::Line {
            from: p(40.0, 0.0),
            to: p(40.0, 8.0),
        },
        PlanarSegment::Line {
            from: p(40.0, 8.0),
            to: p(13.0, 8.0),
        },
        PlanarSegment::Arc {
            center: p(13.0, 13.0),
            from: p(13.0, 8.0),
            to: p(8.0, 13.0),
            ccw: false,
        },
        PlanarSegment::Line {
            from: p(8.0, 13.0),
            to: p(8.0, 40.0),
        },
        PlanarSegment::Line {
            from: p(8.0, 40.0),
            to: p(0.0, 40.0),
        },
        PlanarSegment::Line {
            from: p(0.0, 40.0),
            to: p(0.0, 0.0),
        },
    ];
    let hole = vec![PlanarSegment::Arc {
        center: p(28.0, 4.0),
        from: p(31.0, 4.0),
        to: p(31.0, 4.0),
        ccw: false,
    }];
    extrude(
        &PlanarProfile {
            outer,
            holes: vec![hole],
        },
        0.0,
        20.0,
    )
    .expect("bracket")
}

/// The single contact of a report, checked for the closed-form distance `expected` and for
/// the invariant: the connecting vector is along both surfaces' normals.
fn one_contact(report: &PairReport, expected: f64, what: &str) -> FeatureLocation {
    assert_eq!(report.state, PairState::Contact, "{what}: {report:?}");
    assert_eq!(report.contacts.len(), 1, "{what}: {:?}", report.contacts);
    let c = &report.contacts[0];
    assert!(
        (c.distance - expected).abs() < 1e-9,
        "{what}: distance {} vs closed form {expected}",
        c.distance
    );
    let connecting = c.point_b - c.point_a;
    assert!(
        (connecting - c.distance * c.normal).length() < 1e-9,
        "{what}: connecting vector {connecting} not along the normal {}",
        c.normal
    );
    c.location_a
}

#[test]
fn ball_over_the_faces_fillets_and_corners_of_a_rounded_box() {
    let gap = 0.05;
    let fillet =
        DVec3::new(17.0, 2.0, 7.0) + (3.0 + 5.0 + gap) * DVec3::new(1.0, 0.0, 1.0).normalize();
    let corner =
        DVec3::new(17.0, 12.0, 7.0) + (3.0 + 5.0 + gap) * DVec3::new(1.0, 2.0, 2.0).normalize();
    let reports = queries(
        model("rounded box", box_solid()),
        &[
            // Above the top face (z = 10): a plane.
            (5.0, DVec3::new(4.0, -3.0, 15.0 + gap)),
            // Over the fillet along the edge x = 17, z = 7 (radius 3), diagonally in xz.
            (5.0, fillet),
            // Over the corner sphere at (17, 12, 7).
            (5.0, corner),
            // Over the line where the top face meets its fillet.
            (5.0, DVec3::new(17.0, 0.0, 15.0 + gap)),
        ],
    );
    let loc = one_contact(&reports[0], gap, "face");
    assert!(matches!(loc, FeatureLocation::Face { .. }), "{loc:?}");
    one_contact(&reports[1], gap, "fillet");
    one_contact(&reports[2], gap, "corner");
    one_contact(&reports[3], gap, "tangent line");
}

#[test]
fn ball_in_a_tube_bore_and_on_its_cap() {
    let gap = 0.03;
    let reports = queries(
        model("tube", tube_solid()),
        &[
            // In the bore (radius 8), off the axis by 8 - 3 - gap: the concave inner wall.
            (3.0, DVec3::new(0.0, 8.0 - 3.0 - gap, 15.0)),
            // On the annular top cap (z = 30), between the radii.
            (1.5, DVec3::new(-10.0, 0.0, 31.5 + gap)),
        ],
    );
    let loc = one_contact(&reports[0], gap, "bore");
    assert!(matches!(loc, FeatureLocation::Face { .. }), "{loc:?}");
    one_contact(&reports[1], gap, "cap");
}

#[test]
fn ball_on_an_extruded_bracket_its_fillet_and_its_hole() {
    let gap = 0.04;
    // The inner corner's fillet: centre (13, 13), radius 5; a ball of radius 2 on the side of
    // its axis, 5 - 2 - gap from it towards the arc.
    let fillet = DVec2::new(13.0, 13.0) + (5.0 - 2.0 - gap) * DVec2::new(-1.0, -1.0).normalize();
    // The hole: centre (28, 4), radius 3; a ball of radius 1 next to its wall.
    let hole = DVec2::new(28.0, 4.0) + DVec2::new(3.0 - 1.0 - gap, 0.0);
    let reports = queries(
        model("bracket", bracket_solid()),
        &[
            (2.0, DVec3::new(36.0, 4.0, 22.0 + gap)),
            (2.0, DVec3::new(fillet.x, fillet.y, 10.0)),
            (1.0, DVec3::new(hole.x, hole.y, 10.0)),
        ],
    );
    one_contact(&reports[0], gap, "top");
    let loc = one_contact(&reports[1], gap, "fillet");
    assert!(matches!(loc, FeatureLocation::Face { .. }), "{loc:?}");
    one_contact(&reports[2], gap, "hole");
}
