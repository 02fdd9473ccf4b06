//! Error-checked tessellation of a general B-rep solid (trimmed faces on any surface) into
//! component meshes.
//!
//! 1. Each edge is sampled once, adaptively, until every chord is within the edge budget of the
//!    curve and of both faces' surfaces along it, and no longer than the faces' target length
//!    (`edge_sampling.rs`). Edge end vertices are the solid's vertices. Both faces use the same
//!    samples, so the mesh is watertight across edges.
//! 2. Each face's region in its (u, v) plane is bounded by loops of those samples
//!    (`face_boundary.rs`): the four sides of its parameter rectangle (edges, poles collapsed to
//!    one vertex, periodic parameters cut open at a seam whose two copies share vertices), or
//!    its trim loops through their p-curves.
//! 3. The region is triangulated (constrained Delaunay in a plane scaled by the typical |S_u|
//!    and |S_v|) and refined for shape and by measured error (`face_triangulation.rs`).
//!
//! Budgets: triangles are refined to 0.8 of the tolerance (room for the error between sample
//! points), edge chords to half of that (a triangle along an edge is then bounded by its
//! interior, which refinement controls). The target length caps every edge at
//! sqrt(6 budget size) for the solid's half diagonal `size` (the spacing a sphere of the
//! object's size would need), and below that at 4 sqrt(6 budget / κ_max) per face (the
//! measured-error refinement grades the mesh down to the curvature where it is needed).

use crate::object_model::ModelError;
use crate::tessellation::component_mesh::ComponentMesh;
use crate::tessellation::edge_sampling::{EdgeSamples, sample_edge};
use crate::tessellation::face_boundary::{BoundaryInput, face_boundary};
use crate::tessellation::face_metric::{FaceMetric, face_metric};
use crate::tessellation::face_triangulation::{FaceMesh, TriangulationInput, triangulate_face};
use crate::tessellation::surface_extent::sampled_extent;
use crate::tessellation::vertex_table::{TableVertex, VertexTable};
use crate::topology::components::SurfaceComponent;
use crate::topology::feature::{EdgeId, FaceId};
use crate::topology::solid::Solid;
use glam::DVec3;
use std::collections::HashMap;

/// The refinement aims at this fraction of the requested tolerance, leaving room for the error
/// between the sampled points.
const BUDGET_FRACTION: f64 = 0.8;
/// Edge chords aim at this fraction of the face budget.
const EDGE_FRACTION: f64 = 0.5;

/// The tessellation of a whole solid: shared vertices and each face's triangles on them.
#[derive(Debug)]
pub(crate) struct SolidTessellation {
    vertices: Vec<TableVertex>,
    normals: Vec<DVec3>,
    faces: Vec<FaceMesh>,
}

/// Tessellates `solid`, which must have passed [`crate::validate`] (every id in range, every
/// use pointing back at its edge), so that every face's measured chordal error is within
/// `tolerance` (mm).
///
/// # Errors
/// [`ModelError::Tessellation`] for a face that cannot be meshed: a surface or curve that
/// evaluates to non-finite points, a boundary that does not bound a region, or a face whose
/// refinement stops above the tolerance.
pub(crate) fn tessellate_solid(
    solid: &Solid,
    tolerance: f64,
) -> Result<SolidTessellation, ModelError> {
    let (lo, hi) = sampled_extent(solid)?;
    let size = 0.5 * (hi - lo).length();
    let budget = BUDGET_FRACTION * tolerance;
    let edge_budget = EDGE_FRACTION * budget;
    let max_length = (6.0 * budget * size).sqrt().max(tolerance);

    let metrics = (0..solid.faces.len())
        .map(|f| {
            let id = FaceId(f as u32);
            face_metric(solid, id, budget, max_length).map_err(|reason| fail(id, reason))
        })
        .collect::<Result<Vec<FaceMetric>, ModelError>>()?;

    let mut table = VertexTable::new(solid);
    let edges = (0..solid.edges.len())
        .map(|e| {
            let id = EdgeId(e as u32);
            sample_edge(solid, id, edge_budget, &metrics, &mut table)
                .map_err(|reason| fail(solid.edge(id).uses[0].face, reason))
        })
        .collect::<Result<Vec<EdgeSamples>, ModelError>>()?;

    let mut rims = vec![0.0_f64; solid.faces.len()];
    for (e, samples) in edges.iter().enumerate() {
        let deviation = chord_deviation(solid, EdgeId(e as u32), samples, &table);
        for u in &solid.edge(EdgeId(e as u32)).uses {
            let rim = &mut rims[u.face.0 as usize];
            *rim = rim.max(deviation);
        }
    }
    let mut faces = Vec::with_capacity(solid.faces.len());
    for (f, metric) in metrics.iter().enumerate() {
        let face = FaceId(f as u32);
        let boundary = BoundaryInput {
            solid,
            face,
            metric,
            edges: &edges,
            edge_budget,
            budget,
        };
        let loops = face_boundary(&boundary, &mut table).map_err(|reason| fail(face, reason))?;
        let input = TriangulationInput {
            solid,
            face,
            metric,
            budget,
            tolerance,
        };
        let mut mesh =
            triangulate_face(&input, &loops, &mut table).map_err(|reason| fail(face, reason))?;
        // The exact face reaches its boundary curves, which stand off the mesh's boundary
        // chords by up to their deviation.
        mesh.chordal_error = mesh.chordal_error.max(rims[f]);
        faces.push(mesh);
    }

    let normals = fill_normals(&table, &faces);
    let vertices = (0..table.len() as u32).map(|i| *table.get(i)).collect();
    Ok(SolidTessellation {
        vertices,
        normals,
        faces,
    })
}

