//! Simultaneous traversal of two patch trees ([`crate::cones::patch_tree`]) under a relative pose:
//! node pairs farther apart than the band, or whose normal cones rule out every critical pair
//! of the distance (and that cannot intersect), are dropped; pairs certified to hold at most one
//! local minimum stop there; the rest descend to leaf pairs. Apexes are points traversed
//! against the other tree.

use crate::cones::normal_cone::{CriticalKinds, NormalBand, NormalCone};
use crate::cones::patch_tree::{PatchLeaf, PatchNode, PatchTree};
use crate::triangles::triangle_distance::separating_gap;
use geom_param::DPose3;
use glam::{DMat3, DVec3};

/// Largest half-angle (rad) of a node's normal cone for a pair to be certified: 30°. Wider
/// patches are not graphs over one plane with a margin.
pub const CERTIFY_CONE: f64 = std::f64::consts::PI / 6.0;

/// Relative allowance on the curvature bound of a certified pair: the bound must exceed zero
/// by 5 % of the curvatures' magnitudes (curvature between the sampled corners, which lie at
/// mesh resolution, differs from the samples by far less).
pub const CURVATURE_MARGIN: f64 = 0.05;

/// A node pair at which the traversal stopped without dropping it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StopPair {
    /// Node of A's tree.
    pub a: u32,
    /// Node of B's tree.
    pub b: u32,
    /// The lower bound (mm) on the distance between their volumes (0 or less: they overlap).
    pub lower: f64,
    /// The normal cones allow a critical pair here.
    pub critical: bool,
    /// The two nodes' mesh pieces may intersect: their volumes shrunk by their
    /// [`PatchNode::mesh_inset`]s overlap, and for two leaves, no separating axis of their
    /// triangles ([`separating_gap`]) sets them apart.
    pub meshes_may_meet: bool,
}

/// A node pair where a traversal stopped, kept for the next query of the same pair
/// ([`crate::cones::cone_front`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FrontEntry {
    /// Node of A's tree.
    pub a: u32,
    /// Node of B's tree.
    pub b: u32,
    /// For a pair dropped because its volumes were farther apart than the reach: by how much
    /// (mm), less the motion of B since the front's reference pose, so that the pair stays
    /// dropped for any pose that moves no point of B's component by more than this from the
    /// reference pose; for a pair dropped by its cones, the motion it survives
    /// ([`CONE_CARRY`]) less that motion; for a kept leaf or certified pair ([`KeptLeaf`]),
    /// the motion it is kept for less that motion. Negative for every other stop (a leaf pair
    /// whose cones would not hold, a cone drop too close to the limit, a pair kept for less
    /// than the motion so far), which the next query tests again.
    pub slack: f64,
    /// Dropped by its cones: when the motion uses its slack up, the pair is tested again like
    /// every pair with a negative slack (it does not count towards rebuilding the front, see
    /// [`crate::cones::cone_front`]).
    pub by_cones: bool,
    /// A leaf pair kept as a leaf pair, or a certified pair as a certified pair, without being
    /// tested again, while its slack lasts ([`KeptLeaf`]).
    pub kept: Option<KeptLeaf>,
}

/// A node where an apex's traversal ([`traverse_point`]) stopped, kept for the next query of the
/// same pair ([`crate::cones::cone_front::ApexFront`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ApexEntry {
    /// The node of the other component's tree.
    pub node: u32,
    /// For a node dropped by distance (its ball or its slab beyond the reach): by how much (mm),
    /// less the apex's motion since the front's reference point; for a kept leaf, the motion it
    /// is kept for ([`LEAF_CARRY`] of its ball radius) less that motion; negative for a node
    /// tested again next query (one dropped by its cones, a leaf kept for less than the motion
    /// so far).
    pub slack: f64,
    /// A leaf kept as one the apex reaches, untested, while its slack lasts.
    pub leaf: bool,
}

