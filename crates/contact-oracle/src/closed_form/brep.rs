//! Solids built face by face for the closed-form scenes and tests: a rectangular block and a
//! tetrahedron whose faces are all trimmed planes (every edge between two trims), and, through
//! geom-param's extrusion, a square plate with a cylindrical hole.
//!
//! The polyhedra: each face is a plane (origin at its first corner, x along its first side)
//! trimmed by one counter-clockwise loop of straight edges; each edge is the line from one
//! corner to another, t the arc length, used forwards by the face that meets it first and
//! backwards by the other; every corner is a vertex ending its edges.

use geom_param::{
    Boundary, BuildError, Edge, EdgeConvexity, EdgeId, EdgeOn, EdgeUse, Face, FaceConvexity,
    FaceId, Line2, LineCurve, ParamRange, Placement, PlanarProfile, PlanarSegment, Plane, Solid,
    Trim, TrimEntry, TrimLoop, Vertex, VertexId, extrude, validate,
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

/// A plane's frame: (u, v) of a point is its offset from `origin` along `x` and `y`.
#[derive(Clone, Copy, Debug)]
struct Frame {
    origin: DVec3,
    x: DVec3,
    y: DVec3,
}

impl Frame {
    fn params_of(&self, p: DVec3) -> DVec2 {
        let d = p - self.origin;
        DVec2::new(d.dot(self.x), d.dot(self.y))
    }
}

/// A face under construction: the plane and its loop of entries.
struct FaceDraft {
    plane: Plane,
    entries: Vec<TrimEntry>,
}

/// An edge under construction: its line, its uses as far as known, its end vertices.
struct EdgeDraft {
    curve: LineCurve,
    uses: [Option<EdgeUse>; 2],
    ends: [VertexId; 2],
}

fn id32(i: usize) -> u32 {
    u32::try_from(i).expect("a handful of features")
}

/// The polyhedron with corners `points` and faces `cycles` (corner indices, counter-clockwise
/// seen from outside, each side shared by exactly two faces in opposite directions), every
/// face a trimmed plane whose domain is its loop's (u, v) box grown by a quarter on every side
/// (so the trim lies strictly inside); validated.
fn polyhedron(points: &[DVec3], cycles: &[&[usize]]) -> Result<Solid, BuildError> {
    let mut faces: Vec<FaceDraft> = Vec::new();
    let mut edges: Vec<EdgeDraft> = Vec::new();
    let mut straight: BTreeMap<(usize, usize), EdgeId> = BTreeMap::new();
    for cycle in cycles {
        let p = |k: usize| points[cycle[k % cycle.len()]];
        let x = (p(1) - p(0)).normalize();
        let n = (p(1) - p(0)).cross(p(2) - p(1)).normalize();
        let frame = Frame {
            origin: p(0),
            x,
            y: n.cross(x),
        };
        let uvs: Vec<DVec2> = (0..cycle.len()).map(|k| frame.params_of(p(k))).collect();
        let lo = uvs.iter().copied().fold(DVec2::INFINITY, DVec2::min);
        let hi = uvs.iter().copied().fold(DVec2::NEG_INFINITY, DVec2::max);
        let grow = 0.25 * (hi - lo);
        let range = |i: usize| ParamRange {
            min: lo[i] - grow[i],
            max: hi[i] + grow[i],
            periodic: false,
        };
        let plane = Plane::new(Placement::new(p(0), n, x)?, [range(0), range(1)])?;
        let face = faces.len();
        let mut entries = Vec::new();
        for k in 0..cycle.len() {
            let (i, j) = (cycle[k], cycle[(k + 1) % cycle.len()]);
            let use_ = EdgeUse {
                face: FaceId(id32(face)),
                on: EdgeOn::Trim {
                    loop_index: 0,
                    index: id32(k),
                },
            };
            // The edge runs from its first face's corner i to j; the other face walks it back.
            let (start, end, reversed) = if straight.contains_key(&(j, i)) {
                (j, i, true)
            } else {
                (i, j, false)
            };
            let (a, b) = (points[start], points[end]);
            let length = a.distance(b);
            let t_range = ParamRange {
                min: 0.0,
                max: length,
                periodic: false,
            };
            let edge = if reversed {
                let edge = straight[&(j, i)];
                edges[edge.0 as usize].uses[1] = Some(use_);
                edge
            } else {
                let edge = EdgeId(id32(edges.len()));
                edges.push(EdgeDraft {
                    curve: LineCurve::new(a, (b - a) / length, t_range)?,
                    uses: [Some(use_), None],
                    ends: [VertexId(id32(i)), VertexId(id32(j))],
                });
                straight.insert((i, j), edge);
                edge
            };
            let pcurve = Line2 {
                origin: frame.params_of(a),
                direction: (frame.params_of(b) - frame.params_of(a)) / length,
                range: t_range,
            };
            entries.push(TrimEntry::new(edge, Box::new(pcurve), reversed));
        }
        faces.push(FaceDraft { plane, entries });
    }
    let faces: Vec<Face> = faces
        .into_iter()
        .map(|f| {
            let domain = geom_param::Surface::domain(&f.plane);
            Face {
                surface: Box::new(f.plane),
                boundary: [Boundary::Trimmed; 4],
                trim: Some(Trim::new(vec![TrimLoop::new(f.entries)], &domain)),
                convexity: FaceConvexity::Flat,
            }
        })
        .collect();
    let mut vertices: Vec<Vertex> = points
        .iter()
        .map(|&point| Vertex {
            point,
            faces: Vec::new(),
            edges: Vec::new(),
        })
        .collect();
    let mut out_edges = Vec::new();
    for (e, draft) in edges.into_iter().enumerate() {
        for v in draft.ends {
            vertices[v.0 as usize].edges.push(EdgeId(id32(e)));
        }
        let [Some(first), Some(second)] = draft.uses else {
            return Err(BuildError::BadDimension {
                what: "polyhedron edge uses",
                value: e as f64,
                requirement: "every side shared by two faces",
            });
        };
        out_edges.push(Edge {
            curve: Box::new(draft.curve),
            uses: [first, second],
            ends: Some(draft.ends),
            convexity: EdgeConvexity::Convex,
        });
    }
    let solid = Solid::new(faces, out_edges, vertices, 0.0);
    validate(&solid)?;
    Ok(solid)
}

/// Checks that a dimension is finite and positive.
fn positive(what: &'static str, value: f64) -> Result<f64, BuildError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(BuildError::BadDimension {
            what,
            value,
            requirement: "finite and > 0",
        })
    }
}

