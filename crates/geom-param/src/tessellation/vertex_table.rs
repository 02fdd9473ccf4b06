//! The vertices of a whole solid's tessellation, shared by every face that meets them: each one
//! on its exact feature, with its outward normal averaged over the faces that meet there.

use crate::topology::feature::{FaceId, FeatureLocation, VertexId};
use crate::topology::solid::Solid;
use glam::DVec3;

/// One mesh vertex of the solid.
#[derive(Clone, Copy, Debug)]
pub(crate) struct TableVertex {
    /// The exact point `Solid::point_at(location)` (mm, object frame).
    pub position: DVec3,
    /// Where the vertex lies: a face point, an edge point or a solid vertex.
    pub location: FeatureLocation,
}

/// Global vertices: solid vertex k is entry k; edge samples, seam samples and face interior
/// points follow in the order they are created.
#[derive(Debug)]
pub(crate) struct VertexTable {
    vertices: Vec<TableVertex>,
    /// Sum of the unit normals contributed by the faces that meet at each vertex.
    normal_sums: Vec<DVec3>,
    /// For the solid's vertices: the faces that have contributed a normal already (each face
    /// counts once however many of its edges end there).
    vertex_faces: Vec<Vec<FaceId>>,
}

impl VertexTable {
    /// A table holding the solid's vertices (entry k is `VertexId(k)`), with no normal yet.
    pub fn new(solid: &Solid) -> Self {
        let vertices: Vec<TableVertex> = solid
            .vertices
            .iter()
            .enumerate()
            .map(|(k, v)| TableVertex {
                position: v.point,
                location: FeatureLocation::Vertex {
                    id: VertexId(k as u32),
                },
            })
            .collect();
        let n = vertices.len();
        Self {
            vertices,
            normal_sums: vec![DVec3::ZERO; n],
            vertex_faces: vec![Vec::new(); n],
        }
    }

    /// Adds the vertex at `location` (its position is evaluated exactly there) and returns its id.
    pub fn add(&mut self, solid: &Solid, location: FeatureLocation) -> u32 {
        self.vertices.push(TableVertex {
            position: solid.point_at(&location),
            location,
        });
        self.normal_sums.push(DVec3::ZERO);
        (self.vertices.len() - 1) as u32
    }

    /// The vertex with id `id`.
    pub fn get(&self, id: u32) -> &TableVertex {
        &self.vertices[id as usize]
    }

    /// Number of vertices.
    pub fn len(&self) -> usize {
        self.vertices.len()
    }

    /// Adds face `face`'s unit normal `normal` to vertex `id`'s average. At a solid vertex each
    /// face contributes once; elsewhere every call counts (an edge point gets one call per face).
    pub fn add_normal(&mut self, id: u32, face: FaceId, normal: DVec3) {
        let k = id as usize;
        if let Some(seen) = self.vertex_faces.get_mut(k) {
            if seen.contains(&face) {
                return;
            }
            seen.push(face);
        }
        self.normal_sums[k] += normal;
    }

    /// The averaged unit normal of each vertex, or `None` where no face gave one (a singular
    /// point of every face that meets there).
    pub fn normals(&self) -> Vec<Option<DVec3>> {
        self.normal_sums.iter().map(|n| n.try_normalize()).collect()
    }
}
