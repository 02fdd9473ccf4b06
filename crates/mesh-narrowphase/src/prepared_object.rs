//! Per-object preprocessing of the default mesh phase: a triangle tree per component and a
//! lazily filled proxy cache.

use crate::proxy_mesh::ProxyCache;
use crate::triangle_bvh::TriangleBvh;
use geom_param::ObjectModel;

/// What [`crate::MeshNarrowphase`] prepares for one object.
#[derive(Debug)]
pub struct PreparedObject {
    /// Per component (indexed by `ComponentId`): its triangle tree and proxies.
    pub components: Vec<PreparedComponent>,
}

/// One component's prepared data.
#[derive(Debug)]
pub struct PreparedComponent {
    /// Tree over the component mesh's triangles (object frame).
    pub bvh: TriangleBvh,
    /// Proxy meshes, built on first use.
    pub proxies: ProxyCache,
    /// Largest coordinate magnitude of the mesh (mm): the scale of relative tolerances.
    pub size: f64,
}

impl PreparedObject {
    /// Builds the triangle trees of all of `object`'s components (proxies come later, lazily).
    #[must_use]
    pub fn new(object: &ObjectModel) -> Self {
        let components = object
            .meshes
            .iter()
            .map(|m| PreparedComponent {
                bvh: TriangleBvh::new(&m.positions, &m.triangles),
                proxies: ProxyCache::default(),
                size: m
                    .positions
                    .iter()
                    .map(|p| p.abs().max_element())
                    .filter(|x| x.is_finite())
                    .fold(0.0, f64::max),
            })
            .collect();
        Self { components }
    }
}
