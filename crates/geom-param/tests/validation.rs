//! `validate` refuses every kind of broken B-rep with its own typed error, and accepts what the
//! builders make. Each broken solid is a valid one with one thing changed.

use geom_param::{
    BuildError, Circle2, DVec2, DVec3, EdgeId, FaceId, ParamRange, PlanarProfile, PlanarSegment,
    Solid, TopologyError, TrimEntry, TrimLoop, extrude, tube, validate,
};
use std::f64::consts::TAU;

const TURN: ParamRange = ParamRange {
    min: 0.0,
    max: TAU,
    periodic: true,
};

fn valid_tube() -> Solid {
    tube(12.0, 8.0, 30.0).expect("valid")
}

fn square(side: f64, at: DVec2) -> Vec<PlanarSegment> {
    let c = [
        at,
        at + DVec2::new(side, 0.0),
        at + DVec2::new(side, side),
        at + DVec2::new(0.0, side),
    ];
    (0..4)
        .map(|k| PlanarSegment::Line {
            from: c[k],
            to: c[(k + 1) % 4],
        })
        .collect()
}

fn circle(center: DVec2, radius: f64, ccw: bool) -> Vec<PlanarSegment> {
    let p = center + DVec2::new(radius, 0.0);
    vec![PlanarSegment::Arc {
        center,
        from: p,
        to: p,
        ccw,
    }]
}

fn topology_error(result: Result<Solid, BuildError>) -> TopologyError {
    match result {
        Err(BuildError::Topology(e)) => e,
        other => panic!(
            "expected a topology error, got {:?}",
            other.map(|s| s.faces.len())
        ),
    }
}

#[test]
fn builders_make_valid_solids() {
    assert_eq!(validate(&valid_tube()), Ok(()));
    let plate = PlanarProfile {
        outer: square(10.0, DVec2::ZERO),
        holes: vec![circle(DVec2::splat(5.0), 2.0, false)],
    };
    assert_eq!(validate(&extrude(&plate, 0.0, 1.0).expect("valid")), Ok(()));
}

#[test]
fn a_free_edge_is_an_open_shell() {
    let mut solid = valid_tube();
    // The top cap forgets its hole: the inner top circle then lies on one face only.
    solid.faces[3]
        .trim
        .as_mut()
        .expect("trimmed")
        .loops
        .truncate(1);
    assert!(matches!(
        validate(&solid),
        Err(TopologyError::EdgeUseCount { count: 1, .. }) | Err(TopologyError::BadReference { .. })
    ));
}

#[test]
fn a_reference_to_a_missing_face_is_an_error() {
    let mut solid = valid_tube();
    solid.edges[0].uses[1].face = FaceId(99);
    assert!(matches!(
        validate(&solid),
        Err(TopologyError::BadReference { .. })
    ));
}

#[test]
fn faces_that_run_an_edge_the_same_way_are_inconsistently_oriented() {
    let mut solid = valid_tube();
    let entry = &mut solid.faces[3].trim.as_mut().expect("trimmed").loops[0].entries[0];
    entry.reversed = !entry.reversed;
    assert!(matches!(
        validate(&solid),
        Err(TopologyError::InconsistentOrientation {
            edge: EdgeId(1),
            ..
        })
    ));
}

#[test]
fn a_pcurve_off_its_edge_is_an_error() {
    let mut solid = valid_tube();
    // The top cap's outer loop drawn 0.5 mm too wide.
    let wide = TrimLoop::new(vec![TrimEntry::new(
        EdgeId(1),
        Box::new(Circle2 {
            center: DVec2::ZERO,
            radius: 12.5,
            phase: 0.0,
            sense: 1.0,
            range: TURN,
        }),
        false,
    )]);
    solid.faces[3].trim.as_mut().expect("trimmed").loops[0] = wide;
    match validate(&solid) {
        Err(TopologyError::PCurveOffEdge {
            edge, deviation, ..
        }) => {
            assert_eq!(edge, EdgeId(1));
            assert!((deviation - 0.5).abs() < 1e-9, "{deviation}");
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn a_non_finite_vertex_is_an_error() {
    let plate = PlanarProfile {
        outer: square(10.0, DVec2::ZERO),
        holes: Vec::new(),
    };
    let mut solid = extrude(&plate, 0.0, 1.0).expect("valid");
    solid.vertices[0].point = DVec3::new(f64::NAN, 0.0, 0.0);
    assert!(matches!(
        validate(&solid),
        Err(TopologyError::NonFinite { .. })
    ));
}

#[test]
fn a_self_intersecting_profile_is_refused() {
    // A bow tie: (0,0) -> (10,10) -> (10,0) -> (0,10) -> back.
    let p = DVec2::new;
    let corners = [p(0.0, 0.0), p(10.0, 0.0), p(0.0, 10.0), p(10.0, 10.0)];
    let outer = (0..4)
        .map(|k| PlanarSegment::Line {
            from: corners[k],
            to: corners[(k + 1) % 4],
        })
        .collect();
    let error = topology_error(extrude(
        &PlanarProfile {
            outer,
            holes: Vec::new(),
        },
        0.0,
        1.0,
    ));
    assert!(
        matches!(
            error,
            TopologyError::SelfIntersectingLoop { .. } | TopologyError::WrongLoopOrientation { .. }
        ),
        "{error:?}"
    );
}

#[test]
fn a_hole_crossing_the_outer_loop_is_refused() {
    // Its centre on the boundary: the crossings fall on polyline vertices of the circle.
    let error = topology_error(extrude(
        &PlanarProfile {
            outer: square(10.0, DVec2::ZERO),
            holes: vec![circle(DVec2::new(10.0, 5.0), 2.0, false)],
        },
        0.0,
        1.0,
    ));
    assert!(
        matches!(error, TopologyError::LoopsCross { .. }),
        "{error:?}"
    );
}

#[test]
fn a_hole_outside_or_running_the_wrong_way_is_refused() {
    let outside = topology_error(extrude(
        &PlanarProfile {
            outer: square(10.0, DVec2::ZERO),
            holes: vec![circle(DVec2::new(20.0, 5.0), 2.0, false)],
        },
        0.0,
        1.0,
    ));
    assert!(
        matches!(
            outside,
            TopologyError::WrongLoopOrientation { loop_index: 1, .. }
        ),
        "{outside:?}"
    );
    let counter_clockwise = topology_error(extrude(
        &PlanarProfile {
            outer: square(10.0, DVec2::ZERO),
            holes: vec![circle(DVec2::splat(5.0), 2.0, true)],
        },
        0.0,
        1.0,
    ));
    assert!(
        matches!(
            counter_clockwise,
            TopologyError::WrongLoopOrientation { loop_index: 1, .. }
        ),
        "{counter_clockwise:?}"
    );
}
