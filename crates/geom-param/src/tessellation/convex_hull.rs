//! The convex hull of a convex component's mesh, with vertex adjacency for hill-climbing
//! support maps.

use crate::tessellation::component_mesh::ComponentMesh;
use glam::DVec3;
use std::collections::HashMap;

/// Convex hull of a component mesh's vertices (object frame, mm).
#[derive(Clone, Debug)]
pub struct ConvexHull {
    /// Hull vertices.
    pub points: Vec<DVec3>,
    /// For each hull vertex, the index of the same vertex in the component mesh (and so its
    /// exact feature location).
    pub mesh_vertices: Vec<u32>,
    /// Hull triangles over `points`, counter-clockwise seen from outside.
    pub triangles: Vec<[u32; 3]>,
    adjacency_offsets: Vec<u32>,
    adjacency: Vec<u32>,
}

impl ConvexHull {
    /// The hull of `mesh`'s vertices, or `None` when they do not span a hull (fewer than four
    /// points in general position, e.g. a lone flat disk): such a component has no volume to
    /// run GJK on, and callers treat it through its triangles instead.
    #[must_use]
    pub fn of_mesh(mesh: &ComponentMesh) -> Option<Self> {
        let (points, triangles) =
            parry3d_f64::transformation::try_convex_hull(&mesh.positions).ok()?;
        if triangles.len() < 4 {
            return None;
        }
        let by_bits: HashMap<[u64; 3], u32> = mesh
            .positions
            .iter()
            .enumerate()
            .map(|(i, p)| (p.to_array().map(f64::to_bits), i as u32))
            .collect();
        let mesh_vertices = points
            .iter()
            .map(|p| by_bits.get(&p.to_array().map(f64::to_bits)).copied())
            .collect::<Option<Vec<u32>>>()?;

        let mut neighbours: Vec<Vec<u32>> = vec![Vec::new(); points.len()];
        for t in &triangles {
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                neighbours[a as usize].push(b);
                neighbours[b as usize].push(a);
            }
        }
        let mut adjacency_offsets = Vec::with_capacity(points.len() + 1);
        let mut adjacency = Vec::new();
        adjacency_offsets.push(0);
        for mut list in neighbours {
            list.sort_unstable();
            list.dedup();
            adjacency.extend(list);
            adjacency_offsets.push(adjacency.len() as u32);
        }
        Some(Self {
            points,
            mesh_vertices,
            triangles,
            adjacency_offsets,
            adjacency,
        })
    }

    /// Hull vertices joined to hull vertex `vertex` by a hull edge.
    ///
    /// # Panics
    /// If `vertex` is out of range.
    #[must_use]
    pub fn neighbors(&self, vertex: u32) -> &[u32] {
        let v = vertex as usize;
        &self.adjacency[self.adjacency_offsets[v] as usize..self.adjacency_offsets[v + 1] as usize]
    }
}
