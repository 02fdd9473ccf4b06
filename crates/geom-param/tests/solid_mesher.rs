//! The general solid mesher (`ObjectModel::from_solid`) against truth it does not produce:
//! closed-form volumes and areas of a box, a cylinder, a sphere and a plate with a hole, the
//! revolved mesher's values for the paper objects, and, on every mesh, an independent dense
//! sampling of the chordal error and of the normal deviation, watertightness after merging
//! vertices by their exact feature location, vertices on their exact features and outward
//! orientation.
//!
//! The solids are built here from small test-local surfaces and curves (a plane, a cylinder, a
//! sphere, lines and circles), trimmed planes with line and circle p-curves.

use geom_param::{
    Boundary, CircleEdge, Closure, ComponentMesh, Curve, Curve2, Curve2Point, CurvePoint, DVec2,
    DVec3, Edge, EdgeConvexity, EdgeId, EdgeOn, EdgeUse, Face, FaceConvexity, FaceId,
    FeatureLocation, Line2, MeshOptions, ModelError, ObjectDescription, ObjectModel, ParamRange,
    ParamSide, Profile, RevolvedSurface, Solid, Surface, SurfacePoint, TopologyError, Trim,
    TrimEntry, TrimLoop, Vertex, VertexId, classify_joint, classify_revolved_face,
};
use std::collections::HashMap;
use std::f64::consts::{FRAC_PI_2, PI, TAU};
use std::path::PathBuf;
use std::time::Instant;

// ---------------------------------------------------------------------------------------------
// Test-local geometry.

fn open(min: f64, max: f64) -> ParamRange {
    ParamRange {
        min,
        max,
        periodic: false,
    }
}

fn closed(min: f64, max: f64) -> ParamRange {
    ParamRange {
        min,
        max,
        periodic: true,
    }
}

/// S(u, v) = origin + u e1 + v e2 with e1, e2 orthonormal; e1 x e2 is the outward normal.
#[derive(Debug, Clone, Copy)]
struct Plane {
    origin: DVec3,
    e1: DVec3,
    e2: DVec3,
}

impl Plane {
    /// The plane through `origin` with outward `normal`, u along `e1` (projected).
    fn new(origin: DVec3, normal: DVec3, e1: DVec3) -> Self {
        let n = normal.normalize();
        let e1 = (e1 - n * e1.dot(n)).normalize();
        Self {
            origin,
            e1,
            e2: n.cross(e1),
        }
    }

    fn uv(&self, p: DVec3) -> DVec2 {
        DVec2::new(
            (p - self.origin).dot(self.e1),
            (p - self.origin).dot(self.e2),
        )
    }
}

impl Surface for Plane {
    fn eval(&self, u: f64, v: f64) -> SurfacePoint {
        SurfacePoint {
            point: self.origin + u * self.e1 + v * self.e2,
            du: self.e1,
            dv: self.e2,
            duu: DVec3::ZERO,
            duv: DVec3::ZERO,
            dvv: DVec3::ZERO,
        }
    }

    fn domain(&self) -> [ParamRange; 2] {
        [open(-1e4, 1e4), open(-1e4, 1e4)]
    }
}

/// A cylinder about the z axis through `centre` from z = centre.z to centre.z + height:
/// S(u, v) = centre + r (cos u, sin u, 0) + (0, 0, v) facing out, or with v measured down from
/// the top (S_v = -z) facing in (the wall of a hole).
#[derive(Debug, Clone, Copy)]
struct Cylinder {
    centre: DVec3,
    radius: f64,
    height: f64,
    inward: bool,
}

impl Surface for Cylinder {
    fn eval(&self, u: f64, v: f64) -> SurfacePoint {
        let (s, c) = u.sin_cos();
        let r = self.radius;
        let (z, dz) = if self.inward {
            (self.height - v, -1.0)
        } else {
            (v, 1.0)
        };
        SurfacePoint {
            point: self.centre + DVec3::new(r * c, r * s, z),
            du: DVec3::new(-r * s, r * c, 0.0),
            dv: DVec3::new(0.0, 0.0, dz),
            duu: DVec3::new(-r * c, -r * s, 0.0),
            duv: DVec3::ZERO,
            dvv: DVec3::ZERO,
        }
    }

    fn domain(&self) -> [ParamRange; 2] {
        [closed(0.0, TAU), open(0.0, self.height)]
    }
}

/// S(u, v) = r (cos v cos u, cos v sin u, sin v), v in [-π/2, π/2]: poles at v = ±π/2, where
/// ∂S/∂u vanishes and the default normal is undefined.
#[derive(Debug, Clone, Copy)]
struct Sphere {
    radius: f64,
}

impl Surface for Sphere {
    fn eval(&self, u: f64, v: f64) -> SurfacePoint {
        let (su, cu) = u.sin_cos();
        let (sv, cv) = v.sin_cos();
        let r = self.radius;
        SurfacePoint {
            point: r * DVec3::new(cv * cu, cv * su, sv),
            du: r * DVec3::new(-cv * su, cv * cu, 0.0),
            dv: r * DVec3::new(-sv * cu, -sv * su, cv),
            duu: r * DVec3::new(-cv * cu, -cv * su, 0.0),
            duv: r * DVec3::new(sv * su, -sv * cu, 0.0),
            dvv: r * DVec3::new(-cv * cu, -cv * su, -sv),
        }
    }

