//! Every `GeometryError` variant, each triggered by the bad input it names (and a valid input
//! next to it accepted, so the check cannot pass by rejecting everything).

use geom_param::{
    BSplineBasis, CircleCurve, ConeSurface, CylinderSurface, DVec3, EllipseCurve, GeometryError,
    LineCurve, LinearExtrusionSurface, MAX_DEGREE, NurbsCurve, NurbsCurve2, NurbsSurface,
    ParamRange, Placement, Plane, RevolutionSurface, SphereSurface, TorusSurface,
};
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

const P: Placement = Placement::IDENTITY;

fn line() -> LineCurve {
    LineCurve::new(DVec3::X, DVec3::Z, range(0.0, 1.0)).unwrap()
}

/// A valid clamped cubic: 5 points, knots 0,0,0,0,1,2,2,2,2.
fn cubic(knots: Vec<f64>, weights: Vec<f64>, periodic: bool) -> Result<NurbsCurve, GeometryError> {
    let points = (0..5)
        .map(|i| DVec3::new(i as f64, (i % 2) as f64, 0.0))
        .collect();
    NurbsCurve::new(3, knots, points, weights, periodic)
}

fn cubic_knots() -> Vec<f64> {
    vec![0.0, 0.0, 0.0, 0.0, 1.0, 2.0, 2.0, 2.0, 2.0]
}

#[track_caller]
fn assert_variant<T: std::fmt::Debug>(
    result: Result<T, GeometryError>,
    matches: fn(&GeometryError) -> bool,
) {
    let err = result.expect_err("bad input accepted");
    assert!(matches(&err), "unexpected error {err:?}");
    assert!(!err.to_string().is_empty());
}

#[test]
fn valid_inputs_are_accepted() {
    Plane::new(P, [range(-1.0, 1.0), range(-1.0, 1.0)]).unwrap();
    CylinderSurface::new(P, 1.0, [turn(), range(0.0, 1.0)]).unwrap();
    ConeSurface::new(P, 0.0, 0.5, [turn(), range(0.0, 1.0)]).unwrap();
    SphereSurface::new(P, 1.0, [turn(), range(-FRAC_PI_2, FRAC_PI_2)]).unwrap();
    TorusSurface::new(P, 2.0, 1.0, [turn(), turn()]).unwrap();
    cubic(cubic_knots(), vec![1.0; 5], false).unwrap();
    CircleCurve::new(
        P,
        1.0,
        ParamRange {
            min: -PI,
            max: PI,
            periodic: true,
        },
    )
    .unwrap();
}

#[test]
fn non_finite() {
    let nan = f64::NAN;
    let is = |e: &GeometryError| matches!(e, GeometryError::NonFinite { .. });
    assert_variant(
        Placement::new(DVec3::new(nan, 0.0, 0.0), DVec3::Z, DVec3::X),
        is,
    );
    assert_variant(
        CylinderSurface::new(P, f64::INFINITY, [turn(), range(0.0, 1.0)]),
        is,
    );
    assert_variant(Plane::new(P, [range(nan, 1.0), range(0.0, 1.0)]), is);
    assert_variant(ConeSurface::new(P, 1.0, nan, [turn(), range(0.0, 1.0)]), is);
    assert_variant(
        cubic(
            vec![0.0, 0.0, 0.0, 0.0, nan, 2.0, 2.0, 2.0, 2.0],
            vec![1.0; 5],
            false,
        ),
        is,
    );
    assert_variant(
        cubic(
            cubic_knots(),
            vec![1.0, 1.0, f64::INFINITY, 1.0, 1.0],
            false,
        ),
        is,
    );
    let points = vec![DVec3::ZERO, DVec3::new(nan, 0.0, 0.0)];
    assert_variant(
        NurbsCurve::new(1, vec![0.0, 0.0, 1.0, 1.0], points, vec![1.0; 2], false),
        is,
    );
    assert_variant(NurbsCurve::circle_arc(&P, 1.0, 0.0, nan), is);
}

#[test]
fn non_positive_radius() {
    let is = |e: &GeometryError| matches!(e, GeometryError::NonPositiveRadius { .. });
    assert_variant(CylinderSurface::new(P, 0.0, [turn(), range(0.0, 1.0)]), is);
    assert_variant(SphereSurface::new(P, -2.0, [turn(), range(0.0, 1.0)]), is);
    assert_variant(TorusSurface::new(P, 3.0, 0.0, [turn(), turn()]), is);
    assert_variant(CircleCurve::new(P, 0.0, turn()), is);
    assert_variant(EllipseCurve::new(P, 2.0, 0.0, turn()), is);
    assert_variant(NurbsCurve::circle_arc(&P, -1.0, 0.0, 1.0), is);
}

