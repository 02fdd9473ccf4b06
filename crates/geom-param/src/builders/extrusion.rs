//! Extrusion of a closed planar profile (lines, circular arcs and NURBS curves in the xy
//! plane, with holes) between two planes z = z₀ and z = z₁: one side face per segment, two
//! trimmed caps.
//!
//! Every side face is parametrised alike: u runs along its segment in the loop's direction
//! (arc length for a line, the angle for an arc, the curve's own parameter for a NURBS curve),
//! v = z − z₀. So its v_min side is the bottom edge, v_max the top edge, u_min the vertical edge
//! at the segment's start and u_max the one at its end. A line's side is a plane; an arc turning
//! counter-clockwise is a cylinder, one turning clockwise (a concave fillet, a hole) a reversed
//! cylinder; a NURBS curve's side is its [`LinearExtrusionSurface`] along +z, whose normal
//! C'(u) × z is the right of the direction of travel: outward, since the material is on the
//! left of every loop. The top cap's (u, v) are (x, y), the bottom cap's (x, −y) (its normal is
//! −z).

use crate::builders::CAP_DOMAIN_FACTOR;
use crate::builders::build_error::BuildError;
use crate::curves::circle_curve::CircleCurve;
use crate::curves::curve::{Curve, ParamRange};
use crate::curves::curve2::{Circle2, Curve2, Line2};
use crate::curves::line_curve::LineCurve;
use crate::curves::nurbs_curve::NurbsCurve;
use crate::curves::nurbs_curve2::NurbsCurve2;
use crate::surfaces::cylinder_surface::CylinderSurface;
use crate::surfaces::linear_extrusion_surface::LinearExtrusionSurface;
use crate::surfaces::placement::Placement;
use crate::surfaces::plane::Plane;
use crate::surfaces::reversed_surface::ReversedSurface;
use crate::surfaces::surface::Surface;
use crate::topology::feature::{EdgeId, FaceId, VertexId};
use crate::topology::solid::{
    Boundary, Edge, EdgeConvexity, EdgeOn, EdgeUse, Face, FaceConvexity, ParamSide, Solid, Vertex,
};
use crate::topology::trim::{Trim, TrimEntry, TrimLoop};
use crate::topology::validate::validate;
use glam::{DVec2, DVec3};
use std::f64::consts::TAU;

/// One segment of a planar profile, in the xy plane (mm).
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(
    feature = "json",
    derive(serde::Serialize, serde::Deserialize),
    serde(rename_all = "snake_case", deny_unknown_fields)
)]
pub enum PlanarSegment {
    /// The straight segment from `from` to `to`.
    Line {
        /// Start point.
        from: DVec2,
        /// End point.
        to: DVec2,
    },
    /// The circular arc about `center` from `from` to `to`, counter-clockwise when `ccw`.
    /// `from` and `to` must lie at the same distance from `center`; equal end points make a
    /// full circle.
    Arc {
        /// Centre.
        center: DVec2,
        /// Start point.
        from: DVec2,
        /// End point.
        to: DVec2,
        /// Direction of travel.
        ccw: bool,
    },
    /// A rational B-spline curve in the xy plane, run from its parameter's start to its end
    /// (a spline, a conic, a polyline with creases: interior knots of multiplicity = degree).
    /// A closed (periodic) curve alone makes a whole loop. Its derivative must not vanish
    /// (the side face would have no normal there). JSON: `{"nurbs": {"degree": 2, "knots":
    /// [...], "points": [[x, y], ...], "weights": [...], "periodic": false}}`, weights
    /// optional (1).
    Nurbs(#[cfg_attr(feature = "json", serde(with = "crate::io::nurbs_curve2_json"))] NurbsCurve2),
}

impl PlanarSegment {
    fn start(&self) -> DVec2 {
        match self {
            Self::Line { from, .. } | Self::Arc { from, .. } => *from,
            Self::Nurbs(curve) => curve.eval(curve.param_range().min).point,
        }
    }

