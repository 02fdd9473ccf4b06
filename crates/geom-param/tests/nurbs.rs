//! NURBS numerics: the basis against an independent Cox–de Boor recursion, curves (3D and
//! p-curves) and surfaces against brute-force rational sums and finite differences, the exact
//! circle (A7.1), the NURBS sphere and torus from A8.1 against the analytic surfaces, the
//! extrusion against `LinearExtrusionSurface`, creases, extreme weights and periodic curves.

mod geometry_support;

use geom_param::{
    BSplineBasis, Curve, Curve2, DVec2, DVec3, LinearExtrusionSurface, MAX_DEGREE, NurbsCurve,
    NurbsCurve2, NurbsSurface, ParamRange, Placement, SphereSurface, Surface, SurfacePoint,
    TorusSurface,
};
use geometry_support::{Pieces, SplitMix64, check_curve, check_curve2, check_surface, knot_pieces};
use std::f64::consts::{FRAC_PI_2, PI, TAU};

// ---------------------------------------------------------------------------------------------
// Independent reference: the Cox–de Boor recursion (The NURBS Book eq. 2.5) and the derivative
// recursion (eq. 2.9), written from the definitions, sharing nothing with A2.1/A2.3.

/// N^(k)_{i,p}(t), with half-open support intervals [u_i, u_{i+1}).
fn reference_basis(knots: &[f64], i: usize, p: usize, k: usize, t: f64) -> f64 {
    if k > p {
        return 0.0;
    }
    if p == 0 {
        return if knots[i] <= t && t < knots[i + 1] {
            1.0
        } else {
            0.0
        };
    }
    let left_span = knots[i + p] - knots[i];
    let right_span = knots[i + p + 1] - knots[i + 1];
    if k == 0 {
        let mut value = 0.0;
        if left_span > 0.0 {
            value += (t - knots[i]) / left_span * reference_basis(knots, i, p - 1, 0, t);
        }
        if right_span > 0.0 {
            value +=
                (knots[i + p + 1] - t) / right_span * reference_basis(knots, i + 1, p - 1, 0, t);
        }
        value
    } else {
        let mut value = 0.0;
        if left_span > 0.0 {
            value += reference_basis(knots, i, p - 1, k - 1, t) / left_span;
        }
        if right_span > 0.0 {
            value -= reference_basis(knots, i + 1, p - 1, k - 1, t) / right_span;
        }
        p as f64 * value
    }
}

/// Σ N_i w_i P_i / Σ N_i w_i by the reference basis.
fn reference_curve_point<P>(knots: &[f64], p: usize, points: &[P], weights: &[f64], t: f64) -> P
where
    P: Copy + std::ops::Add<Output = P> + std::ops::Mul<f64, Output = P> + Default,
{
    let (mut sum, mut weight) = (P::default(), 0.0);
    for (i, (&point, &w)) in points.iter().zip(weights).enumerate() {
        let n = reference_basis(knots, i, p, 0, t) * w;
        sum = sum + point * n;
        weight += n;
    }
    sum * (1.0 / weight)
}

// ---------------------------------------------------------------------------------------------
// Random inputs.

/// A knot vector for `count` points of degree `p`: clamped (ends repeated p + 1 times) or not,
/// with interior knots repeated up to `max_interior` times (<= p).
fn random_knots(
    rng: &mut SplitMix64,
    p: usize,
    count: usize,
    clamped: bool,
    max_interior: usize,
) -> Vec<f64> {
    loop {
        let knots = random_knots_once(rng, p, count, clamped, max_interior);
        if knots[p] < knots[count] {
            return knots;
        }
    }
}

/// One draw of [`random_knots`], whose domain [u_p, u_{n+1}] may be empty.
fn random_knots_once(
    rng: &mut SplitMix64,
    p: usize,
    count: usize,
    clamped: bool,
    max_interior: usize,
) -> Vec<f64> {
    let length = count + p + 1;
    let mut knots = Vec::with_capacity(length);
    let mut value = rng.range(-3.0, 3.0);
    if clamped {
        knots.extend(std::iter::repeat_n(value, p + 1));
    }
    let tail = if clamped { p + 1 } else { 0 };
    while knots.len() < length - tail {
        value += rng.range(0.2, 1.5);
        let multiplicity = 1 + (rng.next_u64() % max_interior as u64) as usize;
        let room = length - tail - knots.len();
        knots.extend(std::iter::repeat_n(value, multiplicity.min(room)));
    }
    if clamped {
        value += rng.range(0.2, 1.5);
        knots.extend(std::iter::repeat_n(value, p + 1));
    }
    knots
}

