//! Bad STEP input: each case gives its typed [`StepError`] naming the entity type and `#id`,
//! never a panic, a hang or a NaN. The cases are edits of the shipped real exports
//! (`fixtures/step/`) and small files written here.

use geom_param::step::part21::MAX_ENTITIES;
use geom_param::step::{StepError, read_step};
use std::time::Instant;

fn fixture(name: &str) -> String {
    let path = format!("{}/../../fixtures/step/{name}", env!("CARGO_MANIFEST_DIR"));
    // The SolidWorks exports end their lines with CR LF; the edits below are written with LF.
    std::fs::read_to_string(&path)
        .unwrap_or_else(|e| panic!("{path}: {e}"))
        .replace("\r\n", "\n")
}

/// The cube and cylinder of CadQuery's test data (two solids, 18 kB).
fn cube() -> String {
    fixture("red_cube_blue_cylinder.step")
}

/// `text` with `from` replaced by `to`, which must occur exactly once.
fn edit(text: &str, from: &str, to: &str) -> String {
    assert_eq!(text.matches(from).count(), 1, "{from:?} occurs once");
    text.replacen(from, to, 1)
}

fn err(text: &str) -> StepError {
    match read_step(text.as_bytes()) {
        Ok(solids) => panic!("expected an error, read {} solids", solids.len()),
        Err(e) => e,
    }
}

const HEADER: &str = "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION((''),'2;1');\nFILE_NAME('t','',(''),(''),'','','');\nFILE_SCHEMA(('AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }'));\nENDSEC;\nDATA;\n";
const FOOTER: &str = "ENDSEC;\nEND-ISO-10303-21;\n";

#[test]
fn the_unedited_files_read() {
    assert_eq!(read_step(cube().as_bytes()).expect("reads").len(), 2);
}

#[test]
fn truncated_file() {
    let text = cube();
    for cut in [text.len() / 2, text.len() - 30, 200] {
        let e = err(&text[..cut]);
        assert!(
            matches!(e, StepError::Truncated { .. }),
            "cut at {cut}: {e}"
        );
    }
}

#[test]
fn wrong_header_or_schema() {
    let e = err(&edit(
        &cube(),
        "ISO-10303-21;\nHEADER;",
        "ISO-10303-28;\nHEADER;",
    ));
    assert!(matches!(e, StepError::NotStep { .. }), "{e}");
    let e = err(&edit(
        &cube(),
        "AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }",
        "IFC2X3",
    ));
    assert_eq!(
        e,
        StepError::UnsupportedSchema {
            schema: "IFC2X3".into()
        }
    );
    let e = err(&edit(&cube(), "HEADER;", "HEADERS;"));
    assert!(matches!(e, StepError::Syntax { .. }), "{e}");
}

#[test]
fn missing_id() {
    let e = err(&edit(
        &cube(),
        "#106 = CLOSED_SHELL( '', ( #44, #50, #54 ) );",
        "#106 = CLOSED_SHELL( '', ( #44, #50, #54, #99999 ) );",
    ));
    assert_eq!(
        e,
        StepError::MissingReference {
            id: 106,
            entity: "CLOSED_SHELL".into(),
            target: 99999
        }
    );
}

#[test]
fn reference_cycle() {
    // The plane's placement refers back to the face that uses the plane.
    let e = err(&edit(
        &cube(),
        "#78 = PLANE( '', #118 );",
        "#78 = PLANE( '', #38 );",
    ));
    assert!(matches!(e, StepError::ReferenceCycle { .. }), "{e}");
    let e = err(&format!(
        "{HEADER}#1 = MANIFOLD_SOLID_BREP('',#2);\n#2 = CLOSED_SHELL('',(#3));\n#3 = ADVANCED_FACE('',(#4),#5,.T.);\n#4 = FACE_BOUND('',#2,.T.);\n#5 = PLANE('',#6);\n#6 = CARTESIAN_POINT('',(0.,0.,0.));\n{FOOTER}"
    ));
    assert_eq!(
        e,
        StepError::ReferenceCycle {
            id: 2,
            entity: "CLOSED_SHELL".into()
        }
    );
}

