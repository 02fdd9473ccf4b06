//! A hierarchy of exact surface patches over one component: every node bounds the exact
//! surface of a set of mesh triangle pieces (and apex points) by a ball, a slab along its
//! normal cone's axis and the cone itself, and carries the mean curvature tensor of the surface
//! with a bound on its spread, so that a pair of nodes can be pruned, or certified to hold at
//! most one local minimum of distance, without looking at its triangles.
//!
//! Built once per component from the [`ComponentMesh`] and the exact [`Solid`] (through the
//! `Surface` trait only: the faces' normals and derivatives at parameters interpolated from the
//! triangles' corner parameters), so it works on every surface kind the mesh covers.
//!
//! Leaves are *pieces* of mesh triangles: a triangle much longer than it is wide (a straight
//! profile line gives triangles as long as the whole face) is bisected along its longest edge
//! until no piece is more than [`MAX_ASPECT`] times longer than the triangle is wide (or than
//! the mesh's chordal error, for slivers narrower than that), so that every leaf is spatially
//! compact and its normals and curvature are sampled at its own corners.

use crate::cones::normal_cone::{NormalBand, NormalCone};
use geom_param::{
    ComponentMesh, EdgeConvexity, EdgeId, FaceConvexity, FaceId, FeatureLocation, Solid,
    SurfacePoint,
};
use glam::{DMat2, DMat3, DVec2, DVec3};

/// What a node is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PatchLeaf {
    /// An inner node: its children are the next node and [`PatchNode::right`].
    Inner,
    /// A leaf holding piece `k` of [`PatchTree::pieces`].
    Piece(u32),
}

/// One node of a [`PatchTree`]. All of it in the component's object frame (mm).
///
/// The exact surface of the node's pieces (the points S(u, v) over their parameter triangles)
/// and the pieces themselves lie in the ball (`centre`, `radius`) and in the slab
/// `slab[0] <= cone.axis · (x - centre) <= slab[1]`: both are built from the pieces' corners
/// and grown by each piece's bound on its distance to its exact surface (at most the mesh's
/// chordal error, [`ComponentMesh::chordal_error`]; see `piece_deviation`). `cone` contains every outward normal of that
/// exact surface, including the normals of the creases between its faces; see
/// [`PatchTree::build`] for how.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PatchNode {
    /// Centre of the bounding ball.
    pub centre: DVec3,
    /// Radius of the bounding ball.
    pub radius: f64,
    /// Cap containing every outward normal of the node's exact surface.
    pub cone: NormalCone,
    /// A band containing them too, about the axis their spread is narrowest around (a
    /// cylinder's axis for a strip wrapped around it, or for a single piece of it, whose
    /// normals turn about that axis only: the band is then far thinner than the cap);
    /// [`NormalBand::ALL`] where it would confine the normals no more than the cap (see
    /// `node_band`).
    pub band: NormalBand,
    /// The slab along `cone.axis`, relative to `centre`: [lowest, highest].
    pub slab: [f64; 2],
    /// Centre of the (grown) axis-aligned bounding box, relative to `centre`.
    pub box_offset: DVec3,
    /// Half-extents of the axis-aligned bounding box (the volume also lies in this box).
    pub half_extents: DVec3,
    /// Mean of the curvature tensors sampled at every corner of the node's pieces, each
    /// restricted to the plane normal to `cone.axis` (P C P with P = I - axis axisᵀ; 1/mm; see
    /// [`CurvatureTensor`]).
    pub curvature: CurvatureTensor,
    /// Largest Frobenius distance (1/mm) from a sampled tensor, restricted likewise, to
    /// `curvature`: infinite when some corner has no curvature. (Restricting first makes this
    /// a second-order quantity in the cone's angle: a tangent plane turned by φ changes the
    /// restriction of its tensor by O(φ²) only.)
    pub curvature_spread: f64,
    /// The least deviation bound (mm) of the node's pieces: every bound of the node (ball,
    /// slab, box) is built from the pieces' corners grown by their own deviations, so the mesh
    /// pieces themselves lie in the volume shrunk by this much.
    pub mesh_inset: f64,
    /// The node's surface is smooth enough to certify pairs: every corner had a tangent plane
    /// and curvature, and no corner lies on a concave crease or at an apex.
    pub smooth: bool,
    /// Index of the second child (the first is the next node); unused for leaves.
    pub right: u32,
    /// Leaf payload, or [`PatchLeaf::Inner`].
    pub leaf: PatchLeaf,
    /// A piece of the node near its centre.
    pub representative: u32,
    /// The exact surface point at the representative piece's centroid parameters (object
    /// frame): with `anchor_normal` and `curvature`, a second-order model of the node's patch.
    pub anchor: DVec3,
    /// The exact outward normal there (the cone's axis where the face has none).
    pub anchor_normal: DVec3,
}

impl PatchNode {
    /// Whether this node is a leaf.
    #[must_use]
    pub fn is_leaf(&self) -> bool {
        self.leaf != PatchLeaf::Inner
    }
}

/// A piece of a mesh triangle: the triangle itself, or a part cut from it by bisections.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Piece {
    /// The mesh triangle.
    pub triangle: u32,
    /// Barycentric coordinates (in the triangle) of the piece's three corners.
    pub barycentric: [DVec3; 3],
    /// The corners (object frame).
    pub corners: [DVec3; 3],
    /// Bound (mm) on the distance between the piece and its exact surface (see
    /// `piece_deviation`).
    pub deviation: f64,
    /// Bit k set when the piece's side k (corners (0, 1), (1, 2), (2, 0)) lies along a convex
    /// edge of the solid whose faces both belong to the mesh's component ([`ridge_sides`]).
    pub inner_ridges: u8,
}

/// The sides of a piece, as pairs of corner indices, in the order of [`Piece::inner_ridges`].
pub const PIECE_SIDES: [(usize, usize); 3] = [(0, 1), (1, 2), (2, 0)];

/// The convex edge that the point with `barycentric` coordinates in mesh triangle `triangle`
/// lies on: every corner that carries weight is a mesh vertex on that edge (so the point is on
/// the triangle's side along the edge, or at its corner there).
#[must_use]
pub fn ridge_at(
    mesh: &ComponentMesh,
    solid: &Solid,
    triangle: u32,
    barycentric: [f64; 3],
) -> Option<EdgeId> {
    const ZERO: f64 = 1e-12;
    let corners = mesh.triangles.get(triangle as usize)?;
    let mut on = None;
    for (&vertex, &weight) in corners.iter().zip(&barycentric) {
        if weight <= ZERO {
            continue;
        }
        let FeatureLocation::Edge { id, .. } = *mesh.vertex_locations.get(vertex as usize)? else {
            return None;
        };
        if on.is_some_and(|e| e != id) {
            return None;
        }
        on = Some(id);
    }
    let convexity = solid.edges.get(on?.0 as usize)?.convexity;
    on.filter(|_| convexity == EdgeConvexity::Convex)
}

