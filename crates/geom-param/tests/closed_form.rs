//! Closed-form checks: points, outward normals and principal curvatures of revolved spheres,
//! spherical sockets, cylinders (outer and inner), cones, tori and planes against formulas written
//! in terms of the 3D point; poles and apexes; `CircleEdge`; `ParamRange::normalize`.

use geom_param::{
    ArcSegment, CircleEdge, Curve, DVec2, DVec3, LineSegment, ParamRange, PrincipalCurvatures,
    ProfileSegment, RevolvedSurface, Surface,
};
use std::f64::consts::{FRAC_PI_2, PI, TAU};

/// Relative accuracy demanded of every closed-form comparison.
const REL: f64 = 1e-12;

/// Random samples per surface.
const SAMPLES: usize = 2000;

/// SplitMix64 (Steele, Lea, Flood 2014): a tiny, seedable, portable PRNG.
struct SplitMix64(u64);

impl SplitMix64 {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1) with 53 random bits.
    fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }

    /// Uniform in [lo, hi).
    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }
}

/// What a closed form says about the surface at one 3D point.
struct Expected {
    /// Residual of the surface's implicit equation at the point, in mm (0 on the surface).
    residual: f64,
    /// Unit outward normal.
    normal: DVec3,
    /// Principal curvatures, in any order.
    curvatures: [f64; 2],
}

/// A face to check: the surface, its length scale (mm) and its closed forms as a function of the
/// evaluated 3D point.
struct Case {
    name: &'static str,
    surface: RevolvedSurface,
    length: f64,
    closed_form: Box<dyn Fn(DVec3) -> Expected>,
}

fn line(from: [f64; 2], to: [f64; 2]) -> RevolvedSurface {
    RevolvedSurface {
        segment: ProfileSegment::Line(LineSegment {
            from: from.into(),
            to: to.into(),
        }),
    }
}

fn arc(center: [f64; 2], radius: f64, start_angle: f64, sweep: f64) -> RevolvedSurface {
    RevolvedSurface {
        segment: ProfileSegment::Arc(ArcSegment {
            center: center.into(),
            radius,
            start_angle,
            sweep,
        }),
    }
}

/// Distance of a point from the z axis.
fn rho(p: DVec3) -> f64 {
    p.x.hypot(p.y)
}

/// Unit radial direction (x, y, 0)/ρ.
fn radial(p: DVec3) -> DVec3 {
    DVec3::new(p.x, p.y, 0.0) / rho(p)
}

/// Sphere of radius r centred on the axis at height zc: arc from the south to the north pole,
/// counter-clockwise (material inside).
fn sphere(zc: f64, r: f64) -> Case {
    let c = DVec3::new(0.0, 0.0, zc);
    Case {
        name: "sphere",
        surface: arc([0.0, zc], r, -FRAC_PI_2, PI),
        length: r + zc.abs(),
        closed_form: Box::new(move |p| Expected {
            residual: (p - c).length() - r,
            normal: (p - c) / r,
            curvatures: [1.0 / r, 1.0 / r],
        }),
    }
}

/// Spherical socket: the same sphere walked clockwise from the north to the south pole, so the
/// material is outside and the normal points to the centre.
fn socket(zc: f64, r: f64) -> Case {
    let c = DVec3::new(0.0, 0.0, zc);
    Case {
        name: "socket",
        surface: arc([0.0, zc], r, FRAC_PI_2, -PI),
        length: r + zc.abs(),
        closed_form: Box::new(move |p| Expected {
            residual: (p - c).length() - r,
            normal: (c - p) / r,
            curvatures: [-1.0 / r, -1.0 / r],
        }),
    }
}

