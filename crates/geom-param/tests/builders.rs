//! The builders: each solid validates, has the topology and convexity its shape implies, and a
//! mesh whose volume and area match the closed forms (or, for the free-form loft, a numeric
//! integral of its exact cross-sections) within the measured chordal error. The general object
//! format (`SolidDescription`) round-trips through JSON.

use geom_param::{
    BuildError, ComponentKind, DVec2, DVec3, EdgeConvexity, EllipseSection, FaceConvexity, FaceId,
    MeshOptions, NurbsCurve2, ObjectModel, PlanarProfile, PlanarSegment, Solid, SolidDescription,
    SolidLoadError, SolidSpec, Surface, extrude, loft, rounded_box, tube,
};
use std::f64::consts::{FRAC_1_SQRT_2, PI, TAU};

fn model(solid: Solid, tolerance: f64) -> ObjectModel {
    ObjectModel::from_solid(
        "test",
        solid,
        &MeshOptions {
            chordal_tolerance: tolerance,
        },
    )
    .expect("meshes")
}

/// Volume (divergence theorem) and area of every component mesh together, and the largest
/// measured chordal error.
fn volume_area(m: &ObjectModel) -> (f64, f64, f64) {
    let (mut volume, mut area, mut error) = (0.0, 0.0, 0.0f64);
    for mesh in &m.meshes {
        for t in &mesh.triangles {
            let [a, b, c] = t.map(|i| mesh.positions[i as usize]);
            volume += a.dot(b.cross(c)) / 6.0;
            area += 0.5 * (b - a).cross(c - a).length();
        }
        error = error.max(mesh.chordal_error);
    }
    (volume, area, error)
}

/// Asserts |measured - exact| <= slack (closed forms of curved solids: a mesh inside the
/// chordal band differs from the exact value by at most error x area, plus rounding).
fn close(measured: f64, exact: f64, slack: f64, what: &str) {
    assert!(
        (measured - exact).abs() <= slack,
        "{what}: {measured} vs {exact} (slack {slack})"
    );
}

#[test]
fn rounded_box_topology_convexity_and_volume() {
    let (h, r) = (DVec3::new(20.0, 15.0, 10.0), 3.0);
    let solid = rounded_box(h, r).expect("valid");
    assert_eq!(
        (solid.faces.len(), solid.edges.len(), solid.vertices.len()),
        (26, 48, 24)
    );
    let m = model(solid, 0.02);
    assert!(
        m.solid
            .edges
            .iter()
            .all(|e| e.convexity == EdgeConvexity::Smooth)
    );
    assert_eq!(m.components.len(), 1);
    assert_eq!(m.components[0].kind, ComponentKind::Convex);
    let inner = h - DVec3::splat(r);
    let exact_volume = 8.0 * inner.x * inner.y * inner.z
        + 2.0 * r * 4.0 * (inner.x * inner.y + inner.y * inner.z + inner.z * inner.x)
        + PI * r * r * 2.0 * (inner.x + inner.y + inner.z)
        + 4.0 / 3.0 * PI * r * r * r;
    let exact_area = 8.0 * (inner.x * inner.y + inner.y * inner.z + inner.z * inner.x)
        + 2.0 * PI * r * 2.0 * (inner.x + inner.y + inner.z)
        + 4.0 * PI * r * r;
    let (volume, area, error) = volume_area(&m);
    assert!(error <= 0.02, "measured chordal error {error}");
    close(volume, exact_volume, error * exact_area, "volume");
    close(area, exact_area, 0.01 * exact_area, "area");
}