#[test]
fn negative_cone_radius() {
    assert_variant(
        ConeSurface::new(P, -1.0, 0.5, [turn(), range(0.0, 1.0)]),
        |e| matches!(e, GeometryError::NegativeRadius { .. }),
    );
}

#[test]
fn not_a_ring_torus() {
    let is = |e: &GeometryError| matches!(e, GeometryError::NotRingTorus { .. });
    assert_variant(TorusSurface::new(P, 2.0, 2.0, [turn(), turn()]), is);
    assert_variant(TorusSurface::new(P, 1.0, 2.0, [turn(), turn()]), is);
}

#[test]
fn bad_semi_angle() {
    let is = |e: &GeometryError| matches!(e, GeometryError::BadSemiAngle { .. });
    for angle in [0.0, -0.1, FRAC_PI_2, 2.0] {
        assert_variant(
            ConeSurface::new(P, 1.0, angle, [turn(), range(0.0, 1.0)]),
            is,
        );
    }
}

#[test]
fn degenerate_placement() {
    let is = |e: &GeometryError| matches!(e, GeometryError::DegeneratePlacement { .. });
    assert_variant(Placement::new(DVec3::ZERO, DVec3::ZERO, DVec3::X), is);
    assert_variant(Placement::new(DVec3::ZERO, DVec3::Z, DVec3::ZERO), is);
    assert_variant(Placement::new(DVec3::ZERO, DVec3::Z, -3.0 * DVec3::Z), is);
}

#[test]
fn zero_direction() {
    let is = |e: &GeometryError| matches!(e, GeometryError::ZeroDirection { .. });
    assert_variant(LineCurve::new(DVec3::X, DVec3::ZERO, range(0.0, 1.0)), is);
    assert_variant(
        LinearExtrusionSurface::new(line(), DVec3::ZERO, range(0.0, 1.0)),
        is,
    );
    assert_variant(
        RevolutionSurface::new(line(), DVec3::ZERO, DVec3::ZERO, turn()),
        is,
    );
    let curve = cubic(cubic_knots(), vec![1.0; 5], false).unwrap();
    assert_variant(
        NurbsSurface::revolution(&curve, DVec3::ZERO, DVec3::ZERO, 1.0),
        is,
    );
    assert_variant(
        NurbsSurface::extrusion(&curve, DVec3::ZERO, range(0.0, 1.0)),
        is,
    );
}

#[test]
fn bad_degree() {
    let is = |e: &GeometryError| matches!(e, GeometryError::BadDegree { .. });
    assert_variant(BSplineBasis::new(0, vec![0.0, 1.0, 2.0], 2), is);
    let degree = MAX_DEGREE + 1;
    let count = degree + 1;
    let knots: Vec<f64> = (0..count + degree + 1).map(|i| i as f64).collect();
    assert_variant(BSplineBasis::new(degree, knots.clone(), count), is);
    let points = vec![DVec3::ZERO; count];
    assert_variant(
        NurbsCurve::new(degree, knots.clone(), points, vec![1.0; count], false),
        is,
    );
    let net = vec![vec![DVec3::ZERO; 2]; count];
    let net_weights = vec![vec![1.0; 2]; count];
    assert_variant(
        NurbsSurface::new(
            [degree, 1],
            [knots, vec![0.0, 0.0, 1.0, 1.0]],
            net,
            net_weights,
            [false; 2],
        ),
        is,
    );
    // MAX_DEGREE itself is fine.
    let count = MAX_DEGREE + 1;
    let knots: Vec<f64> = (0..count + MAX_DEGREE + 1).map(|i| i as f64).collect();
    BSplineBasis::new(MAX_DEGREE, knots, count).unwrap();
}

#[test]
fn too_few_control_points() {
    let is = |e: &GeometryError| matches!(e, GeometryError::TooFewControlPoints { .. });
    assert_variant(BSplineBasis::new(3, vec![0.0; 6], 2), is);
    let points = vec![DVec3::ZERO, DVec3::X, DVec3::Y];
    assert_variant(
        NurbsCurve::new(
            3,
            vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
            points,
            vec![1.0; 3],
            false,
        ),
        is,
    );
    assert_variant(
        NurbsSurface::new([1, 1], [vec![], vec![]], vec![], vec![], [false; 2]),
        is,
    );
}

