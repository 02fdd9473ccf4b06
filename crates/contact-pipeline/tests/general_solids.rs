//! The whole pipeline on general solids (built in code, not revolved) against closed forms:
//! a ball above a rounded box's flat face, over one of its fillet cylinders, over a corner
//! sphere; a ball inside a tube's bore and on its annular cap; a ball on an extruded
//! L-bracket's flat face, against the concave fillet of its inner corner and inside its hole;
//! a ball against the free-form NURBS side of a twisted, waisted loft (its saddle waist, its
//! flanks), where the truth is a brute-force distance: dense sampling of the NURBS surface,
//! the best sample polished by Newton projection, sharing no code with the stages.
//! Every contact's connecting vector is checked to be normal to both surfaces.

use contact_pipeline::{ContactOptions, ContactPipeline, PairReport, PairState, QueryScratch};
use geom_param::{
    DPose3, DVec2, DVec3, EllipseSection, FaceId, FeatureLocation, MeshOptions, ObjectModel,
    PlanarProfile, PlanarSegment, Profile, SegmentSpec, Solid, Surface, extrude, loft, rounded_box,
    tube,
};
use std::f64::consts::TAU;

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

/// The twisted, waisted loft of `geom-param`'s builder tests: five ellipses 10 mm apart,
/// narrowest at z = 20, turned by 100 degrees in all.
fn loft_solid() -> Solid {
    let section = |cx: f64, cy: f64, a: f64, b: f64, degrees: f64, z: f64| EllipseSection {
        center: DVec2::new(cx, cy),
        semi_axes: DVec2::new(a, b),
        rotation: degrees.to_radians(),
        z,
    };
    loft(&[
        section(0.0, 0.0, 13.0, 9.0, 0.0, 0.0),
        section(1.0, 0.0, 9.0, 7.0, 25.0, 10.0),
        section(1.5, 1.0, 7.0, 5.5, 50.0, 20.0),
        section(0.5, 1.5, 9.0, 6.5, 75.0, 30.0),
        section(-1.0, 1.0, 12.0, 8.0, 100.0, 40.0),
    ])
    .expect("loft")
}

/// The point of `surface` nearest to `centre`, by brute force: the best of a 720 x 400 grid of
/// samples, polished by Newton's method on ½|S(u, v) − centre|² (gradient and Hessian from the
/// surface's derivatives), u wrapped, v kept in its domain. Returns (u, v, distance).
fn nearest_by_sampling(surface: &dyn Surface, centre: DVec3) -> (f64, f64, f64) {
    let [du, dv] = surface.domain();
    let (nu, nv) = (720, 400);
    let mut best = (0.0, 0.0, f64::INFINITY);
    for i in 0..nu {
        for j in 0..=nv {
            let u = du.min + du.span() * i as f64 / nu as f64;
            let v = dv.min + dv.span() * j as f64 / nv as f64;
            let d = surface.eval(u, v).point.distance(centre);
            if d < best.2 {
                best = (u, v, d);
            }
        }
    }
    let (mut u, mut v) = (best.0, best.1);
    for _ in 0..50 {
        let s = surface.eval(u, v);
        let r = s.point - centre;
        let g = [r.dot(s.du), r.dot(s.dv)];
        let h = [
            [s.du.dot(s.du) + r.dot(s.duu), s.du.dot(s.dv) + r.dot(s.duv)],
            [s.du.dot(s.dv) + r.dot(s.duv), s.dv.dot(s.dv) + r.dot(s.dvv)],
        ];
        let det = h[0][0] * h[1][1] - h[0][1] * h[1][0];
        assert!(det > 0.0, "the projection is not at an isolated minimum");
        let step = [
            (h[1][1] * g[0] - h[0][1] * g[1]) / det,
            (h[0][0] * g[1] - h[1][0] * g[0]) / det,
        ];
        u = (u - step[0]).rem_euclid(TAU);
        v = (v - step[1]).clamp(dv.min, dv.max);
    }
    let s = surface.eval(u, v);
    let r = s.point - centre;
    assert!(
        r.dot(s.du).abs() + r.dot(s.dv).abs() < 1e-10 * r.length() * s.du.length().max(1.0),
        "projection did not converge"
    );
    assert!(
        v > dv.min && v < dv.max,
        "the nearest point is on a cap's rim"
    );
    (u, v, r.length())
}

