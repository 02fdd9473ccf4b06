//! Triangulation of one face's region: a constrained Delaunay triangulation (spade) of its
//! boundary loops in the scaled parameter plane, refined for shape and then by measured error.
//!
//! The plane (`plane_map.rs`) scales (u, v) by typical derivative lengths and warps one of them
//! where needed, so that lengths and angles there approximate those on the surface. The region is
//! what lies inside an odd number of loops (found by crossing constraint edges from outside).
//! Refinement alternates two steps until every triangle meets the budget:
//! - shape: Ruppert-Chew refinement with a 20° angle limit and an area cap from the face's
//!   target length, never splitting a boundary segment (the neighbouring face shares it), so
//!   triangles stay stout and triangle trees over the mesh can cull;
//! - error and size: each triangle is sampled at 13 barycentric points (quarters and the
//!   centroid), the distance between S(Σ bᵢ uvᵢ) and Σ bᵢ Pᵢ is taken, and a triangle over
//!   budget, or with a side longer than 1.5 target lengths in space, gets a vertex at its
//!   centroid.
//!
//! The result is measured, not predicted: the face's chordal error is the largest sampled
//! deviation of its final triangles.

use crate::tessellation::face_boundary::FaceBoundary;
use crate::tessellation::face_metric::FaceMetric;
use crate::tessellation::plane_map::PlaneMap;
use crate::tessellation::vertex_table::VertexTable;
use crate::topology::feature::{FaceId, FeatureLocation};
use crate::topology::solid::Solid;
use glam::{DVec2, DVec3};
use spade::handles::FixedFaceHandle;
use spade::{
    AngleLimit, ConstrainedDelaunayTriangulation, Point2, PositionInTriangulation,
    RefinementParameters, Triangulation,
};

type Cdt = ConstrainedDelaunayTriangulation<Point2<f64>>;

/// Smallest angle the shape refinement aims for (degrees).
const ANGLE_LIMIT_DEG: f64 = 20.0;
/// Largest triangle area in the scaled plane, as a fraction of the target length squared
/// (an equilateral triangle of side h has 0.433 h²).
const MAX_AREA_FRACTION: f64 = 0.5;
/// Triangles smaller than this fraction of the target length squared are left as they are by
/// the shape refinement (it cannot improve angles that the boundary imposes).
const MIN_AREA_FRACTION: f64 = 1e-8;
/// Longest triangle side, as a fraction of the face's target length, before a triangle is
/// split for size (an equilateral triangle of the shape refinement's largest area has sides of
/// about 1.07 target lengths).
const MAX_EDGE_FRACTION: f64 = 1.5;
/// Passes of error refinement before giving up.
const MAX_PASSES: usize = 48;
/// Vertices one face may reach before giving up.
const MAX_FACE_VERTICES: usize = 1 << 19;

/// Barycentric sample points other than the corners: quarters of the edges, the three interior
/// quarter points and the centroid.
const SAMPLES: [[f64; 3]; 13] = [
    [0.75, 0.25, 0.0],
    [0.5, 0.5, 0.0],
    [0.25, 0.75, 0.0],
    [0.0, 0.75, 0.25],
    [0.0, 0.5, 0.5],
    [0.0, 0.25, 0.75],
    [0.25, 0.0, 0.75],
    [0.5, 0.0, 0.5],
    [0.75, 0.0, 0.25],
    [0.5, 0.25, 0.25],
    [0.25, 0.5, 0.25],
    [0.25, 0.25, 0.5],
    [1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0],
];

/// The triangles of one face.
#[derive(Clone, Debug, Default)]
pub(crate) struct FaceMesh {
    /// Triangles as vertex ids of the solid's [`VertexTable`], counter-clockwise seen from
    /// outside.
    pub triangles: Vec<[u32; 3]>,
    /// The (u, v) of each triangle's corners (periodic parameters continuous per triangle).
    pub params: Vec<[[f64; 2]; 3]>,
    /// Largest sampled distance between the face and its triangles (mm).
    pub chordal_error: f64,
}

/// What the triangulation of one face needs.
pub(crate) struct TriangulationInput<'a> {
    /// The solid.
    pub solid: &'a Solid,
    /// The face.
    pub face: FaceId,
    /// Its metric (scaled plane and target length).
    pub metric: &'a FaceMetric,
    /// The error every triangle is refined to (mm).
    pub budget: f64,
    /// The error the face must not exceed once refinement stops (mm).
    pub tolerance: f64,
}