#[test]
fn tube_has_holed_caps_and_a_concave_bore() {
    let (ro, ri, l) = (12.0, 8.0, 30.0);
    let m = model(tube(ro, ri, l).expect("valid"), 0.02);
    assert_eq!(m.solid.faces[1].convexity, FaceConvexity::Concave);
    assert_eq!(m.solid.faces[2].convexity, FaceConvexity::Flat);
    assert_eq!(
        m.solid.faces[2].trim.as_ref().map(|t| t.loops.len()),
        Some(2)
    );
    assert!(
        m.components
            .iter()
            .any(|c| c.kind == ComponentKind::Concave)
    );
    let exact_area = 2.0 * PI * (ro + ri) * l + 2.0 * PI * (ro * ro - ri * ri);
    let (volume, area, error) = volume_area(&m);
    close(
        volume,
        PI * (ro * ro - ri * ri) * l,
        error * exact_area,
        "volume",
    );
    close(area, exact_area, 0.01 * exact_area, "area");
}

fn l_bracket() -> PlanarProfile {
    let p = |x: f64, y: f64| DVec2::new(x, y);
    let line = |a: DVec2, b: DVec2| PlanarSegment::Line { from: a, to: b };
    PlanarProfile {
        outer: vec![
            line(p(0.0, 0.0), p(40.0, 0.0)),
            line(p(40.0, 0.0), p(40.0, 8.0)),
            line(p(40.0, 8.0), p(13.0, 8.0)),
            PlanarSegment::Arc {
                center: p(13.0, 13.0),
                from: p(13.0, 8.0),
                to: p(8.0, 13.0),
                ccw: false,
            },
            line(p(8.0, 13.0), p(8.0, 40.0)),
            line(p(8.0, 40.0), p(0.0, 40.0)),
            line(p(0.0, 40.0), p(0.0, 0.0)),
        ],
        holes: vec![vec![PlanarSegment::Arc {
            center: p(28.0, 4.0),
            from: p(31.0, 4.0),
            to: p(31.0, 4.0),
            ccw: false,
        }]],
    }
}

#[test]
fn extruded_bracket_with_a_fillet_and_a_hole() {
    let m = model(extrude(&l_bracket(), 0.0, 20.0).expect("valid"), 0.02);
    // Faces: 7 sides, the hole's side, two caps.
    assert_eq!(m.solid.faces.len(), 10);
    assert_eq!(m.solid.faces[3].convexity, FaceConvexity::Concave, "fillet");
    assert_eq!(m.solid.faces[7].convexity, FaceConvexity::Concave, "hole");
    // The fillet meets its neighbours tangentially; the outer corners are ridges.
    let smooth = m
        .solid
        .edges
        .iter()
        .filter(|e| e.convexity == EdgeConvexity::Smooth)
        .count();
    assert_eq!(smooth, 2, "the fillet's two vertical edges");
    let fillet_area = 25.0 - PI * 25.0 / 4.0;
    let exact_section = 40.0 * 8.0 + 32.0 * 8.0 + fillet_area - PI * 9.0;
    let (volume, _, error) = volume_area(&m);
    close(volume, exact_section * 20.0, error * 6000.0, "volume");
}

#[test]
fn builders_refuse_bad_dimensions() {
    assert!(matches!(
        rounded_box(DVec3::new(1.0, 1.0, 1.0), 1.5),
        Err(BuildError::BadDimension { .. })
    ));
    assert!(matches!(
        rounded_box(DVec3::new(f64::NAN, 1.0, 1.0), 0.5),
        Err(BuildError::BadDimension { .. })
    ));
    assert!(matches!(
        tube(5.0, 6.0, 1.0),
        Err(BuildError::BadDimension { .. })
    ));
    assert!(matches!(
        tube(5.0, 1.0, 0.0),
        Err(BuildError::BadDimension { .. })
    ));
    // A clockwise outer loop is refused by validation.
    let mut reversed = l_bracket();
    reversed.outer = vec![
        PlanarSegment::Line {
            from: DVec2::new(0.0, 0.0),
            to: DVec2::new(0.0, 10.0),
        },
        PlanarSegment::Line {
            from: DVec2::new(0.0, 10.0),
            to: DVec2::new(10.0, 0.0),
        },
        PlanarSegment::Line {
            from: DVec2::new(10.0, 0.0),
            to: DVec2::new(0.0, 0.0),
        },
    ];
    reversed.holes.clear();
    assert!(matches!(
        extrude(&reversed, 0.0, 1.0),
        Err(BuildError::Topology(_))
    ));
    // A profile that does not close.
    let open = PlanarProfile {
        outer: vec![
            PlanarSegment::Line {
                from: DVec2::new(0.0, 0.0),
                to: DVec2::new(10.0, 0.0),
            },
            PlanarSegment::Line {
                from: DVec2::new(10.0, 0.0),
                to: DVec2::new(0.0, 9.0),
            },
        ],
        holes: Vec::new(),
    };
    assert!(extrude(&open, 0.0, 1.0).is_err());
}

