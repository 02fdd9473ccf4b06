//! The analytic surfaces (plane, cylinder, cone, sphere, torus), the swept surfaces (linear
//! extrusion, revolution) and the reversed surface: derivatives against finite differences,
//! points against their closed forms (or against a second surface type with the same
//! parametrisation), outward normals pointing the documented way, and the degenerate points
//! (sphere poles, cone apex, revolution poles).

mod geometry_support;

use geom_param::{
    ConeSurface, Curve, CylinderSurface, DVec2, DVec3, EllipseCurve, LineCurve, LineSegment,
    LinearExtrusionSurface, ParamRange, Placement, Plane, ProfileSegment, ReversedSurface,
    RevolutionSurface, RevolvedSurface, SphereSurface, Surface, SurfacePoint, TorusSurface,
};
use geometry_support::{Pieces, SplitMix64, check_surface, whole};
use std::f64::consts::{FRAC_PI_2, PI, TAU};

fn range(min: f64, max: f64) -> ParamRange {
    ParamRange {
        min,
        max,
        periodic: false,
    }
}

fn turn() -> ParamRange {
    ParamRange {
        min: 0.0,
        max: TAU,
        periodic: true,
    }
}

/// A placement tilted away from the object axes, so a swapped or missing axis shows.
fn tilted() -> Placement {
    Placement::new(
        DVec3::new(12.0, -7.0, 30.0),
        DVec3::new(0.3, -0.5, 0.8),
        DVec3::new(1.0, 0.2, 0.1),
    )
    .unwrap()
}

/// Coordinates of an object point in a placement's frame.
fn local(p: &Placement, point: DVec3) -> DVec3 {
    let d = point - p.origin;
    DVec3::new(d.dot(p.x), d.dot(p.y), d.dot(p.z))
}

fn pieces(s: &dyn Surface) -> [Pieces; 2] {
    s.domain().map(whole)
}

fn check(name: &str, s: &dyn Surface, seed: u64) {
    let [pu, pv] = pieces(s);
    check_surface(name, s, [&pu, &pv], seed);
}

/// Every field of two surface points agrees to `tol` times the size of the first.
#[track_caller]
fn assert_same(a: SurfacePoint, b: SurfacePoint, tol: f64) {
    let pairs = [
        (a.point, b.point),
        (a.du, b.du),
        (a.dv, b.dv),
        (a.duu, b.duu),
        (a.duv, b.duv),
        (a.dvv, b.dvv),
    ];
    for (x, y) in pairs {
        assert!(
            (x - y).length() <= tol * (1.0 + x.length()),
            "{a:?}\n!=\n{b:?}"
        );
    }
}

#[test]
fn placement_orthonormalises_the_reference_direction() {
    let p = Placement::new(
        DVec3::new(1.0, 2.0, 3.0),
        DVec3::new(0.0, 0.0, 2.0),
        DVec3::new(3.0, 0.0, 5.0),
    )
    .unwrap();
    assert_eq!((p.x, p.y, p.z), (DVec3::X, DVec3::Y, DVec3::Z));
    assert_eq!(
        p.local_to_object(DVec3::new(1.0, -1.0, 2.0)),
        DVec3::new(2.0, 1.0, 5.0)
    );
    let q = tilted();
    for (a, b) in [(q.x, q.y), (q.y, q.z), (q.z, q.x)] {
        assert!(a.dot(b).abs() < 1e-15);
    }
    for axis in [q.x, q.y, q.z] {
        assert!((axis.length() - 1.0).abs() < 1e-15);
    }
    assert!((q.x.cross(q.y) - q.z).length() < 1e-15, "not right-handed");
    assert!((q.z - DVec3::new(0.3, -0.5, 0.8).normalize()).length() < 1e-15);
    assert!(q.x.dot(DVec3::new(1.0, 0.2, 0.1)) > 0.0);
}

#[test]
fn plane_points_derivatives_and_normal() {
    let p = tilted();
    let plane = Plane::new(p, [range(-40.0, 25.0), range(-10.0, 60.0)]).unwrap();
    let s = plane.eval(3.0, -2.0);
    assert!((s.point - (p.origin + 3.0 * p.x - 2.0 * p.y)).length() < 1e-12);
    assert_eq!(plane.normal(3.0, -2.0), Some(p.z));
    check("plane", &plane, 1);
}

