//! A bounding-volume hierarchy over one mesh's triangles: simultaneous traversal of two trees
//! under a relative pose, and nearest-point queries.

use geom_param::DPose3;
use glam::{DMat3, DVec3};
use parry3d_f64::bounding_volume::Aabb;
use parry3d_f64::partitioning::{Bvh, BvhBuildStrategy, BvhNode};
use parry3d_f64::query::{PointQuery, PointQueryWithLocation};
use parry3d_f64::shape::{Triangle, TrianglePointLocation};

/// An AABB tree whose leaf `i` is triangle `i` of a mesh (in the mesh's frame).
#[derive(Clone, Debug)]
pub struct TriangleBvh {
    bvh: Bvh,
}

/// The nearest point of a mesh to a query point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NearestOnMesh {
    /// The triangle it lies on.
    pub triangle: u32,
    /// Its barycentric coordinates in that triangle (corner order of the mesh's triangle).
    pub barycentric: [f64; 3],
    /// The point, in the mesh's frame.
    pub point: DVec3,
    /// Its distance to the query point.
    pub distance: f64,
}

impl TriangleBvh {
    /// Builds the tree over `triangles` (indices into `positions`). Triangles with an index out
    /// of range get an empty box and are never reported.
    #[must_use]
    pub fn new(positions: &[DVec3], triangles: &[[u32; 3]]) -> Self {
        let leaves: Vec<Aabb> = triangles
            .iter()
            .map(|t| match corners(positions, t) {
                Some(p) => Aabb::from_points(p),
                None => Aabb::new(DVec3::splat(f64::MAX), DVec3::splat(f64::MAX)),
            })
            .collect();
        Self {
            bvh: Bvh::from_leaves(BvhBuildStrategy::Binned, &leaves),
        }
    }

    /// Appends to `out` every pair (triangle of `self`, triangle of `other`) whose boxes overlap
    /// once `self`'s boxes are grown by `inflate_self` and `other`'s by `inflate_other` (mm, in
    /// their own frames), and `other`'s are moved by `pose` (other's pose in self's frame) and
    /// re-boxed there, which only grows them.
    pub fn overlapping_pairs(
        &self,
        other: &Self,
        pose: &DPose3,
        (inflate_self, inflate_other): (f64, f64),
        out: &mut Vec<(u32, u32)>,
    ) {
        let grow_self = DVec3::splat(inflate_self.max(0.0));
        let grow_other = DVec3::splat(inflate_other.max(0.0));
        let rotation = DMat3::from_quat(pose.rotation);
        let abs_rotation = DMat3::from_cols(
            rotation.x_axis.abs(),
            rotation.y_axis.abs(),
            rotation.z_axis.abs(),
        );
        let check = |n1: &BvhNode, n2: &BvhNode| {
            let centre = rotation * (0.5 * (n2.mins() + n2.maxs())) + pose.translation;
            let half = abs_rotation * (0.5 * (n2.maxs() - n2.mins()) + grow_other) + grow_self;
            let (lo, hi) = (n1.mins() - half, n1.maxs() + half);
            centre.cmpge(lo).all() && centre.cmple(hi).all()
        };
        out.extend(self.bvh.leaf_pairs(&other.bvh, check));
    }

    /// The point of the mesh nearest to `point` (mesh frame), if one lies within `max_distance`.
    #[must_use]
    pub fn nearest(
        &self,
        positions: &[DVec3],
        triangles: &[[u32; 3]],
        point: DVec3,
        max_distance: f64,
    ) -> Option<NearestOnMesh> {
        if !point.is_finite() {
            return None;
        }
        let found = self.bvh.find_best(
            max_distance,
            |node: &BvhNode, _| node.aabb().distance_to_local_point(point, true),
            |leaf, _| {
                let n = nearest_on_triangle(positions, triangles, leaf, point)?;
                Some((n.distance, n))
            },
        );
        found.map(|(_, (_, n))| n)
    }

    /// Calls `visit` with the nearest point of every triangle that comes within `radius` (mm)
    /// of `point` (mesh frame), in no particular order.
    pub fn within(
        &self,
        positions: &[DVec3],
        triangles: &[[u32; 3]],
        point: DVec3,
        radius: f64,
        mut visit: impl FnMut(NearestOnMesh),
    ) {
        if !(point.is_finite() && radius >= 0.0) {
            return;
        }
        let near = |node: &BvhNode| node.aabb().distance_to_local_point(point, true) <= radius;
        for leaf in self.bvh.leaves(near) {
            if let Some(n) = nearest_on_triangle(positions, triangles, leaf, point)
                .filter(|n| n.distance <= radius)
            {
                visit(n);
            }
        }
    }
}

/// The point of triangle `leaf` nearest to `point`; `None` for an index out of range or a
/// degenerate location.
fn nearest_on_triangle(
    positions: &[DVec3],
    triangles: &[[u32; 3]],
    leaf: u32,
    point: DVec3,
) -> Option<NearestOnMesh> {
    let [a, b, c] = corners(positions, triangles.get(leaf as usize)?)?;
    let (proj, location) =
        Triangle::new(a, b, c).project_local_point_and_get_location(point, false);
    Some(NearestOnMesh {
        triangle: leaf,
        barycentric: barycentric(location)?,
        point: proj.point,
        distance: proj.point.distance(point),
    })
}

fn corners(positions: &[DVec3], t: &[u32; 3]) -> Option<[DVec3; 3]> {
    Some([
        *positions.get(t[0] as usize)?,
        *positions.get(t[1] as usize)?,
        *positions.get(t[2] as usize)?,
    ])
}

fn barycentric(location: TrianglePointLocation) -> Option<[f64; 3]> {
    let b = location.barycentric_coordinates()?;
    b.iter().all(|x| x.is_finite()).then_some(b)
}
