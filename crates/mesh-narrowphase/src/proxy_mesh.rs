//! Proxy meshes: a component mesh offset outwards along its vertex normals, built lazily once
//! per component and offset.

use crate::triangle_bvh::TriangleBvh;
use geom_param::ComponentMesh;
use glam::DVec3;
use std::sync::{Arc, OnceLock, PoisonError, RwLock};

/// A component's mesh moved outwards by `offset` along its vertex normals (same triangles), with
/// its own triangle tree. Paper section II: "we first offset the mesh of one concave component
/// by δ to obtain a proxy mesh". (Its own tree rather than the mesh's tree with boxes grown by
/// the offset: grown boxes pair every triangle within the offset band with every other there,
/// which made the ball-in-bowl benchmark 6 to 300 times slower.)
#[derive(Debug)]
pub struct ProxyMesh {
    /// The offset (mm).
    pub offset: f64,
    /// Offset vertex positions (object frame); the triangles are the component mesh's.
    pub positions: Vec<DVec3>,
    /// Tree over the offset triangles.
    pub bvh: TriangleBvh,
}

impl ProxyMesh {
    /// Offsets `mesh` by `offset` (mm).
    #[must_use]
    pub fn build(mesh: &ComponentMesh, offset: f64) -> Self {
        let positions = mesh.offset_positions(offset);
        let bvh = TriangleBvh::new(&positions, &mesh.triangles);
        Self {
            offset,
            positions,
            bvh,
        }
    }
}

/// The proxies of one component, keyed by offset: the first offset asked for lives behind a
/// `OnceLock` (no locking once built); further offsets in a short list behind a `RwLock`.
#[derive(Debug, Default)]
pub struct ProxyCache {
    first: OnceLock<Arc<ProxyMesh>>,
    others: RwLock<Vec<Arc<ProxyMesh>>>,
}

impl ProxyCache {
    /// How many proxies have been built.
    #[must_use]
    pub fn len(&self) -> usize {
        usize::from(self.first.get().is_some())
            + self
                .others
                .read()
                .unwrap_or_else(PoisonError::into_inner)
                .len()
    }

    /// True when no proxy has been built.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The proxy of `mesh` at `offset`, building it on first use; the flag says whether this
    /// call built it. Offsets are matched bit for bit.
    pub fn get_or_build(&self, mesh: &ComponentMesh, offset: f64) -> (Arc<ProxyMesh>, bool) {
        let mut built = false;
        let first = self.first.get_or_init(|| {
            built = true;
            Arc::new(ProxyMesh::build(mesh, offset))
        });
        if first.offset.to_bits() == offset.to_bits() {
            return (Arc::clone(first), built);
        }
        let same = |p: &&Arc<ProxyMesh>| p.offset.to_bits() == offset.to_bits();
        if let Some(p) = self
            .others
            .read()
            .unwrap_or_else(PoisonError::into_inner)
            .iter()
            .find(same)
        {
            return (Arc::clone(p), false);
        }
        let mut others = self.others.write().unwrap_or_else(PoisonError::into_inner);
        if let Some(p) = others.iter().find(same) {
            return (Arc::clone(p), false);
        }
        let proxy = Arc::new(ProxyMesh::build(mesh, offset));
        others.push(Arc::clone(&proxy));
        (proxy, true)
    }
}