    /// The largest absolute coordinate of a box that holds the segment (mm).
    fn extent(&self) -> f64 {
        match self {
            Self::Line { from, to } => from.abs().max(to.abs()).max_element(),
            Self::Arc { center, from, .. } => center.abs().max_element() + center.distance(*from),
            // The curve lies in its control points' convex hull.
            Self::Nurbs(curve) => curve
                .control_points()
                .iter()
                .map(|p| p.abs().max_element())
                .fold(0.0, f64::max),
        }
    }
}

/// A planar region: an outer loop (counter-clockwise in xy) and holes (clockwise), each a
/// closed chain of segments, each starting where the previous one ends.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(
    feature = "json",
    derive(serde::Serialize, serde::Deserialize),
    serde(deny_unknown_fields)
)]
pub struct PlanarProfile {
    /// The outer loop.
    pub outer: Vec<PlanarSegment>,
    /// The holes.
    #[cfg_attr(feature = "json", serde(default))]
    pub holes: Vec<Vec<PlanarSegment>>,
}

fn range(min: f64, max: f64) -> ParamRange {
    ParamRange {
        min,
        max,
        periodic: false,
    }
}

/// Samples per knot span at which a NURBS segment's speed is checked.
const SPEED_SAMPLES_PER_SPAN: usize = 16;
/// Speed |C'(t)| below which a NURBS segment counts as stopping (relative to its control
/// polygon's extent per unit of its parameter span).
const MIN_RELATIVE_SPEED: f64 = 1e-9;

/// A segment's side face, bottom edge curve and p-curves on the top and bottom caps.
struct SegmentGeometry {
    side: Box<dyn Surface>,
    bottom: Box<dyn Curve>,
    top: Box<dyn Curve>,
    top_pcurve: Box<dyn Curve2>,
    bottom_pcurve: Box<dyn Curve2>,
    /// Whether the segment is a full circle (u periodic).
    periodic: bool,
}

fn segment_geometry(
    segment: &PlanarSegment,
    z0: f64,
    height: f64,
    tolerance: f64,
) -> Result<SegmentGeometry, BuildError> {
    let lift = |p: DVec2, z: f64| DVec3::new(p.x, p.y, z);
    match *segment {
        PlanarSegment::Nurbs(ref curve) => nurbs_geometry(curve, z0, height, tolerance),
        PlanarSegment::Line { from, to } => {
            let length = from.distance(to);
            if length.is_nan() || length <= tolerance {
                return Err(BuildError::BadDimension {
                    what: "profile line length",
                    value: length,
                    requirement: "longer than the model tolerance",
                });
            }
            let dir = (to - from) / length;
            let x = lift(dir, 0.0);
            // Outward: the right of the direction of travel (the material is on the left).
            let normal = DVec3::new(dir.y, -dir.x, 0.0);
            let side = Plane::new(
                Placement::new(lift(from, z0), normal, x)?,
                [range(0.0, length), range(0.0, height)],
            )?;
            let t = range(0.0, length);
            Ok(SegmentGeometry {
                side: Box::new(side),
                bottom: Box::new(LineCurve::new(lift(from, z0), x, t)?),
                top: Box::new(LineCurve::new(lift(from, z0 + height), x, t)?),
                top_pcurve: Box::new(Line2 {
                    origin: from,
                    direction: dir,
                    range: t,
                }),
                bottom_pcurve: Box::new(Line2 {
                    origin: DVec2::new(from.x, -from.y),
                    direction: DVec2::new(dir.x, -dir.y),
                    range: t,
                }),
                periodic: false,
            })
        }
        PlanarSegment::Arc {
            center,
            from,
            to,
            ccw,
        } => {
            let radius = from.distance(center);
            if !(radius > tolerance && (to.distance(center) - radius).abs() <= tolerance) {
                return Err(BuildError::BadDimension {
                    what: "arc radius",
                    value: radius,
                    requirement: "above the model tolerance, the same at both ends",
                });
            }
            let (a, b) = (from - center, to - center);
            let sense = if ccw { 1.0 } else { -1.0 };
            let mut sweep = (sense * a.perp_dot(b)).atan2(a.dot(b));
            if sweep <= tolerance / radius {
                sweep += TAU;
            }
            let t = ParamRange {
                min: 0.0,
                max: sweep,
                periodic: (sweep - TAU).abs() <= tolerance / radius,
            };
            let x = lift(a / radius, 0.0);
            // The axis is +z for a counter-clockwise arc so that u grows along the loop.
            let axis = DVec3::new(0.0, 0.0, sense);
            let phase = a.y.atan2(a.x);
            let circle = |z: f64| -> Result<CircleCurve, BuildError> {
                Ok(CircleCurve::new(
                    Placement::new(lift(center, z), axis, x)?,
                    radius,
                    t,
                )?)
            };
            let side: Box<dyn Surface> = if ccw {
                Box::new(CylinderSurface::new(
                    Placement::new(lift(center, z0), axis, x)?,
                    radius,
                    [t, range(0.0, height)],
                )?)
            } else {
                // Axis −z: v = z₀ − z; reversed, v' = z − z₀ and the normal points at the axis.
                Box::new(ReversedSurface {
                    inner: CylinderSurface::new(
                        Placement::new(lift(center, z0), axis, x)?,
                        radius,
                        [t, range(-height, 0.0)],
                    )?,
                })
            };
            Ok(SegmentGeometry {
                side,
                bottom: Box::new(circle(z0)?),
                top: Box::new(circle(z0 + height)?),
                top_pcurve: Box::new(Circle2 {
                    center,
                    radius,
                    phase,
                    sense,
                    range: t,
                }),
                bottom_pcurve: Box::new(Circle2 {
                    center: DVec2::new(center.x, -center.y),
                    radius,
                    phase: -phase,
                    sense: -sense,
                    range: t,
                }),
                periodic: t.periodic,
            })
        }
    }
}