#[test]
fn unsupported_entity_in_the_brep() {
    let e = err(&edit(
        &cube(),
        "#103 = CYLINDRICAL_SURFACE( '', #143, 0.00500000000000000 );",
        "#103 = OFFSET_SURFACE( '', #143, 0.005, .F. );",
    ));
    assert_eq!(
        e,
        StepError::Unsupported {
            id: 103,
            entity: "OFFSET_SURFACE".into(),
            role: "a face surface"
        }
    );
    let e = err(&edit(
        &cube(),
        "#255 = CIRCLE( '', #298, 0.00500000000000000 );",
        "#255 = HYPERBOLA( '', #298, 0.005, 0.002 );",
    ));
    assert_eq!(
        e,
        StepError::Unsupported {
            id: 255,
            entity: "HYPERBOLA".into(),
            role: "an edge curve"
        }
    );
}

#[test]
fn open_shell() {
    // The cube without its face #38.
    let e = err(&edit(
        &cube(),
        "( #46, #40, #52, #48, #42, #38 )",
        "( #46, #40, #52, #48, #42 )",
    ));
    assert!(
        matches!(
            e,
            StepError::OpenShell {
                solid: 61,
                count: 1,
                ..
            }
        ),
        "{e}"
    );
}

#[test]
fn loop_that_does_not_close() {
    // One oriented edge of a square loop turned around: its start is a side's length away.
    let e = err(&edit(
        &cube(),
        "#146 = ORIENTED_EDGE( '', *, *, #210, .T. );",
        "#146 = ORIENTED_EDGE( '', *, *, #210, .F. );",
    ));
    assert!(
        matches!(e, StepError::LoopNotClosed { id: 117, gap, .. } if (gap - 10.0).abs() < 1e-6),
        "{e}"
    );
}

#[test]
fn nurbs_with_bad_knots_or_weights() {
    let text = fixture("solidworks_featuretype.step");
    // Multiplicities that do not add up to points + degree + 1.
    let e = err(&edit(
        &text,
        " ( 4, 1, 1, 1, 1, 1, 1, 4 ),\n ( 0.1804171056932548400",
        " ( 4, 1, 1, 1, 1, 1, 1, 3 ),\n ( 0.1804171056932548400",
    ));
    assert!(matches!(e, StepError::Geometry { id: 381, .. }), "{e}");
    // Decreasing knots.
    let e = err(&edit(
        &text,
        "( 0.1804171056932548400, 0.2574214255684045300,",
        "( 0.2574214255684045300, 0.1804171056932548400,",
    ));
    assert!(matches!(e, StepError::Geometry { id: 381, .. }), "{e}");
    // A multiplicity that is not a positive integer.
    let e = err(&edit(
        &text,
        " ( 4, 1, 1, 1, 1, 1, 1, 4 ),\n ( 0.1804171056932548400",
        " ( 4, 1, 1, 0, 1, 1, 1, 4 ),\n ( 0.1804171056932548400",
    ));
    assert!(matches!(e, StepError::Malformed { id: 381, .. }), "{e}");
    // The rational complex form: unit weights read as the plain curve, a negative weight not.
    let plain = "#381 = B_SPLINE_CURVE_WITH_KNOTS ( 'NONE', 3,\n ( #1303, #628, #2703, #1286, #2941, #616, #2475, #1096, #1797, #2925 ),\n .UNSPECIFIED., .F., .F.,\n ( 4, 1, 1, 1, 1, 1, 1, 4 ),";
    let knots = "( 0.1804171056932548400, 0.2574214255684045300, 0.3271167815832054000, 0.3787956272272490800, 0.4753932694299508600, 0.5595206077257001100, 0.6412861705332345600, 0.6905092016622677000 )";
    let points = "( #1303, #628, #2703, #1286, #2941, #616, #2475, #1096, #1797, #2925 )";
    let make = |weights: &str| {
        let complex = format!(
            "#381 = ( BOUNDED_CURVE() B_SPLINE_CURVE(3, {points}, .UNSPECIFIED., .F., .F.) B_SPLINE_CURVE_WITH_KNOTS(( 4, 1, 1, 1, 1, 1, 1, 4 ), {knots}, .UNSPECIFIED.) CURVE() GEOMETRIC_REPRESENTATION_ITEM() RATIONAL_B_SPLINE_CURVE(({weights})) REPRESENTATION_ITEM('NONE') );"
        );
        edit(
            &text,
            &format!("{plain}\n {knots},\n .UNSPECIFIED. ) ;"),
            &complex,
        )
    };
    read_step(make("1.,1.,1.,1.,1.,1.,1.,1.,1.,1.").as_bytes()).expect("unit weights read");
    let e = err(&make("1.,1.,1.,-1.,1.,1.,1.,1.,1.,1."));
    assert!(matches!(e, StepError::Geometry { id: 381, .. }), "{e}");
    let e = err(&make("1.,1.,1."));
    assert!(matches!(e, StepError::Geometry { id: 381, .. }), "{e}");
}

