//! One side of a mesh-phase query, resolved from its [`ComponentRef`]: the component's mesh,
//! prepared data, hull and kind.

use crate::cones::patch_tree::PatchTree;
use crate::mesh_phase::{ComponentRef, MeshInputError};
use crate::prepared_object::{PreparedComponent, PreparedObject};
use crate::seeds::MeshSide;
use geom_param::{ComponentId, ComponentKind, ComponentMesh, ConvexHull, ObjectModel};

/// One side of a query, resolved.
pub(crate) struct Side<'a> {
    pub(crate) object: &'a ObjectModel,
    pub(crate) component: ComponentId,
    pub(crate) mesh: &'a ComponentMesh,
    pub(crate) prepared: &'a PreparedComponent,
    pub(crate) hull: Option<&'a ConvexHull>,
    pub(crate) kind: ComponentKind,
    pub(crate) seed_side: MeshSide<'a>,
    pub(crate) size: f64,
}

impl<'a> Side<'a> {
    pub(crate) fn resolve(c: &ComponentRef<'a, PreparedObject>) -> Result<Self, MeshInputError> {
        let object = c.object;
        let i = c.component.0 as usize;
        if c.prepared.components.len() != object.meshes.len() {
            return Err(MeshInputError::PreparedMismatch);
        }
        let (Some(mesh), Some(prepared), Some(component)) = (
            object.meshes.get(i),
            c.prepared.components.get(i),
            object.components.get(i),
        ) else {
            return Err(MeshInputError::NoSuchComponent {
                component: c.component,
                count: object.components.len(),
            });
        };
        Ok(Self {
            object,
            component: c.component,
            mesh,
            prepared,
            hull: object.hulls.get(i).and_then(Option::as_ref),
            kind: component.kind,
            seed_side: MeshSide {
                component: c.component,
                mesh,
                bvh: &prepared.bvh,
            },
            size: prepared.size,
        })
    }

    /// The mesh's chordal error (mm), 0 when not a finite non-negative number.
    pub(crate) fn chordal_error(&self) -> f64 {
        let e = self.mesh.chordal_error;
        if e.is_finite() { e.max(0.0) } else { 0.0 }
    }

    /// The component's patch tree, built on first use; the flag says whether this call built it.
    pub(crate) fn patches(&self) -> (&'a PatchTree, bool) {
        self.prepared.patches(self.mesh, &self.object.solid)
    }
}