fn random_point(rng: &mut SplitMix64) -> DVec3 {
    DVec3::new(
        rng.range(-20.0, 20.0),
        rng.range(-20.0, 20.0),
        rng.range(-20.0, 20.0),
    )
}

fn random_curve(rng: &mut SplitMix64, p: usize, count: usize, clamped: bool) -> NurbsCurve {
    let knots = random_knots(rng, p, count, clamped, p);
    let points = (0..count).map(|_| random_point(rng)).collect();
    let weights = (0..count).map(|_| rng.range(0.3, 3.0)).collect();
    NurbsCurve::new(p, knots, points, weights, false).unwrap()
}

fn random_surface(rng: &mut SplitMix64, degree: [usize; 2], count: [usize; 2]) -> NurbsSurface {
    let knots = [0, 1].map(|d| random_knots(rng, degree[d], count[d], d == 0, degree[d]));
    let points = (0..count[0])
        .map(|_| (0..count[1]).map(|_| random_point(rng)).collect())
        .collect();
    let weights = (0..count[0])
        .map(|_| (0..count[1]).map(|_| rng.range(0.3, 3.0)).collect())
        .collect();
    NurbsSurface::new(degree, knots, points, weights, [false, false]).unwrap()
}

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

/// Coordinates of an object point in a placement's frame.
fn local(p: &Placement, point: DVec3) -> DVec3 {
    let d = point - p.origin;
    DVec3::new(d.dot(p.x), d.dot(p.y), d.dot(p.z))
}

fn all_finite(s: &SurfacePoint) -> bool {
    [s.point, s.du, s.dv, s.duu, s.duv, s.dvv]
        .iter()
        .all(|v| v.is_finite())
}

// ---------------------------------------------------------------------------------------------
// Basis.

#[test]
fn basis_derivatives_match_the_cox_de_boor_recursion() {
    let mut rng = SplitMix64(31);
    for case in 0..200 {
        let p = 1 + case % MAX_DEGREE;
        let count = p + 1 + (rng.next_u64() % 8) as usize;
        let knots = random_knots(&mut rng, p, count, case % 3 != 0, p);
        let basis = BSplineBasis::new(p, knots.clone(), count).unwrap();
        let (min, max) = basis.domain();
        let shortest = knots
            .windows(2)
            .map(|w| w[1] - w[0])
            .filter(|&d| d > 0.0)
            .fold(f64::INFINITY, f64::min);
        for _ in 0..20 {
            let t = rng.range(min, max);
            let span = basis.find_span(t);
            assert!(
                knots[span] <= t && t < knots[span + 1],
                "span {span} misses {t}"
            );
            let ders = basis.derivatives(span, t);
            let sum: f64 = ders[0][..=p].iter().sum();
            assert!((sum - 1.0).abs() < 1e-13, "partition of unity: {sum}");
            for (k, row) in ders.iter().enumerate() {
                // N^(k) scales like (p / shortest interval)^k.
                let scale = (p as f64 / shortest).powi(k as i32);
                for i in 0..count {
                    let expected = reference_basis(&knots, i, p, k, t);
                    let got = if i + p >= span && i <= span {
                        row[i + p - span]
                    } else {
                        0.0
                    };
                    assert!(
                        (got - expected).abs() <= 1e-10 * scale,
                        "degree {p}, N^({k})_{i}({t}) = {got} vs Cox–de Boor {expected}"
                    );
                }
            }
        }
    }
}

#[test]
fn find_span_at_the_ends_and_on_repeated_knots() {
    let knots = vec![0.0, 0.0, 0.0, 1.0, 1.0, 3.0, 4.0, 4.0, 4.0];
    let basis = BSplineBasis::new(2, knots, 6).unwrap();
    assert_eq!(basis.domain(), (0.0, 4.0));
    assert_eq!(basis.find_span(0.0), 2);
    assert_eq!(basis.find_span(-5.0), 2);
    assert_eq!(basis.find_span(0.5), 2);
    assert_eq!(
        basis.find_span(1.0),
        4,
        "a repeated knot starts the next non-empty span"
    );
    assert_eq!(basis.find_span(2.9), 4);
    assert_eq!(basis.find_span(3.0), 5);
    assert_eq!(
        basis.find_span(4.0),
        5,
        "the domain's end belongs to the last span"
    );
    assert_eq!(basis.find_span(9.0), 5);
    let _ = basis.find_span(f64::NAN);
}