/// [`Piece::inner_ridges`] of `piece`: its sides whose two corners lie on one convex edge
/// ([`ridge_at`]) both of whose faces are among the mesh's (`faces`, sorted). A ridge on the
/// component's open boundary is also one of the neighbouring component, whose own pairs seed
/// it; one inside the component has only this component's candidates.
fn ridge_sides(mesh: &ComponentMesh, solid: &Solid, faces: &[FaceId], piece: &Piece) -> u8 {
    let on = |corner: usize| {
        ridge_at(
            mesh,
            solid,
            piece.triangle,
            piece.barycentric[corner].to_array(),
        )
    };
    let inside = |edge: EdgeId| {
        solid
            .edges
            .get(edge.0 as usize)
            .is_some_and(|e| e.uses.iter().all(|u| faces.binary_search(&u.face).is_ok()))
    };
    let mut mask = 0;
    for (k, &(i, j)) in PIECE_SIDES.iter().enumerate() {
        if on(i).is_some_and(|e| on(j) == Some(e) && inside(e)) {
            mask |= 1 << k;
        }
    }
    mask
}

impl Piece {
    /// The triangle's barycentric coordinates of the point with coordinates `b` in the piece.
    #[must_use]
    pub fn to_triangle(&self, b: [f64; 3]) -> [f64; 3] {
        let [p, q, r] = self.barycentric;
        (p * b[0] + q * b[1] + r * b[2]).to_array()
    }

    /// The face and the parameters of the piece's centroid, from the triangle's corner
    /// parameters (`None` when the triangle does not resolve).
    #[must_use]
    pub fn centroid_params(&self, mesh: &ComponentMesh) -> Option<(FaceId, DVec2)> {
        let t = self.triangle as usize;
        let face = *mesh.triangle_faces.get(t)?;
        let params = mesh.triangle_params.get(t)?;
        let b = (self.barycentric[0] + self.barycentric[1] + self.barycentric[2]) / 3.0;
        let uv = DVec2::from(params[0]) * b.x
            + DVec2::from(params[1]) * b.y
            + DVec2::from(params[2]) * b.z;
        Some((face, uv))
    }
}

/// A point where a face has no tangent plane (a cone's apex): kept apart from the tree (its
/// pieces carry only the normals around it) and queried as a point against the other tree, with
/// the apex's cone of normals.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Apex {
    /// The mesh vertex.
    pub vertex: u32,
    /// Its position (object frame, exact: mesh vertices lie on the surface).
    pub point: DVec3,
    /// Its exact location.
    pub location: FeatureLocation,
    /// A cap containing its normals: the normals of the faces around it and the mesh's vertex
    /// normal there.
    pub cone: NormalCone,
}

/// The patch hierarchy of one component: nodes in depth-first order (node 0 is the root), the
/// pieces its leaves refer to, and the apexes (outside the tree).
#[derive(Clone, Debug, Default)]
pub struct PatchTree {
    /// Nodes, root first; empty for an empty mesh.
    pub nodes: Vec<PatchNode>,
    /// Triangle pieces.
    pub pieces: Vec<Piece>,
    /// Apex points.
    pub apexes: Vec<Apex>,
    /// The mesh's chordal error (mm): no piece's volume is grown by more.
    pub inflation: f64,
}

/// Largest ratio of a piece's longest edge to its triangle's height over the triangle's
/// longest edge (or to the mesh's chordal error where that is larger): longer pieces are
/// bisected at the midpoint of their longest edge.
pub const MAX_ASPECT: f64 = 4.0;

/// Most bisections of one triangle (2^12 pieces at most).
const MAX_BISECTIONS: u32 = 12;

/// Angle (rad) every piece's cone is widened by beyond its sampled normals: the rounding of
/// the normals themselves is far below it.
const NORMAL_FLOOR: f64 = 1e-6;

/// Fraction of the angular spread of a piece's sampled face normals (at its corners, edge
/// midpoints and centroid) added to its cone: the exact normal inside the piece lies, to first
/// order, in the spherical hull of the corner normals (the normal map is smooth and the piece
/// small against the curvature radius), which the sampled cap already contains; the samples
/// inside the piece catch the second-order bending of the normal map, and between samples half
/// a piece apart what is left is of third order, far below a tenth of the spread.
const INTERIOR_SPREAD: f64 = 0.1;

/// Per-leaf data gathered before the tree is built.
struct Item {
    corners: [DVec3; 3],
    count: usize,
    /// Bound (mm) on the distance between the item and its exact surface.
    deviation: f64,
    cone: NormalCone,
    /// A band containing the item's normals too ([`NormalBand::ALL`] when none is known).
    band: NormalBand,
    /// Curvature tensors at the corners (meaningful where the item is smooth).
    tensors: [CurvatureTensor; 3],
    smooth: bool,
    leaf: PatchLeaf,
}

impl Item {
    fn points(&self) -> &[DVec3] {
        &self.corners[..self.count]
    }

    fn centroid(&self) -> DVec3 {
        self.points().iter().sum::<DVec3>() / self.count as f64
    }
}

/// Where a piece's corner lies on the solid, as far as the cone and the certificate care.
enum CornerFeature {
    /// Inside a face.
    Interior,
    /// At mesh vertex `v` (on an edge or a vertex of the solid when its location says so).
    Vertex(u32),
    /// On the mesh edge between vertices `i` and `j`, both on solid edge `edge` (the edge's
    /// chord): a crease.
    Crease { i: u32, j: u32, edge: EdgeId },
}

impl PatchTree {
    /// Builds the hierarchy of `mesh`, a component mesh of `solid`.
    ///
    /// Normals per piece: the exact outward normal of the triangle's face at each corner's
    /// parameters (`Surface::normal`) and at its edge midpoints and centroid, the cone about them
    /// widened by a tenth of their spread (`INTERIOR_SPREAD`); where a corner lies on an edge or vertex of the solid, the mesh's
    /// vertex normal too (the mean of the faces' normals there, interpolated along a crease's
    /// chord), so the pieces on either side of a crease together cover its arc of normals. A
    /// corner where the face has no normal is an apex: its pieces keep only their other corners'
    /// normals, and the apex becomes a leaf whose cone bounds the normals of every piece around
    /// it and the vertex normal. Curvature tensors are sampled at every corner. Triangles with
    /// an index or parameter that does not resolve get the whole sphere as cone and are not
    /// smooth.
    #[must_use]
    pub fn build(mesh: &ComponentMesh, solid: &Solid) -> Self {
        let inflation = if mesh.chordal_error.is_finite() {
            mesh.chordal_error.max(0.0)
        } else {
            0.0
        };
        let mut items = Vec::with_capacity(mesh.triangles.len());
        let mut pieces = Vec::with_capacity(mesh.triangles.len());
        let mut apex_normals: Vec<(u32, Vec<DVec3>)> = Vec::new();
        for (t, tri) in mesh.triangles.iter().enumerate() {
            let Some(corners) = corners_of(mesh, tri) else {
                continue;
            };
            split_triangle(t as u32, corners, inflation, &mut pieces);
        }
        let mut faces = mesh.triangle_faces.clone();
        faces.sort_unstable();
        faces.dedup();
        for (k, piece) in pieces.iter_mut().enumerate() {
            let item = piece_item(mesh, solid, piece, k as u32, &mut apex_normals);
            piece.deviation = item.deviation;
            piece.inner_ridges = ridge_sides(mesh, solid, &faces, piece);
            items.push(item);
        }
        let mut apexes = Vec::with_capacity(apex_normals.len());
        for (vertex, mut normals) in apex_normals {
            let v = vertex as usize;
            let (Some(&point), Some(&location)) =
                (mesh.positions.get(v), mesh.vertex_locations.get(v))
            else {
                continue;
            };
            if let Some(&n) = mesh.normals.get(v) {
                normals.push(n);
            }
            let cone = NormalCone::bounding(&normals).widened(NORMAL_FLOOR);
            apexes.push(Apex {
                vertex,
                point,
                location,
                cone,
            });
        }
        let mut nodes = Vec::with_capacity(2 * items.len());
        let mut order: Vec<u32> = (0..items.len() as u32).collect();
        if !order.is_empty() {
            build_node(&items, &mut order, &mut nodes);
        }
        for node in &mut nodes {
            let anchor = pieces
                .get(node.representative as usize)
                .and_then(|piece| anchor_of(mesh, solid, piece));
            (node.anchor, node.anchor_normal) = anchor.unwrap_or((node.centre, node.cone.axis));
        }
        Self {
            nodes,
            pieces,
            apexes,
            inflation,
        }
    }
}