// ---------------------------------------------------------------------------------------------
// Loft: one NURBS side face through horizontal ellipses.

/// The default loft: five ellipses 10 mm apart that shrink to a waist at z = 20 and twist by
/// 100 degrees in all, their centres wandering off the z axis. Free-form: the side face is a
/// saddle around the waist (the meridians bend outwards, the rows inwards).
fn twisted_waist() -> Vec<EllipseSection> {
    let section = |cx: f64, cy: f64, a: f64, b: f64, degrees: f64, z: f64| EllipseSection {
        center: DVec2::new(cx, cy),
        semi_axes: DVec2::new(a, b),
        rotation: degrees.to_radians(),
        z,
    };
    vec![
        section(0.0, 0.0, 13.0, 9.0, 0.0, 0.0),
        section(1.0, 0.0, 9.0, 7.0, 25.0, 10.0),
        section(1.5, 1.0, 7.0, 5.5, 50.0, 20.0),
        section(0.5, 1.5, 9.0, 6.5, 75.0, 30.0),
        section(-1.0, 1.0, 12.0, 8.0, 100.0, 40.0),
    ]
}

/// 8-point Gauss-Legendre nodes and weights on [-1, 1] (exact for polynomials of degree 15).
const GAUSS_8: [(f64, f64); 8] = [
    (-0.960_289_856_497_536_3, 0.101_228_536_290_376_3),
    (-0.796_666_477_413_626_7, 0.222_381_034_453_374_5),
    (-0.525_532_409_916_329, 0.313_706_645_877_887_3),
    (-0.183_434_642_495_649_8, 0.362_683_783_378_362),
    (0.183_434_642_495_649_8, 0.362_683_783_378_362),
    (0.525_532_409_916_329, 0.313_706_645_877_887_3),
    (0.796_666_477_413_626_7, 0.222_381_034_453_374_5),
    (0.960_289_856_497_536_3, 0.101_228_536_290_376_3),
];

/// ∫ f over [a, b], composite 8-point Gauss-Legendre on `pieces` equal pieces.
fn integrate(f: impl Fn(f64) -> f64, a: f64, b: f64, pieces: usize) -> f64 {
    let h = (b - a) / pieces as f64;
    (0..pieces)
        .map(|k| {
            let mid = a + (k as f64 + 0.5) * h;
            GAUSS_8
                .iter()
                .map(|&(x, w)| w * f(mid + 0.5 * h * x))
                .sum::<f64>()
                * 0.5
                * h
        })
        .sum()
}

/// Area enclosed by the side face's row at v (Green: ½ ∮ x dy − y dx over u), from the exact
/// surface's points and u-derivatives.
fn row_area(side: &dyn Surface, v: f64) -> f64 {
    integrate(
        |u| {
            let s = side.eval(u, v);
            0.5 * (s.point.x * s.du.y - s.point.y * s.du.x)
        },
        0.0,
        TAU,
        64,
    )
}