/// A leaf pair carried by the front ([`FrontEntry::kept`]) as a leaf pair, without being
/// tested again, while its slack lasts: only its distance bound and whether its meshes may
/// meet follow the motion, conservatively.
///
/// - With a possible critical pair: keeping it is always sound, as its candidate is only one
///   more candidate, which the seed selection weighs like any other (a pair that has lost its
///   critical pair gives a candidate that is no minimum of the mesh distance, or one that a
///   lower neighbour covers). Kept for a motion of [`LEAF_CARRY`] of its smaller ball radius.
/// - Without one, but with meshes that may meet (kept for their exact intersection tests, as
///   a leaf pair that a fresh test would drop has triangles apart, which those tests find):
///   kept for a motion of [`CONE_CARRY`] of its smaller ball radius when its cones rule out a
///   critical pair for any motion that long, as for a pair dropped by its cones.
/// - A certified pair ([`KeptLeaf::certified`]), kept for a motion of [`LEAF_CARRY`] of its
///   smaller ball radius while it is still certified at the query's rotation: a resting
///   pencil in a bowl has 45 of them, which every query tested again before. Those certified
///   for any turn that such a motion allows ([`Certificate::ForTurn`]) are not tested again.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct KeptLeaf {
    /// Whether the cones allowed a critical pair.
    pub critical: bool,
    /// The lower bound (mm) on the distance between the two volumes when the pair was tested,
    /// less the motion of B since the front's reference pose then: the bound at a pose that
    /// moved B by `moved` since the reference pose is at least this less `moved`.
    pub lower: f64,
    /// The sum of the two nodes' [`PatchNode::mesh_inset`]s: the meshes may meet while the
    /// bound less the insets is not positive.
    pub inset: f64,
    /// The separating gap (mm) of the two triangles ([`separating_gap`], less its rounding
    /// allowance) when the pair was tested, less the motion of B since the front's reference
    /// pose then, as for `lower`: the triangles stay apart while it less `moved` is positive.
    /// −∞ for a certified pair.
    pub gap: f64,
    /// For a certified pair ([`certificate`]) kept as one, not a leaf pair, while its slack
    /// lasts: how far its certificate reaches. One for the turn of its slack is kept as it is;
    /// one for its rotation only is tested again at the query's rotation (the certificate
    /// depends on the two nodes' relative orientation only, and keeping a pair that a fresh
    /// test would drop only adds a candidate, as for a leaf pair).
    pub certified: Option<Certificate>,
}

impl FrontEntry {
    /// The leaf pair this entry keeps, at a pose that moved B by `moved` (mm) since the front's
    /// reference pose (`None` for an entry that keeps no leaf).
    #[must_use]
    pub fn kept_leaf(&self, moved: f64) -> Option<StopPair> {
        self.kept.map(|k| {
            let lower = k.lower - moved;
            StopPair {
                a: self.a,
                b: self.b,
                lower,
                critical: k.critical,
                meshes_may_meet: lower + k.inset <= 0.0 && k.gap - moved <= 0.0,
            }
        })
    }
}

/// Fraction of the smaller ball radius of a leaf pair with a possible critical pair by which B
/// may move before the pair is tested again ([`KeptLeaf`]): the pair is kept meanwhile, so
/// this only bounds how long a pair that has lost its critical pair is carried.
pub const LEAF_CARRY: f64 = 0.1;

/// What a traversal found. Reuse one across queries.
#[derive(Clone, Debug, Default)]
pub struct TraversalOutput {
    /// Node pairs certified to hold at most one local minimum of the distance (and at most one
    /// penetration witness): each stands for one seed at most.
    pub certified: Vec<StopPair>,
    /// Leaf pairs that could be neither dropped nor certified.
    pub leaves: Vec<StopPair>,
    /// Leaves of B's tree reached by an apex of A: (apex index, leaf node).
    pub apex_a_leaves: Vec<(u32, u32)>,
    /// Leaves of A's tree reached by an apex of B: (apex index, leaf node).
    pub apex_b_leaves: Vec<(u32, u32)>,
    /// Node pairs (and apex-node pairs) examined.
    pub visited: u32,
    /// Every node pair where the pair traversal stopped (see [`FrontEntry`]).
    pub front: Vec<FrontEntry>,
    /// Every node where the last apex's traversal stopped (see [`ApexEntry`]).
    pub apex_front: Vec<ApexEntry>,
    stack: Vec<(u32, u32)>,
}

impl TraversalOutput {
    /// Empties every list, keeping the allocations.
    pub fn clear(&mut self) {
        self.certified.clear();
        self.leaves.clear();
        self.apex_a_leaves.clear();
        self.apex_b_leaves.clear();
        self.visited = 0;
        self.front.clear();
        self.apex_front.clear();
        self.stack.clear();
    }

    /// Queues a node pair for [`traverse`] (a node, paired with 0, for [`traverse_point`]).
    pub fn queue(&mut self, a: u32, b: u32) {
        self.stack.push((a, b));
    }

    /// Records leaf `node` as reached by apex `apex` (of A when `point_is_a`, the leaf B's).
    pub fn reach_apex_leaf(&mut self, apex: u32, node: u32, point_is_a: bool) {
        if point_is_a {
            self.apex_a_leaves.push((apex, node));
        } else {
            self.apex_b_leaves.push((apex, node));
        }
    }
}

/// B's pose in A's frame as a matrix and its transpose, for the node tests.
#[derive(Clone, Copy, Debug)]
pub struct PairFrame {
    /// Rotation of B's frame into A's.
    pub rotation: DMat3,
    /// Its inverse.
    pub inverse: DMat3,
    /// Translation of B's frame in A's.
    pub translation: DVec3,
}

impl PairFrame {
    /// The frame of `pose_ab` (B's pose in A's frame).
    #[must_use]
    pub fn new(pose_ab: &DPose3) -> Self {
        let rotation = DMat3::from_quat(pose_ab.rotation);
        Self {
            rotation,
            inverse: rotation.transpose(),
            translation: pose_ab.translation,
        }
    }
}

