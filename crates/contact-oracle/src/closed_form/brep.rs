//! Solids built face by face for the closed-form scenes and tests: a rectangular block, a
//! tetrahedron and a square plate with a cylindrical hole. Every planar face is a plane trimmed by its loops (an outer loop of
//! straight edges, counter-clockwise, and for the plate a circular hole, clockwise); edges are
//! straight lines between corner vertices, or circles about the z axis.

use super::analytic::{CylinderSurface, EllipseCurve2, LineCurve, PlaneSurface};
use geom_param::{
    Boundary, CircleEdge, Curve, Edge, EdgeConvexity, EdgeId, EdgeOn, EdgeUse, Face, FaceConvexity,
    FaceId, Line2, ParamRange, Solid, Trim, TrimEntry, TrimLoop, Vertex, VertexId,
};
use glam::{DVec2, DVec3};
use std::collections::BTreeMap;

/// The corners of the box [lo, hi]: index bit 0 picks x, bit 1 y, bit 2 z (0: lo, 1: hi).
fn corners(lo: DVec3, hi: DVec3) -> Vec<DVec3> {
    (0..8)
        .map(|k| {
            DVec3::new(
                if k & 1 == 0 { lo.x } else { hi.x },
                if k & 2 == 0 { lo.y } else { hi.y },
                if k & 4 == 0 { lo.z } else { hi.z },
            )
        })
        .collect()
}

/// The six faces of a box as corner cycles, counter-clockwise seen from outside: bottom, top,
/// front (y = lo), back, left (x = lo), right.
const BOX_FACES: [[usize; 4]; 6] = [
    [0, 2, 3, 1],
    [4, 5, 7, 6],
    [0, 1, 5, 4],
    [2, 6, 7, 3],
    [0, 4, 6, 2],
    [1, 3, 7, 5],
];

/// An edge under construction: its curve, its uses as far as known, its end vertices.
struct EdgeDraft {
    curve: Box<dyn Curve>,
    uses: [Option<EdgeUse>; 2],
    ends: Option<[VertexId; 2]>,
}

/// [`BOX_FACES`] as slices.
fn box_faces() -> Vec<&'static [usize]> {
    BOX_FACES.iter().map(|f| &f[..]).collect()
}

/// A polyhedron of trimmed planar faces under construction.
struct PlanarBuilder {
    points: Vec<DVec3>,
    planes: Vec<PlaneSurface>,
    /// Per face, its loops of entries (loop 0 outer).
    loops: Vec<Vec<Vec<TrimEntry>>>,
    edges: Vec<EdgeDraft>,
    /// Straight edges by (start corner, end corner).
    straight: BTreeMap<(usize, usize), EdgeId>,
}

fn id32(i: usize) -> u32 {
    u32::try_from(i).expect("a handful of features")
}

impl PlanarBuilder {
    /// Planar faces with the corner cycles `faces` (counter-clockwise seen from outside) over
    /// the corner `points`. Each plane has its origin at the cycle's first corner and its x
    /// axis along the first side; its domain is the cycle's (u, v) box grown by a quarter on
    /// every side, so the trim lies strictly inside.
    fn new(points: Vec<DVec3>, faces: &[&[usize]]) -> Self {
        let mut out = Self {
            points,
            planes: Vec::new(),
            loops: Vec::new(),
            edges: Vec::new(),
            straight: BTreeMap::new(),
        };
        for cycle in faces {
            let p = |k: usize| out.points[cycle[k % cycle.len()]];
            let x = (p(1) - p(0)).normalize();
            let n = (p(1) - p(0)).cross(p(2) - p(1)).normalize();
            let y = n.cross(x);
            let mut plane = PlaneSurface {
                origin: p(0),
                x,
                y,
                domain: [ParamRange {
                    min: 0.0,
                    max: 0.0,
                    periodic: false,
                }; 2],
            };
            let uvs: Vec<DVec2> = (0..cycle.len()).map(|k| plane.params_of(p(k))).collect();
            let lo = uvs.iter().copied().fold(DVec2::INFINITY, DVec2::min);
            let hi = uvs.iter().copied().fold(DVec2::NEG_INFINITY, DVec2::max);
            let grow = 0.25 * (hi - lo);
            for i in 0..2 {
                plane.domain[i] = ParamRange {
                    min: lo[i] - grow[i],
                    max: hi[i] + grow[i],
                    periodic: false,
                };
            }
            let face = out.planes.len();
            out.planes.push(plane);
            out.loops.push(vec![Vec::new()]);
            for k in 0..cycle.len() {
                out.side(face, cycle[k], cycle[(k + 1) % cycle.len()]);
            }
        }
        out
    }