#[test]
fn loft_is_one_nurbs_face_through_its_sections_with_a_saddle() {
    let sections = twisted_waist();
    let solid = loft(&sections).expect("valid loft");
    assert_eq!(
        (solid.faces.len(), solid.edges.len(), solid.vertices.len()),
        (3, 2, 0)
    );
    let side = solid.faces[0].surface.as_ref();
    let [du, dv] = side.domain();
    assert!(du.periodic && (du.min, du.max) == (0.0, TAU), "{du:?}");
    assert_eq!((dv.min, dv.max, dv.periodic), (0.0, 40.0, false));
    // Through every section: at v = z_k each row point satisfies the ellipse's implicit
    // equation ((R⁻¹(p − c)).x / a)² + ((R⁻¹(p − c)).y / b)² = 1 at height z_k.
    for s in &sections {
        for k in 0..50 {
            let p = side.eval(TAU * k as f64 / 50.0, s.z).point;
            let local = glam::DMat2::from_angle(-s.rotation) * (p.truncate() - s.center);
            let implicit = (local / s.semi_axes).length_squared() - 1.0;
            assert!(implicit.abs() < 1e-12, "section z = {}: {implicit:e}", s.z);
            assert!((p.z - s.z).abs() < 1e-12, "height {} vs {}", p.z, s.z);
        }
        assert!(
            (row_area(side, s.z) - s.area()).abs() < 1e-10 * s.area(),
            "area at z = {}",
            s.z
        );
    }
    // Between sections every row is horizontal at z = v, and the normal points away from the
    // row's centre (outwards).
    for j in 0..=40 {
        let v = 40.0 * j as f64 / 40.0;
        let centre = 0.5 * (side.eval(0.0, v).point + side.eval(PI, v).point);
        for k in 0..24 {
            let u = TAU * k as f64 / 24.0;
            let p = side.eval(u, v).point;
            assert!(
                (p.z - v).abs() < 1e-12 * 40.0,
                "row {v} at u = {u}: z = {}",
                p.z
            );
            let n = side.normal(u, v).expect("regular");
            assert!(n.dot(p - centre) > 0.0, "inward normal at ({u}, {v})");
        }
    }
    // A saddle at the waist, measured by second differences of points (not the derivative
    // code): the row bends away from the outward normal (convex), the meridian towards it.
    let h = 1e-3;
    for k in 0..8 {
        let u = TAU * k as f64 / 8.0 + 0.1;
        let v = 20.0;
        let n = side.normal(u, v).expect("regular");
        let p = |du: f64, dv: f64| side.eval(u + du, v + dv).point;
        let along_u = (p(h, 0.0) - 2.0 * p(0.0, 0.0) + p(-h, 0.0)).dot(n);
        let along_v = (p(0.0, 10.0 * h) - 2.0 * p(0.0, 0.0) + p(0.0, -10.0 * h)).dot(n);
        assert!(
            along_u < 0.0 && along_v > 0.0,
            "no saddle at u = {u}: {along_u:e}, {along_v:e}"
        );
    }

    let m = model(solid, 0.02);
    assert_eq!(m.solid.faces[0].convexity, FaceConvexity::Concave);
    assert_eq!(m.solid.faces[1].convexity, FaceConvexity::Flat);
    assert_eq!(m.solid.faces[2].convexity, FaceConvexity::Flat);
    assert!(
        m.components
            .iter()
            .any(|c| c.kind == ComponentKind::Concave)
    );
    // Volume: the numeric integral of the exact rows' areas over z (= v, checked above), each
    // by Green's theorem along the surface; Gauss-Legendre converges to ~1e-13 here. The mesh
    // (divergence theorem) must agree within its measured chordal error times its area.
    let side = m.solid.faces[0].surface.as_ref();
    let exact_volume = integrate(|v| row_area(side, v), 0.0, 40.0, 40);
    let (volume, area, error) = volume_area(&m);
    assert!(error <= 0.02, "measured chordal error {error}");
    close(volume, exact_volume, error * area, "loft volume");
    // A cruder independent bound: between the sections' frustum-like averages.
    let sum: f64 = sections
        .windows(2)
        .map(|w| 5.0 * (w[0].area() + w[1].area()))
        .sum();
    assert!(
        (exact_volume - sum).abs() < 0.1 * sum,
        "{exact_volume} vs trapezoid {sum}"
    );
}