/// The largest values (mm) of `u · y` and of `-u · y` over the node's volume relative to its
/// centre (ball of radius `r` intersected with the slab `lo <= a · y <= hi`), for a unit `u`
/// with `u · a = alpha`.
///
/// Writing y = s a + t w with w ⟂ a in the plane of a and u: maximise α s + β t, β = √(1 - α²),
/// over s in [lo, hi], s² + t² <= r²; for fixed s the best t is √(r² - s²), and the concave
/// function α s + β √(r² - s²) of s peaks at s = α r (value r), so its maximum over the
/// interval is at that peak clamped into it. The same for -u with -α.
#[must_use]
pub fn support_pair(r: f64, [lo, hi]: [f64; 2], alpha: f64) -> (f64, f64) {
    let alpha = alpha.clamp(-1.0, 1.0);
    let beta = (1.0 - alpha * alpha).max(0.0).sqrt();
    let (lo, hi) = (lo.max(-r), hi.min(r));
    if lo > hi || lo.is_nan() || hi.is_nan() {
        return (r, r);
    }
    let one = |alpha: f64| {
        let s = (alpha * r).clamp(lo, hi);
        alpha * s + beta * (r * r - s * s).max(0.0).sqrt()
    };
    (one(alpha), one(-alpha))
}

/// The largest values (mm) of `u · (x - centre)` and of `-u · (x - centre)` over the node's
/// volume, for a unit `u` in the node's own frame: over a piece, its corners grown by its
/// deviation; over an inner node, the smaller of the ball-and-slab bound ([`support_pair`]) and
/// the axis-aligned box's.
#[must_use]
pub fn extents(tree: &PatchTree, node: &PatchNode, u: DVec3) -> (f64, f64) {
    if let PatchLeaf::Piece(k) = node.leaf {
        if let Some(piece) = tree.pieces.get(k as usize) {
            let c = node.centre;
            let [p, q, r] = piece.corners.map(|x| u.dot(x - c));
            return (
                p.max(q).max(r) + piece.deviation,
                (-p).max(-q).max(-r) + piece.deviation,
            );
        }
    }
    let (up, down) = support_pair(node.radius, node.slab, u.dot(node.cone.axis));
    let (offset, half) = (node.box_offset.dot(u), node.half_extents.dot(u.abs()));
    (up.min(offset + half), down.min(half - offset))
}

/// The larger of the gaps between the volumes of node `a` of `tree_a` and node `b` of `tree_b`
/// (B posed by `frame`) along A's cone axis (A's slab against B's [`extents`]) and along B's
/// (B's slab against A's): a lower bound (mm) on their distance, since projection onto a unit
/// vector does not increase distances. `d` is B's centre minus A's and `axis_b` B's axis, both
/// in A's frame.
#[must_use]
pub fn slab_lower_bound(
    (tree_a, a): (&PatchTree, &PatchNode),
    (tree_b, b): (&PatchTree, &PatchNode),
    frame: &PairFrame,
    d: DVec3,
    axis_b: DVec3,
) -> f64 {
    // Along A's axis: B's extent about t = axis_a · d.
    let axis_a = a.cone.axis;
    let t = axis_a.dot(d);
    let (b_up, b_down) = extents(tree_b, b, frame.inverse * axis_a);
    let along_a = (t - b_down - a.slab[1]).max(a.slab[0] - t - b_up);
    // Along B's axis: A's extent about t' = axis_b · (ca - cb).
    let t = -axis_b.dot(d);
    let (a_up, a_down) = extents(tree_a, a, axis_b);
    along_a.max((t - a_down - b.slab[1]).max(b.slab[0] - t - a_up))
}

/// How long a certificate ([`certificate`]) holds as B turns against A.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Certificate {
    /// At the rotation it was tested at; a carried pair is tested again at every other.
    AtRotation,
    /// At every relative rotation within the tested turn of it.
    ForTurn,
}

