//! One closed triangle mesh per object: the component meshes of an [`ObjectModel`] welded at
//! equal vertex positions, checked closed and outward, as a parry [`TriMesh`].

use crate::error::ShapeError;
use geom_param::ObjectModel;
use glam::DVec3;
use parry3d_f64::math::Pose;
use parry3d_f64::shape::{TriMesh, TriMeshFlags};
use std::collections::HashMap;

/// An object's whole boundary as one welded, closed, outward-oriented triangle mesh (shape
/// frame, mm), within `chordal_error` of the exact surface (the largest of the component
/// meshes' measured errors). Parry's [`TriMesh`] is built with `ORIENTED` (pseudo-normals:
/// inside/outside tests) and `FIX_INTERNAL_EDGES`.
#[derive(Clone)]
pub struct ClosedMesh {
    /// The parry mesh.
    pub trimesh: TriMesh,
    /// Largest distance between the mesh and the exact surface (mm).
    pub chordal_error: f64,
    /// Total triangle area (mm²).
    pub area: f64,
    /// Enclosed volume (mm³), > 0.
    pub volume: f64,
}

impl std::fmt::Debug for ClosedMesh {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ClosedMesh")
            .field("triangles", &self.trimesh.indices().len())
            .field("chordal_error", &self.chordal_error)
            .field("area", &self.area)
            .field("volume", &self.volume)
            .finish()
    }
}

impl ClosedMesh {
    /// Welds `model`'s component meshes: vertices with bit-identical positions (the meshers
    /// sample every edge once, so components meet at identical points) become one; then checks
    /// that every directed edge has exactly one reverse edge (closed and consistently oriented)
    /// and that the enclosed volume (divergence theorem, sum of a·(b×c)/6) is positive.
    ///
    /// The vertices are then moved by `placement` (the object's frame in the shape's frame).
    ///
    /// # Errors
    /// [`ShapeError::EmptyMesh`], [`ShapeError::NotClosed`], [`ShapeError::NotOutward`], or
    /// [`ShapeError::Parry`] when parry refuses the mesh.
    pub fn weld(model: &ObjectModel, placement: &Pose) -> Result<Self, ShapeError> {
        let name = || model.name.clone();
        let mut index: HashMap<[u64; 3], u32> = HashMap::new();
        let mut positions: Vec<DVec3> = Vec::new();
        let mut triangles: Vec<[u32; 3]> = Vec::new();
        let mut chordal_error = 0.0_f64;
        for mesh in &model.meshes {
            chordal_error = chordal_error.max(mesh.chordal_error);
            let welded: Vec<u32> = mesh
                .positions
                .iter()
                .map(|p| {
                    // +0.0 and -0.0 are the same point.
                    let key = [p.x + 0.0, p.y + 0.0, p.z + 0.0].map(f64::to_bits);
                    *index.entry(key).or_insert_with(|| {
                        positions.push(*p);
                        (positions.len() - 1) as u32
                    })
                })
                .collect();
            triangles.extend(mesh.triangles.iter().map(|t| t.map(|i| welded[i as usize])));
        }
        if triangles.is_empty() {
            return Err(ShapeError::EmptyMesh { name: name() });
        }
        let mut edges: HashMap<(u32, u32), u32> = HashMap::with_capacity(3 * triangles.len());
        for t in &triangles {
            for k in 0..3 {
                *edges.entry((t[k], t[(k + 1) % 3])).or_default() += 1;
            }
        }
        let mut unmatched: Vec<(u32, u32)> = edges
            .iter()
            .filter(|&(&(a, b), &count)| count != 1 || edges.get(&(b, a)) != Some(&1))
            .map(|(&e, _)| e)
            .collect();
        unmatched.sort_unstable();
        if let Some(&(from, to)) = unmatched.first() {
            return Err(ShapeError::NotClosed {
                name: name(),
                from,
                to,
            });
        }
        let (mut volume, mut area) = (0.0, 0.0);
        for t in &triangles {
            let [a, b, c] = t.map(|i| positions[i as usize]);
            volume += a.dot(b.cross(c)) / 6.0;
            area += 0.5 * (b - a).cross(c - a).length();
        }
        if volume.is_nan() || volume <= 0.0 {
            return Err(ShapeError::NotOutward {
                name: name(),
                volume,
            });
        }
        for p in &mut positions {
            *p = *placement * *p;
        }
        let trimesh = TriMesh::with_flags(
            positions,
            triangles,
            TriMeshFlags::ORIENTED | TriMeshFlags::FIX_INTERNAL_EDGES,
        )
        .map_err(|e| ShapeError::Parry {
            name: name(),
            reason: e.to_string(),
        })?;
        Ok(Self {
            trimesh,
            chordal_error,
            area,
            volume,
        })
    }
}
