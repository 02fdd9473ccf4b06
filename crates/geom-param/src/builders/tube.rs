//! A tube: a cylinder with a coaxial through hole. Two cylinders (the inner one reversed, so
//! its outward normal points at the axis) and two annular caps, trimmed planes whose inner
//! loop is the hole.

use crate::builders::CAP_DOMAIN_FACTOR;
use crate::builders::MIN_RELATIVE_FEATURE;
use crate::builders::build_error::BuildError;
use crate::curves::circle_curve::CircleCurve;
use crate::curves::curve::ParamRange;
use crate::curves::curve2::Circle2;
use crate::surfaces::cylinder_surface::CylinderSurface;
use crate::surfaces::placement::Placement;
use crate::surfaces::plane::Plane;
use crate::surfaces::reversed_surface::ReversedSurface;
use crate::topology::feature::{EdgeId, FaceId};
use crate::topology::solid::{
    Boundary, Edge, EdgeConvexity, EdgeOn, EdgeUse, Face, FaceConvexity, ParamSide, Solid,
};
use crate::topology::trim::{Trim, TrimEntry, TrimLoop};
use crate::topology::validate::validate;
use glam::{DVec2, DVec3};
use std::f64::consts::TAU;

const TURN: ParamRange = ParamRange {
    min: 0.0,
    max: TAU,
    periodic: true,
};

fn range(min: f64, max: f64) -> ParamRange {
    ParamRange {
        min,
        max,
        periodic: false,
    }
}

/// The tube r_inner <= √(x² + y²) <= r_outer, 0 <= z <= length (mm) in its own frame.
///
/// Faces: 0 the outer cylinder, 1 the inner (reversed) cylinder, 2 the bottom cap (z = 0),
/// 3 the top cap; edges: 0 and 1 the outer circles at the bottom and top, 2 and 3 the inner
/// ones. The caps are planes over [−2 r_outer, 2 r_outer]² trimmed by two circles each. The model tolerance is 1e-9 of the
/// size.
///
/// # Errors
/// [`BuildError::BadDimension`] unless every dimension is finite, the hole radius, the wall
/// thickness and the length at least 1e-6 of the size.
pub fn tube(outer_radius: f64, inner_radius: f64, length: f64) -> Result<Solid, BuildError> {
    if !(outer_radius.is_finite() && outer_radius > 0.0) {
        return Err(BuildError::BadDimension {
            what: "outer radius",
            value: outer_radius,
            requirement: "finite and > 0",
        });
    }
    if !(length.is_finite() && length > 0.0) {
        return Err(BuildError::BadDimension {
            what: "length",
            value: length,
            requirement: "finite and > 0",
        });
    }
    let smallest = MIN_RELATIVE_FEATURE * outer_radius.max(length);
    if !(inner_radius >= smallest && outer_radius - inner_radius >= smallest) {
        return Err(BuildError::BadDimension {
            what: "inner radius",
            value: inner_radius,
            requirement: "at least 1e-6 of the size, and below the outer radius by as much",
        });
    }
    if length < smallest {
        return Err(BuildError::BadDimension {
            what: "length",
            value: length,
            requirement: "at least 1e-6 of the outer radius",
        });
    }
    let axis = Placement::new(DVec3::ZERO, DVec3::Z, DVec3::X)?;
    let at_height = |z: f64| Placement::new(DVec3::new(0.0, 0.0, z), DVec3::Z, DVec3::X);
    let circle = |radius: f64, z: f64| -> Result<Edge, BuildError> {
        Ok(Edge {
            curve: Box::new(CircleCurve::new(at_height(z)?, radius, TURN)?),
            uses: [
                EdgeUse {
                    face: FaceId(0),
                    on: EdgeOn::Side(ParamSide::VMin),
                },
                EdgeUse {
                    face: FaceId(0),
                    on: EdgeOn::Side(ParamSide::VMin),
                },
            ],
            ends: None,
            convexity: EdgeConvexity::Convex,
        })
    };
    let mut edges = vec![
        circle(outer_radius, 0.0)?,
        circle(outer_radius, length)?,
        circle(inner_radius, 0.0)?,
        circle(inner_radius, length)?,
    ];
    let trim_use = |face: u32, loop_index: u32| EdgeUse {
        face: FaceId(face),
        on: EdgeOn::Trim {
            loop_index,
            index: 0,
        },
    };
    let side_use = |face: u32, side: ParamSide| EdgeUse {
        face: FaceId(face),
        on: EdgeOn::Side(side),
    };
    edges[0].uses = [side_use(0, ParamSide::VMin), trim_use(2, 0)];
    edges[1].uses = [side_use(0, ParamSide::VMax), trim_use(3, 0)];
    // The reversed inner cylinder has v' = −z: its v_min side is the top, v_max the bottom.
    edges[2].uses = [side_use(1, ParamSide::VMax), trim_use(2, 1)];
    edges[3].uses = [side_use(1, ParamSide::VMin), trim_use(3, 1)];

    let outer = CylinderSurface::new(axis, outer_radius, [TURN, range(0.0, length)])?;
    let inner = ReversedSurface {
        inner: CylinderSurface::new(axis, inner_radius, [TURN, range(0.0, length)])?,
    };
    let half = range(
        -CAP_DOMAIN_FACTOR * outer_radius,
        CAP_DOMAIN_FACTOR * outer_radius,
    );
    // Bottom cap: normal −z, frame x = +x so y = −y: (u, v) = (x, −y), circles run clockwise.
    let bottom = Plane::new(
        Placement::new(DVec3::ZERO, DVec3::NEG_Z, DVec3::X)?,
        [half, half],
    )?;
    let top = Plane::new(at_height(length)?, [half, half])?;
    let cap_loop = |edge: u32, radius: f64, sense: f64, reversed: bool| {
        TrimLoop::new(vec![TrimEntry::new(
            EdgeId(edge),
            Box::new(Circle2 {
                center: DVec2::ZERO,
                radius,
                phase: 0.0,
                sense,
                range: TURN,
            }),
            reversed,
        )])
    };
    let plane_domain = [half, half];
    let bottom_trim = Trim::new(
        vec![
            cap_loop(0, outer_radius, -1.0, true),
            cap_loop(2, inner_radius, -1.0, false),
        ],
        &plane_domain,
    );
    let top_trim = Trim::new(
        vec![
            cap_loop(1, outer_radius, 1.0, false),
            cap_loop(3, inner_radius, 1.0, true),
        ],
        &plane_domain,
    );
    let cylinder_face = |surface: Box<dyn crate::Surface>, v_min: u32, v_max: u32| Face {
        surface,
        boundary: [
            Boundary::Periodic,
            Boundary::Periodic,
            Boundary::Edge(EdgeId(v_min)),
            Boundary::Edge(EdgeId(v_max)),
        ],
        trim: None,
        convexity: FaceConvexity::Convex,
    };
    let cap = |surface: Plane, trim: Trim| Face {
        surface: Box::new(surface),
        boundary: [Boundary::Trimmed; 4],
        trim: Some(trim),
        convexity: FaceConvexity::Flat,
    };
    let solid = Solid::new(
        vec![
            cylinder_face(Box::new(outer), 0, 1),
            cylinder_face(Box::new(inner), 3, 2),
            cap(bottom, bottom_trim),
            cap(top, top_trim),
        ],
        edges,
        Vec::new(),
        1e-9 * outer_radius.max(length),
    );
    validate(&solid)?;
    Ok(solid)
}