/// Whether the node pair holds at most one local minimum of the distance between the exact
/// surfaces (and at most one penetration witness), so that one seed stands for it; `None` when
/// that is not certain, and [`Certificate::ForTurn`] when it stays certain for any turn of B
/// against A by at most `turn` (rad) from `rotation`.
/// `rotation` turns B's frame into A's; `axis_b` is B's cone axis in A's frame.
///
/// Both nodes must be smooth (no apex, no concave crease, curvature sampled everywhere) with
/// normal cones of half-angle at most [`CERTIFY_CONE`]. Then each patch is a graph over the
/// plane Π normal to w, the bisector of A's axis and the reverse of B's, with every normal of
/// patch X tilted from w by at most τ_X = θ_X + ½ angle(axis_A, -axis_B) (below 90°: the cone
/// test keeps the misalignment below θ_A + θ_B). The gap between the patches (B's height minus
/// A's along w) has Hessian H_A + H_B, each a graph's height Hessian: its curvature tensor
/// ([`crate::cones::patch_tree::CurvatureTensor`], library sign, convex positive, both facing
/// each other) as the node stores it (restricted to the plane normal to its axis), evaluated
/// on Π (M = C|Π) and distorted by the tilt, ‖H - M‖ <= s_X ‖M‖ with s_X the [`stretch`]
/// of patch X's own tilt and cone (about c⁻⁵ - 1 for c = cos τ_X). Every sampled tensor of a
/// node lies within its spread ε of the node's mean C̄ (Frobenius norm, which bounds the
/// spectral norm of the restriction), so the smallest eigenvalue of the gap's Hessian is at
/// least λ_min((C̄_A + C̄_B)|Π) - ε_A - ε_B - s_A ‖C_A‖ - s_B ‖C_B‖ (the wider cone's
/// tilt for both would charge a pencil's narrow shaft for a bowl rim's wide cone). When that
/// exceeds [`CURVATURE_MARGIN`] of ‖C_A‖ + ‖C_B‖ (the margin covers curvature between the sampled
/// corners, which lie at mesh resolution), the gap is strictly convex over the pair: one
/// minimum at most, whatever its sign. Convex creases inside a patch only add convex kinks to
/// the gap and are allowed. This certifies crossed cylinders (each flat along one direction) as
/// well as a ball in a bowl.
///
/// After a turn of B by ω <= `turn` the same test passes when it passes here with these
/// allowances: μ changes by at most ω, so τ by at most ω/2; B's tensor in A's frame, Q C Qᵀ
/// for the turn Q, moves by at most 2 |Q - I| ‖C_B‖ <= 2ω‖C_B‖; w, the bisector of axis_A and
/// -axis_B, turns by β <= ω / (2 cos((μ + ω)/2)) (|axis_A - axis_B| >= 2 cos((μ + ω)/2) along
/// the turn), and a quadratic form restricted to a plane turned by β moves by at most
/// 2β‖M‖, M = C̄_A + C̄_B. So λ_min falls by at most 2ω‖C_B‖ + 2β(‖C_A‖ + ‖C_B‖), and the
/// stretches are taken at τ_X + ω/2. A carried certified pair ([`KeptLeaf`]) is thus not tested
/// again while B turns by less than `turn` since the test.
#[must_use]
pub fn certificate(
    a: &PatchNode,
    b: &PatchNode,
    (axis_b, rotation): (DVec3, &DMat3),
    turn: f64,
) -> Option<Certificate> {
    let narrow = CERTIFY_CONE.cos();
    if !(a.smooth && b.smooth && a.cone.cos >= narrow && b.cone.cos >= narrow) {
        return None;
    }
    let axis_a = a.cone.axis;
    // cos τ_X for τ_X = θ_X + μ/2, μ = angle(axis_A, -axis_B), without trigonometry:
    // cos(μ/2) = √((1 + cos μ)/2).
    let cos_mu = (-axis_a.dot(axis_b)).clamp(-1.0, 1.0);
    let (ch, sh) = ((0.5 * (1.0 + cos_mu)).sqrt(), (0.5 * (1.0 - cos_mu)).sqrt());
    let tilt = |cone: &NormalCone| (cone.cos * ch - cone.sin * sh, cone.sin * ch + cone.cos * sh);
    let (tilt_a, tilt_b) = (tilt(&a.cone), tilt(&b.cone));
    if !(tilt_a.0 > 0.0 && tilt_b.0 > 0.0) {
        return None;
    }
    let w = (axis_a - axis_b).try_normalize()?;
    let (e1, e2) = w.any_orthonormal_pair();
    let inverse = rotation.transpose();
    let (f1, f2) = (inverse * e1, inverse * e2);
    let (ca, cb) = (&a.curvature, &b.curvature);
    let m11 = ca.form(e1, e1) + cb.form(f1, f1);
    let m22 = ca.form(e2, e2) + cb.form(f2, f2);
    let m12 = ca.form(e1, e2) + cb.form(f1, f2);
    let half_trace = 0.5 * (m11 + m22);
    let lambda_min = half_trace - (0.25 * (m11 - m22) * (m11 - m22) + m12 * m12).sqrt();
    let (na, nb) = (
        ca.norm() + a.curvature_spread,
        cb.norm() + b.curvature_spread,
    );
    let margin = CURVATURE_MARGIN * (na + nb);
    let bound = lambda_min - a.curvature_spread - b.curvature_spread;
    let here =
        bound - stretch(tilt_a, &a.cone, (ch, sh)) * na - stretch(tilt_b, &b.cone, (ch, sh)) * nb;
    if !(here > margin && here.is_finite()) {
        return None;
    }
    // The same after a turn by `turn`: cos(τ_X + ω/2) and cos((μ + ω)/2) by the angle sums.
    let (ct, st) = ((0.5 * turn).cos(), (0.5 * turn).sin());
    let half_turned = |(c, s): (f64, f64)| (c * ct - s * st, s * ct + c * st);
    let (tilt_a_turned, tilt_b_turned) = (half_turned(tilt_a), half_turned(tilt_b));
    let half_mu_turned = half_turned((ch, sh));
    let turned = if tilt_a_turned.0 > 0.0 && tilt_b_turned.0 > 0.0 && half_mu_turned.0 > 0.0 {
        let beta = turn / (2.0 * half_mu_turned.0);
        bound
            - stretch(tilt_a_turned, &a.cone, half_mu_turned) * na
            - stretch(tilt_b_turned, &b.cone, half_mu_turned) * nb
            - 2.0 * turn * nb
            - 2.0 * beta * (na + nb)
    } else {
        f64::NEG_INFINITY
    };
    Some(if turned > margin {
        Certificate::ForTurn
    } else {
        Certificate::AtRotation
    })
}