fn corners_of(mesh: &ComponentMesh, tri: &[u32; 3]) -> Option<[DVec3; 3]> {
    Some([
        *mesh.positions.get(tri[0] as usize)?,
        *mesh.positions.get(tri[1] as usize)?,
        *mesh.positions.get(tri[2] as usize)?,
    ])
}

/// The exact point and outward normal at the centroid parameters of `piece`.
fn anchor_of(mesh: &ComponentMesh, solid: &Solid, piece: &Piece) -> Option<(DVec3, DVec3)> {
    let (face, uv) = piece.centroid_params(mesh)?;
    let surface = &solid.faces.get(face.0 as usize)?.surface;
    let [du, dv] = surface.domain();
    let (u, v) = (du.normalize(uv.x), dv.normalize(uv.y));
    let point = surface.eval(u, v).point;
    let normal = surface.normal(u, v)?;
    (point.is_finite() && normal.is_finite()).then_some((point, normal))
}

/// The longest edge of a triangle (corner indices) and its length.
fn longest_edge(c: &[DVec3; 3]) -> ((usize, usize), f64) {
    [(0, 1), (1, 2), (2, 0)]
        .into_iter()
        .map(|(i, j)| ((i, j), c[i].distance(c[j])))
        .max_by(|x, y| x.1.total_cmp(&y.1))
        .unwrap_or(((0, 1), 0.0))
}

/// Appends the pieces of triangle `t` (corners `corners`): with h the triangle's height over
/// its longest edge (its width), pieces are bisected at the midpoint of their longest edge
/// while that edge exceeds [`MAX_ASPECT`] max(h, `min_width`) (mm). (Measured against the
/// triangle's width rather than each piece's own, so that the needle-like pieces at the tip of
/// a fan triangle, as narrow as they are short, stop splitting.)
///
/// `min_width` is the mesh's chordal error: a sliver narrower than that is, at the mesh's
/// resolution, a segment, and pieces [`MAX_ASPECT`] chordal errors long are as compact as the
/// leaves of a triangle that wide. Without it a degenerate sliver (1e-10 mm wide and 1 mm
/// long at the pole of a sphere patch) never reaches the aspect and is cut into
/// 2^[`MAX_BISECTIONS`] pieces. The pieces only subdivide the triangle, so the tree's bounds
/// hold whatever the width used.
fn split_triangle(t: u32, corners: [DVec3; 3], min_width: f64, pieces: &mut Vec<Piece>) {
    let (_, longest) = longest_edge(&corners);
    let twice_area = (corners[1] - corners[0])
        .cross(corners[2] - corners[0])
        .length();
    let limit = MAX_ASPECT * (twice_area / longest).max(min_width);
    let mut stack = vec![(
        Piece {
            triangle: t,
            barycentric: [DVec3::X, DVec3::Y, DVec3::Z],
            corners,
            deviation: 0.0,
            inner_ridges: 0,
        },
        0,
    )];
    while let Some((piece, depth)) = stack.pop() {
        let c = piece.corners;
        let ((i, j), longest) = longest_edge(&c);
        let settled = longest <= limit || longest.is_nan();
        if depth >= MAX_BISECTIONS || settled || limit <= 0.0 || limit.is_nan() {
            pieces.push(piece);
            continue;
        }
        let mid = 0.5 * (c[i] + c[j]);
        let mid_b = 0.5 * (piece.barycentric[i] + piece.barycentric[j]);
        // Two halves, each keeping the corner order (and so the orientation) of the piece.
        let mut first = piece;
        first.corners[j] = mid;
        first.barycentric[j] = mid_b;
        let mut second = piece;
        second.corners[i] = mid;
        second.barycentric[i] = mid_b;
        stack.push((first, depth + 1));
        stack.push((second, depth + 1));
    }
}

/// A bound (mm) on the distance between `piece` and its exact surface (points with the same
/// parameters), at most the mesh's `chordal_error`.
///
/// Between corners that lie on the surface, the deviation of a smooth surface from the plane
/// piece is, to second order, a quadratic f = Σ c_ij b_i b_j in the barycentric coordinates that
/// vanishes at the corners; its values at the edge midpoints are c_ij / 4, and |f| <=
/// max |c_ij| Σ b_i b_j <= max |c_ij| / 3 = 4/3 of the largest midpoint value. The bound is
/// twice the largest deviation sampled at the three edge midpoints (leaving the third-order
/// remainder, O(h³) against the O(h²) samples, a wide margin), plus a rounding allowance of
/// 1e-12 of the coordinates' magnitude, and never more than the chordal error. An exactly flat
/// piece gets the rounding allowance alone.
fn piece_deviation(
    piece: &Piece,
    params: &[[f64; 2]; 3],
    surface: &dyn geom_param::Surface,
    chordal_error: f64,
) -> f64 {
    let [du, dv] = surface.domain();
    let mut largest = 0.0_f64;
    for (i, j) in [(0, 1), (1, 2), (2, 0)] {
        let b = 0.5 * (piece.barycentric[i] + piece.barycentric[j]);
        let uv = DVec2::from(params[0]) * b.x
            + DVec2::from(params[1]) * b.y
            + DVec2::from(params[2]) * b.z;
        let exact = surface.eval(du.normalize(uv.x), dv.normalize(uv.y)).point;
        let on_piece = 0.5 * (piece.corners[i] + piece.corners[j]);
        let d = exact.distance(on_piece);
        if !d.is_finite() {
            return chordal_error;
        }
        largest = largest.max(d);
    }
    let magnitude = piece
        .corners
        .iter()
        .map(|c| c.abs().max_element())
        .fold(0.0, f64::max);
    (2.0 * largest + 1e-12 * magnitude).min(chordal_error)
}

/// Where corner `k` of `piece` lies (see [`CornerFeature`]).
fn corner_feature(mesh: &ComponentMesh, piece: &Piece, k: usize) -> CornerFeature {
    let Some(tri) = mesh.triangles.get(piece.triangle as usize) else {
        return CornerFeature::Interior;
    };
    let b = piece.barycentric[k].to_array();
    let zero = |m: usize| b[m] == 0.0;
    match (zero(0), zero(1), zero(2)) {
        (false, true, true) => CornerFeature::Vertex(tri[0]),
        (true, false, true) => CornerFeature::Vertex(tri[1]),
        (true, true, false) => CornerFeature::Vertex(tri[2]),
        (false, false, true) | (true, false, false) | (false, true, false) => {
            let (m, n) = if zero(2) {
                (0, 1)
            } else if zero(0) {
                (1, 2)
            } else {
                (0, 2)
            };
            let (i, j) = (tri[m], tri[n]);
            match (
                mesh.vertex_locations.get(i as usize),
                mesh.vertex_locations.get(j as usize),
            ) {
                (
                    Some(FeatureLocation::Edge { id: e1, .. }),
                    Some(FeatureLocation::Edge { id: e2, .. }),
                ) if e1 == e2 => CornerFeature::Crease { i, j, edge: *e1 },
                _ => CornerFeature::Interior,
            }
        }
        _ => CornerFeature::Interior,
    }
}