#[test]
fn cylinder_points_derivatives_and_normal() {
    let p = tilted();
    let cylinder = CylinderSurface::new(p, 7.5, [turn(), range(-20.0, 35.0)]).unwrap();
    assert!((cylinder.eval(0.0, 5.0).point - (p.origin + 7.5 * p.x + 5.0 * p.z)).length() < 1e-12);
    assert!((cylinder.eval(FRAC_PI_2, -1.0).point - (p.origin + 7.5 * p.y - p.z)).length() < 1e-12);
    let mut rng = SplitMix64(2);
    for _ in 0..200 {
        let (u, v) = (rng.range(0.0, TAU), rng.range(-20.0, 35.0));
        let l = local(&p, cylinder.eval(u, v).point);
        assert!((l.truncate().length() - 7.5).abs() < 1e-12 * 7.5);
        assert!((l.z - v).abs() < 1e-12 * 35.0);
        // Outward: away from the axis.
        let n = cylinder.normal(u, v).unwrap();
        let from_axis = DVec3::new(l.x, l.y, 0.0);
        assert!((local(&p, p.origin + n) - from_axis / 7.5).length() < 1e-12);
    }
    check("cylinder", &cylinder, 3);
}

#[test]
fn cone_points_derivatives_normal_and_apex() {
    let p = tilted();
    let (radius, angle): (f64, f64) = (4.0, 0.4);
    let apex = -radius / angle.sin();
    let cone = ConeSurface::new(p, radius, angle, [turn(), range(apex, 30.0)]).unwrap();
    let mut rng = SplitMix64(4);
    for _ in 0..200 {
        let (u, v) = (rng.range(0.0, TAU), rng.range(apex + 1e-3, 30.0));
        let l = local(&p, cone.eval(u, v).point);
        let rho = radius + v * angle.sin();
        let expected = DVec3::new(rho * u.cos(), rho * u.sin(), v * angle.cos());
        assert!((l - expected).length() < 1e-12 * 40.0);
        // Outward: away from the axis, tilted by the semi-angle (−z component sin a).
        let n = local(&p, p.origin + cone.normal(u, v).unwrap());
        let radial = DVec3::new(l.x, l.y, 0.0).normalize();
        assert!((n - (angle.cos() * radial - angle.sin() * DVec3::Z)).length() < 1e-12);
    }
    assert!((cone.eval(1.0, apex).point - (p.origin + apex * angle.cos() * p.z)).length() < 1e-12);
    assert_eq!(cone.normal(1.0, apex), None, "no tangent plane at the apex");
    assert_eq!(cone.principal_curvatures(1.0, apex), None);
    // FD away from the apex, where the parametrisation is smooth anyway.
    let pu = whole(turn());
    let pv = Pieces::new(apex + 1.0, 30.0, &[]);
    check_surface("cone", &cone, [&pu, &pv], 5);
}

#[test]
fn sphere_points_derivatives_and_normals_at_the_poles() {
    let p = tilted();
    let r = 9.0;
    let sphere = SphereSurface::new(p, r, [turn(), range(-FRAC_PI_2, FRAC_PI_2)]).unwrap();
    let mut rng = SplitMix64(6);
    for _ in 0..200 {
        let (u, v) = (rng.range(0.0, TAU), rng.range(-FRAC_PI_2, FRAC_PI_2));
        let point = sphere.eval(u, v).point;
        assert!(((point - p.origin).length() - r).abs() < 1e-12 * r);
        assert!((local(&p, point).z - r * v.sin()).abs() < 1e-12 * r);
        let n = sphere.normal(u, v).unwrap();
        assert!(
            (n - (point - p.origin) / r).length() < 1e-12,
            "not away from the centre"
        );
    }
    for u in [0.0, 1.0, 4.0] {
        assert!((sphere.eval(u, FRAC_PI_2).point - (p.origin + r * p.z)).length() < 1e-12);
        assert!((sphere.normal(u, -FRAC_PI_2).unwrap() + p.z).length() < 1e-15);
        assert!((sphere.normal(u, FRAC_PI_2).unwrap() - p.z).length() < 1e-15);
        let k = sphere.principal_curvatures(u, FRAC_PI_2).unwrap();
        assert_eq!((k.min, k.max), (1.0 / r, 1.0 / r));
    }
    check("sphere", &sphere, 7);
}