/// The side face, edges and p-curves of a NURBS segment: the side is the extrusion of the
/// curve lifted to z₀ (u = the curve's t, v = z − z₀), the bottom and top edges are the curve
/// lifted to z₀ and z₁ (edge t = u), the p-curves the curve itself (top cap) and its mirror
/// image in y (bottom cap), with the same knots and weights.
fn nurbs_geometry(
    curve: &NurbsCurve2,
    z0: f64,
    height: f64,
    tolerance: f64,
) -> Result<SegmentGeometry, BuildError> {
    let points = curve.control_points();
    let extent = points
        .iter()
        .map(|p| p.distance(points[0]))
        .fold(0.0, f64::max);
    if extent <= tolerance {
        return Err(BuildError::BadDimension {
            what: "NURBS segment extent",
            value: extent,
            requirement: "longer than the model tolerance",
        });
    }
    let domain = curve.param_range();
    let slowest = curve
        .basis()
        .knots()
        .windows(2)
        .filter(|w| w[1] > w[0])
        .flat_map(|w| {
            (0..=SPEED_SAMPLES_PER_SPAN)
                .map(move |k| w[0] + (w[1] - w[0]) * k as f64 / SPEED_SAMPLES_PER_SPAN as f64)
        })
        .filter(|t| *t >= domain.min && *t <= domain.max)
        .map(|t| curve.eval(t).d1.length())
        .fold(f64::INFINITY, f64::min);
    if slowest.is_nan() || slowest <= MIN_RELATIVE_SPEED * extent / domain.span() {
        return Err(BuildError::BadDimension {
            what: "speed of a NURBS segment",
            value: slowest,
            requirement: "non-zero along the curve (the side face needs a normal)",
        });
    }
    let degree = curve.basis().degree();
    let knots = curve.basis().knots().to_vec();
    let weights = curve.weights().to_vec();
    let periodic = curve.is_periodic();
    let lifted = |z: f64| {
        NurbsCurve::new(
            degree,
            knots.clone(),
            points.iter().map(|p| DVec3::new(p.x, p.y, z)).collect(),
            weights.clone(),
            periodic,
        )
    };
    let mirrored = NurbsCurve2::new(
        degree,
        knots.clone(),
        points.iter().map(|p| DVec2::new(p.x, -p.y)).collect(),
        weights.clone(),
        periodic,
    )?;
    Ok(SegmentGeometry {
        side: Box::new(LinearExtrusionSurface::new(
            lifted(z0)?,
            DVec3::Z,
            range(0.0, height),
        )?),
        bottom: Box::new(lifted(z0)?),
        top: Box::new(lifted(z0 + height)?),
        top_pcurve: Box::new(curve.clone()),
        bottom_pcurve: Box::new(mirrored),
        periodic,
    })
}