/// The leaf item of `piece` (number `k`); records its apex corners in `apex_normals`.
fn piece_item(
    mesh: &ComponentMesh,
    solid: &Solid,
    piece: &Piece,
    k: u32,
    apex_normals: &mut Vec<(u32, Vec<DVec3>)>,
) -> Item {
    let chordal_error = if mesh.chordal_error.is_finite() {
        mesh.chordal_error.max(0.0)
    } else {
        0.0
    };
    let t = piece.triangle as usize;
    let broken = Item {
        corners: piece.corners,
        count: 3,
        deviation: chordal_error,
        cone: NormalCone::ALL,
        band: NormalBand::ALL,
        tensors: [CurvatureTensor::ZERO; 3],
        smooth: false,
        leaf: PatchLeaf::Piece(k),
    };
    let (Some(face), Some(params)) = (mesh.triangle_faces.get(t), mesh.triangle_params.get(t))
    else {
        return broken;
    };
    let Some(face_data) = solid.faces.get(face.0 as usize) else {
        return broken;
    };
    let surface = &face_data.surface;
    let [du, dv] = surface.domain();
    let mut face_normals: [DVec3; 3] = [DVec3::ZERO; 3];
    let mut face_count = 0;
    // Normals at the corners on edges or vertices of the solid, beyond the face's own.
    let mut extra: Vec<DVec3> = Vec::new();
    // On a concave face, the normals of the faces across a convex edge at its parameter `t`
    // where those are convex or flat: the whole arc of the edge's normals then lies in the
    // piece's cone, not only the half on this face's side of the mean. The face across is in
    // a convex component, which the convex path answers with its single global minimum (GJK),
    // so a minimum on the edge with its connecting vector on that side has to be found from
    // this side (a pencil against a goblet's cup at the lip and at the crease where the cup
    // meets the stem: the crease's minimum was missed).
    let own_concave = face_data.convexity == FaceConvexity::Concave;
    let edge_face_normals = |id: EdgeId, t: f64, into: &mut Vec<DVec3>| {
        let Some(edge) = solid.edges.get(id.0 as usize) else {
            return;
        };
        if !own_concave || edge.convexity == EdgeConvexity::Concave {
            return;
        }
        for use_ in &edge.uses {
            let Some(across) = solid.faces.get(use_.face.0 as usize) else {
                continue;
            };
            if use_.face == *face || across.convexity == FaceConvexity::Concave {
                continue;
            }
            let [u, v] = solid.use_params(use_, t);
            let [ru, rv] = across.surface.domain();
            if let Some(n) = across.surface.normal(ru.normalize(u), rv.normalize(v)) {
                if n.is_finite() {
                    into.push(n);
                }
            }
        }
    };
    let mut tensors = [CurvatureTensor::ZERO; 3];
    let mut smooth = true;
    let mut apex_corners: [Option<u32>; 3] = [None; 3];
    // Tangents of the solid's edges at the piece's points on them (see `crease_band`), and
    // whether some such point has no known tangent or is a vertex of the solid.
    let mut tangents = EdgeTangents::default();
    let edge_is_concave = |id: EdgeId| {
        solid
            .edges
            .get(id.0 as usize)
            .is_none_or(|e| e.convexity == EdgeConvexity::Concave)
    };
    for (c, (b, apex_corner)) in piece
        .barycentric
        .iter()
        .copied()
        .zip(apex_corners.iter_mut())
        .enumerate()
    {
        let uv = DVec2::from(params[0]) * b.x
            + DVec2::from(params[1]) * b.y
            + DVec2::from(params[2]) * b.z;
        let (u, v) = (du.normalize(uv.x), dv.normalize(uv.y));
        let feature = corner_feature(mesh, piece, c);
        match surface.normal(u, v) {
            Some(n) if n.is_finite() => {
                match CurvatureTensor::at(&surface.eval(u, v), n) {
                    Some(tensor) => tensors[face_count] = tensor,
                    None => smooth = false,
                }
                face_normals[face_count] = n;
                face_count += 1;
            }
            _ => {
                smooth = false;
                if let CornerFeature::Vertex(vertex) = feature {
                    *apex_corner = Some(vertex);
                }
                continue;
            }
        }
        match feature {
            CornerFeature::Interior => {}
            CornerFeature::Vertex(vertex) => match mesh.vertex_locations.get(vertex as usize) {
                Some(FeatureLocation::Edge { id, t }) => {
                    if let Some(&n) = mesh.normals.get(vertex as usize) {
                        extra.push(n);
                    }
                    edge_face_normals(*id, *t, &mut extra);
                    tangents.add_at(solid, *id, *t);
                    smooth &= !edge_is_concave(*id);
                }
                Some(FeatureLocation::Vertex { id }) => {
                    if let Some(&n) = mesh.normals.get(vertex as usize) {
                        extra.push(n);
                    }
                    // A corner of the solid: the faces across each edge that ends here.
                    for &e in solid
                        .vertices
                        .get(id.0 as usize)
                        .map_or(&[][..], |v| &v.edges)
                    {
                        let Some(edge) = solid.edges.get(e.0 as usize) else {
                            continue;
                        };
                        let range = edge.curve.domain();
                        for (end, t) in edge.ends.into_iter().flatten().zip([range.min, range.max])
                        {
                            if end == *id {
                                edge_face_normals(e, t, &mut extra);
                            }
                        }
                    }
                    tangents.unknown = true;
                }
                _ => {}
            },
            CornerFeature::Crease { i, j, edge } => {
                tangents.add_chord(mesh, solid, (i, j), edge);
                let b = b.to_array();
                let tri = mesh.triangles[t];
                let weight = |v: u32| (0..3).find(|&m| tri[m] == v).map_or(0.0, |m| b[m]);
                if let (Some(&ni), Some(&nj)) =
                    (mesh.normals.get(i as usize), mesh.normals.get(j as usize))
                {
                    if let Some(n) = (ni * weight(i) + nj * weight(j)).try_normalize() {
                        extra.push(n);
                    }
                }
                for end in [i, j] {
                    if let Some(FeatureLocation::Edge { id, t }) =
                        mesh.vertex_locations.get(end as usize)
                    {
                        if *id == edge {
                            edge_face_normals(edge, *t, &mut extra);
                        }
                    }
                }
                smooth &= !edge_is_concave(edge);
            }
        }
    }
    if face_count == 0 {
        return broken;
    }
    let face_normals = &face_normals[..face_count];
    for vertex in apex_corners.into_iter().flatten() {
        match apex_normals.iter_mut().find(|(v, _)| *v == vertex) {
            Some((_, list)) => list.extend_from_slice(face_normals),
            None => apex_normals.push((vertex, face_normals.to_vec())),
        }
    }
    // The face's normals inside the piece too: at its edge midpoints and centroid.
    let mut all = [DVec3::ZERO; 7];
    all[..face_count].copy_from_slice(face_normals);
    let mut count = face_count;
    let inside = [
        (piece.barycentric[0] + piece.barycentric[1]) * 0.5,
        (piece.barycentric[1] + piece.barycentric[2]) * 0.5,
        (piece.barycentric[2] + piece.barycentric[0]) * 0.5,
        (piece.barycentric[0] + piece.barycentric[1] + piece.barycentric[2]) / 3.0,
    ];
    for b in inside {
        let uv = DVec2::from(params[0]) * b.x
            + DVec2::from(params[1]) * b.y
            + DVec2::from(params[2]) * b.z;
        if let Some(n) = surface.normal(du.normalize(uv.x), dv.normalize(uv.y)) {
            if n.is_finite() {
                all[count] = n;
                count += 1;
            }
        }
    }
    let sampled = &all[..count];
    // The largest angle between two samples: one `acos` of the least cosine.
    let spread = sampled
        .iter()
        .flat_map(|a| {
            sampled
                .iter()
                .map(move |b| a.dot(*b) / (a.length_squared() * b.length_squared()).sqrt())
        })
        .fold(1.0_f64, f64::min)
        .clamp(-1.0, 1.0)
        .acos();
    // A piece on an edge of the solid also holds the arc of normals between the edge's two
    // faces at each of its edge points, all normal to the edge: a band about the edge.
    let band = if tangents.unknown || face_count < 3 {
        NormalBand::ALL
    } else if tangents.count > 0 {
        crease_band(sampled, spread, tangents.list())
    } else if extra.is_empty() {
        piece_band(sampled, spread)
    } else {
        NormalBand::ALL
    };
    let mut normals = sampled.to_vec();
    normals.extend_from_slice(&extra);
    let cone = NormalCone::bounding(&normals).widened(INTERIOR_SPREAD * spread + NORMAL_FLOOR);
    Item {
        corners: piece.corners,
        count: 3,
        deviation: piece_deviation(piece, params, surface.as_ref(), chordal_error),
        cone,
        band,
        tensors,
        smooth: smooth && face_count == 3,
        leaf: PatchLeaf::Piece(k),
    }
}