/// Cylinder r = R, z in [z0, z1], walked upwards (material inside): normal radial outwards,
/// curvatures 0 (meridian) and 1/R (parallel). Walked downwards it is a bore: everything flips.
fn cylinder(r: f64, z0: f64, z1: f64, inner: bool) -> Case {
    let sign = if inner { -1.0 } else { 1.0 };
    let (from, to) = if inner {
        ([r, z1], [r, z0])
    } else {
        ([r, z0], [r, z1])
    };
    Case {
        name: if inner { "inner cylinder" } else { "cylinder" },
        surface: line(from, to),
        length: r.max(z0.abs()).max(z1.abs()),
        closed_form: Box::new(move |p| Expected {
            residual: (rho(p) - r).abs() + (p.z - p.z.clamp(z0, z1)).abs(),
            normal: radial(p) * sign,
            curvatures: [0.0, sign / r],
        }),
    }
}

/// Cone from the base circle (R, 0) to the apex (0, H). With L = √(R² + H²) and half-angle α at
/// the apex (tan α = R/H, cos α = H/L): implicit ρ/R + z/H = 1; outward normal
/// (H x̂ + R ẑ)/L with x̂ the radial direction; meridian curvature 0; parallel curvature
/// z'/(r |t|) = H/(ρ L) = cos α / ρ (the normal section along the parallel has radius ρ / cos α,
/// Meusnier).
fn cone(r: f64, h: f64) -> Case {
    let l = r.hypot(h);
    Case {
        name: "cone",
        surface: line([r, 0.0], [0.0, h]),
        length: r.max(h),
        // ρ/R + z/H - 1 scaled to mm by R H / L (the distance to the cone's surface line).
        closed_form: Box::new(move |p| Expected {
            residual: (rho(p) / r + p.z / h - 1.0) * r * h / l,
            normal: (radial(p) * h + DVec3::Z * r) / l,
            curvatures: [0.0, (h / l) / rho(p)],
        }),
    }
}

/// Torus zone: arc of radius a about (rc, 0), counter-clockwise from just past the bottom
/// (θ = -π/2 + 0.01) nearly all the way round (θ up to 3π/2 - 0.01), so it covers the outer
/// (θ = 0) and inner (θ = π) equators. With ρ the distance from the axis and cos θ = (ρ - rc)/a:
/// normal (cos θ x̂, sin θ) = ((ρ - rc) x̂ + z ẑ)/a, meridian curvature 1/a, parallel curvature
/// cos θ/(rc + a cos θ) = (ρ - rc)/(a ρ) (negative on the inner half: a saddle).
const TORUS_START: f64 = -FRAC_PI_2 + 0.01;
const TORUS_SWEEP: f64 = TAU - 0.02;

fn torus(rc: f64, a: f64) -> Case {
    assert!(a < rc);
    Case {
        name: "torus",
        surface: arc([rc, 0.0], a, TORUS_START, TORUS_SWEEP),
        length: rc + a,
        closed_form: Box::new(move |p| {
            let q = rho(p) - rc;
            Expected {
                residual: q.hypot(p.z) - a,
                normal: (radial(p) * q + DVec3::Z * p.z) / a,
                curvatures: [1.0 / a, q / (a * rho(p))],
            }
        }),
    }
}

/// Flat disk of radius r at height z. `bottom`: walked outwards from the axis (material above,
/// normal -z); otherwise walked inwards to the axis (material below, normal +z).
fn disk(r: f64, z: f64, bottom: bool) -> Case {
    let (from, to, n) = if bottom {
        ([0.0, z], [r, z], -DVec3::Z)
    } else {
        ([r, z], [0.0, z], DVec3::Z)
    };
    Case {
        name: if bottom { "bottom disk" } else { "top disk" },
        surface: line(from, to),
        length: r.max(z.abs()),
        closed_form: Box::new(move |p| Expected {
            residual: (p.z - z).abs() + (rho(p) - rho(p).min(r)),
            normal: n,
            curvatures: [0.0, 0.0],
        }),
    }
}

fn all_cases() -> Vec<Case> {
    vec![
        sphere(3.0, 7.0),
        sphere(-40.0, 0.25),
        socket(12.0, 5.0),
        cylinder(8.0, -3.0, 17.0, false),
        cylinder(8.0, -3.0, 17.0, true),
        cone(6.0, 14.0),
        cone(30.0, 2.0),
        torus(20.0, 5.0),
        torus(4.0, 3.5),
        disk(9.0, -2.0, true),
        disk(9.0, 11.0, false),
    ]
}