/// The relative bound s = c⁻¹ (1 + f)² − 1 on how far a patch's height Hessian H over the
/// plane Π (normal w) lies from its stored tensor restricted to Π, M = C|Π, in norm:
/// ‖H − M‖ <= s ‖M‖ at every point of the patch ([`certificate`]). `tilt` is (cos τ, sin τ) for
/// τ the largest angle between w and the patch's normals, `cone` its normal cone (half-angle θ
/// about its axis a) and `half_mu` (cos, sin) of the angle between w and a.
///
/// At a point with normal n (angle τ_p <= τ from w, c_p = cos τ_p) the height Hessian is
/// H(ξ, ξ) = c_p⁻¹ C(Jξ, Jξ) for the lift Jξ = ξ − (n·ξ)/c_p w of ξ ∈ Π into the tangent
/// plane, while the node stores C restricted to the plane normal to a, so that
/// M(ξ, ξ) = C(Kξ, Kξ) with K = P_T P_a (projections onto the tangent plane and onto a's
/// plane). Then H = c_p⁻¹ Rᵀ M R with R = K⁻¹ J, and
/// Jξ − Kξ = (n·ξ)(n − w/c_p) + (a·ξ) P_T a, of length at most sin²τ / cos τ +
/// sin(μ/2) sin θ for a unit ξ, while K shrinks no vector by more than cos(μ/2) cos θ (each
/// projection by the cosine of the angle between its planes). So ‖R − I‖ <= f =
/// (sin²τ / cos τ + sin(μ/2) sin θ) / (cos(μ/2) cos θ), ‖RᵀMR − M‖ <= ((1 + f)² − 1)‖M‖, and
/// ‖H − M‖ <= (c_p⁻¹ (1 + f)² − 1)‖M‖. With the cone's axis along w (μ = 0) this is
/// cos⁻⁵τ − 1, which a sphere's graph attains along its tilt (a curvature κ c² in M,
/// κ c⁻³ in H).
fn stretch((c, s): (f64, f64), cone: &NormalCone, (ch, sh): (f64, f64)) -> f64 {
    let f = (s * s / c + sh * cone.sin) / (ch * cone.cos);
    (1.0 + f) * (1.0 + f) / c - 1.0
}

/// The directions from a ball (centre `from`, radius `r_from`) to another at offset `d`
/// (length `length`) with radius sum `radii`: [`NormalCone::between_balls`] without its square
/// root, which the caller has.
fn directions(d: DVec3, length: f64, radii: f64) -> NormalCone {
    if length > radii {
        let sin = radii / length;
        NormalCone {
            axis: d / length,
            cos: (1.0 - sin * sin).max(0.0).sqrt(),
            sin,
        }
    } else {
        NormalCone::ALL
    }
}

/// The separating-axis gap ([`separating_gap`]) between two leaves' triangles (B's posed by
/// `frame`) less a rounding allowance (1e-9 of the coordinates' magnitude): positive only for
/// triangles apart; `None` for a node without a piece.
fn leaf_triangles_gap(
    (tree_a, a): (&PatchTree, &PatchNode),
    (tree_b, b): (&PatchTree, &PatchNode),
    frame: &PairFrame,
) -> Option<f64> {
    let corners = |tree: &PatchTree, node: &PatchNode| match node.leaf {
        PatchLeaf::Piece(k) => tree.pieces.get(k as usize).map(|p| p.corners),
        PatchLeaf::Inner => None,
    };
    let ta = corners(tree_a, a)?;
    let tb = corners(tree_b, b)?.map(|p| frame.rotation * p + frame.translation);
    let magnitude = ta
        .iter()
        .chain(tb.iter())
        .map(|p| p.abs().max_element())
        .fold(0.0, f64::max);
    Some(separating_gap(&ta, &tb) - 1e-9 * magnitude)
}

/// The deviation bound (mm) of a leaf's piece from its exact surface (infinite for a node
/// without a piece).
fn piece_deviation(tree: &PatchTree, node: &PatchNode) -> f64 {
    match node.leaf {
        PatchLeaf::Piece(k) => tree
            .pieces
            .get(k as usize)
            .map_or(f64::INFINITY, |p| p.deviation),
        PatchLeaf::Inner => f64::INFINITY,
    }
}

/// Fraction of the smaller ball radius of a node pair dropped by its cones by which B may move
/// (every point of B's component) before the pair is tested again ([`CarriedDrop`]).
pub const CONE_CARRY: f64 = 0.01;

/// Fraction of a cone drop's margin ([`CONE_CARRY`], [`GAP_CARRY`]) tried when the pair does
/// not stay dropped for the whole margin ([`CarriedDrop::slack`]): a pair whose cones nearly
/// allow a critical pair is then carried for small motions instead of tested again every query
/// (a pencil leaning in a tube: seven such pairs, 6% of a query at rest).
pub const NEAR_CRITICAL_CARRY: f64 = 1.0 / 16.0;