// ---------------------------------------------------------------------------------------------
// Curves and surfaces: brute force and finite differences.

#[test]
fn curves_match_brute_force_and_finite_differences() {
    let mut rng = SplitMix64(41);
    for (case, p) in [1, 2, 3, 4, 5, 7, MAX_DEGREE].into_iter().enumerate() {
        for clamped in [true, false] {
            let count = p + 1 + (rng.next_u64() % 6) as usize;
            let curve = random_curve(&mut rng, p, count, clamped);
            let knots = curve.basis().knots();
            let (min, max) = curve.basis().domain();
            for _ in 0..100 {
                let t = rng.range(min, max);
                let expected =
                    reference_curve_point(knots, p, curve.control_points(), curve.weights(), t);
                let got = curve.eval(t).point;
                assert!(
                    (got - expected).length() < 1e-11 * 40.0,
                    "{got:?} vs {expected:?}"
                );
            }
            let name = format!("degree {p} curve (clamped: {clamped})");
            check_curve(&name, &curve, &knot_pieces(curve.basis()), 42 + case as u64);
        }
    }
}

#[test]
fn pcurves_match_brute_force_and_finite_differences() {
    let mut rng = SplitMix64(51);
    for p in [1, 2, 3, 6] {
        let count = p + 4;
        let knots = random_knots(&mut rng, p, count, true, p);
        let points: Vec<DVec2> = (0..count)
            .map(|_| DVec2::new(rng.range(0.0, 6.0), rng.range(-1.0, 1.0)))
            .collect();
        let weights: Vec<f64> = (0..count).map(|_| rng.range(0.5, 2.0)).collect();
        let curve =
            NurbsCurve2::new(p, knots.clone(), points.clone(), weights.clone(), false).unwrap();
        let domain = Curve2::domain(&curve);
        for _ in 0..100 {
            let t = rng.range(domain.min, domain.max);
            let expected = reference_curve_point(&knots, p, &points, &weights, t);
            assert!((Curve2::eval(&curve, t).point - expected).length() < 1e-12 * 6.0);
        }
        check_curve2(
            &format!("degree {p} p-curve"),
            &curve,
            &knot_pieces(curve.basis()),
            52,
        );
    }
}

#[test]
fn surfaces_match_brute_force_and_finite_differences() {
    let mut rng = SplitMix64(61);
    for (case, degree) in [[3, 3], [2, 3], [1, 4], [5, 2], [MAX_DEGREE, 1]]
        .into_iter()
        .enumerate()
    {
        let count = [degree[0] + 3, degree[1] + 2];
        let surface = random_surface(&mut rng, degree, count);
        let [range_u, range_v] = surface.domain();
        let knots = [surface.basis(0).knots(), surface.basis(1).knots()];
        for _ in 0..50 {
            let (u, v) = (
                rng.range(range_u.min, range_u.max),
                rng.range(range_v.min, range_v.max),
            );
            let (mut sum, mut weight) = (DVec3::ZERO, 0.0);
            for i in 0..count[0] {
                for j in 0..count[1] {
                    let n = reference_basis(knots[0], i, degree[0], 0, u)
                        * reference_basis(knots[1], j, degree[1], 0, v)
                        * surface.weight(i, j);
                    sum += surface.control_point(i, j) * n;
                    weight += n;
                }
            }
            let got = surface.eval(u, v).point;
            assert!((got - sum / weight).length() < 1e-11 * 40.0);
        }
        let pieces = [knot_pieces(surface.basis(0)), knot_pieces(surface.basis(1))];
        let name = format!("degree {degree:?} surface");
        check_surface(&name, &surface, [&pieces[0], &pieces[1]], 62 + case as u64);
    }
}

// ---------------------------------------------------------------------------------------------
// The exact circle (A7.1).

fn tilted() -> Placement {
    Placement::new(
        DVec3::new(5.0, -2.0, 9.0),
        DVec3::new(0.6, 0.3, -0.7),
        DVec3::new(0.0, 1.0, 1.0),
    )
    .unwrap()
}

