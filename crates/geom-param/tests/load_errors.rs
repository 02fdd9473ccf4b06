//! Every `LoadError`, `ProfileError` and `ModelError` variant, produced from malformed object
//! files (JSON text through `ObjectDescription::from_json` and `.build`) or, for non-finite
//! coordinates, from profiles built in code; checks the variant, the segment it names and its
//! message. Also that valid files (a flat-ended cylinder, a two-arc ring) load and build.
#![cfg(feature = "json")]

use geom_param::{
    Closure, DVec3, FaceId, LoadError, MeshOptions, ModelError, ObjectDescription, ObjectModel,
    Profile, ProfileError, SegmentSpec,
};
use std::f64::consts::PI;

// ---------------------------------------------------------------------------------------------
// Writing object files (independently of `ObjectDescription::to_json`).

fn pt(p: [f64; 2]) -> String {
    format!("[{:?}, {:?}]", p[0], p[1])
}

fn segment_json(s: &SegmentSpec) -> String {
    match *s {
        SegmentSpec::Line { from, to } => {
            format!(r#"{{"line": {{"from": {}, "to": {}}}}}"#, pt(from), pt(to))
        }
        SegmentSpec::Arc {
            center,
            from,
            to,
            ccw,
        } => format!(
            r#"{{"arc": {{"center": {}, "from": {}, "to": {}, "ccw": {ccw}}}}}"#,
            pt(center),
            pt(from),
            pt(to)
        ),
        SegmentSpec::Bezier { points } => {
            let list: Vec<String> = points.iter().map(|&p| pt(p)).collect();
            format!(r#"{{"bezier": {{"points": [{}]}}}}"#, list.join(", "))
        }
    }
}

fn object_json(name: &str, specs: &[SegmentSpec]) -> String {
    let list: Vec<String> = specs
        .iter()
        .map(|s| format!("    {}", segment_json(s)))
        .collect();
    format!(
        "{{\n  \"name\": \"{name}\",\n  \"profile\": [\n{}\n  ]\n}}\n",
        list.join(",\n")
    )
}

fn line(from: [f64; 2], to: [f64; 2]) -> SegmentSpec {
    SegmentSpec::Line { from, to }
}

fn arc(center: [f64; 2], from: [f64; 2], to: [f64; 2], ccw: bool) -> SegmentSpec {
    SegmentSpec::Arc {
        center,
        from,
        to,
        ccw,
    }
}

fn bezier(points: [[f64; 2]; 4]) -> SegmentSpec {
    SegmentSpec::Bezier { points }
}

/// The same path walked backwards: segments in reverse order, each one reversed.
fn reversed(specs: &[SegmentSpec]) -> Vec<SegmentSpec> {
    specs
        .iter()
        .rev()
        .map(|s| match *s {
            SegmentSpec::Line { from, to } => line(to, from),
            SegmentSpec::Arc {
                center,
                from,
                to,
                ccw,
            } => arc(center, to, from, !ccw),
            SegmentSpec::Bezier {
                points: [a, b, c, d],
            } => bezier([d, c, b, a]),
        })
        .collect()
}

/// Cylinder r = 10, z in [0, 20] with flat ends, counter-clockwise around the material.
fn cylinder() -> Vec<SegmentSpec> {
    vec![
        line([0.0, 0.0], [10.0, 0.0]),
        line([10.0, 0.0], [10.0, 20.0]),
        line([10.0, 20.0], [0.0, 20.0]),
    ]
}

/// Ring: a circle of radius 5 about (20, 0) as two counter-clockwise half arcs.
fn ring() -> Vec<SegmentSpec> {
    vec![
        arc([20.0, 0.0], [25.0, 0.0], [15.0, 0.0], true),
        arc([20.0, 0.0], [15.0, 0.0], [25.0, 0.0], true),
    ]
}

/// A profile with all three kinds: flat bottom, rounded corner, Bezier flank, flat top.
fn mixed() -> Vec<SegmentSpec> {
    vec![
        line([0.0, 0.0], [8.0, 0.0]),
        arc([8.0, 2.0], [8.0, 0.0], [10.0, 2.0], true),
        bezier([[10.0, 2.0], [10.0, 8.0], [9.0, 14.0], [6.0, 18.0]]),
        line([6.0, 18.0], [0.0, 18.0]),
    ]
}

fn load(text: &str) -> Result<ObjectModel, LoadError> {
    ObjectDescription::from_json(text)?.build(&MeshOptions::default())
}

#[track_caller]
fn load_err(text: &str) -> LoadError {
    match load(text) {
        Ok(model) => panic!("expected an error, loaded {:?}", model.name),
        Err(e) => e,
    }
}

#[track_caller]
fn profile_err(specs: &[SegmentSpec]) -> ProfileError {
    match load_err(&object_json("bad", specs)) {
        LoadError::Profile(e) => e,
        other => panic!("expected a profile error, got {other:?}"),
    }
}

#[track_caller]
fn mentions(error: &impl std::fmt::Display, needles: &[&str]) {
    let text = error.to_string();
    for needle in needles {
        assert!(
            text.contains(needle),
            "message {text:?} does not mention {needle:?}"
        );
    }
}

// ---------------------------------------------------------------------------------------------
// JSON-level errors.

#[test]
fn syntax_errors() {
    let e = load_err(r#"{"name": "cyl", "profile": ["#);
    let LoadError::Syntax {
        line,
        column,
        message,
    } = &e
    else {
        panic!("{e:?}")
    };
    assert_eq!(*line, 1, "{e:?}");
    assert!(*column >= 1 && !message.is_empty(), "{e:?}");
    mentions(&e, &["line 1"]);

    let e = load_err("{\n  \"name\": \"x\",\n  \"profile\": [1, 2,,]\n}\n");
    let LoadError::Syntax { line, column, .. } = &e else {
        panic!("{e:?}")
    };
    assert_eq!((*line, *column), (3, 20), "{e:?}");
    mentions(&e, &["line 3", "column 20"]);

    // Not a JSON document at all, and a trailing comma in an object.
    assert!(matches!(
        load_err("cylinder please"),
        LoadError::Syntax { line: 1, .. }
    ));
    assert!(matches!(
        load_err(r#"{"name": "x",}"#),
        LoadError::Syntax { .. }
    ));
    assert!(matches!(load_err(""), LoadError::Syntax { .. }));
}

#[test]
fn number_out_of_range_is_a_syntax_error() {
    // JSON has no NaN or infinity; 1e400 overflows f64 and must be rejected by the parser, not
    // turn into an infinite coordinate or a panic.
    let text = r#"{"name": "big", "profile": [{"line": {"from": [0, 0], "to": [1e400, 0]}}]}"#;
    let result = std::panic::catch_unwind(|| ObjectDescription::from_json(text));
    let e = result
        .expect("from_json panicked on 1e400")
        .expect_err("1e400 accepted");
    let LoadError::Syntax { line, message, .. } = &e else {
        panic!("{e:?}")
    };
    assert_eq!(*line, 1);
    assert!(message.contains("out of range"), "{message}");
    let e =
        load_err(r#"{"name": "big", "profile": [{"line": {"from": [0, -1e400], "to": [1, 0]}}]}"#);
    assert!(matches!(e, LoadError::Syntax { .. }), "{e:?}");
}

#[test]
fn unknown_fields() {
    // Top level.
    let text = r#"{"name": "cyl", "colour": "red", "profile": []}"#;
    let e = load_err(text);
    assert_eq!(
        e,
        LoadError::UnknownField {
            path: "object".into(),
            field: "colour".into()
        }
    );
    mentions(&e, &["colour", "object"]);

    // Inside the body of segment 1.
    let mut specs: Vec<String> = cylinder().iter().map(segment_json).collect();
    specs[1] = r#"{"line": {"from": [10, 0], "to": [10, 20], "width": 2}}"#.into();
    let text = format!(r#"{{"name": "cyl", "profile": [{}]}}"#, specs.join(", "));
    let e = load_err(&text);
    assert_eq!(
        e,
        LoadError::UnknownField {
            path: "object.profile[1].line".into(),
            field: "width".into()
        }
    );
    mentions(&e, &["profile[1]", "width"]);

    // An unknown segment kind (segment 2).
    let mut specs: Vec<String> = cylinder().iter().map(segment_json).collect();
    specs[2] = r#"{"spline": {"points": [[10, 20], [0, 20]]}}"#.into();
    let text = format!(r#"{{"name": "cyl", "profile": [{}]}}"#, specs.join(", "));
    let e = load_err(&text);
    assert_eq!(
        e,
        LoadError::UnknownField {
            path: "object.profile[2]".into(),
            field: "spline".into()
        }
    );
    mentions(&e, &["profile[2]", "spline"]);

    // In an arc.
    let text = r#"{"name": "r", "profile": [
        {"arc": {"center": [20, 0], "from": [25, 0], "to": [15, 0], "ccw": true, "radius": 5}}]}"#;
    let e = load_err(text);
    assert_eq!(
        e,
        LoadError::UnknownField {
            path: "object.profile[0].arc".into(),
            field: "radius".into()
        }
    );
}

#[test]
fn missing_fields() {
    let e = load_err(r#"{"profile": []}"#);
    assert_eq!(
        e,
        LoadError::MissingField {
            path: "object".into(),
            field: "name"
        }
    );
    mentions(&e, &["name"]);

    let e = load_err(r#"{"name": "x"}"#);
    assert_eq!(
        e,
        LoadError::MissingField {
            path: "object".into(),
            field: "profile"
        }
    );

    // Segment 1 is an arc without `ccw`.
    let text = r#"{"name": "r", "profile": [
        {"arc": {"center": [20, 0], "from": [25, 0], "to": [15, 0], "ccw": true}},
        {"arc": {"center": [20, 0], "from": [15, 0], "to": [25, 0]}}]}"#;
    let e = load_err(text);
    assert_eq!(
        e,
        LoadError::MissingField {
            path: "object.profile[1].arc".into(),
            field: "ccw"
        }
    );
    mentions(&e, &["profile[1]", "ccw"]);

    // Segment 0 is a line without `to`; segment 2 a Bezier without points.
    let e = load_err(r#"{"name": "x", "profile": [{"line": {"from": [0, 0]}}]}"#);
    assert_eq!(
        e,
        LoadError::MissingField {
            path: "object.profile[0].line".into(),
            field: "to"
        }
    );
    let mut specs: Vec<String> = cylinder().iter().map(segment_json).collect();
    specs[2] = r#"{"bezier": {}}"#.into();
    let text = format!(r#"{{"name": "cyl", "profile": [{}]}}"#, specs.join(", "));
    let e = load_err(&text);
    assert_eq!(
        e,
        LoadError::MissingField {
            path: "object.profile[2].bezier".into(),
            field: "points"
        }
    );
    mentions(&e, &["profile[2]", "points"]);
}

#[test]
fn wrong_types() {
    let cases: &[(&str, &str, &str)] = &[
        (r#"[1, 2]"#, "object", "an object"),
        (r#"{"name": 5, "profile": []}"#, "object.name", "a string"),
        (
            r#"{"name": "x", "note": ["a"], "profile": []}"#,
            "object.note",
            "a string",
        ),
        (
            r#"{"name": "x", "profile": {}}"#,
            "object.profile",
            "an array of segments",
        ),
        (
            r#"{"name": "x", "profile": [7]}"#,
            "object.profile[0]",
            "an object",
        ),
        (
            r#"{"name": "x", "profile": [{"line": {"from": [0, 0], "to": [1, 0]}}, {"line": {"from": [1, 0], "to": [1, 2, 3]}}]}"#,
            "object.profile[1].line.to",
            "a point [r, z] of two numbers",
        ),
        (
            r#"{"name": "x", "profile": [{"line": {"from": ["0", 0], "to": [1, 0]}}]}"#,
            "object.profile[0].line.from",
            "a point [r, z] of two numbers",
        ),
        (
            r#"{"name": "x", "profile": [{"line": {"from": [0, 0], "to": [1, 0]}}, {"arc": {"center": [1, 1], "from": [1, 0], "to": [2, 1], "ccw": "yes"}}]}"#,
            "object.profile[1].arc.ccw",
            "true or false",
        ),
        (
            r#"{"name": "x", "profile": [{"bezier": {"points": [[0, 0], [1, 0], [2, 0]]}}]}"#,
            "object.profile[0].bezier.points",
            "four control points",
        ),
        (
            r#"{"name": "x", "profile": [{"line": {"from": [0, 0], "to": [1, 0]}}, {"line": {"from": [1, 0], "to": [1, 2]}, "arc": {}}]}"#,
            "object.profile[1]",
            "exactly one of `line`, `arc`, `bezier`",
        ),
        (
            r#"{"name": "x", "profile": [{}]}"#,
            "object.profile[0]",
            "exactly one of `line`, `arc`, `bezier`",
        ),
        (
            r#"{"name": "x", "profile": [{"line": [0, 0, 1, 0]}]}"#,
            "object.profile[0].line",
            "an object",
        ),
    ];
    for &(text, path, expected) in cases {
        let e = load_err(text);
        assert_eq!(
            e,
            LoadError::WrongType {
                path: path.into(),
                expected
            },
            "{text}"
        );
        mentions(&e, &[path, expected]);
    }
}

// ---------------------------------------------------------------------------------------------
// Profile errors, from JSON text through `build`.

#[test]
fn empty_profile() {
    let e = load_err(r#"{"name": "nothing", "profile": []}"#);
    assert_eq!(e, LoadError::Profile(ProfileError::Empty));
    mentions(&e, &["no segments"]);
}

#[test]
fn gap_between_segments() {
    let mut specs = cylinder();
    specs[1] = line([10.0, 1.0], [10.0, 20.0]);
    let e = profile_err(&specs);
    assert_eq!(
        e,
        ProfileError::Gap {
            segment: 1,
            previous: 0,
            start: [10.0, 1.0],
            end: [10.0, 0.0],
            gap: 1.0
        }
    );
    mentions(&e, &["segment 1", "segment 0"]);
    // A gap just above the joining tolerance (1e-9 of the size 20) is still a gap; just below it
    // is closed.
    let mut specs = cylinder();
    specs[2] = line([10.0, 20.0 + 1e-7], [0.0, 20.0]);
    assert!(matches!(
        profile_err(&specs),
        ProfileError::Gap {
            segment: 2,
            previous: 1,
            ..
        }
    ));
    let mut specs = cylinder();
    specs[2] = line([10.0, 20.0 + 1e-9], [0.0, 20.0]);
    load(&object_json("almost", &specs)).expect("a 1e-9 mm gap is closed");
}

#[test]
fn negative_radius() {
    // Segment 3: a clockwise half circle about (2, 25) of radius 5 bulging across the axis to
    // r = 2 - 5 = -3 (at its middle, θ = π).
    let specs = vec![
        line([0.0, 0.0], [10.0, 0.0]),
        line([10.0, 0.0], [10.0, 20.0]),
        line([10.0, 20.0], [2.0, 20.0]),
        arc([2.0, 25.0], [2.0, 20.0], [2.0, 30.0], false),
        line([2.0, 30.0], [0.0, 30.0]),
    ];
    let e = profile_err(&specs);
    let ProfileError::NegativeRadius { segment, kind, r } = e else {
        panic!("{e:?}")
    };
    assert_eq!((segment, kind), (3, "arc"));
    assert!(
        (r + 3.0).abs() <= 1e-12 * 30.0,
        "smallest r {r}, expected -3"
    );
    mentions(&e, &["segment 3", "arc"]);

    // Segment 2: a line over to r = -5.
    let specs = vec![
        line([0.0, 0.0], [10.0, 0.0]),
        line([10.0, 0.0], [10.0, 20.0]),
        line([10.0, 20.0], [-5.0, 20.0]),
        line([-5.0, 20.0], [0.0, 30.0]),
    ];
    let e = profile_err(&specs);
    assert_eq!(
        e,
        ProfileError::NegativeRadius {
            segment: 2,
            kind: "line",
            r: -5.0
        }
    );
    mentions(&e, &["segment 2", "line"]);
}

/// `NegativeRadius::r` is documented as "the smallest r reached"; the arc below (centre
/// (-1, 20), radius 5, counter-clockwise from θ = 0 to θ = 0.9π) first goes negative at θ = π/2
/// (r = -1) and reaches its smallest r = -1 + 5 cos(0.9π) ≈ -5.755 at its end.
#[test]
fn negative_radius_reports_the_smallest_r() {
    let theta = 0.9 * PI;
    let end = [-1.0 + 5.0 * theta.cos(), 20.0 + 5.0 * theta.sin()];
    let specs = vec![
        line([0.0, 0.0], [10.0, 0.0]),
        line([10.0, 0.0], [10.0, 20.0]),
        line([10.0, 20.0], [4.0, 20.0]),
        arc([-1.0, 20.0], [4.0, 20.0], end, true),
        line(end, [0.0, 30.0]),
    ];
    let e = profile_err(&specs);
    let ProfileError::NegativeRadius { segment, kind, r } = e else {
        panic!("{e:?}")
    };
    assert_eq!((segment, kind), (3, "arc"));
    assert!(
        (r - end[0]).abs() <= 1e-9 * 30.0,
        "reported r = {r}, smallest r = {}",
        end[0]
    );
}

#[test]
fn touches_axis() {
    // Segment 3: a clockwise half circle about (5, 25) of radius 5, tangent to the axis at
    // (0, 25) in its middle.
    let specs = vec![
        line([0.0, 0.0], [10.0, 0.0]),
        line([10.0, 0.0], [10.0, 20.0]),
        line([10.0, 20.0], [5.0, 20.0]),
        arc([5.0, 25.0], [5.0, 20.0], [5.0, 30.0], false),
        line([5.0, 30.0], [0.0, 30.0]),
    ];
    let e = profile_err(&specs);
    assert_eq!(
        e,
        ProfileError::TouchesAxis {
            segment: 3,
            kind: "arc"
        }
    );
    mentions(&e, &["segment 3", "arc"]);

    // Segment 1 ends on the axis although the profile goes on.
    let specs = vec![
        line([0.0, 0.0], [10.0, 0.0]),
        line([10.0, 0.0], [0.0, 10.0]),
        line([0.0, 10.0], [10.0, 20.0]),
        line([10.0, 20.0], [0.0, 20.0]),
    ];
    let e = profile_err(&specs);
    assert_eq!(
        e,
        ProfileError::TouchesAxis {
            segment: 1,
            kind: "line"
        }
    );
    mentions(&e, &["segment 1", "line"]);
}

#[test]
fn arc_radius_mismatch() {
    // Segment 1: from (8, 0) is 2 from the centre (8, 2), to (10, 2.5) is √4.25.
    let specs = vec![
        line([0.0, 0.0], [8.0, 0.0]),
        arc([8.0, 2.0], [8.0, 0.0], [10.0, 2.5], true),
        line([10.0, 2.5], [10.0, 20.0]),
        line([10.0, 20.0], [0.0, 20.0]),
    ];
    let e = profile_err(&specs);
    let ProfileError::ArcRadiusMismatch {
        segment,
        from_radius,
        to_radius,
    } = e
    else {
        panic!("{e:?}")
    };
    assert_eq!(segment, 1);
    assert_eq!(from_radius, 2.0);
    assert!((to_radius - 4.25_f64.sqrt()).abs() <= 1e-15, "{to_radius}");
    mentions(&e, &["segment 1", "arc"]);
}

#[test]
fn zero_length_segments() {
    let c = cylinder();
    let cases: Vec<(SegmentSpec, &str)> = vec![
        // A line from a point to itself.
        (line([10.0, 0.0], [10.0, 0.0]), "line"),
        // A Bezier whose four control points coincide.
        (bezier([[10.0, 0.0]; 4]), "bezier"),
        // An arc from a point to itself (a full circle or nothing).
        (arc([10.0, 5.0], [10.0, 0.0], [10.0, 0.0], true), "arc"),
    ];
    for (spec, kind) in cases {
        let specs = vec![c[0], spec, c[1], c[2]];
        let e = profile_err(&specs);
        assert_eq!(e, ProfileError::ZeroLength { segment: 1, kind }, "{spec:?}");
        mentions(&e, &["segment 1", kind]);
    }
    // A Bezier with a collapsed control leg (P1 = P0): its tangent vanishes at the start.
    let specs = vec![
        c[0],
        bezier([[10.0, 0.0], [10.0, 0.0], [10.0, 15.0], [10.0, 20.0]]),
        c[2],
    ];
    let e = profile_err(&specs);
    assert_eq!(
        e,
        ProfileError::ZeroLength {
            segment: 1,
            kind: "bezier"
        }
    );
    // A degenerate arc of radius 0.
    let specs = vec![
        c[0],
        arc([10.0, 0.0], [10.0, 0.0], [10.0, 0.0], false),
        c[1],
        c[2],
    ];
    assert_eq!(
        profile_err(&specs),
        ProfileError::ZeroLength {
            segment: 1,
            kind: "arc"
        }
    );
}

#[test]
fn self_intersection() {
    // Axis profile whose segment 2 dives back across the bottom (segment 0) at z = 0:
    // (10, 10) → (5, -5) crosses z = 0 at t = 2/3, r = 10 - 5·2/3 = 20/3.
    let specs = vec![
        line([0.0, 0.0], [10.0, 0.0]),
        line([10.0, 0.0], [10.0, 10.0]),
        line([10.0, 10.0], [5.0, -5.0]),
        line([5.0, -5.0], [0.0, -5.0]),
    ];
    let e = profile_err(&specs);
    let ProfileError::SelfIntersection { first, second, at } = e else {
        panic!("{e:?}")
    };
    assert_eq!((first, second), (0, 2));
    assert!(
        (at[0] - 20.0 / 3.0).abs() <= 1e-12 * 10.0 && at[1].abs() <= 1e-12 * 10.0,
        "{at:?}"
    );
    mentions(&e, &["segments 0 and 2"]);

    // A figure-8 (bow-tie) ring: segments 0 and 2 cross at (7.5, 5).
    let specs = vec![
        line([5.0, 0.0], [10.0, 10.0]),
        line([10.0, 10.0], [10.0, 0.0]),
        line([10.0, 0.0], [5.0, 10.0]),
        line([5.0, 10.0], [5.0, 0.0]),
    ];
    let e = profile_err(&specs);
    let ProfileError::SelfIntersection { first, second, at } = e else {
        panic!("{e:?}")
    };
    assert_eq!((first, second), (0, 2));
    assert!(
        (at[0] - 7.5).abs() <= 1e-12 * 10.0 && (at[1] - 5.0).abs() <= 1e-12 * 10.0,
        "{at:?}"
    );
    mentions(&e, &["segments 0 and 2"]);

    // A Bezier that loops over itself (segment 1): P = (10,0), (40,30), (-10,30), (20,0) crosses
    // its own path at r = 15 by symmetry about r = 15.
    let specs = vec![
        line([0.0, 0.0], [10.0, 0.0]),
        bezier([[10.0, 0.0], [40.0, 30.0], [-10.0, 30.0], [20.0, 0.0]]),
        line([20.0, 0.0], [30.0, 0.0]),
        line([30.0, 0.0], [30.0, 40.0]),
        line([30.0, 40.0], [0.0, 40.0]),
    ];
    let e = profile_err(&specs);
    let ProfileError::SelfIntersection { first, second, at } = e else {
        panic!("{e:?}")
    };
    assert_eq!((first, second), (1, 1), "{e:?}");
    assert!((at[0] - 15.0).abs() <= 0.5, "{at:?}");
    mentions(&e, &["segments 1 and 1"]);
}

/// A ring whose profile is one closed Bezier (P0 = P3, a teardrop with one corner) has a
/// non-zero length and a non-vanishing tangent, and `check_self_intersection` explicitly allows
/// "a single closed segment's own ends"; it should be accepted.
#[test]
fn single_closed_bezier_ring_is_valid() {
    let specs = [bezier([
        [10.0, 0.0],
        [30.0, -10.0],
        [30.0, 20.0],
        [10.0, 0.0],
    ])];
    let profile = Profile::new(&specs).expect("a closed Bezier ring is a valid profile");
    assert_eq!(profile.closure(), Closure::Ring);
}

#[test]
fn cusp() {
    // Segment 1 goes up to z = 20, segment 2 comes straight back down.
    let specs = vec![
        line([0.0, 0.0], [10.0, 0.0]),
        line([10.0, 0.0], [10.0, 20.0]),
        line([10.0, 20.0], [10.0, 10.0]),
        line([10.0, 10.0], [0.0, 10.0]),
    ];
    let e = profile_err(&specs);
    assert_eq!(
        e,
        ProfileError::Cusp {
            first: 1,
            second: 2
        }
    );
    mentions(&e, &["segments 1 and 2"]);

    // A ring whose closing joint (segment 3 back into segment 0) folds back.
    let specs = vec![
        line([5.0, 0.0], [10.0, 0.0]),
        line([10.0, 0.0], [10.0, 10.0]),
        line([10.0, 10.0], [8.0, 0.0]),
        line([8.0, 0.0], [5.0, 0.0]),
    ];
    let e = profile_err(&specs);
    assert_eq!(
        e,
        ProfileError::Cusp {
            first: 3,
            second: 0
        }
    );
    mentions(&e, &["segments 3 and 0"]);

    // An arc leaving tangentially backwards: segment 0 ends going +r at (10, 0); the arc about
    // (10, 2) starting there clockwise leaves going -r.
    let specs = vec![
        line([0.0, 0.0], [10.0, 0.0]),
        arc([10.0, 2.0], [10.0, 0.0], [12.0, 2.0], false),
        line([12.0, 2.0], [12.0, 20.0]),
        line([12.0, 20.0], [0.0, 20.0]),
    ];
    assert_eq!(
        profile_err(&specs),
        ProfileError::Cusp {
            first: 0,
            second: 1
        }
    );
}

#[test]
fn not_closed() {
    let specs = vec![
        line([0.0, 0.0], [10.0, 0.0]),
        line([10.0, 0.0], [10.0, 20.0]),
    ];
    let e = profile_err(&specs);
    assert_eq!(
        e,
        ProfileError::NotClosed {
            start: [0.0, 0.0],
            end: [10.0, 20.0]
        }
    );
    mentions(&e, &["[0.0, 0.0]", "[10.0, 20.0]"]);
    // Ring-like but open.
    let specs = vec![arc([20.0, 0.0], [25.0, 0.0], [15.0, 0.0], true)];
    let e = profile_err(&specs);
    assert_eq!(
        e,
        ProfileError::NotClosed {
            start: [25.0, 0.0],
            end: [15.0, 0.0]
        }
    );
}

#[test]
fn wrong_orientation() {
    // The cylinder walked clockwise: signed area -(10 × 20) (the run along the axis adds 0).
    let e = profile_err(&reversed(&cylinder()));
    let ProfileError::WrongOrientation { area } = e else {
        panic!("{e:?}")
    };
    assert!((area + 200.0).abs() <= 1e-12 * 200.0, "area {area}");
    mentions(&e, &["clockwise"]);

    // The ring walked clockwise: area -π·5², up to the polyline approximation of the arcs (an
    // inscribed polygon with pieces of at most a few degrees is within 1e-3 of the disk).
    let e = profile_err(&reversed(&ring()));
    let ProfileError::WrongOrientation { area } = e else {
        panic!("{e:?}")
    };
    assert!(
        area < 0.0 && (area + 25.0 * PI).abs() <= 1e-3 * 25.0 * PI,
        "area {area}"
    );

    // A line / arc / Bezier profile walked backwards.
    let e = profile_err(&reversed(&mixed()));
    let ProfileError::WrongOrientation { area } = e else {
        panic!("{e:?}")
    };
    assert!(area < -100.0, "area {area}");
}

#[test]
fn not_finite_coordinates() {
    // JSON cannot carry NaN, so these profiles are built in code.
    let nan = Profile::new(&[
        line([f64::NAN, 0.0], [10.0, 0.0]),
        line([10.0, 0.0], [10.0, 20.0]),
        line([10.0, 20.0], [0.0, 20.0]),
    ]);
    let e = nan.expect_err("NaN accepted");
    assert_eq!(
        e,
        ProfileError::NotFinite {
            segment: 0,
            kind: "line"
        }
    );
    mentions(&e, &["segment 0", "line"]);

    let c = cylinder();
    let e = Profile::new(&[
        c[0],
        arc([10.0, f64::NEG_INFINITY], [10.0, 0.0], [10.0, 20.0], true),
        c[2],
    ])
    .expect_err("-inf accepted");
    assert_eq!(
        e,
        ProfileError::NotFinite {
            segment: 1,
            kind: "arc"
        }
    );
    mentions(&e, &["segment 1", "arc"]);

    let specs = vec![
        c[0],
        c[1],
        bezier([[10.0, 20.0], [5.0, f64::INFINITY], [2.0, 20.0], [0.0, 20.0]]),
    ];
    let e = Profile::new(&specs).expect_err("inf accepted");
    assert_eq!(
        e,
        ProfileError::NotFinite {
            segment: 2,
            kind: "bezier"
        }
    );
    // Through the object description too.
    let description = ObjectDescription {
        name: "inf".into(),
        note: None,
        profile: specs,
    };
    let e = description
        .build(&MeshOptions::default())
        .expect_err("inf accepted");
    assert_eq!(
        e,
        LoadError::Profile(ProfileError::NotFinite {
            segment: 2,
            kind: "bezier"
        })
    );
    mentions(&e, &["segment 2", "bezier"]);
}

#[test]
fn bad_tolerance() {
    let description =
        ObjectDescription::from_json(&object_json("cyl", &cylinder())).expect("parses");
    // Size of the cylinder: its largest coordinate, 20 mm. Usable: [2e-5, 1] × 20 mm.
    for tolerance in [
        0.0,
        -0.0,
        -0.05,
        f64::NAN,
        f64::INFINITY,
        f64::NEG_INFINITY,
        1e-9,
        3.9e-4,
        25.0,
    ] {
        let e = description
            .build(&MeshOptions {
                chordal_tolerance: tolerance,
            })
            .expect_err(&format!("tolerance {tolerance} accepted"));
        let LoadError::Model(ModelError::BadTolerance {
            tolerance: t,
            scale,
        }) = &e
        else {
            panic!("{e:?}")
        };
        assert!(t.to_bits() == tolerance.to_bits(), "{t} vs {tolerance}");
        assert_eq!(*scale, 20.0);
        mentions(&e, &[&tolerance.to_string()]);
    }
}

// ---------------------------------------------------------------------------------------------
// Valid files.

#[test]
fn cylinder_with_flat_ends_loads_and_builds() {
    let text = r#"{
  "name": "cylinder",
  "note": "r = 10, h = 20",
  "profile": [
    {"line": {"from": [0, 0], "to": [10, 0]}},
    {"line": {"from": [10, 0], "to": [10, 20]}},
    {"line": {"from": [10, 20], "to": [0, 20]}}
  ]
}"#;
    let description = ObjectDescription::from_json(text).expect("parses");
    assert_eq!(description.name, "cylinder");
    assert_eq!(description.note.as_deref(), Some("r = 10, h = 20"));
    assert_eq!(description.profile, cylinder());
    let model = description.build(&MeshOptions::default()).expect("builds");
    assert_eq!(model.name, "cylinder");
    assert_eq!(
        model.profile.as_ref().expect("revolved").closure(),
        Closure::Axis
    );
    assert_eq!(
        model.profile.as_ref().expect("revolved").segments().len(),
        3
    );
    let solid = &model.solid;
    assert_eq!(
        (solid.faces.len(), solid.edges.len(), solid.vertices.len()),
        (3, 2, 2)
    );
    // Edges: circles r = 10 at z = 0 and z = 20. Vertices: the disk centres.
    for (edge, z) in solid.edges.iter().zip([0.0, 20.0]) {
        let p = edge.curve.eval(PI / 2.0).point;
        assert!(
            (p - DVec3::new(0.0, 10.0, z)).length() <= 1e-12 * 20.0,
            "{p:?}"
        );
    }
    assert_eq!(solid.vertices[0].point, DVec3::new(0.0, 0.0, 0.0));
    assert_eq!(solid.vertices[1].point, DVec3::new(0.0, 0.0, 20.0));
    // Normals: bottom -z, side radial, top +z.
    let expected = [DVec3::NEG_Z, DVec3::X, DVec3::Z];
    for (face, n) in solid.faces.iter().zip(expected) {
        let got = face.surface.normal(0.0, 0.5).expect("normal");
        assert!((got - n).length() <= 1e-12, "{got:?} vs {n:?}");
    }
    // One convex component, meshed within the requested tolerance.
    assert_eq!(model.components.len(), 1);
    assert_eq!(model.component_of_face(FaceId(1)), model.components[0].id);
    assert!(model.meshes.iter().all(|m| !m.triangles.is_empty()));
    assert!(model.meshes.iter().all(|m| m.chordal_error <= 0.05 + 1e-12));
}

#[test]
fn two_arc_ring_loads_and_builds() {
    let text = object_json("ring", &ring());
    let model = load(&text).expect("ring builds");
    assert_eq!(
        model.profile.as_ref().expect("revolved").closure(),
        Closure::Ring
    );
    let solid = &model.solid;
    assert_eq!(
        (solid.faces.len(), solid.edges.len(), solid.vertices.len()),
        (2, 2, 0)
    );
    // Edges at the outer (r = 25) and inner (r = 15) equator circles, in joint order (0 → 1 at
    // (15, 0), then the closing joint 1 → 0 at (25, 0)).
    for (edge, r) in solid.edges.iter().zip([15.0, 25.0]) {
        let p = edge.curve.eval(0.0).point;
        assert!(
            (p - DVec3::new(r, 0.0, 0.0)).length() <= 1e-12 * 25.0,
            "{p:?}"
        );
    }
    // Mid-points of the two faces: the top (+z) and the bottom (-z) of the tube.
    for (face, nz) in solid.faces.iter().zip([1.0, -1.0]) {
        let p = face.surface.eval(1.0, 0.5).point;
        assert!(
            (p - DVec3::new(20.0 * 1.0_f64.cos(), 20.0 * 1.0_f64.sin(), 5.0 * nz)).length()
                <= 1e-12 * 25.0
        );
        let n = face.surface.normal(1.0, 0.5).expect("normal");
        assert!((n - DVec3::new(0.0, 0.0, nz)).length() <= 1e-12, "{n:?}");
    }
    assert!(!model.components.is_empty());
    assert!(model.meshes.iter().all(|m| !m.triangles.is_empty()));
    // The other valid profile used above builds too.
    load(&object_json("mixed", &mixed())).expect("mixed profile builds");
}
