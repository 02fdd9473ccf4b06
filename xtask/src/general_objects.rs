//! The general (not revolved) fixture objects, made by geom-param's builders: a rounded box, a
//! tube (faces with holes, a concave bore) and a filleted L-bracket with a hole.

use crate::paper_objects::GENERATED_NOTE;
use geom_param::{DVec2, DVec3, PlanarProfile, PlanarSegment, SolidDescription, SolidSpec};

fn object(name: &str, spec: SolidSpec) -> SolidDescription {
    SolidDescription {
        name: name.into(),
        note: Some(GENERATED_NOTE.into()),
        spec,
    }
}

/// A 60 x 40 x 24 mm box with every edge rounded at 4 mm: convex, every edge smooth.
fn rounded_box() -> SolidDescription {
    object(
        "rounded-box",
        SolidSpec::RoundedBox {
            half_extents: DVec3::new(30.0, 20.0, 12.0),
            radius: 4.0,
        },
    )
}

/// A tube 18 mm across with a 10 mm bore, 60 mm long: trimmed annular caps, a concave bore.
fn tube() -> SolidDescription {
    object(
        "tube",
        SolidSpec::Tube {
            outer_radius: 9.0,
            inner_radius: 5.0,
            length: 60.0,
        },
    )
}

/// An L-bracket with 60 mm legs 10 mm thick, a concave 8 mm fillet in its inner corner and a
/// 5 mm hole through the horizontal leg, 30 mm deep.
fn bracket() -> SolidDescription {
    let p = DVec2::new;
    let line = |from: DVec2, to: DVec2| PlanarSegment::Line { from, to };
    let outer = vec![
        line(p(0.0, 0.0), p(60.0, 0.0)),
        line(p(60.0, 0.0), p(60.0, 10.0)),
        line(p(60.0, 10.0), p(18.0, 10.0)),
        PlanarSegment::Arc {
            center: p(18.0, 18.0),
            from: p(18.0, 10.0),
            to: p(10.0, 18.0),
            ccw: false,
        },
        line(p(10.0, 18.0), p(10.0, 60.0)),
        line(p(10.0, 60.0), p(0.0, 60.0)),
        line(p(0.0, 60.0), p(0.0, 0.0)),
    ];
    let hole = vec![PlanarSegment::Arc {
        center: p(42.0, 5.0),
        from: p(45.0, 5.0),
        to: p(45.0, 5.0),
        ccw: false,
    }];
    object(
        "bracket",
        SolidSpec::Extrusion {
            profile: PlanarProfile {
                outer,
                holes: vec![hole],
            },
            z: [0.0, 30.0],
        },
    )
}

/// Every general fixture object.
#[must_use]
pub fn general_objects() -> Vec<SolidDescription> {
    vec![rounded_box(), tube(), bracket()]
}
