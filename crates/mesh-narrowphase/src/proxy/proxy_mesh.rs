//! Proxy meshes: a component mesh offset outwards along its vertex normals, built lazily once
//! per component and offset.

use crate::triangles::triangle_bvh::TriangleBvh;
use geom_param::ComponentMesh;
use glam::DVec3;
use std::sync::{Arc, OnceLock, PoisonError, RwLock};

/// A component's mesh moved outwards by at least `offset` along its vertex normals (same
/// triangles), with its own triangle tree. Paper section II: "we first offset the mesh of one
/// concave component by δ to obtain a proxy mesh". (Its own tree rather than the mesh's tree
/// with boxes grown by the offset: grown boxes pair every triangle within the offset band with
/// every other there, which made the ball-in-bowl benchmark 6 to 300 times slower.)
///
/// # Thickness of the shell
/// Vertex i moves by `offset / c_i` along its unit normal n_i, where c_i is the smallest
/// n_i · n_f over the triangles f at the vertex (n_f the triangle's unit normal), clamped to
/// [[`MIN_NORMAL_COSINE`], 1]. Every corner of a proxy triangle, and so (by linearity) every
/// point of it, then lies at least `offset` above the plane of its mesh triangle, along that
/// triangle's normal: on smooth parts c_i ≈ 1 and the proxy is the plain offset; on creases and
/// apexes, where the averaged vertex normal leans away from the adjacent triangles (c_i ≈ 0.71
/// on a right-angled rim), the vertex moves further so that the shell does not thin there.
/// Where the mesh is convex this makes every proxy point at least `offset` from the mesh; where
/// it is concave with radius of curvature R the proxy is an offset of a surface within the
/// chordal error e of the mesh, so its distance to the mesh falls short of `offset` by at most
/// about `offset · e / R` (second order), and it folds over itself where R < `offset`.
/// Vertices whose c_i is below the clamp (knife edges, needle apexes) get the shell
/// `offset · MIN_NORMAL_COSINE / c_i` there.
#[derive(Debug)]
pub struct ProxyMesh {
    /// The offset (mm): the least height of the proxy above each mesh triangle's plane.
    pub offset: f64,
    /// Offset vertex positions (object frame); the triangles are the component mesh's.
    pub positions: Vec<DVec3>,
    /// Tree over the offset triangles.
    pub bvh: TriangleBvh,
}

/// The smallest cosine between a vertex normal and an adjacent triangle's normal that the
/// proxy compensates for (a vertex moves at most `offset / MIN_NORMAL_COSINE`): 0.1, i.e. a
/// normal up to 84° away from the triangle, which covers cones of half-angle down to 6°.
pub const MIN_NORMAL_COSINE: f64 = 0.1;

impl ProxyMesh {
    /// Offsets `mesh` by `offset` (mm), as described on [`ProxyMesh`]. Degenerate triangles
    /// (no normal) and non-finite normals do not lower any vertex's c_i.
    #[must_use]
    pub fn build(mesh: &ComponentMesh, offset: f64) -> Self {
        let mut cosine = vec![1.0_f64; mesh.positions.len()];
        for tri in &mesh.triangles {
            let [Some(p0), Some(p1), Some(p2)] =
                tri.map(|i| mesh.positions.get(i as usize).copied())
            else {
                continue;
            };
            let n_f = (p1 - p0).cross(p2 - p0).normalize_or_zero();
            if n_f == DVec3::ZERO {
                continue;
            }
            for &i in tri {
                let i = i as usize;
                if let (Some(n), Some(c)) = (mesh.normals.get(i), cosine.get_mut(i)) {
                    let cos = n.dot(n_f);
                    if cos.is_finite() {
                        *c = c.min(cos);
                    }
                }
            }
        }
        let positions: Vec<DVec3> = mesh
            .positions
            .iter()
            .zip(&mesh.normals)
            .zip(&cosine)
            .map(|((p, n), c)| *p + *n * (offset / c.max(MIN_NORMAL_COSINE)))
            .collect();
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