/// Fraction of the gap between the meshes' volumes of a node pair dropped by its cones by which
/// B may move at most before the pair is tested again ([`CarriedDrop`]): a pair whose meshes
/// nearly meet is carried for a motion short of its gap rather than tested every query.
pub const GAP_CARRY: f64 = 0.5;

/// A node pair dropped because its normal cones allow no critical pair and its meshes cannot
/// meet, with what the test needs to decide whether the drop survives a motion of B.
struct CarriedDrop<'n> {
    a: &'n PatchNode,
    b: &'n PatchNode,
    /// B's cap in A's frame.
    cone_b: &'n NormalCone,
    /// Rotation of B's frame into A's.
    rotation: &'n DMat3,
    /// B's centre minus A's (A's frame) and its length.
    d: DVec3,
    length: f64,
    /// Largest distance of a point of B's component from B's origin (mm).
    b_reach: f64,
}

impl CarriedDrop<'_> {
    /// How far (mm) every point of B may move for the pair to stay dropped: m = [`CONE_CARRY`]
    /// of the smaller ball radius, or [`GAP_CARRY`] of `gap` where that is less (or
    /// [`NEAR_CRITICAL_CARRY`] of that m where m itself fails), when the pair
    /// still fails the tests with B's ball grown by m
    /// (which holds B's moved ball, so that the directions between the balls hold the moved
    /// ones) and B's normal cap and band widened by the largest turn that moves no point of B
    /// by more than m, α = 2 asin(m / 2R) with R B's reach (the front's motion bound counts a
    /// turn by α as 2 sin(α/2) R), and `gap` (by how much the meshes' volumes, shrunk by their
    /// insets, are apart; distances between sets shrink by at most the motion) exceeds m;
    /// -1 (test again) otherwise.
    /// `moved` is the motion (mm) of B since the front's reference pose, which the margin
    /// must exceed to be of use.
    fn slack(&self, gap: f64, moved: f64) -> f64 {
        let margin = (CONE_CARRY * self.a.radius.min(self.b.radius)).min(GAP_CARRY * gap);
        if gap > margin {
            [margin, NEAR_CRITICAL_CARRY * margin]
                .into_iter()
                .find(|&m| self.stays_uncritical(m, moved))
                .unwrap_or(-1.0)
        } else {
            -1.0
        }
    }

    /// Whether the cones still rule out both kinds of critical pair after any motion of B by at
    /// most `margin` (mm), which must exceed `moved`: the tests with B's ball grown by `margin`
    /// and B's cap and band widened by the largest turn that moves no point of B by more (see
    /// [`CarriedDrop::slack`]).
    fn stays_uncritical(&self, margin: f64, moved: f64) -> bool {
        if !(margin > moved && self.b_reach > 0.0) {
            return false;
        }
        let turn = 2.0 * (margin / (2.0 * self.b_reach)).min(1.0).asin();
        let cone_b = self.cone_b.widened(turn);
        let radii = self.a.radius + self.b.radius + margin;
        let towards_b = directions(self.d, self.length, radii);
        let mut kinds = CriticalKinds::of(&self.a.cone, &cone_b, &towards_b);
        if kinds.any() && !(self.a.band.is_all() && self.b.band.is_all()) {
            let band_b = self.b.band.rotated_by(self.rotation);
            let band_b = if band_b.is_all() {
                band_b
            } else {
                NormalBand::new(band_b.axis, band_b.lo - turn, band_b.hi + turn)
            };
            kinds = kinds.with_bands((&self.a.cone, &self.a.band), (&cone_b, &band_b), &towards_b);
        }
        !kinds.any()
    }
}