/// A vertex of the triangulation: its face parameters, its mesh vertex once it has one, and its
/// exact point once evaluated.
#[derive(Clone, Copy, Debug)]
struct CdtVertex {
    uv: DVec2,
    id: Option<u32>,
    position: Option<DVec3>,
}

/// Triangulates the region bounded by `loops` and refines it (see the module docs), adding its
/// interior vertices to `table`.
///
/// # Errors
/// A reason when the loops do not bound a region (coincident points, crossing or overlapping
/// segments, no area), the surface is not finite inside, or refinement cannot bring the
/// measured error within the tolerance.
pub(crate) fn triangulate_face(
    input: &TriangulationInput<'_>,
    boundary: &FaceBoundary,
    table: &mut VertexTable,
) -> Result<FaceMesh, String> {
    // spade documents panics on precision loss (an inserted circumcenter it cannot place);
    // the inputs are checked beforehand, and this turns any that remains into an error.
    let run =
        std::panic::AssertUnwindSafe(|| FaceTriangulation::new(input, boundary, table)?.run());
    let mut mesh = match std::panic::catch_unwind(run) {
        Ok(result) => result?,
        Err(_) => return Err("the constrained triangulation lost precision".into()),
    };
    for (ids, params) in &boundary.fans {
        mesh.triangles.push(*ids);
        mesh.params.push(*params);
    }
    mesh.chordal_error = mesh.chordal_error.max(boundary.fan_error);
    Ok(mesh)
}

/// The spade point of a plane-map point, with coordinates too small for spade (below
/// `spade::MIN_ALLOWED_VALUE`, 2^-142, which it rejects as `TooSmall`) flushed to zero:
/// rounding noise such as 1e-300 next to coordinates of order 1 (real STEP exports write
/// such values, e.g. the CAx-IF `xr1-tu-*.stp` and HiCAD files).
fn spade_point(q: DVec2) -> Point2<f64> {
    let flush = |x: f64| {
        if x.abs() < spade::MIN_ALLOWED_VALUE {
            0.0
        } else {
            x
        }
    };
    Point2::new(flush(q.x), flush(q.y))
}

struct FaceTriangulation<'a, 't> {
    input: &'a TriangulationInput<'a>,
    map: PlaneMap,
    table: &'t mut VertexTable,
    cdt: Cdt,
    vertices: Vec<CdtVertex>,
}

impl<'a, 't> FaceTriangulation<'a, 't> {
    fn new(
        input: &'a TriangulationInput<'a>,
        boundary: &FaceBoundary,
        table: &'t mut VertexTable,
    ) -> Result<Self, String> {
        let loops = &boundary.loops;
        let map = boundary.map.clone();
        let mut cdt = Cdt::new();
        let mut vertices = Vec::new();
        let mut handles = Vec::with_capacity(loops.len());
        for (li, l) in loops.iter().enumerate() {
            let mut loop_handles = Vec::with_capacity(l.len());
            for p in l {
                let q = map.plane_point(p.uv);
                let h = cdt
                    .insert(spade_point(q))
                    .map_err(|e| format!("loop {li} has a point spade rejects: {e:?}"))?;
                if h.index() != vertices.len() {
                    return Err(format!(
                        "loop {li} has a point at (u, v) = ({}, {}) where the boundary already has one",
                        p.uv.x, p.uv.y
                    ));
                }
                vertices.push(CdtVertex {
                    uv: p.uv,
                    id: Some(p.id),
                    position: Some(table.get(p.id).position),
                });
                loop_handles.push(h);
            }
            handles.push(loop_handles);
        }
        for (li, l) in handles.iter().enumerate() {
            for k in 0..l.len() {
                let (a, b) = (l[k], l[(k + 1) % l.len()]);
                let added = cdt.try_add_constraint(a, b);
                if added.len() != 1 {
                    return Err(format!(
                        "loop {li} crosses or touches a boundary segment at its segment {k}"
                    ));
                }
            }
        }
        Ok(Self {
            input,
            map,
            table,
            cdt,
            vertices,
        })
    }

