//! One object as the baseline sees it: a single welded triangle mesh in parry's form.

use crate::error::BaselineError;
use crate::tessellation::tessellate;
use geom_param::{MeshOptions, ObjectDescription, Profile, Solid};
use glam::DVec3;
use parry3d_f64::shape::{TriMesh, TriMeshFlags};
use std::collections::HashMap;

/// A whole object as one welded, closed, outward-oriented triangle mesh (object frame, mm),
/// wrapped in a parry [`TriMesh`] built with `FIX_INTERNAL_EDGES | ORIENTED` (pseudo-normals, so
/// that contact normals are taken from the outward normal cones rather than from whichever side
/// of a triangle is nearer).
#[derive(Clone)]
pub struct BaselineMesh {
    trimesh: TriMesh,
    chordal_error: f64,
}

impl std::fmt::Debug for BaselineMesh {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("BaselineMesh")
            .field("triangles", &self.triangle_count())
            .field("vertices", &self.vertex_count())
            .field("chordal_error", &self.chordal_error)
            .finish()
    }
}

impl BaselineMesh {
    /// The most triangles a baseline mesh may have (16.7 million).
    pub const MAX_TRIANGLES: usize = 1 << 24;

    /// Meshes all faces of `solid` with about `target_triangles` triangles (within 2 % where the
    /// topology allows; vertices spaced evenly over the surface, see the crate's tessellation
    /// notes), welds shared edge and pole vertices, checks the mesh is closed, consistently and
    /// outward oriented with no zero-area triangle, and hands it to parry.
    ///
    /// # Errors
    /// [`BaselineError::BadTarget`] for a count the solid cannot be meshed with,
    /// [`BaselineError::UnsupportedFace`] for a face not periodic in u with its v sides on edges
    /// or vertices, [`BaselineError::EmptySolid`], [`BaselineError::DegenerateTriangle`],
    /// [`BaselineError::NotClosed`], [`BaselineError::NotOutward`] for a solid whose faces do
    /// not close up as their boundaries claim, and [`BaselineError::Parry`] or
    /// [`BaselineError::NoPseudoNormals`] if parry refuses the mesh.
    pub fn new(solid: &Solid, target_triangles: usize) -> Result<Self, BaselineError> {
        let mesh = tessellate(solid, target_triangles, Self::MAX_TRIANGLES)?;
        check_closed(&mesh.triangles)?;
        let size = mesh
            .positions
            .iter()
            .fold(0.0_f64, |m, p| m.max(p.abs().max_element()));
        let mut volume = 0.0;
        for (i, t) in mesh.triangles.iter().enumerate() {
            let [a, b, c] = t.map(|k| mesh.positions[k as usize]);
            let cross = (b - a).cross(c - a);
            // Written so that a NaN area is refused too.
            let has_area = cross.length() > 1e-12 * size * size;
            if !has_area {
                return Err(BaselineError::DegenerateTriangle { triangle: i });
            }
            volume += a.dot(b.cross(c)) / 6.0;
        }
        let outward = volume > 0.0;
        if !outward {
            return Err(BaselineError::NotOutward { volume });
        }
        let trimesh = TriMesh::with_flags(
            mesh.positions,
            mesh.triangles,
            TriMeshFlags::FIX_INTERNAL_EDGES | TriMeshFlags::ORIENTED,
        )?;
        if trimesh.pseudo_normals().is_none() {
            return Err(BaselineError::NoPseudoNormals);
        }
        Ok(Self {
            trimesh,
            chordal_error: mesh.chordal_error,
        })
    }

    /// Builds the described solid of revolution and meshes it as [`Self::new`] does.
    ///
    /// # Errors
    /// [`BaselineError::Load`] for an invalid profile, else as [`Self::new`].
    pub fn from_description(
        description: &ObjectDescription,
        target_triangles: usize,
    ) -> Result<Self, BaselineError> {
        // Only the exact solid is used; the component meshes are built as coarse as allowed.
        let scale = Profile::new(&description.profile)
            .map_err(geom_param::LoadError::from)?
            .scale();
        let model = description.build(&MeshOptions {
            chordal_tolerance: 0.05 * scale,
        })?;
        Self::new(&model.solid, target_triangles)
    }

    /// The parry shape (object frame, mm).
    #[must_use]
    pub fn trimesh(&self) -> &TriMesh {
        &self.trimesh
    }

    /// Welded vertices (object frame, mm).
    #[must_use]
    pub fn vertices(&self) -> &[DVec3] {
        self.trimesh.vertices()
    }

    /// Triangles as vertex indices, counter-clockwise seen from outside.
    #[must_use]
    pub fn indices(&self) -> &[[u32; 3]] {
        self.trimesh.indices()
    }

    /// Number of triangles.
    #[must_use]
    pub fn triangle_count(&self) -> usize {
        self.trimesh.indices().len()
    }

    /// Number of vertices.
    #[must_use]
    pub fn vertex_count(&self) -> usize {
        self.trimesh.vertices().len()
    }

    /// Measured chordal error (mm): the largest distance from 25 sample points of each
    /// triangle (a barycentric grid of step 1/6) to the exact surface. Distances between two
    /// baseline meshes differ from the exact ones by up to the sum of their chordal errors.
    #[must_use]
    pub fn chordal_error(&self) -> f64 {
        self.chordal_error
    }
}

/// Every directed edge (a, b) must be used once, and (b, a) once: a closed, consistently
/// oriented surface.
fn check_closed(triangles: &[[u32; 3]]) -> Result<(), BaselineError> {
    let mut uses: HashMap<(u32, u32), u32> = HashMap::with_capacity(3 * triangles.len());
    for t in triangles {
        for k in 0..3 {
            *uses.entry((t[k], t[(k + 1) % 3])).or_default() += 1;
        }
    }
    for (&(a, b), &n) in &uses {
        if n != 1 || uses.get(&(b, a)) != Some(&1) {
            return Err(BaselineError::NotClosed(a, b));
        }
    }
    Ok(())
}