/// The largest distance (mm) between edge `id`'s curve and the chords of its samples,
/// measured at the quarter points of every piece (where the sampler measured it too): how far
/// the exact boundary of a face along the edge stands off its mesh's boundary. A planar face's
/// triangles lie on its plane, so this is all of its chordal error (a loft's elliptic cap).
fn chord_deviation(solid: &Solid, id: EdgeId, samples: &EdgeSamples, table: &VertexTable) -> f64 {
    let curve = &solid.edge(id).curve;
    let mut deviation: f64 = 0.0;
    for (t, v) in samples.ts.windows(2).zip(samples.ids.windows(2)) {
        let (pa, pb) = (table.get(v[0]).position, table.get(v[1]).position);
        for s in [0.25, 0.5, 0.75] {
            let exact = curve.eval(t[0] + s * (t[1] - t[0])).point;
            deviation = deviation.max(exact.distance(pa.lerp(pb, s)));
        }
    }
    deviation
}

fn fail(face: FaceId, reason: String) -> ModelError {
    ModelError::Tessellation { face, reason }
}

/// The averaged exact normals; where no face has a normal (a singular point of every face
/// there), the area-weighted mean of the incident triangles' normals.
fn fill_normals(table: &VertexTable, faces: &[FaceMesh]) -> Vec<DVec3> {
    let exact = table.normals();
    let mut fallback = vec![DVec3::ZERO; exact.len()];
    if exact.iter().any(Option::is_none) {
        for face in faces {
            for t in &face.triangles {
                let p = t.map(|i| table.get(i).position);
                let n = (p[1] - p[0]).cross(p[2] - p[0]);
                for &i in t {
                    fallback[i as usize] += n;
                }
            }
        }
    }
    exact
        .into_iter()
        .zip(fallback)
        .map(|(n, f)| n.or_else(|| f.try_normalize()).unwrap_or(DVec3::Z))
        .collect()
}

impl SolidTessellation {
    /// The mesh of one component: its faces' triangles with their own copy of the vertices they
    /// share with other components.
    pub(crate) fn component_mesh(&self, component: &SurfaceComponent) -> ComponentMesh {
        let mut mesh = ComponentMesh::default();
        let mut index_of: HashMap<u32, u32> = HashMap::new();
        for &face in &component.faces {
            let Some(face_mesh) = self.faces.get(face.0 as usize) else {
                continue;
            };
            mesh.chordal_error = mesh.chordal_error.max(face_mesh.chordal_error);
            for (t, params) in face_mesh.triangles.iter().zip(&face_mesh.params) {
                let local = t.map(|id| {
                    *index_of.entry(id).or_insert_with(|| {
                        let v = &self.vertices[id as usize];
                        mesh.positions.push(v.position);
                        mesh.normals.push(self.normals[id as usize]);
                        mesh.vertex_locations.push(v.location);
                        (mesh.positions.len() - 1) as u32
                    })
                });
                mesh.triangles.push(local);
                mesh.triangle_faces.push(face);
                mesh.triangle_params.push(*params);
            }
        }
        mesh
    }

    /// Largest absolute coordinate of any mesh vertex (mm): a lower bound of the surface's.
    pub(crate) fn largest_coordinate(&self) -> f64 {
        self.vertices
            .iter()
            .map(|v| v.position.abs().max_element())
            .fold(0.0, f64::max)
    }
}