    /// Refines and returns the face's triangles.
    fn run(mut self) -> Result<FaceMesh, String> {
        self.refine_shape();
        let mut worst = f64::INFINITY;
        for pass in 0..=MAX_PASSES {
            self.sync_vertices();
            let region = self.region();
            let mut bad: Vec<Point2<f64>> = Vec::new();
            worst = 0.0;
            let mut any = false;
            let max_edge = MAX_EDGE_FRACTION * self.input.metric.target_length;
            for tri in self.region_triangles(&region) {
                any = true;
                let error = self.triangle_error(tri)?;
                worst = worst.max(error);
                if error > self.input.budget || self.longest_edge(tri) > max_edge {
                    let c = tri
                        .iter()
                        .map(|&i| self.cdt.vertex(vertex_handle(i)).position())
                        .fold(DVec2::ZERO, |s, p| s + DVec2::new(p.x, p.y))
                        / 3.0;
                    bad.push(spade_point(c));
                }
            }
            if !any {
                return Err("its boundary loops enclose no area".into());
            }
            if bad.is_empty() || pass == MAX_PASSES || self.vertices.len() >= MAX_FACE_VERTICES {
                break;
            }
            let accepted: Vec<Point2<f64>> = bad
                .into_iter()
                .filter(|&p| self.inside_region(p, &region))
                .collect();
            if accepted.is_empty() {
                break;
            }
            for p in accepted {
                self.cdt
                    .insert(p)
                    .map_err(|e| format!("refinement point rejected by spade: {e:?}"))?;
            }
            self.refine_shape();
        }
        if worst > self.input.tolerance {
            return Err(format!(
                "refinement stopped at {} vertices with a measured chordal error of {worst} mm (tolerance {} mm)",
                self.vertices.len(),
                self.input.tolerance
            ));
        }
        self.finish(worst)
    }

    /// Ruppert-Chew shape refinement inside the region, keeping the boundary segments whole.
    fn refine_shape(&mut self) {
        // In the plane, the target length is divided by the local stretch; the cap uses the
        // smallest stretch, and the 3D size check in `run` refines where it is larger.
        let h = self.input.metric.target_length / self.map.min_stretch();
        let n = self.cdt.num_vertices();
        let room = MAX_FACE_VERTICES.saturating_sub(n).min(4 * n + 1024);
        let parameters = RefinementParameters::<f64>::new()
            .with_angle_limit(AngleLimit::from_deg(ANGLE_LIMIT_DEG))
            .with_max_allowed_area(MAX_AREA_FRACTION * h * h)
            .with_min_required_area(MIN_AREA_FRACTION * h * h)
            .keep_constraint_edges()
            .exclude_outer_faces(true)
            .with_max_additional_vertices(room);
        self.cdt.refine(parameters);
    }

    /// Records the vertices spade added since the last call (their (u, v) from the plane).
    fn sync_vertices(&mut self) {
        for i in self.vertices.len()..self.cdt.num_vertices() {
            let p = self.cdt.vertex(vertex_handle(i)).position();
            self.vertices.push(CdtVertex {
                uv: self.map.params_of(DVec2::new(p.x, p.y)),
                id: None,
                position: None,
            });
        }
    }

    /// Whether each face (by index) lies in the region: inside an odd number of loops, found by
    /// crossing constraint edges from the outer face.
    fn region(&self) -> Vec<bool> {
        let mut state: Vec<Option<bool>> = vec![None; self.cdt.num_all_faces()];
        let mut stack: Vec<(FixedFaceHandle<spade::handles::InnerTag>, bool)> = Vec::new();
        for hull in self.cdt.convex_hull() {
            let inward = hull.rev();
            if let Some(face) = inward.face().as_inner() {
                let inside = inward.is_constraint_edge();
                if state[face.fix().index()].is_none() {
                    state[face.fix().index()] = Some(inside);
                    stack.push((face.fix(), inside));
                }
            }
        }
        while let Some((face, inside)) = stack.pop() {
            for edge in self.cdt.face(face).adjacent_edges() {
                if let Some(next) = edge.rev().face().as_inner() {
                    let k = next.fix().index();
                    if state[k].is_none() {
                        let next_inside = inside ^ edge.is_constraint_edge();
                        state[k] = Some(next_inside);
                        stack.push((next.fix(), next_inside));
                    }
                }
            }
        }
        state.into_iter().map(|s| s == Some(true)).collect()
    }

    /// Corner vertex indices of the region's triangles, counter-clockwise.
    fn region_triangles(&self, region: &[bool]) -> Vec<[usize; 3]> {
        self.cdt
            .inner_faces()
            .filter(|f| region[f.fix().index()])
            .map(|f| f.vertices().map(|v| v.fix().index()))
            .collect()
    }