#[test]
fn ball_against_a_free_form_nurbs_loft() {
    let solid = loft_solid();
    let side = solid.faces[0].surface.as_ref();
    // Each ball (radius r) is put on the outward normal of the side face at (u, v), `gap` from
    // it: at the saddle waist, on the flanks above and below it, near the flaring top.
    let gap = 0.05;
    let spots = [
        (3.0, 1.0, 20.0),
        (2.0, 4.0, 12.0),
        (2.5, 2.5, 31.0),
        (1.5, 5.5, 37.0),
    ];
    let balls: Vec<(f64, DVec3)> = spots
        .iter()
        .map(|&(r, u, v)| {
            let n = side.normal(u, v).expect("regular");
            (r, side.eval(u, v).point + (r + gap) * n)
        })
        .collect();
    let truths: Vec<f64> = balls
        .iter()
        .map(|&(r, centre)| nearest_by_sampling(side, centre).2 - r)
        .collect();
    let reports = queries(model("loft", loft_solid()), &balls);
    for (k, ((report, truth), &(r, centre))) in reports.iter().zip(&truths).zip(&balls).enumerate()
    {
        let what = format!("loft spot {k} {:?}", spots[k]);
        // Planted at `gap` along the normal: the brute force agrees to its own accuracy.
        assert!((truth - gap).abs() < 1e-9, "{what}: brute force {truth}");
        let loc = one_contact(report, *truth, &what);
        assert!(
            matches!(loc, FeatureLocation::Face { id: FaceId(0), .. }),
            "{what}: {loc:?}"
        );
        let c = &report.contacts[0];
        // Normal to both surfaces: the loft's exact normal at the contact's parameters, the
        // ball's radial direction at its point.
        let n_loft = solid.face_normal_at(&c.location_a).expect("regular");
        let connecting = (c.point_b - c.point_a).normalize();
        assert!(
            connecting.cross(n_loft).length() < 1e-9,
            "{what}: loft normal"
        );
        let radial = (centre - c.point_b) / r;
        assert!(
            connecting.cross(radial).length() < 1e-9,
            "{what}: ball normal"
        );
    }
}

/// A block [0, 20]² x [0, 10] extruded from a square.
fn block_solid() -> Solid {
    let p = |x: f64, y: f64| DVec2::new(x, y);
    let corners = [p(0.0, 0.0), p(20.0, 0.0), p(20.0, 20.0), p(0.0, 20.0)];
    let outer = (0..4)
        .map(|k| PlanarSegment::Line {
            from: corners[k],
            to: corners[(k + 1) % 4],
        })
        .collect();
    extrude(
        &PlanarProfile {
            outer,
            holes: Vec::new(),
        },
        0.0,
        10.0,
    )
    .expect("block")
}

#[test]
fn ball_at_the_edges_and_corner_of_an_extruded_block() {
    // Regression: the extrusion's caps were planes over [-20, 20]², whose sides the square's
    // edges x = 20 and y = 20 lay on. Stage 3 cuts steps at a domain's side, so from a seed on
    // the top cap it stayed on the cap at x = 20 (128 steps, distance -0.05) and every ball
    // below was reported separated.
    let gap = 0.05;
    let corner = DVec3::new(20.0, 20.0, 10.0);
    let mut balls: Vec<(f64, DVec3)> = [
        DVec3::ONE,
        DVec3::new(1.0, 2.0, 3.0),
        DVec3::new(3.0, 1.0, 1.0),
        DVec3::new(1.0, 1.0, 3.0),
    ]
    .iter()
    .map(|w| (3.0, corner + (3.0 + gap) * w.normalize()))
    .collect();
    // The top edge along x = 20 and the vertical edge at (20, 20).
    let diagonal = DVec3::new(1.0, 0.0, 1.0).normalize();
    balls.push((3.0, DVec3::new(20.0, 10.0, 10.0) + (3.0 + gap) * diagonal));
    let across = DVec3::new(1.0, 1.0, 0.0).normalize();
    balls.push((3.0, DVec3::new(20.0, 20.0, 5.0) + (3.0 + gap) * across));
    let reports = queries(model("block", block_solid()), &balls);
    for (k, report) in reports.iter().enumerate() {
        let what = format!("block ball {k}");
        let loc = one_contact(report, gap, &what);
        let expected = match k {
            0..4 => matches!(loc, FeatureLocation::Vertex { .. }),
            _ => matches!(loc, FeatureLocation::Edge { .. }),
        };
        assert!(expected, "{what}: {loc:?}");
    }
}