#[test]
fn loft_refuses_bad_sections() {
    let good = twisted_waist();
    let bad = |what: &str, sections: &[EllipseSection]| {
        assert!(
            matches!(loft(sections), Err(BuildError::BadDimension { .. })),
            "{what}: {:?}",
            loft(sections).map(|_| ())
        );
    };
    bad("one section", &good[..1]);
    let mut nan = good.clone();
    nan[2].center.x = f64::NAN;
    bad("NaN centre", &nan);
    let mut flat = good.clone();
    flat[1].semi_axes.y = 0.0;
    bad("zero semi-axis", &flat);
    let mut unordered = good.clone();
    unordered[3].z = 15.0;
    bad("heights not increasing", &unordered);
    let mut same = good.clone();
    same[1].z = 0.0;
    bad("two sections at one height", &same);
    // Half a turn between two sections: the interpolated ellipse shrinks to a point midway.
    let mut turned = good[..2].to_vec();
    turned[1].semi_axes = turned[0].semi_axes;
    turned[1].center = turned[0].center;
    turned[1].rotation = PI;
    bad("half a turn of twist", &turned);
    // Two sections are enough (a ruled side, degree 1 in v), three give degree 2.
    let two = loft(&good[..2]).expect("two sections");
    assert_eq!(two.faces.len(), 3);
    loft(&good[1..4]).expect("three sections");
}

// ---------------------------------------------------------------------------------------------
// Extrusion of NURBS segments.

/// The unit-weight-at-joints rational quadratic circle of radius r about `centre`, run
/// clockwise (a hole): 4 quarter arcs, 9 control points, periodic.
fn nurbs_circle_clockwise(centre: DVec2, r: f64) -> NurbsCurve2 {
    let corners = [
        (1.0, 0.0),
        (1.0, -1.0),
        (0.0, -1.0),
        (-1.0, -1.0),
        (-1.0, 0.0),
        (-1.0, 1.0),
        (0.0, 1.0),
        (1.0, 1.0),
        (1.0, 0.0),
    ];
    let points = corners
        .iter()
        .map(|&(x, y)| centre + r * DVec2::new(x, y))
        .collect();
    let weights = (0..9)
        .map(|i| if i % 2 == 0 { 1.0 } else { FRAC_1_SQRT_2 })
        .collect();
    let knots = vec![0.0, 0.0, 0.0, 1.0, 1.0, 2.0, 2.0, 3.0, 3.0, 4.0, 4.0, 4.0];
    NurbsCurve2::new(2, knots, points, weights, true).expect("circle")
}

/// A "D": the half disk x >= 0 of radius 10 about the origin, its arc an exact rational
/// quadratic NURBS from (0, −10) through (10, 0) to (0, 10), closed by the line back down the
/// y axis; a hole of radius 2 about (4, 0), a periodic NURBS circle.
fn d_profile() -> PlanarProfile {
    let arc = NurbsCurve2::new(
        2,
        vec![0.0, 0.0, 0.0, 1.0, 1.0, 2.0, 2.0, 2.0],
        vec![
            DVec2::new(0.0, -10.0),
            DVec2::new(10.0, -10.0),
            DVec2::new(10.0, 0.0),
            DVec2::new(10.0, 10.0),
            DVec2::new(0.0, 10.0),
        ],
        vec![1.0, FRAC_1_SQRT_2, 1.0, FRAC_1_SQRT_2, 1.0],
        false,
    )
    .expect("half circle");
    PlanarProfile {
        outer: vec![
            PlanarSegment::Nurbs(arc),
            PlanarSegment::Line {
                from: DVec2::new(0.0, 10.0),
                to: DVec2::new(0.0, -10.0),
            },
        ],
        holes: vec![vec![PlanarSegment::Nurbs(nurbs_circle_clockwise(
            DVec2::new(4.0, 0.0),
            2.0,
        ))]],
    }
}