/// Fraction of the range of the sampled normals' angles from a piece's band axis added on each
/// side of the band: a quadratic through the samples at the corners and edge midpoints
/// overshoots their range inside the triangle by at most an eighth of it along an edge, and the
/// centroid sample bounds the rest; a quarter leaves a margin.
const BAND_OVERSHOOT: f64 = 0.25;

/// The band of a piece's face normals `sampled` (corners, edge midpoints, centroid), of
/// angular spread `spread` (rad): about the pole of the great circle through the two samples
/// farthest apart (a cylinder's or an extrusion's axis, along which the normal does not turn;
/// any axis where the normals do not lie on one great circle), from the least
/// to the largest angle of a sample, widened by [`BAND_OVERSHOOT`] of that range (the
/// second-order overshoot between samples), by a tenth of spread³ (the third-order remainder of
/// the normal map between samples half a piece apart, the cube of the turn across the piece,
/// which [`INTERIOR_SPREAD`] covers for the cap with a first-order margin) and by
/// [`NORMAL_FLOOR`]. On a cylinder the samples lie on the great circle about its axis, and so
/// does every normal between them: the band is as thin as the floor, where the cap is as wide
/// as the piece's turn.
fn piece_band(sampled: &[DVec3], spread: f64) -> NormalBand {
    if sampled.len() < 3 {
        return NormalBand::ALL;
    }
    // The pole of the great circle through the two samples farthest apart.
    let (mut far, mut best) = ((sampled[0], sampled[0]), -1.0);
    for (i, a) in sampled.iter().enumerate() {
        for b in &sampled[i + 1..] {
            let d = a.distance_squared(*b);
            if d > best {
                (far, best) = ((*a, *b), d);
            }
        }
    }
    let Some(axis) = far.0.cross(far.1).try_normalize() else {
        return NormalBand::ALL;
    };
    let (lo, hi) = sampled
        .iter()
        .map(|n| axis.dot(*n).clamp(-1.0, 1.0).acos())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), a| {
            (lo.min(a), hi.max(a))
        });
    let widen = BAND_OVERSHOOT * (hi - lo) + INTERIOR_SPREAD * spread.powi(3) + NORMAL_FLOOR;
    if !widen.is_finite() {
        return NormalBand::ALL;
    }
    NormalBand::new(axis, lo - widen, hi + widen)
}

/// Unit tangents of the solid's edges sampled at a piece's points on them: at its corners on
/// edges and, for a side along an edge (a crease), at the side's mesh vertices and along its
/// chord (by the mean value theorem the chord is a positive combination of the tangents between
/// its ends).
#[derive(Default)]
struct EdgeTangents {
    samples: [DVec3; 9],
    count: usize,
    /// Some edge point of the piece is a vertex of the solid (whose normals are a whole
    /// spherical polygon, not an arc), or an edge has no tangent there.
    unknown: bool,
}

impl EdgeTangents {
    fn list(&self) -> &[DVec3] {
        &self.samples[..self.count]
    }

    fn push(&mut self, tangent: Option<DVec3>) {
        match tangent.filter(|t| t.is_finite()) {
            Some(t) if self.count < self.samples.len() => {
                self.samples[self.count] = t;
                self.count += 1;
            }
            Some(_) => {}
            None => self.unknown = true,
        }
    }

    /// The tangent of edge `id` at parameter `t`.
    fn add_at(&mut self, solid: &Solid, id: EdgeId, t: f64) {
        let tangent = solid.edges.get(id.0 as usize).and_then(|e| {
            let curve = &e.curve;
            curve.tangent(curve.domain().normalize(t))
        });
        self.push(tangent);
    }

    /// The tangents at the ends of the mesh side from vertex `i` to vertex `j` along edge
    /// `edge`, and its chord.
    fn add_chord(&mut self, mesh: &ComponentMesh, solid: &Solid, (i, j): (u32, u32), edge: EdgeId) {
        for v in [i, j] {
            match mesh.vertex_locations.get(v as usize) {
                Some(FeatureLocation::Edge { id, t }) if *id == edge => {
                    self.add_at(solid, edge, *t)
                }
                _ => self.unknown = true,
            }
        }
        let chord = match (
            mesh.positions.get(i as usize),
            mesh.positions.get(j as usize),
        ) {
            (Some(p), Some(q)) => (*q - *p).try_normalize(),
            _ => None,
        };
        self.push(chord);
    }
}