    fn domain(&self) -> [ParamRange; 2] {
        [closed(0.0, TAU), open(-FRAC_PI_2, FRAC_PI_2)]
    }
}

/// C(t) = a + t (b - a) / |b - a|, t in [0, |b - a|].
#[derive(Debug, Clone, Copy)]
struct Line {
    a: DVec3,
    b: DVec3,
}

impl Curve for Line {
    fn eval(&self, t: f64) -> CurvePoint {
        let d = (self.b - self.a).normalize();
        CurvePoint {
            point: self.a + t * d,
            d1: d,
            d2: DVec3::ZERO,
        }
    }

    fn domain(&self) -> ParamRange {
        open(0.0, self.a.distance(self.b))
    }
}

/// c(t) = centre + cos t a1 + sin t a2 in a face's (u, v) plane, t in [0, 2π).
#[derive(Debug, Clone, Copy)]
struct Ellipse2 {
    centre: DVec2,
    a1: DVec2,
    a2: DVec2,
}

impl Curve2 for Ellipse2 {
    fn eval(&self, t: f64) -> Curve2Point {
        let (s, c) = t.sin_cos();
        Curve2Point {
            point: self.centre + c * self.a1 + s * self.a2,
            d1: -s * self.a1 + c * self.a2,
            d2: -c * self.a1 - s * self.a2,
        }
    }

    fn domain(&self) -> ParamRange {
        closed(0.0, TAU)
    }
}

/// A face that evaluates to NaN everywhere.
#[derive(Debug)]
struct Broken;

impl Surface for Broken {
    fn eval(&self, _u: f64, _v: f64) -> SurfacePoint {
        let nan = DVec3::splat(f64::NAN);
        SurfacePoint {
            point: nan,
            du: nan,
            dv: nan,
            duu: nan,
            duv: nan,
            dvv: nan,
        }
    }

    fn domain(&self) -> [ParamRange; 2] {
        [open(0.0, 1.0), open(0.0, 1.0)]
    }
}

// ---------------------------------------------------------------------------------------------
// Building solids.

/// One piece of a trimmed plane's loop.
enum Piece {
    /// The line edge from vertex i to vertex j (created on first use, reused reversed).
    Line(usize, usize),
    /// Circle edge `edge` (centre, radius, in the z = centre.z plane), oriented as the loop
    /// needs: counter-clockwise in (u, v) for an outer loop, clockwise for a hole.
    Circle { edge: usize, hole: bool },
}

#[derive(Default)]
struct Builder {
    points: Vec<DVec3>,
    faces: Vec<Face>,
    curves: Vec<Box<dyn Curve>>,
    circles: HashMap<usize, CircleEdge>,
    uses: Vec<Vec<EdgeUse>>,
    ends: Vec<Option<[VertexId; 2]>>,
    lines: HashMap<(usize, usize), usize>,
}

impl Builder {
    fn vertex(&mut self, p: DVec3) -> usize {
        self.points.push(p);
        self.points.len() - 1
    }

    fn edge(&mut self, curve: Box<dyn Curve>, ends: Option<[VertexId; 2]>) -> usize {
        self.curves.push(curve);
        self.uses.push(Vec::new());
        self.ends.push(ends);
        self.curves.len() - 1
    }

    fn circle(&mut self, centre: DVec3, radius: f64) -> usize {
        let edge = self.edge(
            Box::new(CircleEdge {
                radius,
                z: centre.z,
            }),
            None,
        );
        assert_eq!(
            centre.truncate(),
            DVec2::ZERO,
            "circle edges are about the z axis"
        );
        self.circles.insert(
            edge,
            CircleEdge {
                radius,
                z: centre.z,
            },
        );
        edge
    }

    fn next_face(&self) -> FaceId {
        FaceId(self.faces.len() as u32)
    }