/// Curvature tolerance: REL relative to the largest expected curvature, or to 1/length where
/// both vanish (the plane).
fn curvature_tol(expected: [f64; 2], length: f64) -> f64 {
    REL * expected[0].abs().max(expected[1].abs()).max(1.0 / length)
}

fn sorted(k: [f64; 2]) -> [f64; 2] {
    [k[0].min(k[1]), k[0].max(k[1])]
}

fn check_curvatures(got: PrincipalCurvatures, expected: [f64; 2], tol: f64, what: &str) {
    let [min, max] = sorted(expected);
    assert!(got.min <= got.max, "{what}: min > max in {got:?}");
    assert!(
        (got.min - min).abs() <= tol && (got.max - max).abs() <= tol,
        "{what}: curvatures {got:?}, expected [{min:e}, {max:e}] (tol {tol:e})"
    );
}

fn check_normal(got: DVec3, expected: DVec3, what: &str) {
    assert!(
        (got - expected).length() <= REL && (got.length() - 1.0).abs() <= REL,
        "{what}: normal {got:?}, expected {expected:?}"
    );
}

/// Checks the override (closed-form) normal and curvatures of `case` at (u, v) against the case's
/// closed forms, and that the point is on the exact surface at angle u.
fn check_point(case: &Case, u: f64, v: f64) {
    let what = format!("{} at (u, v) = ({u}, {v})", case.name);
    let s = case.surface.eval(u, v);
    let expected = (case.closed_form)(s.point);
    assert!(
        expected.residual.abs() <= REL * case.length,
        "{what}: point {:?} is {:e} mm off the surface",
        s.point,
        expected.residual
    );
    // The point sits at angle u about the axis (skip the axis itself, where the angle is moot).
    if rho(s.point) > REL * case.length {
        let angle = s.point.y.atan2(s.point.x).rem_euclid(TAU);
        let diff = (angle - u).abs();
        assert!(
            diff.min(TAU - diff) <= 4.0 * f64::EPSILON * TAU,
            "{what}: angle {angle} != u"
        );
    }
    let normal = case
        .surface
        .normal(u, v)
        .unwrap_or_else(|| panic!("{what}: no normal"));
    check_normal(normal, expected.normal, &what);
    let k = case
        .surface
        .principal_curvatures(u, v)
        .unwrap_or_else(|| panic!("{what}: no curvatures"));
    check_curvatures(
        k,
        expected.curvatures,
        curvature_tol(expected.curvatures, case.length),
        &what,
    );
}

#[test]
fn revolved_surfaces_match_closed_forms_at_random_points() {
    let mut rng = SplitMix64(0x5EED_0001);
    for case in all_cases() {
        for _ in 0..SAMPLES {
            let u = rng.range(0.0, TAU);
            // Cones: stay 1 % away from the apex, where r = R (1 - v) is computed as R - R v
            // and loses log10(1/(1 - v)) digits to cancellation (2 at v = 0.99, still well
            // inside REL); the apex itself is checked separately.
            let v = if case.name == "cone" {
                rng.range(0.0, 0.99)
            } else {
                rng.unit()
            };
            check_point(&case, u, v);
        }
        // The parameter ends (poles of the sphere, socket and disks are checked here too).
        for v in [0.0, 1.0] {
            if case.name == "cone" && v == 1.0 {
                continue;
            }
            check_point(&case, 1.234, v);
        }
    }
}