#[test]
fn extruded_nurbs_segments_face_outwards_and_enclose_the_closed_form_volume() {
    let (z0, z1) = (-3.0, 12.0);
    let solid = extrude(&d_profile(), z0, z1).expect("valid");
    // Faces: the arc's side, the line's side, the hole's side, two caps; edges: 3 per open
    // segment, 2 for the closed hole; vertices: 2 per open segment.
    assert_eq!(
        (solid.faces.len(), solid.edges.len(), solid.vertices.len()),
        (5, 8, 4)
    );
    // The NURBS sides are on the exact cylinders, their normals radial: out of the D, into
    // the hole's axis.
    for (face, centre, radius, sign) in [
        (0, DVec2::ZERO, 10.0, 1.0),
        (2, DVec2::new(4.0, 0.0), 2.0, -1.0),
    ] {
        let surface = solid.faces[face].surface.as_ref();
        let [du, dv] = surface.domain();
        assert_eq!((dv.min, dv.max), (0.0, z1 - z0));
        for i in 0..=20 {
            for j in 0..=4 {
                let u = du.min + du.span() * i as f64 / 20.0;
                let v = dv.span() * j as f64 / 4.0;
                let p = surface.eval(u, v).point;
                let radial = p.truncate() - centre;
                assert!(
                    (radial.length() - radius).abs() < 1e-12 * 10.0,
                    "face {face}"
                );
                assert!((p.z - (z0 + v)).abs() < 1e-12 * 10.0);
                let n = surface.normal(u, v).expect("regular");
                let expected = (sign * radial / radius).extend(0.0);
                assert!(
                    (n - expected).length() < 1e-12,
                    "face {face}: {n} vs {expected}"
                );
            }
        }
    }
    let m = model(solid, 0.02);
    assert_eq!(m.solid.faces[0].convexity, FaceConvexity::Convex, "the arc");
    assert_eq!(m.solid.faces[1].convexity, FaceConvexity::Flat, "the line");
    assert_eq!(
        m.solid.faces[2].convexity,
        FaceConvexity::Concave,
        "the hole"
    );
    let section = 0.5 * PI * 100.0 - PI * 4.0;
    let exact_area = 2.0 * section + (PI * 10.0 + 20.0 + TAU * 2.0) * (z1 - z0);
    let (volume, area, error) = volume_area(&m);
    close(volume, section * (z1 - z0), error * exact_area, "volume");
    close(area, exact_area, 0.01 * exact_area, "area");
}

#[test]
fn extrusion_refuses_bad_nurbs_segments() {
    // A NURBS segment that stops: two equal control points at the start of a quadratic make
    // C'(t_min) = 0.
    let stopping = NurbsCurve2::new(
        2,
        vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
        vec![
            DVec2::new(10.0, 0.0),
            DVec2::new(10.0, 0.0),
            DVec2::new(0.0, 10.0),
        ],
        vec![1.0; 3],
        false,
    )
    .expect("a valid curve");
    let profile = PlanarProfile {
        outer: vec![
            PlanarSegment::Line {
                from: DVec2::ZERO,
                to: DVec2::new(10.0, 0.0),
            },
            PlanarSegment::Nurbs(stopping),
            PlanarSegment::Line {
                from: DVec2::new(0.0, 10.0),
                to: DVec2::ZERO,
            },
        ],
        holes: Vec::new(),
    };
    assert!(matches!(
        extrude(&profile, 0.0, 1.0),
        Err(BuildError::BadDimension { .. })
    ));
    // A hole run counter-clockwise (the circle reversed twice) is refused by validation.
    let mut wrong = d_profile();
    let PlanarSegment::Nurbs(circle) = &wrong.holes[0][0] else {
        unreachable!("the hole is a NURBS circle")
    };
    let mut points = circle.control_points().to_vec();
    points.reverse();
    wrong.holes[0][0] = PlanarSegment::Nurbs(
        NurbsCurve2::new(
            2,
            circle.basis().knots().to_vec(),
            points,
            circle.weights().to_vec(),
            true,
        )
        .expect("circle"),
    );
    assert!(matches!(
        extrude(&wrong, 0.0, 1.0),
        Err(BuildError::Topology(_))
    ));
}