/// The solid swept by `profile` from z = `z0` to z = `z1` (mm). The model tolerance is 1e-9
/// of the size.
///
/// Faces: one side face per segment (outer loop first, then each hole, in order), then the
/// bottom cap, then the top cap (planes over [−2s, 2s]², s the size, trimmed by the loops). Edges per segment: its bottom, its top, and the vertical edge
/// at its start; two vertices per profile vertex (bottom, top).
///
/// # Errors
/// [`BuildError::BadDimension`] for z1 <= z0, a segment shorter than the tolerance, an arc
/// whose ends are not on one circle, a NURBS segment whose speed vanishes at one of 16
/// samples per knot span; [`BuildError::Geometry`] for non-finite input;
/// [`BuildError::Topology`] for a profile that does not close, crosses itself, or runs the
/// wrong way (outer loop clockwise, a hole counter-clockwise or outside).
pub fn extrude(profile: &PlanarProfile, z0: f64, z1: f64) -> Result<Solid, BuildError> {
    let height = z1 - z0;
    if !(height.is_finite() && height > 0.0) {
        return Err(BuildError::BadDimension {
            what: "extrusion height",
            value: height,
            requirement: "finite and > 0",
        });
    }
    let loops: Vec<&Vec<PlanarSegment>> = std::iter::once(&profile.outer)
        .chain(&profile.holes)
        .collect();
    let size = loops
        .iter()
        .flat_map(|l| l.iter().map(PlanarSegment::extent))
        .fold(z0.abs().max(z1.abs()), f64::max);
    if !size.is_finite() {
        return Err(BuildError::BadDimension {
            what: "profile coordinate",
            value: size,
            requirement: "finite",
        });
    }
    let tolerance = 1e-9 * size.max(height);
    let total: usize = loops.iter().map(|l| l.len()).sum();
    if loops.iter().any(|l| l.is_empty()) {
        return Err(BuildError::BadDimension {
            what: "segments in a loop",
            value: 0.0,
            requirement: "at least one",
        });
    }
    let id = |k: usize| u32::try_from(k).expect("fewer than 2^32 features");
    let (bottom_cap, top_cap) = (FaceId(id(total)), FaceId(id(total + 1)));

    let mut faces: Vec<Face> = Vec::with_capacity(total + 2);
    let mut edges: Vec<Edge> = Vec::with_capacity(3 * total);
    let mut vertices: Vec<Vertex> = Vec::with_capacity(2 * total);
    let mut top_loops = Vec::new();
    let mut bottom_loops = Vec::new();
    for (l, segments) in loops.iter().enumerate() {
        let m = segments.len();
        // A loop of one segment is a full circle: its side is periodic, with no vertical edge
        // and no vertex.
        let closed = m == 1;
        let first_face = faces.len();
        let first_edge = edges.len();
        let first_vertex = vertices.len();
        let stride = if closed { 2 } else { 3 };
        let bottom_edge = |k: usize| EdgeId(id(first_edge + stride * (k % m)));
        let top_edge = |k: usize| EdgeId(id(first_edge + stride * (k % m) + 1));
        let vertical = |k: usize| EdgeId(id(first_edge + stride * (k % m) + 2));
        let bottom_vertex = |k: usize| VertexId(id(first_vertex + 2 * (k % m)));
        let top_vertex = |k: usize| VertexId(id(first_vertex + 2 * (k % m) + 1));
        let mut top_entries = Vec::with_capacity(m);
        let mut bottom_entries = Vec::with_capacity(m);
        for (k, segment) in segments.iter().enumerate() {
            let face = FaceId(id(first_face + k));
            let geometry = segment_geometry(segment, z0, height, tolerance)?;
            if closed != geometry.periodic {
                return Err(BuildError::BadDimension {
                    what: "segments in a loop",
                    value: m as f64,
                    requirement: "one full circle, or segments none of which is a full circle",
                });
            }
            let sides = if closed {
                [Boundary::Periodic, Boundary::Periodic]
            } else {
                [Boundary::Edge(vertical(k)), Boundary::Edge(vertical(k + 1))]
            };
            faces.push(Face {
                surface: geometry.side,
                boundary: [
                    sides[0],
                    sides[1],
                    Boundary::Edge(bottom_edge(k)),
                    Boundary::Edge(top_edge(k)),
                ],
                trim: None,
                convexity: FaceConvexity::Flat,
            });
            let ends = |at: &dyn Fn(usize) -> VertexId| (!closed).then(|| [at(k), at(k + 1)]);
            // The bottom cap's loop runs the profile backwards (its (u, v) are mirrored).
            edges.push(Edge {
                curve: geometry.bottom,
                uses: [
                    EdgeUse {
                        face,
                        on: EdgeOn::Side(ParamSide::VMin),
                    },
                    EdgeUse {
                        face: bottom_cap,
                        on: EdgeOn::Trim {
                            loop_index: id(l),
                            index: id(m - 1 - k),
                        },
                    },
                ],
                ends: ends(&bottom_vertex),
                convexity: EdgeConvexity::Convex,
            });
            edges.push(Edge {
                curve: geometry.top,
                uses: [
                    EdgeUse {
                        face,
                        on: EdgeOn::Side(ParamSide::VMax),
                    },
                    EdgeUse {
                        face: top_cap,
                        on: EdgeOn::Trim {
                            loop_index: id(l),
                            index: id(k),
                        },
                    },
                ],
                ends: ends(&top_vertex),
                convexity: EdgeConvexity::Convex,
            });
            if !closed {
                let corner = segment.start();
                edges.push(Edge {
                    curve: Box::new(LineCurve::new(
                        DVec3::new(corner.x, corner.y, z0),
                        DVec3::Z,
                        range(0.0, height),
                    )?),
                    uses: [
                        EdgeUse {
                            face,
                            on: EdgeOn::Side(ParamSide::UMin),
                        },
                        EdgeUse {
                            face: FaceId(id(first_face + (k + m - 1) % m)),
                            on: EdgeOn::Side(ParamSide::UMax),
                        },
                    ],
                    ends: Some([bottom_vertex(k), top_vertex(k)]),
                    convexity: EdgeConvexity::Convex,
                });
                for z in [z0, z1] {
                    vertices.push(Vertex {
                        point: DVec3::new(corner.x, corner.y, z),
                        faces: Vec::new(),
                        edges: Vec::new(),
                    });
                }
            }
            top_entries.push(TrimEntry::new(top_edge(k), geometry.top_pcurve, false));
            bottom_entries.push(TrimEntry::new(bottom_edge(k), geometry.bottom_pcurve, true));
        }
        bottom_entries.reverse();
        top_loops.push(TrimLoop::new(top_entries));
        bottom_loops.push(TrimLoop::new(bottom_entries));
    }
    for (e, edge) in edges.iter().enumerate() {
        for v in edge.ends.iter().flatten() {
            vertices[v.0 as usize].edges.push(EdgeId(id(e)));
        }
    }
    let half = CAP_DOMAIN_FACTOR * size;
    let cap_domain = [range(-half, half), range(-half, half)];
    let bottom = Plane::new(
        Placement::new(DVec3::new(0.0, 0.0, z0), DVec3::NEG_Z, DVec3::X)?,
        cap_domain,
    )?;
    let top = Plane::new(
        Placement::new(DVec3::new(0.0, 0.0, z1), DVec3::Z, DVec3::X)?,
        cap_domain,
    )?;
    let bottom_trim = Trim::new(bottom_loops, &bottom.domain());
    let top_trim = Trim::new(top_loops, &top.domain());
    for (surface, trim) in [(bottom, bottom_trim), (top, top_trim)] {
        faces.push(Face {
            surface: Box::new(surface),
            boundary: [Boundary::Trimmed; 4],
            trim: Some(trim),
            convexity: FaceConvexity::Flat,
        });
    }
    let solid = Solid::new(faces, edges, vertices, tolerance);
    validate(&solid)?;
    Ok(solid)
}