    /// Adds the straight side from corner `i` to corner `j` to `face`'s outer loop: a new edge
    /// i → j (t = arc length from i), or the existing edge j → i traversed backwards.
    fn side(&mut self, face: usize, i: usize, j: usize) {
        let plane = self.planes[face];
        let index = self.loops[face][0].len();
        let on = EdgeOn::Trim {
            loop_index: 0,
            index: id32(index),
        };
        let use_ = EdgeUse {
            face: FaceId(id32(face)),
            on,
        };
        let (start, end, reversed) = if self.straight.contains_key(&(j, i)) {
            (j, i, true)
        } else {
            (i, j, false)
        };
        let (a, b) = (self.points[start], self.points[end]);
        let length = a.distance(b);
        let range = ParamRange {
            min: 0.0,
            max: length,
            periodic: false,
        };
        let pcurve = Line2 {
            origin: plane.params_of(a),
            direction: (plane.params_of(b) - plane.params_of(a)) / length,
            range,
        };
        let edge = if reversed {
            let edge = self.straight[&(j, i)];
            self.edges[edge.0 as usize].uses[1] = Some(use_);
            edge
        } else {
            let edge = EdgeId(id32(self.edges.len()));
            self.edges.push(EdgeDraft {
                curve: Box::new(LineCurve {
                    origin: a,
                    direction: (b - a) / length,
                    range,
                }),
                uses: [Some(use_), None],
                ends: Some([VertexId(id32(i)), VertexId(id32(j))]),
            });
            self.straight.insert((i, j), edge);
            edge
        };
        self.loops[face][0].push(TrimEntry::new(edge, Box::new(pcurve), reversed));
    }

    /// Adds a circle about the z axis (radius `radius`, height `z`) as a hole loop of `face`,
    /// traversed backwards when `reversed`; returns the edge (its second use still to set).
    fn circle_hole(&mut self, face: usize, radius: f64, z: f64, reversed: bool) -> EdgeId {
        let plane = self.planes[face];
        let centre = DVec3::new(0.0, 0.0, z);
        let c = plane.params_of(centre);
        let pcurve = EllipseCurve2 {
            centre: c,
            a: plane.params_of(centre + radius * DVec3::X) - c,
            b: plane.params_of(centre + radius * DVec3::Y) - c,
        };
        let edge = EdgeId(id32(self.edges.len()));
        let loop_index = self.loops[face].len();
        let use_ = EdgeUse {
            face: FaceId(id32(face)),
            on: EdgeOn::Trim {
                loop_index: id32(loop_index),
                index: 0,
            },
        };
        self.edges.push(EdgeDraft {
            curve: Box::new(CircleEdge { radius, z }),
            uses: [Some(use_), None],
            ends: None,
        });
        self.loops[face].push(vec![TrimEntry::new(edge, Box::new(pcurve), reversed)]);
        edge
    }

    /// The solid: the planar faces (flat, trimmed), then `extra` faces; corners as vertices
    /// with their edges; every edge convex.
    fn finish(self, extra: Vec<Face>) -> Solid {
        let mut faces = Vec::new();
        for (plane, loops) in self.planes.into_iter().zip(self.loops) {
            let domain = plane.domain;
            faces.push(Face {
                surface: Box::new(plane),
                boundary: [Boundary::Trimmed; 4],
                trim: Some(Trim::new(
                    loops.into_iter().map(TrimLoop::new).collect(),
                    &domain,
                )),
                convexity: FaceConvexity::Flat,
            });
        }
        faces.extend(extra);
        let mut vertices: Vec<Vertex> = self
            .points
            .iter()
            .map(|&point| Vertex {
                point,
                faces: Vec::new(),
                edges: Vec::new(),
            })
            .collect();
        let mut edges = Vec::new();
        for (e, EdgeDraft { curve, uses, ends }) in self.edges.into_iter().enumerate() {
            for v in ends.iter().flatten() {
                vertices[v.0 as usize].edges.push(EdgeId(id32(e)));
            }
            edges.push(Edge {
                curve,
                uses: uses.map(|u| u.expect("every edge has both uses")),
                ends,
                convexity: EdgeConvexity::Convex,
            });
        }
        Solid {
            faces,
            edges,
            vertices,
            tolerance: 0.0,
        }
    }
}