    /// A plane face with outward `normal` trimmed by `loops` (loop 0 outer).
    fn plane(&mut self, origin: DVec3, normal: DVec3, e1: DVec3, loops: Vec<Vec<Piece>>) {
        let plane = Plane::new(origin, normal, e1);
        let face = self.next_face();
        let mut trim_loops = Vec::new();
        for (li, pieces) in loops.into_iter().enumerate() {
            let mut entries = Vec::new();
            for (k, piece) in pieces.into_iter().enumerate() {
                let on = EdgeOn::Trim {
                    loop_index: li as u32,
                    index: k as u32,
                };
                let (edge, pcurve, reversed): (usize, Box<dyn Curve2>, bool) = match piece {
                    Piece::Line(i, j) => {
                        let (edge, reversed) = match self.lines.get(&(j, i)) {
                            Some(&e) => (e, true),
                            None => {
                                let line = Line {
                                    a: self.points[i],
                                    b: self.points[j],
                                };
                                let e = self.edge(
                                    Box::new(line),
                                    Some([VertexId(i as u32), VertexId(j as u32)]),
                                );
                                self.lines.insert((i, j), e);
                                (e, false)
                            }
                        };
                        let start = self.curves[edge].eval(0.0).point;
                        let length = self.curves[edge].domain().max;
                        let end = self.curves[edge].eval(length).point;
                        let (a, b) = (plane.uv(start), plane.uv(end));
                        let pcurve = Line2 {
                            origin: a,
                            direction: (b - a) / length,
                            range: open(0.0, length),
                        };
                        (edge, Box::new(pcurve), reversed)
                    }
                    Piece::Circle { edge, hole } => {
                        let c = self.circles[&edge];
                        let centre = plane.uv(DVec3::new(0.0, 0.0, c.z));
                        let a1 = c.radius * DVec2::new(plane.e1.x, plane.e2.x);
                        let a2 = c.radius * DVec2::new(plane.e1.y, plane.e2.y);
                        let ccw = a1.perp_dot(a2) > 0.0;
                        (edge, Box::new(Ellipse2 { centre, a1, a2 }), ccw == hole)
                    }
                };
                self.uses[edge].push(EdgeUse { face, on });
                entries.push(TrimEntry::new(EdgeId(edge as u32), pcurve, reversed));
            }
            trim_loops.push(TrimLoop::new(entries));
        }
        let trim = Trim::new(trim_loops, &plane.domain());
        self.faces.push(Face {
            surface: Box::new(plane),
            boundary: [Boundary::Trimmed; 4],
            trim: Some(trim),
            convexity: FaceConvexity::Flat,
        });
    }

    /// A face over its whole parameter rectangle; `sides` (u_min, u_max, v_min, v_max) name
    /// edges by index through `Boundary::Edge`, and each edge side gets its use.
    fn rectangle(
        &mut self,
        surface: Box<dyn Surface>,
        sides: [Boundary; 4],
        convexity: FaceConvexity,
    ) {
        let face = self.next_face();
        let order = [
            ParamSide::UMin,
            ParamSide::UMax,
            ParamSide::VMin,
            ParamSide::VMax,
        ];
        for (side, b) in order.into_iter().zip(sides) {
            if let Boundary::Edge(e) = b {
                self.uses[e.0 as usize].push(EdgeUse {
                    face,
                    on: EdgeOn::Side(side),
                });
            }
        }
        self.faces.push(Face {
            surface,
            boundary: sides,
            trim: None,
            convexity,
        });
    }

    fn build(self, edge_convexity: impl Fn(usize) -> EdgeConvexity) -> Solid {
        let mut vertices: Vec<Vertex> = self
            .points
            .iter()
            .map(|&point| Vertex {
                point,
                faces: Vec::new(),
                edges: Vec::new(),
            })
            .collect();
        let edges = self
            .curves
            .into_iter()
            .zip(self.uses)
            .zip(self.ends)
            .enumerate()
            .map(|(k, ((curve, uses), ends))| {
                assert_eq!(uses.len(), 2, "edge {k} has {} uses", uses.len());
                if let Some(ends) = ends {
                    for v in ends {
                        vertices[v.0 as usize].edges.push(EdgeId(k as u32));
                    }
                }
                Edge {
                    curve,
                    uses: [uses[0], uses[1]],
                    ends,
                    convexity: edge_convexity(k),
                }
            })
            .collect();
        Solid::new(self.faces, edges, vertices, Solid::DEFAULT_TOLERANCE)
    }
}

/// The box [0, a] x [0, b] x [0, c]: six trimmed planes, twelve line edges, eight vertices.
fn box_solid(size: DVec3) -> Solid {
    let mut s = Builder::default();
    let corner = |i: usize| {
        DVec3::new(
            if i & 1 == 1 { size.x } else { 0.0 },
            if i & 2 == 2 { size.y } else { 0.0 },
            if i & 4 == 4 { size.z } else { 0.0 },
        )
    };
    for i in 0..8 {
        s.vertex(corner(i));
    }
    // Each face's corners counter-clockwise seen from outside.
    let faces: [([usize; 4], DVec3); 6] = [
        ([0, 2, 3, 1], DVec3::NEG_Z),
        ([4, 5, 7, 6], DVec3::Z),
        ([0, 1, 5, 4], DVec3::NEG_Y),
        ([2, 6, 7, 3], DVec3::Y),
        ([0, 4, 6, 2], DVec3::NEG_X),
        ([1, 3, 7, 5], DVec3::X),
    ];
    for (quad, normal) in faces {
        let pieces = (0..4)
            .map(|k| Piece::Line(quad[k], quad[(k + 1) % 4]))
            .collect();
        let origin = corner(quad[0]);
        let e1 = corner(quad[1]) - origin;
        s.plane(origin, normal, e1, vec![pieces]);
    }
    s.build(|_| EdgeConvexity::Convex)
}