#[test]
fn torus_saddle_on_inner_equator() {
    let (rc, a) = (20.0, 5.0);
    let case = torus(rc, a);
    // θ = π: the inner equator, ρ = rc - a, curvatures 1/a and -1/(rc - a).
    let v_inner = (PI - TORUS_START) / TORUS_SWEEP;
    // θ = 0: the outer equator, curvatures 1/a and 1/(rc + a).
    let v_outer = (0.0 - TORUS_START) / TORUS_SWEEP;
    let mut rng = SplitMix64(0x5EED_0002);
    for _ in 0..64 {
        let u = rng.range(0.0, TAU);
        check_point(&case, u, v_inner);
        let k = case
            .surface
            .principal_curvatures(u, v_inner)
            .expect("curvatures");
        let tol = REL / a;
        assert!((k.max - 1.0 / a).abs() <= tol, "{k:?}");
        assert!((k.min + 1.0 / (rc - a)).abs() <= tol, "{k:?}");
        assert!(
            k.min * k.max < 0.0,
            "Gaussian curvature must be negative: {k:?}"
        );
        let n = case.surface.normal(u, v_inner).expect("normal");
        check_normal(n, DVec3::new(-u.cos(), -u.sin(), 0.0), "inner equator");

        check_point(&case, u, v_outer);
        let k = case
            .surface
            .principal_curvatures(u, v_outer)
            .expect("curvatures");
        assert!((k.max - 1.0 / a).abs() <= tol, "{k:?}");
        assert!((k.min - 1.0 / (rc + a)).abs() <= tol, "{k:?}");
    }
    // The saddle band: every sampled point with cos θ < 0 has K < 0.
    let mut saddles = 0;
    for _ in 0..SAMPLES {
        let (u, v) = (rng.range(0.0, TAU), rng.unit());
        let p = case.surface.eval(u, v).point;
        let k = case.surface.principal_curvatures(u, v).expect("curvatures");
        if rho(p) < rc - 1e-9 {
            saddles += 1;
            assert!(k.min * k.max < 0.0, "K >= 0 at inner point {p:?}: {k:?}");
        } else if rho(p) > rc + 1e-9 {
            assert!(k.min * k.max > 0.0, "K <= 0 at outer point {p:?}: {k:?}");
        }
    }
    assert!(saddles > SAMPLES / 4, "too few inner samples: {saddles}");
}

/// The trait's default path (fundamental forms, `principal_curvatures_with`) against the
/// override, away from the axis.
///
/// Mean curvature H and Gaussian curvature K come out of the fundamental forms without
/// cancellation and must agree to REL. The individual principal curvatures are H ∓ √(H² - K):
/// if H² and K carry relative rounding errors of a few ε (say ≤ 8ε κ², κ the largest curvature),
/// the square root moves by at most √(8ε) κ ≈ 4.2e-8 κ, and it does so at an umbilic (sphere:
/// H² - K = 0 exactly), so the individual values are checked to REL + √(8ε) there and wherever
/// |κ1 - κ2| is small. Where |κ1 - κ2| = 2√(H² - K) ≥ κ/4 the derivative of the square root is
/// bounded by 1/(κ/4) and the same 8ε κ² error moves it by at most 32ε κ ≪ REL κ, so those
/// points are held to REL.
#[test]
fn default_fundamental_form_curvatures_agree_with_override() {
    let mut rng = SplitMix64(0x5EED_0003);
    let mut worst_umbilic = 0.0_f64;
    for case in all_cases() {
        for _ in 0..SAMPLES {
            let u = rng.range(0.0, TAU);
            // Away from the axis: r > 1 % of the size for the sphere poles, cone apex and disk
            // centres (the default path has E = r² → 0 there).
            let v = rng.range(0.01, 0.99);
            let s = case.surface.eval(u, v);
            if rho(s.point) < 0.01 * case.length {
                continue;
            }
            let what = format!("{} at (u, v) = ({u}, {v})", case.name);
            let n = case.surface.normal(u, v).expect("normal");
            // The default normal (∂S/∂u × ∂S/∂v normalised) agrees with the override.
            let cross = s.cross_normal().expect("cross normal");
            check_normal(cross, n, &what);

            let over = case.surface.principal_curvatures(u, v).expect("override");
            let dflt = s.principal_curvatures_with(n).expect("default");
            let kappa = over.min.abs().max(over.max.abs()).max(1.0 / case.length);
            let (h_over, h_dflt) = (0.5 * (over.min + over.max), 0.5 * (dflt.min + dflt.max));
            let (k_over, k_dflt) = (over.min * over.max, dflt.min * dflt.max);
            assert!(
                (h_over - h_dflt).abs() <= REL * kappa,
                "{what}: H {h_dflt} vs {h_over}"
            );
            assert!(
                (k_over - k_dflt).abs() <= REL * kappa * kappa,
                "{what}: K {k_dflt} vs {k_over}"
            );
            let tol = if over.max - over.min >= 0.25 * kappa {
                REL * kappa
            } else {
                (REL + (8.0 * f64::EPSILON).sqrt()) * kappa
            };
            if over.max - over.min < 0.25 * kappa {
                let e = (dflt.min - over.min).abs().max((dflt.max - over.max).abs()) / kappa;
                worst_umbilic = worst_umbilic.max(e);
            }
            assert!(
                (dflt.min - over.min).abs() <= tol && (dflt.max - over.max).abs() <= tol,
                "{what}: default {dflt:?} vs override {over:?} (tol {tol:e})"
            );
        }
    }
    eprintln!(
        "worst relative min/max deviation of the default path at umbilics: {worst_umbilic:e}"
    );
}