    /// Whether a refinement point lies strictly inside a region triangle, or on an edge between
    /// two of them (never on a boundary segment, which spade would split).
    fn inside_region(&self, p: Point2<f64>, region: &[bool]) -> bool {
        match self.cdt.locate(p) {
            PositionInTriangulation::OnFace(face) => region[face.index()],
            PositionInTriangulation::OnEdge(edge) => {
                let edge = self.cdt.directed_edge(edge);
                !edge.is_constraint_edge()
                    && [edge.face(), edge.rev().face()]
                        .iter()
                        .all(|f| f.as_inner().is_some_and(|f| region[f.fix().index()]))
            }
            _ => false,
        }
    }

    /// The exact point of triangulation vertex `i`.
    fn position(&mut self, i: usize) -> Result<DVec3, String> {
        if let Some(p) = self.vertices[i].position {
            return Ok(p);
        }
        let location = self.location(self.vertices[i].uv);
        let p = self.input.solid.point_at(&location);
        if !p.is_finite() {
            return Err(format!(
                "its surface is not finite at (u, v) = ({}, {})",
                self.vertices[i].uv.x, self.vertices[i].uv.y
            ));
        }
        self.vertices[i].position = Some(p);
        Ok(p)
    }

    /// The face location at `uv`, periodic parameters wrapped into the domain.
    fn location(&self, uv: DVec2) -> FeatureLocation {
        let [du, dv] = self.input.solid.face(self.input.face).surface.domain();
        FeatureLocation::Face {
            id: self.input.face,
            u: du.normalize(uv.x),
            v: dv.normalize(uv.y),
        }
    }

    /// The longest side of the triangle in space (mm).
    fn longest_edge(&self, tri: [usize; 3]) -> f64 {
        let p = tri.map(|i| self.vertices[i].position.unwrap_or(DVec3::ZERO));
        (0..3)
            .map(|k| p[k].distance(p[(k + 1) % 3]))
            .fold(0.0, f64::max)
    }

    /// Largest sampled distance between the surface and the triangle (mm).
    fn triangle_error(&mut self, tri: [usize; 3]) -> Result<f64, String> {
        let p = [
            self.position(tri[0])?,
            self.position(tri[1])?,
            self.position(tri[2])?,
        ];
        let uv = tri.map(|i| self.vertices[i].uv);
        sampled_deviation(self.input.solid, self.input.face, uv, p)
    }

    /// The region's triangles on the solid's vertices. Triangles with two corners on the same
    /// vertex (the samples of a collapsed side) have no area and are dropped.
    fn finish(mut self, chordal_error: f64) -> Result<FaceMesh, String> {
        self.sync_vertices();
        let region = self.region();
        let mut mesh = FaceMesh {
            chordal_error,
            ..FaceMesh::default()
        };
        for tri in self.region_triangles(&region) {
            let mut ids = [0_u32; 3];
            for (k, &i) in tri.iter().enumerate() {
                ids[k] = match self.vertices[i].id {
                    Some(id) => id,
                    None => {
                        self.position(i)?;
                        let location = self.location(self.vertices[i].uv);
                        let id = self.table.add(self.input.solid, location);
                        if let Some(n) = self.input.solid.face_normal_at(&location) {
                            self.table.add_normal(id, self.input.face, n);
                        }
                        self.vertices[i].id = Some(id);
                        id
                    }
                };
            }
            if ids[0] == ids[1] || ids[1] == ids[2] || ids[0] == ids[2] {
                continue;
            }
            mesh.triangles.push(ids);
            mesh.params
                .push(tri.map(|i| self.vertices[i].uv.to_array()));
        }
        Ok(mesh)
    }
}

/// Largest distance, at the 13 barycentric [`SAMPLES`], between the surface of `face` at the
/// interpolated parameters and the triangle with corners `p` at parameters `uv` (mm).
///
/// # Errors
/// A reason when the surface is not finite at a sample.
pub(crate) fn sampled_deviation(
    solid: &Solid,
    face: FaceId,
    uv: [DVec2; 3],
    p: [DVec3; 3],
) -> Result<f64, String> {
    let mut worst = 0.0_f64;
    for b in SAMPLES {
        let q = uv[0] * b[0] + uv[1] * b[1] + uv[2] * b[2];
        let exact = solid.eval_face(face, q.x, q.y).point;
        let linear = p[0] * b[0] + p[1] * b[1] + p[2] * b[2];
        let d = exact.distance(linear);
        if !d.is_finite() {
            return Err(format!(
                "its surface is not finite at (u, v) = ({}, {})",
                q.x, q.y
            ));
        }
        worst = worst.max(d);
    }
    Ok(worst)
}

fn vertex_handle(i: usize) -> spade::handles::FixedVertexHandle {
    spade::handles::FixedVertexHandle::from_index(i)
}