/// A cylinder of radius r and height h about the z axis: a periodic side face between two
/// circle edges, and two disk caps as planes trimmed by those circles.
fn cylinder_solid(r: f64, h: f64) -> Solid {
    let mut s = Builder::default();
    let bottom = s.circle(DVec3::ZERO, r);
    let top = s.circle(DVec3::new(0.0, 0.0, h), r);
    s.rectangle(
        Box::new(Cylinder {
            centre: DVec3::ZERO,
            radius: r,
            height: h,
            inward: false,
        }),
        [
            Boundary::Periodic,
            Boundary::Periodic,
            Boundary::Edge(EdgeId(bottom as u32)),
            Boundary::Edge(EdgeId(top as u32)),
        ],
        FaceConvexity::Convex,
    );
    s.plane(
        DVec3::ZERO,
        DVec3::NEG_Z,
        DVec3::Y,
        vec![vec![Piece::Circle {
            edge: bottom,
            hole: false,
        }]],
    );
    s.plane(
        DVec3::new(0.0, 0.0, h),
        DVec3::Z,
        DVec3::X,
        vec![vec![Piece::Circle {
            edge: top,
            hole: false,
        }]],
    );
    s.build(|_| EdgeConvexity::Convex)
}

/// The plate [-w/2, w/2] x [-d/2, d/2] x [0, t] with a through hole of radius r about the z axis:
/// top and bottom planes with a circular inner loop, four side planes, and the hole's wall (a
/// cylinder facing the axis) between the two hole circles.
fn plate_with_hole(w: f64, d: f64, t: f64, r: f64) -> Solid {
    let mut s = Builder::default();
    let corner = |i: usize| {
        DVec3::new(
            if i & 1 == 1 { 0.5 * w } else { -0.5 * w },
            if i & 2 == 2 { 0.5 * d } else { -0.5 * d },
            if i & 4 == 4 { t } else { 0.0 },
        )
    };
    for i in 0..8 {
        s.vertex(corner(i));
    }
    let low = s.circle(DVec3::ZERO, r);
    let high = s.circle(DVec3::new(0.0, 0.0, t), r);
    let quad = |q: [usize; 4]| -> Vec<Piece> {
        (0..4).map(|k| Piece::Line(q[k], q[(k + 1) % 4])).collect()
    };
    s.plane(
        corner(0),
        DVec3::NEG_Z,
        DVec3::Y,
        vec![
            quad([0, 2, 3, 1]),
            vec![Piece::Circle {
                edge: low,
                hole: true,
            }],
        ],
    );
    s.plane(
        corner(4),
        DVec3::Z,
        DVec3::X,
        vec![
            quad([4, 5, 7, 6]),
            vec![Piece::Circle {
                edge: high,
                hole: true,
            }],
        ],
    );
    for (q, normal) in [
        ([0, 1, 5, 4], DVec3::NEG_Y),
        ([2, 6, 7, 3], DVec3::Y),
        ([0, 4, 6, 2], DVec3::NEG_X),
        ([1, 3, 7, 5], DVec3::X),
    ] {
        let origin = corner(q[0]);
        s.plane(origin, normal, corner(q[1]) - origin, vec![quad(q)]);
    }
    // The wall: v = 0 on the top circle, v = t on the bottom one.
    s.rectangle(
        Box::new(Cylinder {
            centre: DVec3::ZERO,
            radius: r,
            height: t,
            inward: true,
        }),
        [
            Boundary::Periodic,
            Boundary::Periodic,
            Boundary::Edge(EdgeId(high as u32)),
            Boundary::Edge(EdgeId(low as u32)),
        ],
        FaceConvexity::Concave,
    );
    s.build(|_| EdgeConvexity::Convex)
}

/// A sphere of radius r: one face, periodic in u, collapsed into a pole vertex at each end of v.
fn sphere_solid(r: f64) -> Solid {
    let mut s = Builder::default();
    let south = s.vertex(DVec3::new(0.0, 0.0, -r));
    let north = s.vertex(DVec3::new(0.0, 0.0, r));
    s.rectangle(
        Box::new(Sphere { radius: r }),
        [
            Boundary::Periodic,
            Boundary::Periodic,
            Boundary::Vertex(VertexId(south as u32)),
            Boundary::Vertex(VertexId(north as u32)),
        ],
        FaceConvexity::Convex,
    );
    let mut solid = s.build(|_| EdgeConvexity::Convex);
    solid.vertices[south].faces.push(FaceId(0));
    solid.vertices[north].faces.push(FaceId(0));
    solid
}

/// The solid of revolution of `profile`, built here from the public pieces the way `revolve`
/// builds it: face i is segment i revolved, edge k the circle where segments meet, poles where
/// an axis profile starts and ends.
fn revolved_solid(profile: &Profile) -> Solid {
    let segments = profile.segments();
    let n = segments.len();
    let axis = profile.closure() == Closure::Axis;
    let edges = profile
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
                        face: FaceId(i as u32),
                        on: EdgeOn::Side(ParamSide::VMax),
                    },
                    EdgeUse {
                        face: FaceId(j as u32),
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
                (0, false) => Boundary::Edge(EdgeId(n as u32 - 1)),
                _ => Boundary::Edge(EdgeId(i as u32 - 1)),
            };
            let v_max = if axis && i == n - 1 {
                Boundary::Vertex(VertexId(1))
            } else {
                Boundary::Edge(EdgeId(i as u32))
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
                faces: vec![FaceId(n as u32 - 1)],
                edges: vec![],
            },
        ]
    } else {
        Vec::new()
    };
    Solid::new(faces, edges, vertices, Solid::DEFAULT_TOLERANCE)
}

