//! Lines, circles and ellipses: points against their closed forms, derivatives against finite
//! differences, and the periodic flag of full turns.

mod geometry_support;

use geom_param::{CircleCurve, Curve, DVec3, EllipseCurve, LineCurve, ParamRange, Placement};
use geometry_support::{SplitMix64, check_curve, whole};
use std::f64::consts::{FRAC_PI_2, TAU};

fn range(min: f64, max: f64) -> ParamRange {
    ParamRange {
        min,
        max,
        periodic: false,
    }
}

fn tilted() -> Placement {
    Placement::new(
        DVec3::new(-3.0, 8.0, 1.0),
        DVec3::new(-0.2, 0.9, 0.4),
        DVec3::new(0.5, 0.5, -1.0),
    )
    .unwrap()
}

#[test]
fn line_points_and_derivatives() {
    let (o, d) = (DVec3::new(1.0, -2.0, 3.0), DVec3::new(0.5, 4.0, -2.0));
    let line = LineCurve::new(o, d, range(-3.0, 7.0)).unwrap();
    let c = line.eval(2.5);
    assert_eq!(c.point, o + 2.5 * d);
    assert_eq!((c.d1, c.d2), (d, DVec3::ZERO));
    assert_eq!(line.domain(), range(-3.0, 7.0));
    check_curve("line", &line, &whole(line.domain()), 21);
}

#[test]
fn circle_points_tangents_and_derivatives() {
    let p = tilted();
    let r = 6.5;
    let full = ParamRange {
        min: -1.0,
        max: -1.0 + TAU,
        periodic: true,
    };
    let circle = CircleCurve::new(p, r, full).unwrap();
    assert!(circle.domain().periodic);
    assert!((circle.eval(0.0).point - (p.origin + r * p.x)).length() < 1e-12);
    assert!((circle.eval(FRAC_PI_2).point - (p.origin + r * p.y)).length() < 1e-12);
    let mut rng = SplitMix64(22);
    for _ in 0..300 {
        let t = rng.range(full.min, full.max);
        let c = circle.eval(t);
        let offset = c.point - p.origin;
        assert!((offset.length() - r).abs() < 1e-12 * r);
        assert!(offset.dot(p.z).abs() < 1e-12 * r, "leaves the plane");
        // Counter-clockwise about z, speed R.
        assert!((c.d1 - p.z.cross(offset)).length() < 1e-12 * r);
        assert!((circle.curvature(t) - 1.0 / r).abs() < 1e-12 / r);
    }
    check_curve("circle", &circle, &whole(full), 23);
    let arc = CircleCurve::new(p, r, range(0.5, 2.0)).unwrap();
    assert!(!arc.domain().periodic);
}

#[test]
fn ellipse_points_and_derivatives() {
    let p = tilted();
    let (a, b) = (8.0, 3.0);
    let ellipse = EllipseCurve::new(p, a, b, range(-2.0, 3.5)).unwrap();
    assert!((ellipse.eval(0.0).point - (p.origin + a * p.x)).length() < 1e-12);
    assert!((ellipse.eval(FRAC_PI_2).point - (p.origin + b * p.y)).length() < 1e-12);
    let mut rng = SplitMix64(24);
    for _ in 0..300 {
        let t = rng.range(-2.0, 3.5);
        let d = ellipse.eval(t).point - p.origin;
        let (x, y) = (d.dot(p.x), d.dot(p.y));
        assert!(((x / a).powi(2) + (y / b).powi(2) - 1.0).abs() < 1e-12);
        assert!(d.dot(p.z).abs() < 1e-12 * a);
    }
    // Curvature at the vertices: a / b² at the end of the major axis, b / a² at the minor.
    assert!((ellipse.curvature(0.0) - a / (b * b)).abs() < 1e-12);
    assert!((ellipse.curvature(FRAC_PI_2) - b / (a * a)).abs() < 1e-12);
    check_curve("ellipse", &ellipse, &whole(ellipse.domain()), 25);
}
