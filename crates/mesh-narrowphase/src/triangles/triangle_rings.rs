//! Which triangles of a mesh meet at each vertex: the neighbourhood of a mesh point, for the
//! test that a pair of mesh points is a local minimum of the mesh distance.

/// The triangles around each vertex of one mesh, in compressed rows: vertex `v`'s triangles are
/// `triangles[offsets[v]..offsets[v + 1]]`, in increasing order.
#[derive(Clone, Debug, Default)]
pub struct TriangleRings {
    offsets: Vec<u32>,
    triangles: Vec<u32>,
}

impl TriangleRings {
    /// The rings of a mesh of `vertex_count` vertices and these triangles (vertex indices; an
    /// index out of range is left out).
    #[must_use]
    pub fn new(vertex_count: usize, triangles: &[[u32; 3]]) -> Self {
        let mut counts = vec![0_u32; vertex_count + 1];
        for t in triangles {
            for &v in t {
                if let Some(c) = counts.get_mut(v as usize + 1) {
                    *c += 1;
                }
            }
        }
        for v in 0..vertex_count {
            counts[v + 1] += counts[v];
        }
        let offsets = counts.clone();
        let mut next = counts;
        let mut out = vec![0_u32; offsets[vertex_count] as usize];
        for (k, t) in triangles.iter().enumerate() {
            for &v in t.iter().filter(|&&v| (v as usize) < vertex_count) {
                let slot = &mut next[v as usize];
                out[*slot as usize] = u32::try_from(k).unwrap_or(u32::MAX);
                *slot += 1;
            }
        }
        Self {
            offsets,
            triangles: out,
        }
    }

    /// The triangles that have vertex `v` as a corner (empty for an unknown vertex).
    #[must_use]
    pub fn around(&self, v: u32) -> &[u32] {
        let v = v as usize;
        match (self.offsets.get(v), self.offsets.get(v + 1)) {
            (Some(&s), Some(&e)) => &self.triangles[s as usize..e as usize],
            _ => &[],
        }
    }

    /// The triangles holding the feature of triangle `t` (corners `corners`) on which the point
    /// with barycentric coordinates `b` lies: `t` alone for an interior point, the triangles
    /// sharing the edge for a point on an edge, the vertex's ring at a corner. A coordinate at
    /// most `zero` counts as zero. Together they cover a neighbourhood of the point on the mesh
    /// (where the mesh is a closed manifold there).
    pub fn holding(&self, t: u32, corners: [u32; 3], b: [f64; 3], zero: f64, out: &mut Vec<u32>) {
        out.clear();
        let mut on = [0_u32; 3];
        let mut count = 0;
        for i in 0..3 {
            if b[i] > zero {
                on[count] = corners[i];
                count += 1;
            }
        }
        match &on[..count] {
            [v] => out.extend_from_slice(self.around(*v)),
            [v, w] => out.extend(
                self.around(*v)
                    .iter()
                    .copied()
                    .filter(|x| self.around(*w).binary_search(x).is_ok()),
            ),
            _ => out.push(t),
        }
        if out.is_empty() {
            out.push(t);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A square of two triangles (0 1 2, 0 2 3) and a third triangle on edge 1 2.
    fn rings() -> TriangleRings {
        TriangleRings::new(5, &[[0, 1, 2], [0, 2, 3], [1, 4, 2]])
    }

    #[test]
    fn rings_list_the_triangles_at_each_vertex() {
        let r = rings();
        assert_eq!(r.around(0), &[0, 1]);
        assert_eq!(r.around(2), &[0, 1, 2]);
        assert_eq!(r.around(4), &[2]);
        assert!(r.around(9).is_empty());
    }

    #[test]
    fn a_point_is_held_by_the_triangles_of_its_feature() {
        let r = rings();
        let mut out = Vec::new();
        r.holding(0, [0, 1, 2], [0.2, 0.3, 0.5], 1e-12, &mut out);
        assert_eq!(out, [0]);
        r.holding(0, [0, 1, 2], [0.0, 0.5, 0.5], 1e-12, &mut out);
        assert_eq!(out, [0, 2]);
        r.holding(0, [0, 1, 2], [0.5, 0.0, 0.5], 1e-12, &mut out);
        assert_eq!(out, [0, 1]);
        r.holding(0, [0, 1, 2], [0.0, 0.0, 1.0], 1e-12, &mut out);
        assert_eq!(out, [0, 1, 2]);
    }
}
