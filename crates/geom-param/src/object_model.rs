//! A prepared object: exact solid, surface components and their dual representation.
//!
//! Everything here is preprocessing, done once per object and shared by all queries.

use crate::revolution::profile::Profile;
use crate::revolution::revolve::revolve;
use crate::tessellation::component_mesh::ComponentMesh;
use crate::tessellation::convex_hull::ConvexHull;
use crate::tessellation::revolved_mesher::tessellate;
use crate::tessellation::solid_mesher::tessellate_solid;
use crate::tessellation::surface_extent::sampled_extent;
use crate::topology::components::{ComponentKind, SurfaceComponent, partition};
use crate::topology::convexity::classify_convexity;
use crate::topology::feature::{ComponentId, FaceId};
use crate::topology::solid::Solid;
use crate::topology::validate::{TopologyError, validate};

/// Smallest chordal tolerance relative to the object's size (largest coordinate). A 100 mm
/// object can be meshed to 2 µm; finer meshes (hundreds of thousands of vertices) make the
/// convex hulls take seconds to minutes, which preprocessing must not.
pub const MIN_RELATIVE_TOLERANCE: f64 = 2e-5;

/// How finely to mesh.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeshOptions {
    /// Largest allowed distance between a component mesh and the exact surface (mm).
    pub chordal_tolerance: f64,
}

impl Default for MeshOptions {
    /// 0.05 mm: sub-millimetre meshes of hand-sized objects with a few thousand triangles each.
    fn default() -> Self {
        Self {
            chordal_tolerance: 0.05,
        }
    }
}

/// Options that cannot build a model.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ModelError {
    /// The chordal tolerance is not finite, not positive, or so small against the object
    /// (below [`MIN_RELATIVE_TOLERANCE`] of its size) that meshing and hulls would take seconds
    /// to minutes.
    #[error(
        "chordal tolerance {tolerance} mm is not usable for an object of size {scale} mm (needs a finite value in [2e-5, 1] x size)"
    )]
    BadTolerance {
        /// The requested tolerance (mm).
        tolerance: f64,
        /// The object's size (largest coordinate, mm).
        scale: f64,
    },
    /// A face of a general solid cannot be meshed: its surface or an edge on it evaluates to a
    /// non-finite point, its boundary does not form a region of its parameter plane (loops that
    /// do not close, cross or touch, sides that do not meet at common vertices), or refinement
    /// cannot bring its measured chordal error within the tolerance.
    #[error("face {} cannot be meshed: {reason}", face.0)]
    Tessellation {
        /// The face (for an edge that cannot be sampled, the first face it lies on).
        face: FaceId,
        /// What went wrong, naming the edge, loop or parameters involved.
        reason: String,
    },
    /// The solid is not a valid closed B-rep.
    #[error(transparent)]
    Topology(#[from] TopologyError),
}

/// A solid with its surface components, each with a mesh (and, for convex ones, a hull).
#[derive(Debug)]
pub struct ObjectModel {
    /// Name of the object.
    pub name: String,
    /// The validated profile it was revolved from, for a solid of revolution.
    pub profile: Option<Profile>,
    /// The object's size (mm): the largest absolute coordinate of its surface in its frame.
    pub scale: f64,
    /// The exact boundary representation.
    pub solid: Solid,
    /// Surface components, indexed by [`ComponentId`].
    pub components: Vec<SurfaceComponent>,
    /// Component meshes, indexed by [`ComponentId`].
    pub meshes: Vec<ComponentMesh>,
    /// Convex hulls of the convex components' meshes (`None` for concave components and for
    /// flat convex components with no volume).
    pub hulls: Vec<Option<ConvexHull>>,
    /// The options the meshes were built with.
    pub mesh_options: MeshOptions,
    component_of_face: Vec<ComponentId>,
}