// ---------------------------------------------------------------------------------------------
// The general object format.

#[test]
fn loft_and_nurbs_extrusion_round_trip_through_json() {
    let descriptions = [
        SolidDescription {
            name: "twisted waist".into(),
            note: Some("five ellipses".into()),
            spec: SolidSpec::Loft {
                sections: twisted_waist(),
            },
        },
        SolidDescription {
            name: "D with a hole".into(),
            note: None,
            spec: SolidSpec::Extrusion {
                profile: d_profile(),
                z: [-3.0, 12.0],
            },
        },
    ];
    for d in &descriptions {
        let text = d.to_json();
        let back = SolidDescription::from_json(&text).expect("reads back");
        assert_eq!(&back, d, "{text}");
        assert_eq!(back.to_json(), text);
        let built = back.spec.build_solid().expect("builds");
        let direct = d.spec.build_solid().expect("builds");
        assert_eq!(built.faces.len(), direct.faces.len());
    }
    // Written by hand: weights left out (a non-rational quadratic), a loft of two sections.
    let text = r#"{ "name": "bump", "extrusion": { "profile": { "outer": [
          {"line": {"from": [0, 0], "to": [10, 0]}},
          {"nurbs": {"degree": 2, "knots": [0, 0, 0, 1, 1, 1],
                     "points": [[10, 0], [10, 10], [0, 10]]}},
          {"line": {"from": [0, 10], "to": [0, 0]}} ] }, "z": [0, 5] } }"#;
    let bump = SolidDescription::from_json(text).expect("valid");
    let m = bump
        .build(&MeshOptions {
            chordal_tolerance: 0.02,
        })
        .expect("builds");
    // Area under the parabola-like quadratic: the region's area is 10 * 10 - 100 / 3... its
    // side is a parabola from (10, 0) to (0, 10) bulging towards (10, 10): the area between it
    // and the axes is 100 - 100 / 6 (a quadratic Bezier with corner control point encloses
    // 2/3 of the triangle (10, 0), (10, 10), (0, 10) with the chord).
    let (volume, area, error) = volume_area(&m);
    let section = 50.0 + 2.0 / 3.0 * 50.0;
    close(volume, section * 5.0, error * area, "bump volume");
    assert_eq!(m.solid.face(FaceId(1)).convexity, FaceConvexity::Convex);
    let loft_text = r#"{ "name": "cone-ish", "loft": { "sections": [
          {"center": [0, 0], "semi_axes": [5, 3], "rotation": 0, "z": 0},
          {"center": [1, 0], "semi_axes": [2, 1], "rotation": 0.5, "z": 8} ] } }"#;
    let cone = SolidDescription::from_json(loft_text).expect("valid");
    assert!(matches!(cone.spec, SolidSpec::Loft { ref sections } if sections.len() == 2));
    cone.spec.build_solid().expect("builds");
    // A NURBS with one weight too few and an unknown field are format errors.
    let short = text.replace(
        r#""points": [[10, 0], [10, 10], [0, 10]]"#,
        r#""points": [[10, 0], [10, 10], [0, 10]], "weights": [1, 1]"#,
    );
    assert!(matches!(
        SolidDescription::from_json(&short),
        Err(SolidLoadError::Format(_))
    ));
    let unknown = loft_text.replace(r#""z": 8"#, r#""z": 8, "twist": 1"#);
    assert!(matches!(
        SolidDescription::from_json(&unknown),
        Err(SolidLoadError::Format(_))
    ));
}