#[test]
fn sphere_poles_are_regular() {
    for (zc, r) in [(3.0, 7.0), (-40.0, 0.25), (0.0, 1e3)] {
        let case = sphere(zc, r);
        for (v, nz) in [(0.0, -1.0), (1.0, 1.0)] {
            for u in [0.0, 1.0, 4.0] {
                let what = format!("sphere pole v = {v}, u = {u}");
                let p = case.surface.eval(u, v).point;
                assert!(
                    (p - DVec3::new(0.0, 0.0, zc + nz * r)).length() <= REL * case.length,
                    "{what}: {p:?}"
                );
                let n = case.surface.normal(u, v).expect("pole normal");
                assert!(n.is_finite(), "{what}: {n:?}");
                check_normal(n, DVec3::new(0.0, 0.0, nz), &what);
                let k = case
                    .surface
                    .principal_curvatures(u, v)
                    .expect("pole curvatures");
                assert!(k.min.is_finite() && k.max.is_finite(), "{what}: {k:?}");
                check_curvatures(k, [1.0 / r, 1.0 / r], REL / r, &what);
            }
        }
    }
    // The socket's poles: normal towards the centre (-z at the top, +z at the bottom), -1/R.
    let case = socket(12.0, 5.0);
    for (v, nz) in [(0.0, -1.0), (1.0, 1.0)] {
        let n = case.surface.normal(0.5, v).expect("socket pole normal");
        check_normal(n, DVec3::new(0.0, 0.0, nz), "socket pole");
        let k = case
            .surface
            .principal_curvatures(0.5, v)
            .expect("socket pole curvatures");
        check_curvatures(k, [-0.2, -0.2], REL / 5.0, "socket pole");
    }
    // Disk centres are poles too: ∓z and flat.
    for (case, nz, v) in [
        (disk(9.0, -2.0, true), -1.0, 0.0),
        (disk(9.0, 11.0, false), 1.0, 1.0),
    ] {
        let n = case.surface.normal(2.0, v).expect("disk centre normal");
        check_normal(n, DVec3::new(0.0, 0.0, nz), case.name);
        let k = case
            .surface
            .principal_curvatures(2.0, v)
            .expect("disk centre curvatures");
        assert!(k.min == 0.0 && k.max == 0.0, "{}: {k:?}", case.name);
    }
}

#[test]
fn cone_apex_has_no_normal_and_no_curvatures() {
    for (r, h) in [(6.0, 14.0), (30.0, 2.0)] {
        let case = cone(r, h);
        for u in [0.0, 2.5, 6.0] {
            let s = case.surface.eval(u, 1.0);
            assert_eq!(s.point, DVec3::new(0.0, 0.0, h), "apex point");
            assert!(
                [s.du, s.dv, s.duu, s.duv, s.dvv]
                    .iter()
                    .all(|d| d.is_finite()),
                "derivatives at the apex: {s:?}"
            );
            assert_eq!(case.surface.normal(u, 1.0), None, "apex normal");
            assert_eq!(
                case.surface.principal_curvatures(u, 1.0),
                None,
                "apex curvatures"
            );
        }
        // Just off the apex the normal is still the cone's.
        let v = 1.0 - 1e-6;
        let n = case.surface.normal(0.3, v).expect("normal near the apex");
        let l = r.hypot(h);
        check_normal(
            n,
            DVec3::new(h * 0.3_f64.cos(), h * 0.3_f64.sin(), r) / l,
            "near apex",
        );
    }
}