// ---------------------------------------------------------------------------------------------
// Independent measurements.

fn options(tolerance: f64) -> MeshOptions {
    MeshOptions {
        chordal_tolerance: tolerance,
    }
}

/// Grid resolution of the independent sampling: 66 barycentric points per triangle (the mesher
/// samples quarters and the centroid).
const N: usize = 10;

/// What the independent sampling measures on a model's meshes.
#[derive(Debug, Default)]
struct Measured {
    /// Largest |S(Σ bᵢ uvᵢ) - Σ bᵢ Pᵢ| (mm).
    chordal_error: f64,
    /// Largest reported chordal error of a component mesh (mm).
    reported: f64,
    /// Largest angle between a triangle's normal and the exact normal over it (rad).
    normal_angle: f64,
    /// Signed volume of all component meshes (mm³).
    volume: f64,
    /// Total triangle area (mm²).
    area: f64,
    /// Number of triangles.
    triangles: usize,
}

fn measure(model: &ObjectModel) -> Measured {
    let solid = &model.solid;
    let mut m = Measured::default();
    for mesh in &model.meshes {
        m.reported = m.reported.max(mesh.chordal_error);
        m.triangles += mesh.len();
        for (k, params) in mesh.triangle_params.iter().enumerate() {
            let face = mesh.triangle_faces[k];
            let p = mesh.triangle(k);
            let cross = (p[1] - p[0]).cross(p[2] - p[0]);
            m.area += 0.5 * cross.length();
            m.volume += p[0].dot(p[1].cross(p[2])) / 6.0;
            let tri_normal = cross.normalize();
            for i in 0..=N {
                for j in 0..=N - i {
                    let b = [
                        i as f64 / N as f64,
                        j as f64 / N as f64,
                        (N - i - j) as f64 / N as f64,
                    ];
                    let u = b[0] * params[0][0] + b[1] * params[1][0] + b[2] * params[2][0];
                    let v = b[0] * params[0][1] + b[1] * params[1][1] + b[2] * params[2][1];
                    let exact = solid.eval_face(face, u, v).point;
                    let linear = p[0] * b[0] + p[1] * b[1] + p[2] * b[2];
                    m.chordal_error = m.chordal_error.max(exact.distance(linear));
                    let location = FeatureLocation::Face { id: face, u, v };
                    if let Some(n) = solid.face_normal_at(&location) {
                        let angle = n.dot(tri_normal).clamp(-1.0, 1.0).acos();
                        m.normal_angle = m.normal_angle.max(angle);
                    }
                }
            }
        }
    }
    m
}

/// A hashable key of an exact feature location.
fn location_key(location: &FeatureLocation) -> (u8, u32, u64, u64) {
    match *location {
        FeatureLocation::Face { id, u, v } => (0, id.0, u.to_bits(), v.to_bits()),
        FeatureLocation::Edge { id, t } => (1, id.0, t.to_bits(), 0),
        FeatureLocation::Vertex { id } => (2, id.0, 0, 0),
    }
}

/// Every structural promise of `ComponentMesh` on a general solid's meshes.
fn assert_well_formed(name: &str, model: &ObjectModel) {
    let solid = &model.solid;
    let mut merged: HashMap<(u8, u32, u64, u64), (usize, DVec3)> = HashMap::new();
    let mut directed: HashMap<(usize, usize), usize> = HashMap::new();
    for mesh in &model.meshes {
        check_mesh_arrays(name, mesh);
        // Every vertex on its exact feature, and one point per location across components.
        let ids: Vec<usize> = mesh
            .positions
            .iter()
            .zip(&mesh.vertex_locations)
            .map(|(p, loc)| {
                let exact = solid.point_at(loc);
                assert!(
                    exact.distance(*p) < 1e-9,
                    "{name}: vertex {p} is {} from its feature {loc:?}",
                    exact.distance(*p)
                );
                let n = merged.len();
                let entry = merged.entry(location_key(loc)).or_insert((n, *p));
                assert_eq!(entry.1, *p, "{name}: one location, two positions");
                entry.0
            })
            .collect();
        for (k, t) in mesh.triangles.iter().enumerate() {
            let v = t.map(|i| ids[i as usize]);
            assert!(
                v[0] != v[1] && v[1] != v[2] && v[0] != v[2],
                "{name}: triangle {k} repeats a vertex"
            );
            for e in 0..3 {
                *directed.entry((v[e], v[(e + 1) % 3])).or_default() += 1;
            }
            // Corner parameters evaluate to the corners (edge points within the model
            // tolerance of their p-curve image).
            let face = mesh.triangle_faces[k];
            for (c, (&[u, w], &corner)) in mesh.triangle_params[k].iter().zip(t).enumerate() {
                let q = solid.eval_face(face, u, w).point;
                let p = mesh.positions[corner as usize];
                assert!(q.distance(p) < 1e-9, "{name}: corner {c} of triangle {k}");
            }
            // Counter-clockwise seen from outside: agrees with the exact normal at the centroid.
            let p = mesh.triangle(k);
            let tn = (p[1] - p[0]).cross(p[2] - p[0]);
            let centre = mesh.locate(k, [1.0 / 3.0; 3]);
            if let Some(n) = solid.face_normal_at(&centre) {
                assert!(tn.dot(n) > 0.0, "{name}: triangle {k} faces inward");
            }
        }
        for (n, loc) in mesh.normals.iter().zip(&mesh.vertex_locations) {
            assert!((n.length() - 1.0).abs() < 1e-12, "{name}: normal not unit");
            if let Some(exact) = solid.face_normal_at(loc) {
                assert!(n.distance(exact) < 1e-12, "{name}: face vertex normal");
            }
        }
    }
    for (&(a, b), &count) in &directed {
        assert_eq!(count, 1, "{name}: mesh edge used twice in one direction");
        assert_eq!(
            directed.get(&(b, a)),
            Some(&1),
            "{name}: open mesh edge (not shared by exactly two triangles)"
        );
    }
}