/// Traverses `tree_a` against `tree_b` (B's tree posed by `frame` in A's frame) and fills
/// `out` with the certified node pairs and the leaf pairs left, dropping every node pair
/// - whose volumes are farther apart than `reach` (mm), or
/// - whose meshes cannot intersect (their volumes shrunk by their [`PatchNode::mesh_inset`]s
///   do not overlap) and whose normal cones rule out both kinds of critical pair
///   ([`CriticalKinds`]).
///
/// A pair that may hold a critical pair and is certified ([`certificate`]) stops there; otherwise the node
/// with the larger ball is split (leaves against inner nodes: the inner node). The cheap tests
/// come first: the balls, then the cones (disjoint balls without a critical pair are dropped),
/// then the slabs.
///
/// Starts from the pairs [`TraversalOutput::queue`]d (the root pair, `(0, 0)`, for a fresh
/// traversal). Every pair where it stops goes to `out.front`, a pair dropped by distance with
/// its margin less `moved` (mm), the motion of B since the front's reference pose.
pub fn traverse(
    tree_a: &PatchTree,
    tree_b: &PatchTree,
    frame: &PairFrame,
    (reach, moved): (f64, f64),
    out: &mut TraversalOutput,
) {
    let (nodes_a, nodes_b) = (&tree_a.nodes, &tree_b.nodes);
    if nodes_a.is_empty() || nodes_b.is_empty() {
        out.stack.clear();
        return;
    }
    // The reach of B's points from its frame's origin, as the front's motion bound uses it.
    let b_reach = nodes_b[0].centre.length() + nodes_b[0].radius;
    while let Some((i, j)) = out.stack.pop() {
        let (Some(a), Some(b)) = (nodes_a.get(i as usize), nodes_b.get(j as usize)) else {
            continue;
        };
        out.visited = out.visited.saturating_add(1);
        let stopped = |slack: f64| FrontEntry {
            a: i,
            b: j,
            slack,
            by_cones: false,
            kept: None,
        };
        let cb = frame.rotation * b.centre + frame.translation;
        let d = cb - a.centre;
        let radii = a.radius + b.radius;
        let apart = reach + radii;
        let length_squared = d.length_squared();
        if length_squared > apart * apart {
            out.front
                .push(stopped(length_squared.sqrt() - apart - moved));
            continue;
        }
        let axis_b = frame.rotation * b.cone.axis;
        let cone_b = NormalCone {
            axis: axis_b,
            ..b.cone
        };
        let length = length_squared.sqrt();
        // The slabs before the cones: they cost a fraction of the cones' tests, and a pair
        // dropped by distance stays dropped for longer (its margin, not the cones').
        let lower =
            slab_lower_bound((tree_a, a), (tree_b, b), frame, d, axis_b).max(length - radii);
        if lower > reach {
            out.front.push(stopped(lower - reach - moved));
            continue;
        }
        let towards_b = directions(d, length, radii);
        let mut kinds = CriticalKinds::of(&a.cone, &cone_b, &towards_b);
        if kinds.any() && !(a.band.is_all() && b.band.is_all()) {
            // (Checked here as well: rotating B's band is not free.)
            let band_b = b.band.rotated_by(&frame.rotation);
            kinds = kinds.with_bands((&a.cone, &a.band), (&cone_b, &band_b), &towards_b);
        }
        let critical = kinds.any();
        // The meshes lie in the volumes shrunk by their insets (exact triangle tests are only
        // needed where those overlap).
        let inset = a.mesh_inset + b.mesh_inset;
        let dropped_by_cones = |gap: f64| {
            let carry = CarriedDrop {
                a,
                b,
                cone_b: &cone_b,
                rotation: &frame.rotation,
                d,
                length,
                b_reach,
            };
            FrontEntry {
                by_cones: true,
                ..stopped(carry.slack(gap, moved) - moved)
            }
        };
        // Disjoint balls and no critical pair: nothing to find here.
        if !critical && length + inset > radii {
            out.front.push(dropped_by_cones(length + inset - radii));
            continue;
        }
        let meshes_may_meet = lower + inset <= 0.0;
        if !critical && !meshes_may_meet {
            out.front.push(dropped_by_cones(lower + inset));
            continue;
        }
        let stop = StopPair {
            a: i,
            b: j,
            lower,
            critical,
            meshes_may_meet,
        };
        // The front's entry for a pair kept (a leaf pair, or a certified one) for a motion of
        // `carry` since the reference pose, with its triangles' separating gap ([`KeptLeaf`]);
        // tested again next query when the motion so far has used that up.
        let kept_for = |carry: f64, gap: f64, certified: Option<Certificate>| {
            if carry > moved {
                FrontEntry {
                    kept: Some(KeptLeaf {
                        critical,
                        lower: lower - moved,
                        inset,
                        gap,
                        certified,
                    }),
                    ..stopped(carry - moved)
                }
            } else {
                stopped(-1.0)
            }
        };
        // A certified pair is carried for a motion of `carry`, which turns B by less than
        // `turn`: the front's motion bound counts a turn by ω as 2 sin(ω/2) b_reach, and
        // 2 asin(x/2) <= x π/3 for x <= 1 (a convex function below its chord).
        let carry = LEAF_CARRY * a.radius.min(b.radius);
        let ratio = carry / b_reach;
        let turn = if ratio <= 1.0 {
            ratio * std::f64::consts::FRAC_PI_3
        } else {
            std::f64::consts::PI
        };
        // Two leaves are not certified: they stop here either way, and a leaf pair's
        // candidate (the pieces' closest points, skipped when a candidate already lies in both
        // its balls) costs less than a certified pair's model, and merges with its neighbours
        // by their balls rather than by a quarter of them (a pencil across a bowl's rim at
        // chordal tolerance 0.2 mm: eight certified leaf pairs made a third seed for two
        // minima, and 1.44 times the Stage 2 instructions of the leaf path).
        let certified = if critical && !(a.is_leaf() && b.is_leaf()) {
            certificate(a, b, (axis_b, &frame.rotation), turn)
        } else {
            None
        };
        if certified.is_some() {
            out.certified.push(stop);
            out.front
                .push(kept_for(carry, f64::NEG_INFINITY, certified));
            continue;
        }
        match (a.is_leaf(), b.is_leaf()) {
            (true, true) => {
                // The triangles' separating gap: without a critical pair the leaves matter only
                // if their triangles intersect, so that triangles apart are dropped; with one,
                // the pair is dropped when the gap less the pieces' deviations from their exact
                // patches exceeds the reach. Measured where the volumes overlap too: a piece's
                // ball spans its triangle, far wider than the gaps of a conformal contact (a
                // pencil in a tube: three in four such leaf pairs had triangles beyond the
                // reach), and triangles apart need no exact intersection test.
                let gap = leaf_triangles_gap((tree_a, a), (tree_b, b), frame);
                let meshes_may_meet = meshes_may_meet && gap.is_none_or(|g| g <= 0.0);
                let stop = StopPair {
                    meshes_may_meet,
                    ..stop
                };
                if critical {
                    // The exact patches lie within their pieces' deviations of the triangles.
                    let deviations = piece_deviation(tree_a, a) + piece_deviation(tree_b, b);
                    let lower = gap.map_or(f64::NEG_INFINITY, |g| g - deviations);
                    if lower > reach {
                        out.front.push(stopped(lower - reach - moved));
                        continue;
                    }
                } else if let Some(gap) = gap.filter(|&g| g > 0.0) {
                    out.front.push(dropped_by_cones(gap));
                    continue;
                }
                out.leaves.push(stop);
                let smaller = a.radius.min(b.radius);
                let carry = if critical {
                    LEAF_CARRY * smaller
                } else {
                    let carry = CONE_CARRY * smaller;
                    let drop = CarriedDrop {
                        a,
                        b,
                        cone_b: &cone_b,
                        rotation: &frame.rotation,
                        d,
                        length,
                        b_reach,
                    };
                    if drop.stays_uncritical(carry, moved) {
                        carry
                    } else {
                        0.0
                    }
                };
                out.front.push(kept_for(
                    carry,
                    gap.unwrap_or(f64::NEG_INFINITY) - moved,
                    None,
                ));
            }
            (true, false) => {
                out.stack.push((i, j + 1));
                out.stack.push((i, b.right));
            }
            (false, true) => {
                out.stack.push((i + 1, j));
                out.stack.push((a.right, j));
            }
            (false, false) => {
                if a.radius >= b.radius {
                    out.stack.push((i + 1, j));
                    out.stack.push((a.right, j));
                } else {
                    out.stack.push((i, j + 1));
                    out.stack.push((i, b.right));
                }
            }
        }
    }
}