#[test]
fn knot_count() {
    let is = |e: &GeometryError| matches!(e, GeometryError::KnotCount { .. });
    assert_variant(
        cubic(
            vec![0.0, 0.0, 0.0, 0.0, 2.0, 2.0, 2.0, 2.0],
            vec![1.0; 5],
            false,
        ),
        is,
    );
    assert_variant(
        cubic(
            vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.5, 2.0, 2.0, 2.0, 2.0],
            vec![1.0; 5],
            false,
        ),
        is,
    );
}

#[test]
fn decreasing_knots() {
    assert_variant(
        cubic(
            vec![0.0, 0.0, 0.0, 0.0, 1.5, 1.0, 2.0, 2.0, 2.0],
            vec![1.0; 5],
            false,
        ),
        |e| matches!(e, GeometryError::DecreasingKnots { index: 5, .. }),
    );
}

#[test]
fn knot_multiplicity() {
    let is = |e: &GeometryError| matches!(e, GeometryError::KnotMultiplicity { .. });
    // An interior knot repeated degree + 1 = 4 times (8 points, domain [0, 2]).
    let points: Vec<DVec3> = (0..8).map(|i| DVec3::new(i as f64, 0.0, 0.0)).collect();
    let knots = vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0, 2.0, 2.0, 2.0, 2.0];
    assert_variant(
        NurbsCurve::new(3, knots, points, vec![1.0; 8], false),
        |e| {
            matches!(
                e,
                GeometryError::KnotMultiplicity {
                    multiplicity: 4,
                    max: 3,
                    ..
                }
            )
        },
    );
    let points: Vec<DVec3> = (0..7).map(|i| DVec3::new(i as f64, 0.0, 0.0)).collect();
    // Degree times inside is a crease, accepted.
    let crease = vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 2.0, 2.0, 2.0, 2.0];
    NurbsCurve::new(3, crease, points, vec![1.0; 7], false).unwrap();
    // An end knot repeated degree + 2 = 5 times (unclamped on the other side).
    assert_variant(
        cubic(
            vec![0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 2.0, 3.0, 4.0],
            vec![1.0; 5],
            false,
        ),
        is,
    );
}

#[test]
fn non_positive_weight() {
    for weight in [0.0, -1.0] {
        assert_variant(
            cubic(cubic_knots(), vec![1.0, 1.0, weight, 1.0, 1.0], false),
            |e| matches!(e, GeometryError::NonPositiveWeight { index: 2, .. }),
        );
    }
    let net = vec![vec![DVec3::ZERO, DVec3::X], vec![DVec3::Y, DVec3::ONE]];
    let knots = [vec![0.0, 0.0, 1.0, 1.0], vec![0.0, 0.0, 1.0, 1.0]];
    assert_variant(
        NurbsSurface::new(
            [1, 1],
            knots,
            net,
            vec![vec![1.0, 1.0], vec![1.0, 0.0]],
            [false; 2],
        ),
        |e| matches!(e, GeometryError::NonPositiveWeight { index: 3, .. }),
    );
}

#[test]
fn count_mismatch() {
    let is = |e: &GeometryError| matches!(e, GeometryError::CountMismatch { .. });
    assert_variant(cubic(cubic_knots(), vec![1.0; 4], false), is);
    let points = vec![DVec2Like::p(0.0), DVec2Like::p(1.0)];
    assert_variant(
        NurbsCurve2::new(1, vec![0.0, 0.0, 1.0, 1.0], points, vec![1.0; 3], false),
        is,
    );
    let knots = || [vec![0.0, 0.0, 1.0, 1.0], vec![0.0, 0.0, 1.0, 1.0]];
    let ragged = vec![vec![DVec3::ZERO, DVec3::X], vec![DVec3::Y]];
    assert_variant(
        NurbsSurface::new([1, 1], knots(), ragged, vec![vec![1.0; 2]; 2], [false; 2]),
        is,
    );
    let net = vec![vec![DVec3::ZERO, DVec3::X], vec![DVec3::Y, DVec3::ONE]];
    assert_variant(
        NurbsSurface::new([1, 1], knots(), net.clone(), vec![vec![1.0; 2]], [false; 2]),
        is,
    );
    assert_variant(
        NurbsSurface::new(
            [1, 1],
            knots(),
            net,
            vec![vec![1.0; 2], vec![1.0]],
            [false; 2],
        ),
        is,
    );
}

/// 2D control points for the p-curve case.
struct DVec2Like;

impl DVec2Like {
    fn p(x: f64) -> geom_param::DVec2 {
        geom_param::DVec2::new(x, 2.0 * x)
    }
}