#[test]
fn binary_and_non_utf8_input() {
    let png = b"\x89PNG\r\n\x1a\n\0\0\0\rIHDR";
    assert!(matches!(read_step(png), Err(StepError::NotStep { .. })));
    assert!(matches!(read_step(b""), Err(StepError::NotStep { .. })));
    // A byte above 0x7f outside a string.
    let mut bytes = cube().into_bytes();
    let at = bytes.len() / 2;
    bytes.insert(at, 0xff);
    assert!(matches!(read_step(&bytes), Err(StepError::Syntax { .. })));
    // Inside a string Latin-1 is read (Part 21 strings are ISO 8859-1).
    let latin = edit(
        &cube(),
        "'blue_cylinder', #106",
        "'blue_cylinder_\u{e9}', #106",
    );
    let latin = latin.replace('\u{e9}', "\u{0}");
    let bytes: Vec<u8> = latin
        .bytes()
        .map(|b| if b == 0 { 0xe9 } else { b })
        .collect();
    let solids = read_step(&bytes).expect("Latin-1 name");
    assert_eq!(solids[0].name, "blue_cylinder_\u{e9}");
    // A control byte inside a string is binary data.
    let bytes = edit(&cube(), "'blue_cylinder', #106", "'blue\u{1}', #106").into_bytes();
    assert!(matches!(read_step(&bytes), Err(StepError::Syntax { .. })));
}

#[test]
fn a_million_entities_are_bounded() {
    // MAX_ENTITIES points and one more: refused when the limit is passed, in one linear pass.
    let mut text = String::with_capacity(40 * (MAX_ENTITIES + 2));
    text.push_str(HEADER);
    for i in 1..=MAX_ENTITIES + 1 {
        text.push_str(&format!("#{i}=CARTESIAN_POINT('',(0.,0.,0.));\n"));
    }
    text.push_str(FOOTER);
    let start = Instant::now();
    let e = read_step(text.as_bytes()).expect_err("too many");
    assert_eq!(
        e,
        StepError::TooLarge {
            what: "entity instances",
            limit: MAX_ENTITIES
        }
    );
    println!(
        "refused {} entities in {:?}",
        MAX_ENTITIES + 1,
        start.elapsed()
    );
    // Exactly the limit parses, and holds no solid.
    let cut = text
        .rfind(&format!("#{}=", MAX_ENTITIES + 1))
        .expect("last line");
    let limited = format!("{}{FOOTER}", &text[..cut]);
    assert_eq!(
        read_step(limited.as_bytes()).expect_err("no solid"),
        StepError::NoSolid
    );
}

#[test]
fn deep_nesting_is_bounded() {
    let deep = format!(
        "{HEADER}#1 = CARTESIAN_POINT('',{}0.{});\n{FOOTER}",
        "(".repeat(10_000),
        ")".repeat(10_000)
    );
    assert!(matches!(
        read_step(deep.as_bytes()),
        Err(StepError::TooLarge { .. })
    ));
}

#[test]
fn duplicate_id_and_missing_solid() {
    let e = err(&format!(
        "{HEADER}#1 = CARTESIAN_POINT('',(0.,0.,0.));\n#1 = CARTESIAN_POINT('',(0.,0.,0.));\n{FOOTER}"
    ));
    assert_eq!(e, StepError::DuplicateId { id: 1 });
    let e = err(&format!(
        "{HEADER}#1 = CARTESIAN_POINT('',(0.,0.,0.));\n{FOOTER}"
    ));
    assert_eq!(e, StepError::NoSolid);
}

#[test]
fn euclid_spindle_torus_is_refused_naming_its_surface() {
    // Euclid (Matra Datavision, 1998), from OCCT's test data: a screw whose TOROIDAL_SURFACE
    // #482 has a minor radius (54.87 mm) above its major one (8.25 mm), a self-intersecting
    // torus that STEP writes as DEGENERATE_TOROIDAL_SURFACE; the reader does not guess which
    // part of it is meant.
    let path = format!(
        "{}/../../fixtures/step/euclid_screw.stp",
        env!("CARGO_MANIFEST_DIR")
    );
    let bytes = std::fs::read(&path).expect("fixture");
    let e = read_step(&bytes).expect_err("refused");
    match &e {
        StepError::Geometry { id, entity, .. } => {
            assert_eq!((*id, entity.as_str()), (482, "TOROIDAL_SURFACE"), "{e}");
        }
        other => panic!("{other}"),
    }
}