#[test]
fn nurbs_circle_points_are_on_the_circle_and_tangent() {
    let p = tilted();
    let r = 12.5;
    let mut rng = SplitMix64(71);
    for (sweep, arcs) in [
        (0.3, 1),
        (FRAC_PI_2, 1),
        (2.0, 2),
        (PI, 2),
        (4.0, 3),
        (1.5 * PI, 3),
        (5.5, 4),
        (TAU, 4),
    ] {
        let start = -0.7;
        let arc = NurbsCurve::circle_arc(&p, r, start, sweep).unwrap();
        assert_eq!(arc.control_points().len(), 2 * arcs + 1);
        assert_eq!(arc.is_periodic(), sweep == TAU);
        let domain = arc.domain();
        assert_eq!((domain.min, domain.max), (start, start + sweep));
        for _ in 0..300 {
            let t = rng.range(start, start + sweep);
            let c = arc.eval(t);
            let offset = c.point - p.origin;
            assert!(
                (offset.length() - r).abs() <= 1e-12 * r,
                "sweep {sweep}: |P - C| = {} at t = {t}",
                offset.length()
            );
            assert!(offset.dot(p.z).abs() <= 1e-12 * r, "leaves the plane");
            assert!(
                c.d1.dot(offset).abs() <= 1e-12 * c.d1.length() * r,
                "not tangent"
            );
            assert!(
                c.d1.dot(p.z.cross(offset)) > 0.0,
                "not counter-clockwise about z"
            );
        }
        // At the joints the parameter is the angle.
        for i in 0..=arcs {
            let t = start + sweep * i as f64 / arcs as f64;
            let expected = p.origin + r * (t.cos() * p.x + t.sin() * p.y);
            assert!((arc.eval(t).point - expected).length() < 1e-12 * r);
        }
        check_curve(
            &format!("circle arc {sweep}"),
            &arc,
            &knot_pieces(arc.basis()),
            72,
        );
    }
    let full = NurbsCurve::circle_arc(&p, r, 0.0, TAU).unwrap();
    for t in [0.1, 2.0, 5.0] {
        assert!((full.eval(t + TAU).point - full.eval(t).point).length() < 1e-12 * r);
        assert!((full.eval(t - TAU).point - full.eval(t).point).length() < 1e-12 * r);
    }
}

// ---------------------------------------------------------------------------------------------
// A8.1: the NURBS sphere and torus against the analytic surfaces.

/// A frame with z = `k`: the axis of the swept surfaces below.
fn axis_frame() -> Placement {
    Placement::new(
        DVec3::new(-4.0, 3.0, 7.0),
        DVec3::new(0.2, -0.4, 1.0),
        DVec3::new(1.0, 1.0, 0.0),
    )
    .unwrap()
}

/// The meridian plane through the axis of `frame`: x = the frame's x, y = its z.
fn meridian_plane(frame: &Placement, centre: DVec3) -> Placement {
    Placement::new(centre, -frame.y, frame.x).unwrap()
}

/// Samples of (u, v) over a domain, with both ends of each direction included.
fn samples_with_ends(rng: &mut SplitMix64, domain: [ParamRange; 2]) -> Vec<(f64, f64)> {
    let mut samples: Vec<(f64, f64)> = (0..400)
        .map(|_| {
            (
                rng.range(domain[0].min, domain[0].max),
                rng.range(domain[1].min, domain[1].max),
            )
        })
        .collect();
    for &u in &[domain[0].min, domain[0].max, 1.234] {
        for &v in &[domain[1].min, domain[1].max] {
            samples.push((u, v));
        }
    }
    samples
}

#[test]
fn nurbs_sphere_is_the_sphere() {
    let frame = axis_frame();
    let radius = 8.0;
    let meridian = NurbsCurve::circle_arc(
        &meridian_plane(&frame, frame.origin),
        radius,
        -FRAC_PI_2,
        PI,
    )
    .unwrap();
    let nurbs = NurbsSurface::revolution(&meridian, frame.origin, 2.0 * frame.z, TAU).unwrap();
    assert_eq!(nurbs.is_periodic(), [true, false]);
    let sphere = SphereSurface::new(frame, radius, [turn(), range(-FRAC_PI_2, FRAC_PI_2)]).unwrap();
    let mut rng = SplitMix64(81);
    for (u, v) in samples_with_ends(&mut rng, nurbs.domain()) {
        let point = nurbs.eval(u, v).point;
        assert!(
            ((point - frame.origin).length() - radius).abs() <= 1e-12 * radius,
            "|P - C| = {} at ({u}, {v})",
            (point - frame.origin).length()
        );
        let l = local(&frame, point);
        let (su, sv) = (l.y.atan2(l.x), (l.z / radius).clamp(-1.0, 1.0).asin());
        let expected = sphere.normal(su, sv).unwrap();
        let n = nurbs
            .normal(u, v)
            .unwrap_or_else(|| panic!("no normal at ({u}, {v})"));
        assert!(
            (n - expected).length() < 1e-9,
            "normal {n:?} vs sphere {expected:?} at ({u}, {v})"
        );
    }
    let pieces = [knot_pieces(nurbs.basis(0)), knot_pieces(nurbs.basis(1))];
    check_surface("NURBS sphere", &nurbs, [&pieces[0], &pieces[1]], 82);
}

