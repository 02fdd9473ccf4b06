//! The paper's proxy-mesh path ([`crate::ConcavePath::ProxyRegions`]), kept selectable for
//! comparison: outward-offset proxy meshes tested against the other component's mesh.

pub mod proxy_mesh;
pub(crate) mod proxy_path;