/// The band of a piece on an edge of the solid: about the mean `axis` of the edge's tangents
/// `tangents` at the piece (each turned to the first's side). Every normal at an edge point
/// (the face normals there and the arc between them, whichever arc) is normal to the tangent
/// t there, so its angle from `axis` lies within angle(axis, ±t) of 90°: within τ, the largest
/// such angle over the samples, widened by [`BAND_OVERSHOOT`] of it (the tangent turns
/// monotonically between samples a piece apart, up to second order) and [`NORMAL_FLOOR`]. The
/// face normals `sampled` inside the piece add their own range of angles, widened as in
/// [`piece_band`]. On a circular edge the samples' tangents bound the turn exactly and the
/// band is as wide as the piece's turn along the edge, where the piece's cap spans the whole
/// dihedral angle.
fn crease_band(sampled: &[DVec3], spread: f64, tangents: &[DVec3]) -> NormalBand {
    let Some(&first) = tangents.first() else {
        return NormalBand::ALL;
    };
    let Some(axis) = tangents
        .iter()
        .map(|t| if t.dot(first) < 0.0 { -*t } else { *t })
        .sum::<DVec3>()
        .try_normalize()
    else {
        return NormalBand::ALL;
    };
    let turn = tangents
        .iter()
        .map(|t| axis.dot(*t).abs().min(1.0).acos())
        .fold(0.0, f64::max);
    let half = std::f64::consts::FRAC_PI_2;
    let crease = (1.0 + BAND_OVERSHOOT) * turn + NORMAL_FLOOR;
    let (lo, hi) = sampled
        .iter()
        .map(|n| axis.dot(*n).clamp(-1.0, 1.0).acos())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), a| {
            (lo.min(a), hi.max(a))
        });
    let widen = BAND_OVERSHOOT * (hi - lo) + INTERIOR_SPREAD * spread.powi(3) + NORMAL_FLOOR;
    let (lo, hi) = (
        (lo - widen).min(half - crease),
        (hi + widen).max(half + crease),
    );
    if !(lo.is_finite() && hi.is_finite()) {
        return NormalBand::ALL;
    }
    NormalBand::new(axis, lo, hi)
}

/// Cosine of the half-angle of a node's normal cone above which a split by normals is tried
/// besides the split in space: 45°.
const NORMAL_SPLIT_COS: f64 = std::f64::consts::FRAC_1_SQRT_2;

/// Half-angle (rad) at which a node's cone counts as much as its size in [`split_cost`]: 30°.
const COST_ANGLE: f64 = std::f64::consts::PI / 6.0;