/// A rectangular block with sides `size` (mm) centred at the origin, edges along the axes:
/// six trimmed planes, twelve straight edges, eight corners.
///
/// # Errors
/// [`BuildError::BadDimension`] for a side that is not finite and positive.
pub fn block(size: DVec3) -> Result<Solid, BuildError> {
    for s in size.to_array() {
        positive("block side", s)?;
    }
    let half = 0.5 * size;
    let cycles: Vec<&[usize]> = BOX_FACES.iter().map(|f| &f[..]).collect();
    polyhedron(&corners(-half, half), &cycles)
}

/// The tetrahedron with these four corners: four trimmed triangular planes, six straight
/// edges, four corners.
///
/// # Errors
/// [`BuildError::BadDimension`] when the corners are not finite or are (nearly) coplanar.
pub fn tetrahedron(points: [DVec3; 4]) -> Result<Solid, BuildError> {
    let size = points
        .iter()
        .map(|p| p.distance(points[0]))
        .fold(0.0, f64::max);
    let volume = (points[1] - points[0])
        .cross(points[2] - points[0])
        .dot(points[3] - points[0]);
    // Also refuses NaN.
    let flat = volume.abs().partial_cmp(&(1e-9 * size * size * size));
    if flat != Some(std::cmp::Ordering::Greater) {
        return Err(BuildError::BadDimension {
            what: "tetrahedron volume x 6",
            value: volume,
            requirement: "corners finite and not coplanar",
        });
    }
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
    polyhedron(&points, &cycles)
}

/// The profile of a square `width` wide centred at the origin with a circular hole of radius
/// `radius` about the origin.
#[must_use]
pub fn holed_square(width: f64, radius: f64) -> PlanarProfile {
    let h = 0.5 * width;
    let corner = |x: f64, y: f64| DVec2::new(x * h, y * h);
    let line = |from: DVec2, to: DVec2| PlanarSegment::Line { from, to };
    let start = DVec2::new(radius, 0.0);
    PlanarProfile {
        outer: vec![
            line(corner(-1.0, -1.0), corner(1.0, -1.0)),
            line(corner(1.0, -1.0), corner(1.0, 1.0)),
            line(corner(1.0, 1.0), corner(-1.0, 1.0)),
            line(corner(-1.0, 1.0), corner(-1.0, -1.0)),
        ],
        holes: vec![vec![PlanarSegment::Arc {
            center: DVec2::ZERO,
            from: start,
            to: start,
            ccw: false,
        }]],
    }
}

/// A square plate `width` x `width` x `thickness` (mm) centred at the origin (faces normal to
/// the axes, z through its thickness) with a cylindrical hole of radius `radius` along the z
/// axis: geom-param's [`extrude`] of [`holed_square`]. The caps are planes trimmed by the
/// square and, as a hole, the circle; the hole's wall is a reversed cylinder over its whole
/// parameter rectangle, its normal towards the axis.
///
/// # Errors
/// As [`extrude`] (a hole that does not fit, a non-positive thickness).
pub fn holed_plate(width: f64, thickness: f64, radius: f64) -> Result<Solid, BuildError> {
    extrude(
        &holed_square(width, radius),
        -0.5 * thickness,
        0.5 * thickness,
    )
}