fn check_mesh_arrays(name: &str, mesh: &ComponentMesh) {
    let n = mesh.positions.len();
    assert_eq!(mesh.normals.len(), n, "{name}");
    assert_eq!(mesh.vertex_locations.len(), n, "{name}");
    assert_eq!(mesh.triangle_faces.len(), mesh.triangles.len(), "{name}");
    assert_eq!(mesh.triangle_params.len(), mesh.triangles.len(), "{name}");
    assert!(
        mesh.triangles.iter().flatten().all(|&i| (i as usize) < n),
        "{name}"
    );
}

/// Closed-form checks: the mesh is within ε (measured) of the surface, so the solids differ
/// only inside a band of width ε along it, |ΔV| <= A ε. Each triangle's area is its surface
/// patch's projected area, the patch area times cos of the normal deviation, so the faces'
/// area differs by at most A (1 - cos θ_max); trimmed boundaries move by at most ε, adding at
/// most ε along every curved edge on each of its two faces.
fn assert_closed_form(name: &str, m: &Measured, volume: f64, area: f64, curved_edge_length: f64) {
    let eps = m.chordal_error.max(m.reported);
    let volume_bound = area * eps + 1e-9 * volume;
    assert!(
        (m.volume - volume).abs() <= volume_bound,
        "{name}: volume {} vs {volume} (bound {volume_bound})",
        m.volume
    );
    let area_bound =
        area * (1.0 - m.normal_angle.cos()) + 2.0 * curved_edge_length * eps + 1e-9 * area;
    assert!(
        (m.area - area).abs() <= area_bound,
        "{name}: area {} vs {area} (bound {area_bound})",
        m.area
    );
}

fn assert_within_tolerance(name: &str, m: &Measured, tolerance: f64) {
    assert!(
        m.chordal_error <= tolerance,
        "{name}: independently measured chordal error {} > {tolerance}",
        m.chordal_error
    );
    assert!(
        m.reported <= tolerance,
        "{name}: reported chordal error {} > {tolerance}",
        m.reported
    );
    assert!(m.volume > 0.0, "{name}: inward mesh");
}

// ---------------------------------------------------------------------------------------------
// Tests.

#[test]
fn box_is_exact_and_watertight() {
    let size = DVec3::new(40.0, 25.0, 10.0);
    for tolerance in [0.5, 0.05] {
        let model = ObjectModel::from_solid("box", box_solid(size), &options(tolerance))
            .expect("box meshes");
        assert_well_formed("box", &model);
        let m = measure(&model);
        assert_within_tolerance("box", &m, tolerance);
        // Planes are meshed exactly.
        assert!(m.chordal_error < 1e-12, "box: error {}", m.chordal_error);
        let volume = size.x * size.y * size.z;
        let area = 2.0 * (size.x * size.y + size.y * size.z + size.z * size.x);
        assert!(
            (m.volume - volume).abs() < 1e-9 * volume,
            "box volume {}",
            m.volume
        );
        assert!((m.area - area).abs() < 1e-9 * area, "box area {}", m.area);
        assert_eq!(model.scale, 40.0);
        // All six flat faces form one convex component with a hull.
        assert_eq!(model.components.len(), 1);
        assert!(model.hull(geom_param::ComponentId(0)).is_some());
    }
}

#[test]
fn box_triangles_stay_stout() {
    // A long thin box: the chordal budget alone would allow two needles per face.
    let model = ObjectModel::from_solid(
        "bar",
        box_solid(DVec3::new(100.0, 4.0, 4.0)),
        &options(0.05),
    )
    .expect("bar meshes");
    assert_well_formed("bar", &model);
    let worst = worst_aspect(&model);
    assert!(worst < 6.0, "a triangle with aspect {worst}");
}