#[test]
fn empty_range() {
    let is = |e: &GeometryError| matches!(e, GeometryError::EmptyRange { .. });
    assert_variant(Plane::new(P, [range(1.0, 1.0), range(0.0, 1.0)]), is);
    assert_variant(CylinderSurface::new(P, 1.0, [turn(), range(2.0, 1.0)]), is);
    assert_variant(LineCurve::new(DVec3::X, DVec3::Z, range(3.0, -3.0)), is);
    assert_variant(NurbsCurve::circle_arc(&P, 1.0, 0.0, 0.0), is);
    assert_variant(NurbsCurve::circle_arc(&P, 1.0, 0.0, -1.0), is);
    // A knot vector whose domain [u_p, u_{n+1}] is a single value.
    assert_variant(
        cubic(
            vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 2.0, 2.0, 2.0],
            vec![1.0; 5],
            false,
        ),
        is,
    );
    assert_variant(BSplineBasis::new(1, vec![0.0, 1.0, 1.0, 2.0], 2), is);
}

#[test]
fn bad_period() {
    let is = |e: &GeometryError| matches!(e, GeometryError::BadPeriod { .. });
    let periodic_line = ParamRange {
        min: 0.0,
        max: 5.0,
        periodic: true,
    };
    assert_variant(Plane::new(P, [periodic_line, range(0.0, 1.0)]), is);
    assert_variant(LineCurve::new(DVec3::X, DVec3::Z, periodic_line), is);
    let half_turn = ParamRange {
        min: 0.0,
        max: PI,
        periodic: true,
    };
    assert_variant(
        CylinderSurface::new(P, 1.0, [half_turn, range(0.0, 1.0)]),
        is,
    );
    assert_variant(
        CylinderSurface::new(P, 1.0, [range(0.0, 7.0), range(0.0, 1.0)]),
        is,
    );
    assert_variant(
        SphereSurface::new(
            P,
            1.0,
            [
                turn(),
                ParamRange {
                    min: -1.0,
                    max: 1.0,
                    periodic: true,
                },
            ],
        ),
        is,
    );
    assert_variant(NurbsCurve::circle_arc(&P, 1.0, 0.0, 7.0), is);
    assert_variant(
        NurbsSurface::revolution(
            &cubic(cubic_knots(), vec![1.0; 5], false).unwrap(),
            DVec3::ZERO,
            DVec3::Z,
            7.0,
        ),
        is,
    );
}

#[test]
fn range_outside_surface() {
    let is = |e: &GeometryError| matches!(e, GeometryError::RangeOutsideSurface { .. });
    assert_variant(
        SphereSurface::new(P, 1.0, [turn(), range(-FRAC_PI_2, 1.6)]),
        is,
    );
    assert_variant(SphereSurface::new(P, 1.0, [turn(), range(-2.0, 0.0)]), is);
    // Apex of R = 1, a = π/6 at v = −2.
    assert_variant(
        ConeSurface::new(P, 1.0, PI / 6.0, [turn(), range(-2.5, 1.0)]),
        is,
    );
    ConeSurface::new(P, 1.0, PI / 6.0, [turn(), range(-2.0, 1.0)]).unwrap();
}

#[test]
fn not_closed() {
    let is = |e: &GeometryError| matches!(e, GeometryError::NotClosed { .. });
    assert_variant(cubic(cubic_knots(), vec![1.0; 5], true), is);
    let open = vec![
        vec![DVec3::ZERO, DVec3::X],
        vec![DVec3::Y, DVec3::ONE],
        vec![DVec3::Z, DVec3::new(1.0, 0.0, 1.0)],
    ];
    let knots = [vec![0.0, 0.0, 0.5, 1.0, 1.0], vec![0.0, 0.0, 1.0, 1.0]];
    assert_variant(
        NurbsSurface::new(
            [1, 1],
            knots.clone(),
            open,
            vec![vec![1.0; 2]; 3],
            [true, false],
        ),
        is,
    );
    // The same net closed (last row = first row) is accepted as periodic in u.
    let closed = vec![
        vec![DVec3::ZERO, DVec3::X],
        vec![DVec3::Y, DVec3::ONE],
        vec![DVec3::ZERO, DVec3::X],
    ];
    NurbsSurface::new(
        [1, 1],
        knots.clone(),
        closed.clone(),
        vec![vec![1.0; 2]; 3],
        [true, false],
    )
    .unwrap();
    // ...but not when the closing row's weights differ (a different boundary curve).
    let weights = vec![vec![1.0, 1.0], vec![1.0, 1.0], vec![1.0, 2.0]];
    assert_variant(
        NurbsSurface::new([1, 1], knots, closed, weights, [true, false]),
        is,
    );
}