#[test]
fn torus_points_derivatives_and_normal() {
    let p = tilted();
    let (big, small) = (20.0, 6.0);
    let torus = TorusSurface::new(p, big, small, [turn(), turn()]).unwrap();
    let mut rng = SplitMix64(8);
    for _ in 0..200 {
        let (u, v) = (rng.range(0.0, TAU), rng.range(0.0, TAU));
        let point = torus.eval(u, v).point;
        let l = local(&p, point);
        let rho = l.truncate().length();
        assert!(((rho - big).powi(2) + l.z * l.z - small * small).abs() < 1e-11 * big * big);
        // Outward: away from the centre circle of the tube.
        let centre = p.local_to_object(DVec3::new(l.x, l.y, 0.0) * (big / rho));
        let n = torus.normal(u, v).unwrap();
        assert!((n - (point - centre) / small).length() < 1e-12);
    }
    let outer = torus.principal_curvatures(0.0, 0.0).unwrap();
    assert!((outer.min - 1.0 / (big + small)).abs() < 1e-15 && outer.max == 1.0 / small);
    let inner = torus.principal_curvatures(0.0, PI).unwrap();
    assert!((inner.min + 1.0 / (big - small)).abs() < 1e-15 && inner.max == 1.0 / small);
    check("torus", &torus, 9);
}

#[test]
fn extrusion_of_a_circle_is_the_cylinder() {
    let p = tilted();
    let circle = geom_param::CircleCurve::new(p, 7.5, turn()).unwrap();
    let extrusion = LinearExtrusionSurface::new(circle, p.z, range(-20.0, 35.0)).unwrap();
    let cylinder = CylinderSurface::new(p, 7.5, [turn(), range(-20.0, 35.0)]).unwrap();
    assert_eq!(extrusion.domain(), cylinder.domain());
    let mut rng = SplitMix64(10);
    for _ in 0..200 {
        let (u, v) = (rng.range(0.0, TAU), rng.range(-20.0, 35.0));
        assert_same(extrusion.eval(u, v), cylinder.eval(u, v), 1e-14);
        let (a, b) = (
            extrusion.normal(u, v).unwrap(),
            cylinder.normal(u, v).unwrap(),
        );
        assert!(
            (a - b).length() < 1e-14,
            "extrusion normal {a:?} vs cylinder {b:?}"
        );
    }
}

#[test]
fn extrusion_of_an_ellipse_along_a_slanted_vector() {
    let p = tilted();
    let ellipse = EllipseCurve::new(p, 9.0, 4.0, range(0.3, 5.0)).unwrap();
    let d = DVec3::new(2.0, -1.0, 6.0);
    let boxed: Box<dyn Curve> = Box::new(ellipse.clone());
    let extrusion = LinearExtrusionSurface::new(boxed, d, range(-1.5, 2.0)).unwrap();
    let s = extrusion.eval(1.2, 0.7);
    assert!((s.point - (ellipse.eval(1.2).point + 0.7 * d)).length() < 1e-12);
    assert_eq!(extrusion.domain()[0], range(0.3, 5.0));
    check("ellipse extrusion", &extrusion, 11);
}

#[test]
fn revolution_of_a_line_matches_the_revolved_profile_segment() {
    let (from, to) = (DVec2::new(12.0, -4.0), DVec2::new(7.0, 18.0));
    let revolved = RevolvedSurface {
        segment: ProfileSegment::Line(LineSegment { from, to }),
    };
    let line = LineCurve::new(
        DVec3::new(from.x, 0.0, from.y),
        DVec3::new(to.x - from.x, 0.0, to.y - from.y),
        range(0.0, 1.0),
    )
    .unwrap();
    let revolution = RevolutionSurface::new(line, DVec3::ZERO, DVec3::Z, turn()).unwrap();
    let mut rng = SplitMix64(12);
    for _ in 0..200 {
        let (u, v) = (rng.range(0.0, TAU), rng.unit());
        assert_same(revolution.eval(u, v), revolved.eval(u, v), 1e-14);
        let (a, b) = (
            revolution.normal(u, v).unwrap(),
            revolved.normal(u, v).unwrap(),
        );
        assert!((a - b).length() < 1e-12);
    }
}

#[test]
fn revolution_of_a_circle_is_the_torus() {
    let (big, small) = (20.0, 6.0);
    let meridian_plane = Placement::new(DVec3::new(big, 0.0, 0.0), -DVec3::Y, DVec3::X).unwrap();
    let tube = geom_param::CircleCurve::new(meridian_plane, small, turn()).unwrap();
    let revolution = RevolutionSurface::new(tube, DVec3::ZERO, DVec3::Z, turn()).unwrap();
    let torus = TorusSurface::new(Placement::IDENTITY, big, small, [turn(), turn()]).unwrap();
    let mut rng = SplitMix64(13);
    for _ in 0..200 {
        let (u, v) = (rng.range(0.0, TAU), rng.range(0.0, TAU));
        assert_same(revolution.eval(u, v), torus.eval(u, v), 1e-14);
        let (a, b) = (
            revolution.normal(u, v).unwrap(),
            torus.normal(u, v).unwrap(),
        );
        assert!((a - b).length() < 1e-12);
    }
}