/// The largest ratio of a triangle's longest side to its height onto that side (2/√3 ≈ 1.15 for
/// an equilateral triangle).
fn worst_aspect(model: &ObjectModel) -> f64 {
    let mut worst = 0.0_f64;
    for mesh in &model.meshes {
        for k in 0..mesh.len() {
            let p = mesh.triangle(k);
            let longest = (0..3)
                .map(|i| p[i].distance(p[(i + 1) % 3]))
                .fold(0.0, f64::max);
            let area = 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).length();
            worst = worst.max(longest * longest / (2.0 * area));
        }
    }
    worst
}

#[test]
fn cylinder_matches_closed_forms() {
    let (r, h) = (15.0, 40.0);
    for tolerance in [0.2, 0.05, 0.01] {
        let model = ObjectModel::from_solid("cylinder", cylinder_solid(r, h), &options(tolerance))
            .expect("cylinder meshes");
        assert_well_formed("cylinder", &model);
        let m = measure(&model);
        assert_within_tolerance("cylinder", &m, tolerance);
        let volume = PI * r * r * h;
        let area = 2.0 * PI * r * (r + h);
        assert_closed_form("cylinder", &m, volume, area, 2.0 * TAU * r);
        // Inscribed in a convex solid: the mesh encloses less.
        assert!(m.volume < volume);
    }
}

#[test]
fn plate_with_hole_matches_closed_forms() {
    let (w, d, t, r) = (60.0, 40.0, 8.0, 10.0);
    for tolerance in [0.2, 0.05] {
        let model =
            ObjectModel::from_solid("plate", plate_with_hole(w, d, t, r), &options(tolerance))
                .expect("plate meshes");
        assert_well_formed("plate", &model);
        let m = measure(&model);
        assert_within_tolerance("plate", &m, tolerance);
        let volume = (w * d - PI * r * r) * t;
        let area = 2.0 * (w * d - PI * r * r) + 2.0 * (w + d) * t + TAU * r * t;
        assert_closed_form("plate", &m, volume, area, 2.0 * TAU * r);
        // The hole's chords lie in the material's complement: the mesh encloses more.
        assert!(m.volume > volume);
        // The concave hole wall is a component of its own.
        assert_eq!(model.components.len(), 2);
    }
}

#[test]
fn sphere_poles_are_single_vertices() {
    let r = 30.0;
    for tolerance in [0.2, 0.05] {
        let model = ObjectModel::from_solid("sphere", sphere_solid(r), &options(tolerance))
            .expect("sphere meshes");
        assert_well_formed("sphere", &model);
        let m = measure(&model);
        assert_within_tolerance("sphere", &m, tolerance);
        assert_closed_form(
            "sphere",
            &m,
            4.0 / 3.0 * PI * r * r * r,
            4.0 * PI * r * r,
            0.0,
        );
        let mesh = &model.meshes[0];
        for pole in [0, 1] {
            let count = mesh
                .vertex_locations
                .iter()
                .filter(|l| **l == FeatureLocation::Vertex { id: VertexId(pole) })
                .count();
            assert_eq!(count, 1, "pole {pole} is one mesh vertex");
        }
        // The pole normals are the limits of the surface normal: ∓z.
        for (n, l) in mesh.normals.iter().zip(&mesh.vertex_locations) {
            match l {
                FeatureLocation::Vertex { id } if id.0 == 0 => {
                    assert!(n.distance(DVec3::NEG_Z) < 1e-9)
                }
                FeatureLocation::Vertex { .. } => assert!(n.distance(DVec3::Z) < 1e-9),
                _ => {}
            }
        }
    }
}

fn paper_profile(name: &str) -> Profile {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join(format!("../../fixtures/objects/{name}.json"));
    let text = std::fs::read_to_string(&path).expect("fixture exists");
    let description = ObjectDescription::from_json(&text).expect("fixture parses");
    Profile::new(&description.profile).expect("valid profile")
}