#[test]
fn circle_edge_matches_formula() {
    let mut rng = SplitMix64(0x5EED_0004);
    for (radius, z) in [(1.0, 0.0), (37.5, -12.0), (0.003, 4.0)] {
        let edge = CircleEdge { radius, z };
        let d = edge.domain();
        assert_eq!((d.min, d.max, d.periodic), (0.0, TAU, true));
        for _ in 0..SAMPLES {
            let t = rng.range(0.0, TAU);
            let (sin, cos) = (t.sin(), t.cos());
            let c = edge.eval(t);
            let tol = REL * radius.max(z.abs());
            let what = format!("circle r = {radius}, z = {z}, t = {t}");
            let p = DVec3::new(radius * cos, radius * sin, z);
            let d1 = DVec3::new(-radius * sin, radius * cos, 0.0);
            let d2 = DVec3::new(-radius * cos, -radius * sin, 0.0);
            assert!((c.point - p).length() <= tol, "{what}: point {:?}", c.point);
            assert!(
                (c.d1 - d1).length() <= REL * radius,
                "{what}: d1 {:?}",
                c.d1
            );
            assert!(
                (c.d2 - d2).length() <= REL * radius,
                "{what}: d2 {:?}",
                c.d2
            );
            // On the circle: distance r from the axis at height z.
            assert!((rho(c.point) - radius).abs() <= REL * radius, "{what}");
            let tangent = edge.tangent(t).expect("tangent");
            assert!(
                (tangent - DVec3::new(-sin, cos, 0.0)).length() <= REL,
                "{what}: {tangent}"
            );
            let k = edge.curvature(t);
            assert!(
                (k - 1.0 / radius).abs() <= REL / radius,
                "{what}: curvature {k}"
            );
        }
    }
}

#[test]
fn param_range_normalize_wraps_and_clamps() {
    let u = ParamRange {
        min: 0.0,
        max: TAU,
        periodic: true,
    };
    // Inside: unchanged.
    for t in [0.0, 1e-300, 1.0, PI, TAU - 1e-12] {
        assert_eq!(u.normalize(t), t, "t = {t}");
    }
    // The period's end wraps to its start; so do its multiples.
    assert_eq!(u.normalize(TAU), 0.0);
    assert_eq!(u.normalize(-TAU), 0.0);
    assert_eq!(u.normalize(2.0 * TAU), 0.0);
    // A tiny negative angle is 1e-18 before 2π: mathematically 2π - 1e-18, which rounds to 2π,
    // outside [0, 2π). The nearest representable point of [0, 2π) on the circle is 0.
    assert_eq!(u.normalize(-1e-18), 0.0);
    assert_eq!(u.normalize(-0.0), 0.0);
    // Whole turns are removed exactly (fmod is exact; 3π - 2π is exact by Sterbenz).
    assert_eq!(u.normalize(3.0 * PI), 3.0 * PI - TAU);
    assert_eq!(u.normalize(-FRAC_PI_2), TAU - FRAC_PI_2);
    let mut rng = SplitMix64(0x5EED_0005);
    for _ in 0..SAMPLES {
        let t = rng.range(-1e4, 1e4);
        let w = u.normalize(t);
        assert!(
            (0.0..TAU).contains(&w),
            "normalize({t}) = {w} outside [0, 2π)"
        );
        // Same angle: t - w is a whole number of periods (up to the rounding of t itself).
        let turns = (t - w) / TAU;
        assert!(
            (turns - turns.round()).abs() <= 1e-11,
            "normalize({t}) = {w}"
        );
    }

    // A periodic range not starting at 0: [-π, π).
    let a = ParamRange {
        min: -PI,
        max: PI,
        periodic: true,
    };
    assert_eq!(a.normalize(PI), -PI);
    assert_eq!(a.normalize(0.5), 0.5);
    assert_eq!(a.normalize(-PI), -PI);
    let w = a.normalize(-PI - 1e-9);
    assert!((w - (PI - 1e-9)).abs() <= 2e-15 && w < PI, "{w}");
    // Just below min by one ulp: wraps to just below max, which rounds to max, so back to min.
    let b = ParamRange {
        min: 1.0,
        max: 1.0 + TAU,
        periodic: true,
    };
    let just_below = 1.0 - f64::EPSILON / 2.0;
    let w = b.normalize(just_below);
    assert!((b.min..b.max).contains(&w), "{w}");
    // ... and the nearest point of [min, max) on the circle is min itself (1.1e-16 away).
    assert_eq!(w, b.min);

    // Non-periodic: clamped.
    let v = ParamRange {
        min: 0.0,
        max: 1.0,
        periodic: false,
    };
    assert_eq!(v.normalize(-1e-18), 0.0);
    assert_eq!(v.normalize(-3.0), 0.0);
    assert_eq!(v.normalize(1.0 + 1e-15), 1.0);
    assert_eq!(v.normalize(7.0), 1.0);
    assert_eq!(v.normalize(0.25), 0.25);
    assert_eq!(v.normalize(1.0), 1.0);
    assert_eq!(v.span(), 1.0);
    assert_eq!(u.span(), TAU);
}