/// A rectangular block with sides `size` (mm) centred at the origin, edges along the axes:
/// six trimmed planes, twelve straight edges, eight corners.
#[must_use]
pub fn block(size: DVec3) -> Solid {
    let half = 0.5 * size;
    PlanarBuilder::new(corners(-half, half), &box_faces()).finish(Vec::new())
}

/// The tetrahedron with these four corners (not coplanar): four trimmed triangular planes,
/// six straight edges, four corners.
#[must_use]
pub fn tetrahedron(points: [DVec3; 4]) -> Solid {
    let faces: Vec<[usize; 3]> = (0..4)
        .map(|apart| {
            let mut f: Vec<usize> = (0..4).filter(|&k| k != apart).collect();
            // Counter-clockwise seen from outside: the normal points away from the fourth
            // corner.
            let (a, b, c) = (points[f[0]], points[f[1]], points[f[2]]);
            if (b - a).cross(c - b).dot(points[apart] - a) > 0.0 {
                f.swap(1, 2);
            }
            [f[0], f[1], f[2]]
        })
        .collect();
    let cycles: Vec<&[usize]> = faces.iter().map(|f| &f[..]).collect();
    PlanarBuilder::new(points.to_vec(), &cycles).finish(Vec::new())
}

/// A square plate `width` x `width` x `thickness` (mm) centred at the origin (faces normal to
/// the axes, z through its thickness) with a cylindrical hole of radius `radius` along the z
/// axis. The top and bottom faces are planes trimmed by the square and, as a hole, the circle;
/// the hole's wall is a cylinder face over its whole parameter rectangle (u the angle about z,
/// v from the top down), its normal towards the axis.
#[must_use]
pub fn holed_plate(width: f64, thickness: f64, radius: f64) -> Solid {
    let half = DVec3::new(0.5 * width, 0.5 * width, 0.5 * thickness);
    let mut builder = PlanarBuilder::new(corners(-half, half), &box_faces());
    let (bottom, top) = (0, 1);
    // Seen from above, the top face's (u, v) is (x, y): the hole runs clockwise against the
    // circle's t. The bottom face's (u, v) is (y, x): there increasing t is clockwise.
    let top_edge = builder.circle_hole(top, radius, half.z, true);
    let bottom_edge = builder.circle_hole(bottom, radius, -half.z, false);
    let wall = FaceId(id32(builder.planes.len()));
    builder.edges[top_edge.0 as usize].uses[1] = Some(EdgeUse {
        face: wall,
        on: EdgeOn::Side(geom_param::ParamSide::VMin),
    });
    builder.edges[bottom_edge.0 as usize].uses[1] = Some(EdgeUse {
        face: wall,
        on: EdgeOn::Side(geom_param::ParamSide::VMax),
    });
    // Left-handed (x, y, -z): the normal points at the axis; v = 0 on the top circle.
    let cylinder = CylinderSurface {
        origin: DVec3::new(0.0, 0.0, half.z),
        x: DVec3::X,
        y: DVec3::Y,
        z: DVec3::NEG_Z,
        radius,
        height: ParamRange {
            min: 0.0,
            max: thickness,
            periodic: false,
        },
    };
    builder.finish(vec![Face {
        surface: Box::new(cylinder),
        boundary: [
            Boundary::Periodic,
            Boundary::Periodic,
            Boundary::Edge(top_edge),
            Boundary::Edge(bottom_edge),
        ],
        trim: None,
        convexity: FaceConvexity::Concave,
    }])
}