#[test]
fn paper_objects_agree_with_the_revolved_mesher() {
    let tolerance = 0.05;
    for name in ["paperweight", "goblet", "bowl", "pencil", "jar", "vase"] {
        let profile = paper_profile(name);
        let revolved = ObjectModel::from_profile(name, paper_profile(name), &options(tolerance))
            .expect("revolved mesher");
        let start = Instant::now();
        let general = ObjectModel::from_solid(name, revolved_solid(&profile), &options(tolerance))
            .expect("general mesher");
        let elapsed = start.elapsed();
        assert_well_formed(name, &general);
        let g = measure(&general);
        let r = measure(&revolved);
        assert_within_tolerance(name, &g, tolerance);
        eprintln!(
            "{name}: general {} triangles in {:.0} ms (error {:.4} mm), revolved {} triangles",
            g.triangles,
            elapsed.as_secs_f64() * 1e3,
            g.chordal_error.max(g.reported),
            r.triangles
        );
        // Stout everywhere, poles and seams included (the worst today is 14, on the pencil's
        // narrow band between two close edge circles).
        let aspect = worst_aspect(&general);
        assert!(aspect < 20.0, "{name}: a triangle with aspect {aspect}");
        // Same components, from the same solid description.
        assert_eq!(general.components, revolved.components, "{name}");
        assert!(
            (general.scale - revolved.scale).abs() <= 1e-3 * revolved.scale,
            "{name}: scale {} vs {}",
            general.scale,
            revolved.scale
        );
        // Each mesh is within its ε of the surface: volumes differ by at most A (ε_g + ε_r), and
        // areas by at most each one's projected-area deficit.
        let eps = g.chordal_error.max(g.reported) + r.chordal_error.max(r.reported);
        let area = g.area.max(r.area);
        assert!(
            (g.volume - r.volume).abs() <= area * eps,
            "{name}: volume {} vs revolved {}",
            g.volume,
            r.volume
        );
        let area_bound = area * ((1.0 - g.normal_angle.cos()) + (1.0 - r.normal_angle.cos()));
        assert!(
            (g.area - r.area).abs() <= area_bound,
            "{name}: area {} vs revolved {} (bound {area_bound})",
            g.area,
            r.area
        );
    }
}

#[test]
fn a_face_that_does_not_evaluate_is_an_error() {
    let mut solid = box_solid(DVec3::splat(10.0));
    solid.faces[3].surface = Box::new(Broken);
    match ObjectModel::from_solid("broken", solid, &options(0.05)) {
        Err(ModelError::Topology(TopologyError::NonFinite { what })) => {
            assert!(what.contains("face 3"), "{what}");
        }
        other => panic!(
            "expected a non-finite face, got {:?}",
            other.map(|m| m.name)
        ),
    }
}

#[test]
fn a_loop_without_area_is_an_error() {
    // One plane trimmed by a loop that runs from A to B along one edge and back along a second
    // edge on the same line: it encloses nothing.
    let plane = Plane::new(DVec3::ZERO, DVec3::Z, DVec3::X);
    let (a, b) = (DVec3::ZERO, DVec3::new(10.0, 0.0, 0.0));
    let line = |p: DVec3, q: DVec3| Line2 {
        origin: plane.uv(p),
        direction: (plane.uv(q) - plane.uv(p)) / 10.0,
        range: open(0.0, 10.0),
    };
    let on = |index: u32| EdgeUse {
        face: FaceId(0),
        on: EdgeOn::Trim {
            loop_index: 0,
            index,
        },
    };
    let entries = vec![
        TrimEntry::new(EdgeId(0), Box::new(line(a, b)), false),
        TrimEntry::new(EdgeId(1), Box::new(line(b, a)), false),
    ];
    let solid = Solid::new(
        vec![Face {
            surface: Box::new(plane),
            boundary: [Boundary::Trimmed; 4],
            trim: Some(Trim::new(vec![TrimLoop::new(entries)], &plane.domain())),
            convexity: FaceConvexity::Flat,
        }],
        vec![
            Edge {
                curve: Box::new(Line { a, b }),
                uses: [on(0), on(0)],
                ends: Some([VertexId(0), VertexId(1)]),
                convexity: EdgeConvexity::Convex,
            },
            Edge {
                curve: Box::new(Line { a: b, b: a }),
                uses: [on(1), on(1)],
                ends: Some([VertexId(1), VertexId(0)]),
                convexity: EdgeConvexity::Convex,
            },
        ],
        [a, b]
            .map(|point| Vertex {
                point,
                faces: vec![],
                edges: vec![EdgeId(0), EdgeId(1)],
            })
            .into(),
        0.0,
    );
    // Validation refuses it first: each edge lies on one face only (an open shell).
    let result = ObjectModel::from_solid("flat loop", solid, &options(0.05));
    assert!(
        matches!(
            result,
            Err(ModelError::Topology(TopologyError::EdgeUseCount { .. }))
        ),
        "{:?}",
        result.map(|m| m.name)
    );
}

#[test]
fn a_use_that_does_not_point_back_is_an_error() {
    // Edge 0 claims to be entry 7 of face 0's loop, which has four entries.
    let mut solid = box_solid(DVec3::splat(10.0));
    solid.edges[0].uses[0].on = EdgeOn::Trim {
        loop_index: 0,
        index: 7,
    };
    let result = ObjectModel::from_solid("bad use", solid, &options(0.05));
    assert!(
        matches!(
            result,
            Err(ModelError::Topology(TopologyError::BadReference { .. }))
        ),
        "{:?}",
        result.map(|m| m.name)
    );
}

#[test]
fn unusable_tolerances_are_rejected_as_for_profiles() {
    for tolerance in [0.0, -1.0, f64::NAN, 1e-6, 1e3] {
        let result =
            ObjectModel::from_solid("box", box_solid(DVec3::splat(10.0)), &options(tolerance));
        assert!(
            matches!(result, Err(ModelError::BadTolerance { .. })),
            "{tolerance}"
        );
    }
}