#[test]
fn nurbs_torus_is_the_torus() {
    let frame = axis_frame();
    let (big, small) = (15.0, 4.0);
    let tube = NurbsCurve::circle_arc(
        &meridian_plane(&frame, frame.origin + big * frame.x),
        small,
        0.4,
        TAU,
    )
    .unwrap();
    let nurbs = NurbsSurface::revolution(&tube, frame.origin, frame.z, TAU).unwrap();
    assert_eq!(nurbs.is_periodic(), [true, true]);
    let torus = TorusSurface::new(frame, big, small, [turn(), turn()]).unwrap();
    let mut rng = SplitMix64(91);
    for (u, v) in samples_with_ends(&mut rng, nurbs.domain()) {
        let l = local(&frame, nurbs.eval(u, v).point);
        let rho = l.truncate().length();
        let implicit = (rho - big).powi(2) + l.z * l.z - small * small;
        assert!(
            implicit.abs() <= 1e-12 * big * big,
            "off the torus by {implicit:e}"
        );
        let expected = torus.normal(l.y.atan2(l.x), l.z.atan2(rho - big)).unwrap();
        let n = nurbs.normal(u, v).unwrap();
        assert!(
            (n - expected).length() < 1e-9,
            "normal {n:?} vs torus {expected:?}"
        );
    }
    let pieces = [knot_pieces(nurbs.basis(0)), knot_pieces(nurbs.basis(1))];
    check_surface("NURBS torus", &nurbs, [&pieces[0], &pieces[1]], 92);
}

#[test]
fn partial_revolution_and_cone_tip() {
    let frame = axis_frame();
    // A quarter meridian from the south pole to the equator, swept by 2.5 rad.
    let meridian = NurbsCurve::circle_arc(
        &meridian_plane(&frame, frame.origin),
        3.0,
        -FRAC_PI_2,
        FRAC_PI_2,
    )
    .unwrap();
    let cap = NurbsSurface::revolution(&meridian, frame.origin, frame.z, 2.5).unwrap();
    assert_eq!(cap.is_periodic(), [false, false]);
    assert_eq!(cap.domain()[0], range(0.0, 2.5));
    let mut rng = SplitMix64(93);
    for (u, v) in samples_with_ends(&mut rng, cap.domain()) {
        let point = cap.eval(u, v).point;
        assert!(((point - frame.origin).length() - 3.0).abs() <= 1e-12 * 3.0);
        let n = cap
            .normal(u, v)
            .unwrap_or_else(|| panic!("no normal at ({u}, {v})"));
        assert!((n - (point - frame.origin) / 3.0).length() < 1e-9);
    }
    // The south pole is at v = min: normal −z for every u.
    let v_min = cap.domain()[1].min;
    for u in [0.0, 1.0, 2.5] {
        assert!((cap.normal(u, v_min).unwrap() + frame.z).length() < 1e-9);
    }
    // A line leaving the axis at 45° revolved: a cone whose tip has no tangent plane.
    let line = NurbsCurve::new(
        1,
        vec![0.0, 0.0, 1.0, 1.0],
        vec![frame.origin, frame.origin + 5.0 * (frame.x + frame.z)],
        vec![1.0, 1.0],
        false,
    )
    .unwrap();
    let cone = NurbsSurface::revolution(&line, frame.origin, frame.z, TAU).unwrap();
    assert_eq!(cone.normal(1.0, 0.0), None);
    let n = cone.normal(0.0, 0.5).unwrap();
    assert!((n - (frame.x - frame.z).normalize()).length() < 1e-12);
}

