//! Partition of a solid's surface into surface components (paper section III).
//!
//! A **concave component** is a connected set of concave faces (connected across any edge),
//! together with the flat faces that continue it across concave or smooth edges (the flat bottom
//! inside a bowl). A **convex component** is a connected set of the remaining convex and flat
//! faces joined across convex or smooth edges, so that it forms no concavity; convex faces that
//! meet at a concave edge fall into different convex components. Each face is in exactly one
//! component, and no two components of the same kind could be merged under these rules, which
//! makes the count minimal.

use crate::topology::feature::{ComponentId, EdgeId, FaceId, VertexId};
use crate::topology::solid::{EdgeConvexity, FaceConvexity, Solid};

/// Convex or concave.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ComponentKind {
    /// Forms no concavity: no concave face and no concave edge inside it, so its convex hull
    /// touches all of it, and GJK on the hull applies. The hull may also have facets off the
    /// surface: a cap across its open boundary (a goblet cup's mouth), or a bridge across a
    /// gap between faces that are each convex (an L-bracket's outer faces, around the inner
    /// corner). Where GJK's closest point lies on such a facet, the pair needs the general
    /// path.
    Convex,
    /// Has concave faces: handled through an offset proxy mesh.
    Concave,
}

/// One surface component: a set of faces with the edges and vertices that bound them.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SurfaceComponent {
    /// Its index in the object.
    pub id: ComponentId,
    /// Convex or concave.
    pub kind: ComponentKind,
    /// Faces, ascending.
    pub faces: Vec<FaceId>,
    /// Edges on any of its faces (inner edges and the boundary with other components), ascending.
    pub edges: Vec<EdgeId>,
    /// Vertices of its faces, ascending.
    pub vertices: Vec<VertexId>,
}

/// Partitions `solid` into surface components, ordered by their smallest face id.
#[must_use]
pub fn partition(solid: &Solid) -> Vec<SurfaceComponent> {
    let n = solid.faces.len();
    let mut sets = DisjointSets::new(n);
    let mut concave: Vec<bool> = solid
        .faces
        .iter()
        .map(|f| f.convexity == FaceConvexity::Concave)
        .collect();
    let faces_of =
        |e: &crate::topology::solid::Edge| (e.uses[0].face.0 as usize, e.uses[1].face.0 as usize);

    // Concave faces join across any edge.
    for edge in &solid.edges {
        let (a, b) = faces_of(edge);
        if concave[a] && concave[b] {
            sets.union(a, b);
        }
    }
    // Flat faces continue a concave component across concave or smooth edges (to a fixpoint).
    loop {
        let mut changed = false;
        for edge in &solid.edges {
            if edge.convexity == EdgeConvexity::Convex {
                continue;
            }
            let (a, b) = faces_of(edge);
            for (x, y) in [(a, b), (b, a)] {
                if concave[x] && !concave[y] && solid.faces[y].convexity == FaceConvexity::Flat {
                    concave[y] = true;
                    sets.union(x, y);
                    changed = true;
                }
            }
        }
        if !changed {
            break;
        }
    }
    // The rest join across convex or smooth edges.
    for edge in &solid.edges {
        let (a, b) = faces_of(edge);
        if !concave[a] && !concave[b] && edge.convexity != EdgeConvexity::Concave {
            sets.union(a, b);
        }
    }

    let mut groups: Vec<Vec<usize>> = Vec::new();
    let mut group_of_root = vec![usize::MAX; n];
    for face in 0..n {
        let root = sets.find(face);
        if group_of_root[root] == usize::MAX {
            group_of_root[root] = groups.len();
            groups.push(Vec::new());
        }
        groups[group_of_root[root]].push(face);
    }

    groups
        .into_iter()
        .enumerate()
        .map(|(k, faces)| {
            let mut edges = Vec::new();
            let mut vertices = Vec::new();
            for &f in &faces {
                let id = FaceId(u32::try_from(f).expect("fewer than 2^32 faces"));
                edges.extend(solid.face_edges(id));
                vertices.extend(solid.face_vertices(id));
            }
            edges.sort_unstable();
            edges.dedup();
            vertices.sort_unstable();
            vertices.dedup();
            SurfaceComponent {
                id: ComponentId(u32::try_from(k).expect("fewer than 2^32 components")),
                kind: if concave[faces[0]] {
                    ComponentKind::Concave
                } else {
                    ComponentKind::Convex
                },
                faces: faces.into_iter().map(|f| FaceId(f as u32)).collect(),
                edges,
                vertices,
            }
        })
        .collect()
}

/// Union-find over face indices.
struct DisjointSets {
    parent: Vec<usize>,
}

impl DisjointSets {
    fn new(n: usize) -> Self {
        Self {
            parent: (0..n).collect(),
        }
    }

    fn find(&mut self, mut x: usize) -> usize {
        while self.parent[x] != x {
            self.parent[x] = self.parent[self.parent[x]];
            x = self.parent[x];
        }
        x
    }

    fn union(&mut self, a: usize, b: usize) {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra != rb {
            self.parent[ra.max(rb)] = ra.min(rb);
        }
    }
}