impl ObjectModel {
    /// Revolves `profile`, partitions it into components and meshes each one.
    ///
    /// # Errors
    /// [`ModelError::BadTolerance`] for an unusable chordal tolerance.
    pub fn from_profile(
        name: impl Into<String>,
        profile: Profile,
        options: &MeshOptions,
    ) -> Result<Self, ModelError> {
        let tolerance = options.chordal_tolerance;
        let scale = profile.scale();
        if !(tolerance.is_finite()
            && tolerance >= MIN_RELATIVE_TOLERANCE * scale
            && tolerance <= scale)
        {
            return Err(ModelError::BadTolerance { tolerance, scale });
        }
        let solid = revolve(&profile);
        let components = partition(&solid);
        let tessellation = tessellate(&profile, tolerance);
        let meshes: Vec<ComponentMesh> = components
            .iter()
            .map(|c| tessellation.component_mesh(c))
            .collect();
        Ok(Self::assemble(
            name.into(),
            Some(profile),
            scale,
            solid,
            components,
            meshes,
            options,
        ))
    }

    /// Validates a general solid (trimmed faces on any surface), classifies the convexity of
    /// its faces and edges from the geometry ([`crate::classify_convexity`]; whatever the solid
    /// carried is replaced), meshes it and partitions it into components.
    ///
    /// `scale` is the largest absolute coordinate of the surface, sampled at its
    /// vertices, along its edges, on a grid over each face and at every mesh vertex. The solid
    /// gets no profile.
    ///
    /// # Errors
    /// [`ModelError::Topology`] for a solid that fails [`crate::validate`];
    /// [`ModelError::BadTolerance`] for an unusable chordal tolerance (as
    /// [`ObjectModel::from_profile`]); [`ModelError::Tessellation`] for a face that cannot be
    /// meshed within it.
    pub fn from_solid(
        name: impl Into<String>,
        mut solid: Solid,
        options: &MeshOptions,
    ) -> Result<Self, ModelError> {
        validate(&solid)?;
        classify_convexity(&mut solid);
        let tolerance = options.chordal_tolerance;
        let (lo, hi) = sampled_extent(&solid)?;
        let scale = lo.abs().max(hi.abs()).max_element();
        if !(tolerance.is_finite()
            && tolerance >= MIN_RELATIVE_TOLERANCE * scale
            && tolerance <= scale)
        {
            return Err(ModelError::BadTolerance { tolerance, scale });
        }
        let components = partition(&solid);
        let tessellation = tessellate_solid(&solid, tolerance)?;
        let scale = scale.max(tessellation.largest_coordinate());
        let meshes: Vec<ComponentMesh> = components
            .iter()
            .map(|c| tessellation.component_mesh(c))
            .collect();
        Ok(Self::assemble(
            name.into(),
            None,
            scale,
            solid,
            components,
            meshes,
            options,
        ))
    }

    /// The model from its meshed components: hulls of the convex ones, and the face index.
    fn assemble(
        name: String,
        profile: Option<Profile>,
        scale: f64,
        solid: Solid,
        components: Vec<SurfaceComponent>,
        meshes: Vec<ComponentMesh>,
        options: &MeshOptions,
    ) -> Self {
        let hulls = components
            .iter()
            .zip(&meshes)
            .map(|(c, m)| match c.kind {
                ComponentKind::Convex => ConvexHull::of_mesh(m),
                ComponentKind::Concave => None,
            })
            .collect();
        let mut component_of_face = vec![ComponentId(0); solid.faces.len()];
        for c in &components {
            for f in &c.faces {
                component_of_face[f.0 as usize] = c.id;
            }
        }
        Self {
            name,
            profile,
            scale,
            solid,
            components,
            meshes,
            hulls,
            mesh_options: *options,
            component_of_face,
        }
    }

    /// The component a face belongs to.
    ///
    /// # Panics
    /// If the face id does not belong to this object.
    #[must_use]
    pub fn component_of_face(&self, face: FaceId) -> ComponentId {
        self.component_of_face[face.0 as usize]
    }

    /// The component with this id.
    ///
    /// # Panics
    /// If the id does not belong to this object.
    #[must_use]
    pub fn component(&self, id: ComponentId) -> &SurfaceComponent {
        &self.components[id.0 as usize]
    }

    /// The mesh of a component.
    ///
    /// # Panics
    /// If the id does not belong to this object.
    #[must_use]
    pub fn mesh(&self, id: ComponentId) -> &ComponentMesh {
        &self.meshes[id.0 as usize]
    }

    /// The hull of a convex component, if it has one.
    ///
    /// # Panics
    /// If the id does not belong to this object.
    #[must_use]
    pub fn hull(&self, id: ComponentId) -> Option<&ConvexHull> {
        self.hulls[id.0 as usize].as_ref()
    }
}