#[test]
fn nurbs_extrusion_is_the_linear_extrusion() {
    let mut rng = SplitMix64(101);
    let curve = random_curve(&mut rng, 3, 7, true);
    let d = DVec3::new(1.0, -2.0, 4.0);
    let nurbs = NurbsSurface::extrusion(&curve, d, range(-1.0, 2.5)).unwrap();
    let exact = LinearExtrusionSurface::new(curve.clone(), d, range(-1.0, 2.5)).unwrap();
    assert_eq!(nurbs.domain(), exact.domain());
    let [range_u, range_v] = nurbs.domain();
    for _ in 0..300 {
        let (u, v) = (
            rng.range(range_u.min, range_u.max),
            rng.range(range_v.min, range_v.max),
        );
        let (a, b) = (nurbs.eval(u, v), exact.eval(u, v));
        for (x, y) in [
            (a.point, b.point),
            (a.du, b.du),
            (a.dv, b.dv),
            (a.duu, b.duu),
            (a.duv, b.duv),
            (a.dvv, b.dvv),
        ] {
            assert!(
                (x - y).length() <= 1e-11 * (1.0 + y.length()),
                "{x:?} vs {y:?}"
            );
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Creases, extreme weights, periodic curves, NaN parameters.

#[test]
fn crease_is_continuous_with_one_sided_derivatives() {
    // Cubic, interior knot 1 of multiplicity 3 = degree: the curve passes through P3 with a
    // corner. The end derivatives of the two rational Bezier pieces (The NURBS Book eq. 4.9):
    // left C'(1⁻) = 3 (w2 / w3)(P3 − P2), right C'(1⁺) = 3 (w4 / w3)(P4 − P3).
    let points = vec![
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(1.0, 2.0, 0.0),
        DVec3::new(2.0, 3.0, 1.0),
        DVec3::new(4.0, 3.0, 0.0),
        DVec3::new(4.0, 0.0, -2.0),
        DVec3::new(6.0, -1.0, 0.0),
        DVec3::new(7.0, 1.0, 1.0),
    ];
    let weights = vec![1.0, 2.0, 0.5, 1.5, 3.0, 1.0, 1.0];
    let knots = vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 2.0, 2.0, 2.0, 2.0];
    let curve = NurbsCurve::new(3, knots, points.clone(), weights.clone(), false).unwrap();
    let at = curve.eval(1.0);
    assert!((at.point - points[3]).length() < 1e-14);
    for delta in [1e-6, 1e-9, 1e-12] {
        let (left, right) = (curve.eval(1.0 - delta), curve.eval(1.0 + delta));
        assert!((left.point - at.point).length() < 100.0 * delta);
        assert!((right.point - at.point).length() < 100.0 * delta);
        for c in [left, right] {
            assert!(c.d1.is_finite() && c.d2.is_finite());
        }
    }
    let left = 3.0 * weights[2] / weights[3] * (points[3] - points[2]);
    let right = 3.0 * weights[4] / weights[3] * (points[4] - points[3]);
    assert!(
        (at.d1 - right).length() < 1e-12 * right.length(),
        "at the knot: the right side"
    );
    assert!((curve.eval(1.0 - 1e-12).d1 - left).length() < 1e-9 * left.length());
    assert!((curve.eval(1.0 + 1e-12).d1 - right).length() < 1e-9 * right.length());
    assert!(
        (left.normalize() - right.normalize()).length() > 0.1,
        "no corner"
    );
    check_curve("crease curve", &curve, &knot_pieces(curve.basis()), 111);

    // The same crease across a surface (the curve extruded): a crease row in u.
    let surface = NurbsSurface::extrusion(&curve, DVec3::Z * 3.0, range(0.0, 1.0)).unwrap();
    let at = surface.eval(1.0, 0.4);
    for delta in [1e-9, 1e-12] {
        let (l, r) = (
            surface.eval(1.0 - delta, 0.4),
            surface.eval(1.0 + delta, 0.4),
        );
        assert!((l.point - at.point).length() < 100.0 * delta);
        assert!((r.point - at.point).length() < 100.0 * delta);
        assert!(all_finite(&l) && all_finite(&r));
    }
    assert!((at.du - right).length() < 1e-12 * right.length());
}

#[test]
fn tiny_and_huge_weights_give_finite_results_in_the_hull() {
    let points: Vec<DVec3> = (0..8)
        .map(|i| DVec3::new(i as f64, (i * i % 5) as f64, (i % 3) as f64 - 1.0))
        .collect();
    let weights = vec![1.0, 1e-6, 1e6, 1.0, 1e-6, 1e6, 1e-6, 1.0];
    let knots = vec![0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 2.0, 3.0, 3.0, 3.0, 3.0];
    let curve = NurbsCurve::new(3, knots.clone(), points.clone(), weights.clone(), false).unwrap();
    let (lo, hi) = points
        .iter()
        .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(a, b), &p| {
            (a.min(p), b.max(p))
        });
    for k in 0..=3000 {
        let t = 3.0 * k as f64 / 3000.0;
        let c = curve.eval(t);
        assert!(
            c.point.is_finite() && c.d1.is_finite() && c.d2.is_finite(),
            "at t = {t}"
        );
        assert!(
            c.point.cmpge(lo - 1e-9).all() && c.point.cmple(hi + 1e-9).all(),
            "outside the convex hull at t = {t}: {:?}",
            c.point
        );
    }
    let net: Vec<Vec<DVec3>> = points
        .iter()
        .map(|&p| {
            vec![
                p,
                p + DVec3::new(0.5, 4.0, 1.0),
                p + DVec3::new(-1.0, 6.0, 3.0),
            ]
        })
        .collect();
    let net_weights: Vec<Vec<f64>> = weights.iter().map(|&w| vec![1e6, w, 1e-6]).collect();
    let surface = NurbsSurface::new(
        [3, 2],
        [knots, vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0]],
        net,
        net_weights,
        [false, false],
    )
    .unwrap();
    for i in 0..=60 {
        for j in 0..=20 {
            let s = surface.eval(3.0 * i as f64 / 60.0, j as f64 / 20.0);
            assert!(all_finite(&s), "{s:?}");
        }
    }
}