/// Traverses `tree` (in its own frame) against a point `point` with normal cone `cone` (both in
/// the tree's frame), the apex `apex` of the other component, and records as reached
/// ([`TraversalOutput::reach_apex_leaf`]: the point is A's, the tree B's, when `point_is_a`)
/// every leaf within `reach` (mm) whose cone allows a critical pair with the point (the cone
/// test is not symmetric).
///
/// Starts from the nodes [`TraversalOutput::queue`]d (the root, for a fresh traversal; see
/// [`crate::cones::cone_front::ApexFront`]). Every node where it stops goes to
/// `out.apex_front`, a node dropped by distance with its margin less `moved` (mm), the apex's
/// motion since the front's reference point.
pub fn traverse_point(
    tree: &PatchTree,
    (apex, point, cone): (u32, DVec3, &NormalCone),
    point_is_a: bool,
    (reach, moved): (f64, f64),
    out: &mut TraversalOutput,
) {
    let stopped = |node: u32, slack: f64| ApexEntry {
        node,
        slack,
        leaf: false,
    };
    while let Some((i, _)) = out.stack.pop() {
        let Some(n) = tree.nodes.get(i as usize) else {
            continue;
        };
        out.visited = out.visited.saturating_add(1);
        let d = n.centre - point;
        let apart = reach + n.radius;
        let length_squared = d.length_squared();
        if length_squared > apart * apart {
            out.apex_front
                .push(stopped(i, length_squared.sqrt() - apart - moved));
            continue;
        }
        let length = length_squared.sqrt();
        let t = n.cone.axis.dot(-d);
        let beyond = (n.slab[0] - t).max(t - n.slab[1]);
        if beyond > reach {
            out.apex_front.push(stopped(i, beyond - reach - moved));
            continue;
        }
        let from_point = directions(d, length, n.radius);
        let all = NormalBand::ALL;
        let kinds = if point_is_a {
            CriticalKinds::of(cone, &n.cone, &from_point).with_bands(
                (cone, &all),
                (&n.cone, &n.band),
                &from_point,
            )
        } else {
            let towards_point = from_point.negated();
            CriticalKinds::of(&n.cone, cone, &towards_point).with_bands(
                (&n.cone, &n.band),
                (cone, &all),
                &towards_point,
            )
        };
        if !kinds.any() {
            out.apex_front.push(stopped(i, -1.0));
            continue;
        }
        if n.is_leaf() {
            out.reach_apex_leaf(apex, i, point_is_a);
            out.apex_front.push(ApexEntry {
                leaf: true,
                ..stopped(i, LEAF_CARRY * n.radius - moved)
            });
        } else {
            out.stack.push((i + 1, 0));
            out.stack.push((n.right, 0));
        }
    }
}
