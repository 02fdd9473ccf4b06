//! The closed-form B-rep solids are valid boundary representations (geom-param's validation)
//! with the expected topology, and their trims say inside where the closed form does.

use contact_oracle::closed_form::brep::{block, holed_plate, tetrahedron};
use geom_param::{DVec2, DVec3, validate};

#[test]
fn block_is_a_valid_closed_shell() {
    let solid = block(DVec3::new(20.0, 12.0, 8.0)).expect("builds");
    validate(&solid).expect("valid");
    assert_eq!(
        (solid.faces.len(), solid.edges.len(), solid.vertices.len()),
        (6, 12, 8)
    );
    // Every corner ends three edges, every edge has two ends, 12 mm apart at most.
    for v in &solid.vertices {
        assert_eq!(v.edges.len(), 3);
        assert!((v.point.abs() - DVec3::new(10.0, 6.0, 4.0)).length() < 1e-12);
    }
    // Each face's trim holds the face's centre and not a point beyond its side.
    for (f, face) in solid.faces.iter().enumerate() {
        let trim = face.trim.as_ref().expect("trimmed");
        let (lo, hi) = trim.bounds();
        let mid = 0.5 * (lo + hi);
        assert!(trim.contains(mid, 0.0), "face {f}");
        assert!(!trim.contains(hi + DVec2::splat(0.01), 0.0), "face {f}");
        let n = face.surface.normal(mid.x, mid.y).expect("normal");
        let p = face.surface.eval(mid.x, mid.y).point;
        // Outward: the centre of a face lies along its normal from the block's centre.
        assert!((p.normalize() - n).length() < 1e-12, "face {f}: {p} {n}");
    }
}

#[test]
fn holed_plate_is_a_valid_closed_shell() {
    let solid = holed_plate(40.0, 10.0, 6.0).expect("builds");
    validate(&solid).expect("valid");
    // Four sides and the hole's wall, two caps.
    assert_eq!(solid.faces.len(), 7);
    let caps: Vec<_> = solid.faces.iter().filter(|f| f.trim.is_some()).collect();
    assert_eq!(caps.len(), 2);
    let top = caps
        .iter()
        .find(|f| {
            let (lo, hi) = f.trim.as_ref().expect("trimmed").bounds();
            let mid = 0.5 * (lo + hi);
            f.surface.eval(mid.x, mid.y).point.z > 0.0
        })
        .expect("a top cap");
    let trim = top.trim.as_ref().expect("trimmed");
    assert_eq!(trim.loops.len(), 2);
    // The top cap's (u, v) is (x, y): the hole's centre is out, a point between the hole and
    // the square's side in.
    assert!(!trim.contains(DVec2::new(0.0, 0.0), 0.0));
    assert!(!trim.contains(DVec2::new(5.9, 0.0), 0.0));
    assert!(trim.contains(DVec2::new(6.1, 0.0), 0.0));
    assert!(trim.contains(DVec2::new(-19.0, 19.0), 0.0));
    // The wall (the face whose points lie 6 from the axis) has its normal towards the axis.
    let wall = solid
        .faces
        .iter()
        .find(|f| {
            let [u, v] = f.surface.domain();
            let p = f
                .surface
                .eval(u.min + 0.3 * u.span(), v.min + 0.5 * v.span())
                .point;
            (p.truncate().length() - 6.0).abs() < 1e-12
        })
        .expect("a wall");
    let [u, v] = wall.surface.domain();
    let (u, v) = (u.min + 0.3 * u.span(), v.min + 0.5 * v.span());
    let n = wall.surface.normal(u, v).expect("normal");
    let p = wall.surface.eval(u, v).point;
    assert!((n + DVec3::new(p.x, p.y, 0.0).normalize()).length() < 1e-12);
}

#[test]
fn tetrahedron_is_a_valid_closed_shell() {
    let points = [
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(10.0, 1.0, 0.0),
        DVec3::new(2.0, 9.0, 1.0),
        DVec3::new(3.0, 3.0, 8.0),
    ];
    let solid = tetrahedron(points).expect("builds");
    validate(&solid).expect("valid");
    assert_eq!(
        (solid.faces.len(), solid.edges.len(), solid.vertices.len()),
        (4, 6, 4)
    );
    let centroid = points.iter().copied().sum::<DVec3>() / 4.0;
    for face in &solid.faces {
        let (lo, hi) = face.trim.as_ref().expect("trimmed").bounds();
        let mid = 0.5 * (lo + hi);
        let n = face.surface.normal(mid.x, mid.y).expect("normal");
        let p = face.surface.eval(mid.x, mid.y).point;
        assert!((p - centroid).dot(n) > 0.0, "inward normal");
    }
}
