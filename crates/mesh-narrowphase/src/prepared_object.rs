//! Per-object preprocessing of the default mesh phase: a triangle tree per component, a patch
//! tree per component, and a lazily filled proxy cache.

use crate::cones::patch_tree::PatchTree;
use crate::proxy::proxy_mesh::ProxyCache;
use crate::triangles::triangle_bvh::TriangleBvh;
use crate::triangles::triangle_rings::TriangleRings;
use geom_param::{ComponentMesh, ObjectModel, Solid};
use std::sync::OnceLock;

/// What [`crate::MeshNarrowphase`] prepares for one object.
#[derive(Debug)]
pub struct PreparedObject {
    /// Per component (indexed by `ComponentId`): its triangle tree, patch tree and proxies.
    pub components: Vec<PreparedComponent>,
}

/// One component's prepared data.
#[derive(Debug)]
pub struct PreparedComponent {
    /// Tree over the component mesh's triangles (object frame).
    pub bvh: TriangleBvh,
    /// The triangles around each mesh vertex.
    pub rings: TriangleRings,
    /// The hierarchy of exact patches with normal cones ([`PatchTree`]): built with the object
    /// for every component (a `PreparedComponent` made otherwise builds it on first use).
    pub patch_tree: OnceLock<PatchTree>,
    /// Proxy meshes, built on first use (only by [`crate::ConcavePath::ProxyRegions`]).
    pub proxies: ProxyCache,
    /// Largest coordinate magnitude of the mesh (mm): the scale of relative tolerances.
    pub size: f64,
}

impl PreparedComponent {
    /// The patch tree of this component (whose mesh is `mesh`, of `solid`), building it on first
    /// use; the flag says whether this call built it.
    pub fn patches(&self, mesh: &ComponentMesh, solid: &Solid) -> (&PatchTree, bool) {
        let mut built = false;
        let tree = self.patch_tree.get_or_init(|| {
            built = true;
            PatchTree::build(mesh, solid)
        });
        (tree, built)
    }
}

impl PreparedObject {
    /// Builds the triangle trees and the patch trees of all of `object`'s components (proxies
    /// come later, lazily, for the proxy path only).
    #[must_use]
    pub fn new(object: &ObjectModel) -> Self {
        let components = object
            .meshes
            .iter()
            .map(|m| {
                // Every component's, convex ones too: a convex component meets the normal-cone
                // path against any concave component (or when hulls overlap), and building its
                // tree there would make that pair's first query tens of milliseconds slower.
                let patch_tree = OnceLock::from(PatchTree::build(m, &object.solid));
                PreparedComponent {
                    bvh: TriangleBvh::new(&m.positions, &m.triangles),
                    rings: TriangleRings::new(m.positions.len(), &m.triangles),
                    patch_tree,
                    proxies: ProxyCache::default(),
                    size: m
                        .positions
                        .iter()
                        .map(|p| p.abs().max_element())
                        .filter(|x| x.is_finite())
                        .fold(0.0, f64::max),
                }
            })
            .collect();
        Self { components }
    }
}