#[test]
fn unclamped_periodic_curve_closes_smoothly() {
    // Uniform cubic with its first three control points repeated at the end: a closed C²
    // curve over [u_3, u_{n+1}].
    let mut points: Vec<DVec3> = (0..6)
        .map(|i| {
            let a = i as f64 * TAU / 6.0;
            DVec3::new(10.0 * a.cos(), 6.0 * a.sin(), (2.0 * a).sin())
        })
        .collect();
    points.extend_from_within(0..3);
    let count = points.len();
    let knots: Vec<f64> = (0..count + 4).map(|i| i as f64).collect();
    let weights = vec![1.0; count];
    let curve = NurbsCurve::new(3, knots, points, weights, true).unwrap();
    let domain = curve.domain();
    assert!(domain.periodic);
    assert_eq!((domain.min, domain.max), (3.0, count as f64));
    let (start, end) = (curve.eval(domain.min), curve.eval(domain.max - 1e-9));
    assert!((start.point - end.point).length() < 1e-7);
    assert!((start.d1 - end.d1).length() < 1e-6 * start.d1.length());
    assert!((start.d2 - end.d2).length() < 1e-6 * start.d2.length().max(1.0));
    assert!((curve.eval(4.5).point - curve.eval(4.5 + 6.0).point).length() < 1e-12);
    check_curve("periodic cubic", &curve, &knot_pieces(curve.basis()), 121);
}

#[test]
fn nan_parameters_do_not_panic() {
    let mut rng = SplitMix64(131);
    let curve = random_curve(&mut rng, 3, 6, false);
    let surface = random_surface(&mut rng, [3, 2], [5, 4]);
    let _ = curve.eval(f64::NAN);
    let _ = surface.eval(f64::NAN, 0.5);
    let _ = surface.normal(f64::NAN, f64::NAN);
    let circle = NurbsCurve::circle_arc(&Placement::IDENTITY, 1.0, 0.0, TAU).unwrap();
    let _ = circle.eval(f64::NAN);
    let _ = circle.eval(f64::INFINITY);
}

#[test]
fn pieces_sampler_stays_inside_pieces() {
    // The finite-difference sampler itself: every stencil within one knot interval.
    let pieces = Pieces::new(0.0, 3.0, &[1.0, 1.0, 2.5, 7.0]);
    let mut rng = SplitMix64(141);
    for _ in 0..1000 {
        let t = pieces.sample(&mut rng);
        for b in [0.0, 1.0, 2.5, 3.0] {
            assert!((t - b).abs() >= 2.0 * pieces.h);
        }
    }
}