#[test]
fn revolution_about_a_slanted_axis_with_poles() {
    // A half circle from one point of the axis to another: a sphere of radius 5 about c.
    let (a, k) = (
        DVec3::new(1.0, 2.0, -3.0),
        DVec3::new(1.0, 1.0, 2.0).normalize(),
    );
    let c = a + 4.0 * k;
    let across = k.any_orthonormal_vector();
    // Meridian plane: x = across, y = k, so C(t) = c + 5 (cos t across + sin t k).
    let plane = Placement::new(c, across.cross(k), across).unwrap();
    let half = geom_param::CircleCurve::new(plane, 5.0, range(-FRAC_PI_2, FRAC_PI_2)).unwrap();
    let sphere = RevolutionSurface::new(half, a, 3.0 * k, turn()).unwrap();
    let mut rng = SplitMix64(14);
    for _ in 0..200 {
        let (u, v) = (rng.range(0.0, TAU), rng.range(-FRAC_PI_2, FRAC_PI_2));
        let point = sphere.eval(u, v).point;
        assert!(((point - c).length() - 5.0).abs() < 1e-12 * 5.0);
        let n = sphere.normal(u, v).unwrap();
        assert!(
            (n - (point - c) / 5.0).length() < 1e-9,
            "not away from the centre"
        );
    }
    for u in [0.0, 2.0, 5.0] {
        assert!((sphere.normal(u, -FRAC_PI_2).unwrap() + k).length() < 1e-15);
        assert!((sphere.normal(u, FRAC_PI_2).unwrap() - k).length() < 1e-15);
    }
    check("revolved sphere", &sphere, 15);
}

#[test]
fn revolution_cone_tip_has_no_normal() {
    // A line leaving the axis at 45°: a cone with its tip at the curve's start.
    let line = LineCurve::new(DVec3::ZERO, DVec3::new(1.0, 0.0, 1.0), range(0.0, 10.0)).unwrap();
    let cone = RevolutionSurface::new(line, DVec3::ZERO, DVec3::Z, turn()).unwrap();
    assert_eq!(cone.normal(0.7, 0.0), None);
    let n = cone.normal(0.0, 3.0).unwrap();
    assert!((n - DVec3::new(1.0, 0.0, -1.0).normalize()).length() < 1e-15);
}

#[test]
fn reversed_surface_maps_v_and_flips_the_normal() {
    let p = tilted();
    let cylinder = CylinderSurface::new(p, 7.5, [turn(), range(-20.0, 35.0)]).unwrap();
    let hole = ReversedSurface {
        inner: cylinder.clone(),
    };
    let [u_range, v_range] = hole.domain();
    assert_eq!(u_range, turn());
    assert_eq!(v_range, range(-35.0, 20.0));
    let mut rng = SplitMix64(16);
    for _ in 0..200 {
        let (u, v) = (rng.range(0.0, TAU), rng.range(-35.0, 20.0));
        let (a, b) = (hole.eval(u, v), cylinder.eval(u, -v));
        assert_eq!(a.point, b.point);
        let n = hole.normal(u, v).unwrap();
        assert_eq!(n, -cylinder.normal(u, -v).unwrap());
        // Into the hole: towards the axis.
        let l = local(&p, a.point);
        assert!(local(&p, p.origin + n).dot(DVec3::new(l.x, l.y, 0.0)) < 0.0);
        let k = hole.principal_curvatures(u, v).unwrap();
        assert_eq!((k.min, k.max), (-1.0 / 7.5, 0.0));
    }
    check("reversed cylinder", &hole, 17);
    // A boxed inner surface, and the reversed sphere's poles.
    let sphere = SphereSurface::new(p, 3.0, [turn(), range(-FRAC_PI_2, 1.0)]).unwrap();
    let cavity: ReversedSurface = ReversedSurface {
        inner: Box::new(sphere),
    };
    assert_eq!(cavity.domain()[1], range(-1.0, FRAC_PI_2));
    assert!((cavity.normal(0.4, FRAC_PI_2).unwrap() - p.z).length() < 1e-15);
    check("reversed sphere", &cavity, 18);
}
