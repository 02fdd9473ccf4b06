//! Builds the boundary representation of a solid of revolution from its profile.
//!
//! Face i is segment i revolved ([`RevolvedSurface`], u = angle, v = segment parameter).
//! Edge k is the circle where two consecutive segments meet (k = i for the joint between
//! segments i and i + 1; for a ring, edge n - 1 joins the last segment to the first). An axis
//! profile has vertex 0 where it starts on the axis and vertex 1 where it ends.

use crate::curves::circle_edge::CircleEdge;
use crate::revolution::profile::{Closure, Profile};
use crate::surfaces::revolved_surface::RevolvedSurface;
use crate::topology::convexity::{classify_joint, classify_revolved_face};
use crate::topology::feature::{EdgeId, FaceId, VertexId};
use crate::topology::solid::{Boundary, Edge, EdgeOn, EdgeUse, Face, ParamSide, Solid, Vertex};
use glam::DVec3;

/// The solid swept by `profile` turning about the z axis.
#[must_use]
pub fn revolve(profile: &Profile) -> Solid {
    let segments = profile.segments();
    let n = segments.len();
    let axis = profile.closure() == Closure::Axis;
    let id = |k: usize| u32::try_from(k).expect("profiles have fewer than 2^32 segments");

    let edges: Vec<Edge> = profile
        .joints()
        .into_iter()
        .map(|(i, j)| {
            let p = segments[i].end();
            Edge {
                curve: Box::new(CircleEdge {
                    radius: p.x,
                    z: p.y,
                }),
                uses: [
                    EdgeUse {
                        face: FaceId(id(i)),
                        on: EdgeOn::Side(ParamSide::VMax),
                    },
                    EdgeUse {
                        face: FaceId(id(j)),
                        on: EdgeOn::Side(ParamSide::VMin),
                    },
                ],
                ends: None,
                convexity: classify_joint(&segments[i], &segments[j]),
            }
        })
        .collect();

    let faces = segments
        .iter()
        .enumerate()
        .map(|(i, segment)| {
            let v_min = match (i, axis) {
                (0, true) => Boundary::Vertex(VertexId(0)),
                (0, false) => Boundary::Edge(EdgeId(id(n - 1))),
                _ => Boundary::Edge(EdgeId(id(i - 1))),
            };
            let v_max = if axis && i == n - 1 {
                Boundary::Vertex(VertexId(1))
            } else {
                Boundary::Edge(EdgeId(id(i)))
            };
            Face {
                surface: Box::new(RevolvedSurface { segment: *segment }),
                boundary: [Boundary::Periodic, Boundary::Periodic, v_min, v_max],
                trim: None,
                convexity: classify_revolved_face(segment, profile.scale()),
            }
        })
        .collect();

    let vertices = if axis {
        let (start, end) = (segments[0].start(), segments[n - 1].end());
        vec![
            Vertex {
                point: DVec3::new(0.0, 0.0, start.y),
                faces: vec![FaceId(0)],
                edges: vec![],
            },
            Vertex {
                point: DVec3::new(0.0, 0.0, end.y),
                faces: vec![FaceId(id(n - 1))],
                edges: vec![],
            },
        ]
    } else {
        Vec::new()
    };

    Solid::new(faces, edges, vertices, Solid::DEFAULT_TOLERANCE)
}