/// The cost of splitting `order` at `mid`: for each half, its size (half-diagonal of its
/// corners' box) times 1 + θ / [`COST_ANGLE`] (θ its cone's half-angle). Both a large ball and
/// a wide cone make a node pass more pair tests.
fn split_cost(items: &[Item], order: &[u32], mid: usize) -> f64 {
    let (left, right) = order.split_at(mid);
    [left, right]
        .iter()
        .map(|half| {
            let (lo, hi) = half.iter().fold(
                (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
                |(lo, hi), &i| {
                    items[i as usize]
                        .points()
                        .iter()
                        .fold((lo, hi), |(lo, hi), p| (lo.min(*p), hi.max(*p)))
                },
            );
            let size = 0.5 * (hi - lo).length();
            size * (1.0 + items_cone(items, half).half_angle() / COST_ANGLE)
        })
        .sum()
}

/// The band of a node over `order` (item indices) with cap `cone`: a leaf keeps its item's
/// band; an inner node gets the band about the axis its items' normals spread least around
/// (from their cone axes, or their bands' axes where every item has one) containing each
/// item's cap and band ([`NormalBand::around_items`]). A band that confines the normals no
/// more than the cap does is dropped ([`NormalBand::ALL`]): it would only cost tests.
fn node_band(items: &[Item], order: &[u32], cone: NormalCone) -> NormalBand {
    let band = if let [single] = order {
        items[*single as usize].band
    } else {
        // Where every item has a band, about the mean of their axes (turned to one side: a
        // band about -a is one about a); else about the pole of the items' cap axes.
        let first = items[order[0] as usize].band.axis;
        let banded = order.iter().all(|&i| !items[i as usize].band.is_all());
        let mean = order
            .iter()
            .map(|&i| items[i as usize].band.axis)
            .map(|a| if a.dot(first) < 0.0 { -a } else { a })
            .sum::<DVec3>()
            .try_normalize();
        let axis = match (banded, mean) {
            (true, Some(axis)) => axis,
            _ => narrowest_axis(order.iter().map(|&i| items[i as usize].cone.axis)),
        };
        NormalBand::around_items(
            axis,
            order
                .iter()
                .map(|&i| (items[i as usize].cone, items[i as usize].band)),
        )
    };
    if band.is_all() || cone.is_all() {
        return band;
    }
    // The cap alone confines the angles from the band's axis to [φ - θ, φ + θ].
    let phi = band.axis.dot(cone.axis).clamp(-1.0, 1.0).acos();
    let theta = cone.half_angle();
    if band.lo <= (phi - theta).max(0.0) && band.hi >= (phi + theta).min(std::f64::consts::PI) {
        NormalBand::ALL
    } else {
        band
    }
}

/// The index (0, 1, 2) of the largest component.
fn widest(v: DVec3) -> usize {
    if v.x >= v.y && v.x >= v.z {
        0
    } else if v.y >= v.z {
        1
    } else {
        2
    }
}

/// The unit axis about which the unit vectors `axes` spread least: the eigenvector of the
/// smallest eigenvalue of Σ a aᵀ (a cylinder's axis for its normals), by power iteration on
/// tr(M) I - M.
fn narrowest_axis(axes: impl Iterator<Item = DVec3>) -> DVec3 {
    let mut m = DMat3::ZERO;
    for a in axes {
        m += DMat3::from_cols(a * a.x, a * a.y, a * a.z);
    }
    let shifted = DMat3::from_diagonal(DVec3::splat(m.x_axis.x + m.y_axis.y + m.z_axis.z)) - m;
    let diagonal = DVec3::new(m.x_axis.x, m.y_axis.y, m.z_axis.z);
    let mut v = DVec3::ZERO;
    v[widest(-diagonal)] = 1.0;
    v += DVec3::splat(0.1);
    for _ in 0..40 {
        match (shifted * v).try_normalize() {
            Some(next) => v = next,
            None => break,
        }
    }
    v.normalize_or_zero()
}

/// A cap containing every item's cone: about the normalised mean of their axes, with half-angle
/// the largest angle from it to an axis plus the largest item half-angle (one `acos` per node).
fn items_cone(items: &[Item], order: &[u32]) -> NormalCone {
    let mut sum = DVec3::ZERO;
    let mut widest_item = 0.0_f64;
    for &i in order.iter() {
        let cone = &items[i as usize].cone;
        if cone.is_all() {
            return NormalCone::ALL;
        }
        sum += cone.axis;
        widest_item = widest_item.max(cone.half_angle());
    }
    let Some(axis) = sum.try_normalize() else {
        return NormalCone::ALL;
    };
    let least = order
        .iter()
        .map(|&i| axis.dot(items[i as usize].cone.axis))
        .fold(1.0_f64, f64::min);
    NormalCone::new(axis, least.clamp(-1.0, 1.0).acos() + widest_item)
}

/// Builds the subtree over `order` (item indices) into `nodes` (depth-first) and returns its
/// root's index (see `split_cost` for the split).
fn build_node(items: &[Item], order: &mut [u32], nodes: &mut Vec<PatchNode>) -> u32 {
    let index = nodes.len() as u32;
    nodes.push(PatchNode {
        centre: DVec3::ZERO,
        radius: 0.0,
        cone: NormalCone::ALL,
        band: NormalBand::ALL,
        slab: [0.0; 2],
        box_offset: DVec3::ZERO,
        half_extents: DVec3::ZERO,
        curvature: CurvatureTensor::ZERO,
        curvature_spread: f64::INFINITY,
        mesh_inset: 0.0,
        smooth: false,
        right: u32::MAX,
        leaf: PatchLeaf::Inner,
        representative: u32::MAX,
        anchor: DVec3::ZERO,
        anchor_normal: DVec3::Z,
    });
    let cone = items_cone(items, order);
    let (smooth, leaf) = if let [single] = order {
        let item = &items[*single as usize];
        (item.smooth, item.leaf)
    } else {
        // Two candidate splits at a median: in space (centroids along their widest axis) and
        // in normals (the component of the items' cone axes that varies most); the one whose
        // children are cheaper by [`split_cost`] wins, so that nodes wrapping around a thin
        // cylinder or cone are cut into strips with narrow cones.
        let mid = order.len() / 2;
        let spatial = |item: &Item, axis: usize| item.centroid()[axis];
        let normal = |item: &Item, axis: usize| item.cone.axis[axis];
        let (lo, hi) = order.iter().fold(
            (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
            |(lo, hi), &i| {
                let c = items[i as usize].centroid();
                (lo.min(c), hi.max(c))
            },
        );
        let space_axis = widest(hi - lo);
        let (lo, hi) = order.iter().fold(
            (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
            |(lo, hi), &i| {
                let n = items[i as usize].cone.axis;
                (lo.min(n), hi.max(n))
            },
        );
        let normal_axis = widest(hi - lo);
        if cone.cos < NORMAL_SPLIT_COS {
            let mut trial = order.to_vec();
            trial.select_nth_unstable_by(mid, |&a, &b| {
                normal(&items[a as usize], normal_axis)
                    .total_cmp(&normal(&items[b as usize], normal_axis))
            });
            let normal_cost = split_cost(items, &trial, mid);
            order.select_nth_unstable_by(mid, |&a, &b| {
                spatial(&items[a as usize], space_axis)
                    .total_cmp(&spatial(&items[b as usize], space_axis))
            });
            if normal_cost < split_cost(items, order, mid) {
                order.copy_from_slice(&trial);
            }
        } else {
            order.select_nth_unstable_by(mid, |&a, &b| {
                spatial(&items[a as usize], space_axis)
                    .total_cmp(&spatial(&items[b as usize], space_axis))
            });
        }
        let (left, right) = order.split_at_mut(mid);
        let first = build_node(items, left, nodes);
        let second = build_node(items, right, nodes);
        let (l, r) = (nodes[first as usize], nodes[second as usize]);
        nodes[index as usize].right = second;
        (l.smooth && r.smooth, PatchLeaf::Inner)
    };
    let points = || {
        order
            .iter()
            .flat_map(|&i| items[i as usize].points().iter())
    };
    let (lo, hi) = points().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), p| (lo.min(*p), hi.max(*p)),
    );
    let centre = 0.5 * (lo + hi);
    // Each item's points grown by the item's own deviation from its exact surface.
    let grown = || {
        order.iter().flat_map(|&i| {
            let item = &items[i as usize];
            item.points().iter().map(move |p| (*p, item.deviation))
        })
    };
    let reach = grown()
        .map(|(p, e)| p.distance(centre) + e)
        .fold(0.0, f64::max);
    let (s_lo, s_hi) = grown().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), (p, e)| {
        let s = cone.axis.dot(p - centre);
        (a.min(s - e), b.max(s + e))
    });
    let (box_lo, box_hi) = grown().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), (p, e)| (lo.min(p - e), hi.max(p + e)),
    );
    let (curvature, curvature_spread) = if smooth {
        let samples = || {
            order.iter().flat_map(|&i| {
                let item = &items[i as usize];
                item.tensors[..item.count]
                    .iter()
                    .map(|t| t.restricted(cone.axis))
            })
        };
        let count = order
            .iter()
            .map(|&i| items[i as usize].count)
            .sum::<usize>();
        // Restriction is linear: the mean of the restricted samples is the restricted mean.
        let mean = order
            .iter()
            .flat_map(|&i| {
                let item = &items[i as usize];
                item.tensors[..item.count].iter()
            })
            .fold(CurvatureTensor::ZERO, |acc, t| acc.plus(t))
            .restricted(cone.axis)
            .scaled(1.0 / count.max(1) as f64);
        let spread = samples().map(|t| t.distance(&mean)).fold(0.0, f64::max);
        (mean, spread)
    } else {
        (CurvatureTensor::ZERO, f64::INFINITY)
    };
    let representative = order
        .iter()
        .filter(|&&i| matches!(items[i as usize].leaf, PatchLeaf::Piece(_)))
        .min_by(|&&a, &&b| {
            let da = items[a as usize].centroid().distance_squared(centre);
            let db = items[b as usize].centroid().distance_squared(centre);
            da.total_cmp(&db)
        })
        .and_then(|&i| match items[i as usize].leaf {
            PatchLeaf::Piece(k) => Some(k),
            _ => None,
        })
        .unwrap_or(u32::MAX);
    // A rounding allowance on top of the deviations, far below any tolerance (1e-12 of the
    // coordinates' magnitude).
    let slack = 1e-12 * (centre.abs().max_element() + reach);
    let node = &mut nodes[index as usize];
    node.centre = centre;
    node.radius = reach + slack;
    node.cone = cone;
    node.band = node_band(items, order, cone);
    node.slab = [s_lo - slack, s_hi + slack];
    node.box_offset = 0.5 * (box_lo + box_hi) - centre;
    node.half_extents = 0.5 * (box_hi - box_lo) + slack;
    node.curvature = curvature;
    node.curvature_spread = curvature_spread;
    node.mesh_inset = order
        .iter()
        .map(|&i| items[i as usize].deviation)
        .fold(f64::INFINITY, f64::min)
        .max(0.0);
    node.smooth = smooth && curvature_spread.is_finite();
    node.leaf = leaf;
    node.representative = representative;
    index
}

/// The curvature of a surface at a point as a symmetric 3x3 tensor C in the object frame:
/// for a unit tangent vector t, tᵀ C t is the normal curvature in direction t (library sign:
/// positive where convex seen from outside), and C n = 0 for the normal n. With
/// J = [S_u S_v], the first fundamental form I = JᵀJ and the second II (L = S_uu · n, ...),
/// C = J I⁻¹ (-II) I⁻¹ Jᵀ: for t = J a, tᵀ C t = -aᵀ II a and |t|² = aᵀ I a.
///
/// Stored as its six distinct entries (xx, yy, zz, xy, xz, yz).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CurvatureTensor(pub [f64; 6]);

impl CurvatureTensor {
    /// The zero tensor (a plane).
    pub const ZERO: Self = Self([0.0; 6]);