#[test]
fn profile_segment_closed_forms() {
    // The (r, z) evaluation the surfaces are built on: an arc point is at distance radius from
    // the centre at the polar angle start + sweep s; the outward normal of a ccw arc is radial.
    let a = ProfileSegment::Arc(ArcSegment {
        center: DVec2::new(20.0, 1.0),
        radius: 5.0,
        start_angle: -1.0,
        sweep: 4.0,
    });
    let mut rng = SplitMix64(0x5EED_0006);
    for _ in 0..SAMPLES {
        let s = rng.unit();
        let p = a.eval(s);
        let theta = -1.0 + 4.0 * s;
        let radial = DVec2::new(theta.cos(), theta.sin());
        assert!((p.point - (DVec2::new(20.0, 1.0) + radial * 5.0)).length() <= REL * 25.0);
        assert!((p.outward_normal() - radial).length() <= REL, "s = {s}");
        assert!((p.signed_curvature() - 0.2).abs() <= REL * 0.2, "s = {s}");
    }
    // from_endpoints: sweeps ccw and cw between the same points.
    let (c, f, t) = (
        DVec2::new(0.0, 0.0),
        DVec2::new(0.0, -3.0),
        DVec2::new(0.0, 3.0),
    );
    let ccw = ArcSegment::from_endpoints(c, f, t, true);
    let cw = ArcSegment::from_endpoints(c, f, t, false);
    assert!((ccw.sweep - PI).abs() <= 4.0 * f64::EPSILON * PI, "{ccw:?}");
    assert!((cw.sweep + PI).abs() <= 4.0 * f64::EPSILON * PI, "{cw:?}");
    assert!((ccw.radius - 3.0).abs() <= REL * 3.0 && (cw.radius - 3.0).abs() <= REL * 3.0);
    for arc in [ccw, cw] {
        let seg = ProfileSegment::Arc(arc);
        assert!((seg.start() - f).length() <= REL * 3.0, "{arc:?}");
        assert!((seg.end() - t).length() <= REL * 3.0, "{arc:?}");
    }
    // ccw from the south to the north pole passes r = +3; cw passes r = -3.
    assert!((ProfileSegment::Arc(ccw).eval(0.5).point.x - 3.0).abs() <= REL * 3.0);
    assert!((ProfileSegment::Arc(cw).eval(0.5).point.x + 3.0).abs() <= REL * 3.0);
}
