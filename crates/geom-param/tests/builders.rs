//! The builders: each solid validates, has the topology and convexity its shape implies, and a
//! mesh whose volume and area match the closed forms within the measured chordal error.

use geom_param::{
    BuildError, ComponentKind, DVec2, DVec3, EdgeConvexity, FaceConvexity, MeshOptions,
    ObjectModel, PlanarProfile, PlanarSegment, Solid, extrude, rounded_box, tube,
};
use std::f64::consts::PI;

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