    /// The tensor at `point` with unit outward normal `n`; `None` where the first fundamental
    /// form is singular or a value is not finite.
    #[must_use]
    pub fn at(point: &SurfacePoint, n: DVec3) -> Option<Self> {
        let (du, dv) = (point.du, point.dv);
        let first = DMat2::from_cols(
            DVec2::new(du.dot(du), du.dot(dv)),
            DVec2::new(du.dot(dv), dv.dot(dv)),
        );
        let det = first.determinant();
        if det <= f64::EPSILON * du.length_squared() * dv.length_squared() || det.is_nan() {
            return None;
        }
        let second = DMat2::from_cols(
            DVec2::new(point.duu.dot(n), point.duv.dot(n)),
            DVec2::new(point.duv.dot(n), point.dvv.dot(n)),
        );
        let inverse = first.inverse();
        let middle = inverse * (-second) * inverse;
        // C = J M Jᵀ with J's columns du, dv.
        let c = |x: DVec3, y: DVec3| {
            let (ax, ay) = (
                DVec2::new(du.dot(x), dv.dot(x)),
                DVec2::new(du.dot(y), dv.dot(y)),
            );
            ax.dot(middle * ay)
        };
        let (ex, ey, ez) = (DVec3::X, DVec3::Y, DVec3::Z);
        let t = Self([
            c(ex, ex),
            c(ey, ey),
            c(ez, ez),
            c(ex, ey),
            c(ex, ez),
            c(ey, ez),
        ]);
        t.0.iter().all(|x| x.is_finite()).then_some(t)
    }

    /// The tensor restricted to the plane normal to the unit vector `axis`: P C P with
    /// P = I - axis axisᵀ.
    #[must_use]
    pub fn restricted(&self, axis: DVec3) -> Self {
        let q = [DVec3::X, DVec3::Y, DVec3::Z]
            .map(|e| e - axis * axis.x.mul_add(e.x, axis.y.mul_add(e.y, axis.z * e.z)));
        Self([
            self.form(q[0], q[0]),
            self.form(q[1], q[1]),
            self.form(q[2], q[2]),
            self.form(q[0], q[1]),
            self.form(q[0], q[2]),
            self.form(q[1], q[2]),
        ])
    }

    /// The sum of two tensors.
    #[must_use]
    pub fn plus(&self, other: &Self) -> Self {
        Self(std::array::from_fn(|i| self.0[i] + other.0[i]))
    }

    /// The tensor times `s`.
    #[must_use]
    pub fn scaled(&self, s: f64) -> Self {
        Self(self.0.map(|x| x * s))
    }

    /// Frobenius distance to another tensor (an upper bound of the spectral norm of the
    /// difference).
    #[must_use]
    pub fn distance(&self, other: &Self) -> f64 {
        let d: [f64; 6] = std::array::from_fn(|i| self.0[i] - other.0[i]);
        (d[0] * d[0] + d[1] * d[1] + d[2] * d[2] + 2.0 * (d[3] * d[3] + d[4] * d[4] + d[5] * d[5]))
            .sqrt()
    }

    /// Frobenius norm.
    #[must_use]
    pub fn norm(&self) -> f64 {
        self.distance(&Self::ZERO)
    }

    /// tᵀ C s.
    #[must_use]
    pub fn form(&self, t: DVec3, s: DVec3) -> f64 {
        let [xx, yy, zz, xy, xz, yz] = self.0;
        let cs = DVec3::new(
            xx * s.x + xy * s.y + xz * s.z,
            xy * s.x + yy * s.y + yz * s.z,
            xz * s.x + yz * s.y + zz * s.z,
        );
        t.dot(cs)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn twice_area(c: &[DVec3; 3]) -> f64 {
        (c[1] - c[0]).cross(c[2] - c[0]).length()
    }

    /// The pieces of `corners` under `min_width`, checked against the triangle: each piece's
    /// corners are the triangle's points at the piece's barycentric coordinates, and the pieces
    /// tile it (their areas add up to the triangle's, their barycentric areas to the unit
    /// triangle's).
    fn tiled_pieces(corners: [DVec3; 3], min_width: f64) -> Vec<Piece> {
        let mut pieces = Vec::new();
        split_triangle(7, corners, min_width, &mut pieces);
        let scale = corners.iter().map(|c| c.length()).fold(0.0, f64::max);
        for piece in &pieces {
            assert_eq!(piece.triangle, 7);
            for (b, c) in piece.barycentric.iter().zip(&piece.corners) {
                let at = corners[0] * b.x + corners[1] * b.y + corners[2] * b.z;
                assert!(at.distance(*c) <= 1e-12 * scale, "{at} {c}");
                assert!((b.x + b.y + b.z - 1.0).abs() <= 1e-12, "{b}");
            }
        }
        // Areas agree up to the rounding of the cross products (1e-12 of the coordinates'
        // magnitude times the longest edge, per piece): a sliver's area is that small itself.
        let area: f64 = pieces.iter().map(|p| twice_area(&p.corners)).sum();
        let whole = twice_area(&corners);
        let (_, longest) = longest_edge(&corners);
        let rounding = 1e-12 * scale * longest * pieces.len() as f64;
        assert!(
            (area - whole).abs() <= 1e-9 * whole + rounding,
            "{area} against {whole}"
        );
        let barycentric: f64 = pieces.iter().map(|p| twice_area(&p.barycentric)).sum();
        let unit = twice_area(&[DVec3::X, DVec3::Y, DVec3::Z]);
        assert!((barycentric - unit).abs() <= 1e-9 * unit, "{barycentric}");
        pieces
    }

    /// A long triangle wider than `min_width` (60 mm by 1 mm) is cut until no piece is longer
    /// than [`MAX_ASPECT`] times its width, as without the floor.
    #[test]
    fn a_long_triangle_is_cut_to_its_width() {
        let corners = [
            DVec3::ZERO,
            DVec3::new(60.0, 0.0, 0.0),
            DVec3::new(59.0, 1.0, 0.0),
        ];
        let pieces = tiled_pieces(corners, 0.05);
        assert!(pieces.len() >= 15, "{}", pieces.len());
        for piece in &pieces {
            let (_, longest) = longest_edge(&piece.corners);
            assert!(longest <= MAX_ASPECT * 1.0, "{longest}");
        }
    }

    /// A sliver 1e-10 mm wide and 1 mm long (as at the pole of a sphere patch) is cut into
    /// pieces no longer than [`MAX_ASPECT`] times `min_width`, and no shorter than half that (a
    /// bisected piece keeps half its parent's longest edge): a handful, where without the floor
    /// it is cut into 2^[`MAX_BISECTIONS`] pieces, all still slivers.
    #[test]
    fn a_sliver_is_cut_to_the_width_floor_only() {
        let corners = [
            DVec3::new(1.0, 2.0, 3.0),
            DVec3::new(2.0, 2.0, 3.0),
            DVec3::new(1.999, 2.0, 3.0 + 1e-10),
        ];
        let min_width = 0.05;
        let limit = MAX_ASPECT * min_width;
        let pieces = tiled_pieces(corners, min_width);
        for piece in &pieces {
            let (_, longest) = longest_edge(&piece.corners);
            assert!(longest <= limit && longest > 0.5 * limit, "{longest}");
        }
        assert!(pieces.len() <= 64, "{}", pieces.len());
        let unfloored = tiled_pieces(corners, 0.0);
        assert_eq!(unfloored.len(), 1 << MAX_BISECTIONS);
    }

    /// A triangle with no area (all corners equal, or collinear) stays whole whatever the floor.
    #[test]
    fn a_degenerate_triangle_stays_whole() {
        let p = DVec3::new(1.0, -2.0, 0.5);
        for min_width in [0.0, 0.05] {
            let mut pieces = Vec::new();
            split_triangle(0, [p, p, p], min_width, &mut pieces);
            assert_eq!(pieces.len(), 1);
        }
    }
}
