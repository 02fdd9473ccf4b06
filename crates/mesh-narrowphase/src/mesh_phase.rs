//! The Stage 2 boundary: the [`MeshPhase`] trait and the types it takes and returns.

use geom_param::{ComponentId, DPose3, FeatureLocation, ObjectModel, Seed};
use glam::DVec3;

/// The distance band of the query (mm): contact when `delta1 <= d <= delta2`; `margin` is the
/// broad phase's margin, which must cover the band (`>= delta2`).
///
/// Paper section II: two objects are in contact when their minimum distance d lies in
/// [δ1, δ2], in penetration below δ1 and separated above δ2.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContactBand {
    /// The margin Stage 1 inflated its volumes by (mm), `>= delta2`. Stage 2 only checks that it
    /// covers the band (a pair farther apart than the margin was never handed over, so a
    /// `delta2` beyond it would be a band Stage 1 cannot honour); the proxy offset comes from
    /// `delta2` and the chordal errors, not from the margin (see [`MeshPhase`]).
    pub margin: f64,
    /// Lower end of the contact band (mm); may be negative.
    pub delta1: f64,
    /// Upper end of the contact band (mm), `>= delta1`.
    pub delta2: f64,
}

impl ContactBand {
    /// Checks that the band is usable: all values finite, `delta1 <= delta2 <= margin` and
    /// `margin >= 0`.
    ///
    /// # Errors
    /// [`MeshInputError::BadBand`] otherwise.
    pub fn validate(&self) -> Result<(), MeshInputError> {
        let ok = self.margin.is_finite()
            && self.delta1.is_finite()
            && self.delta2.is_finite()
            && self.delta1 <= self.delta2
            && self.delta2 <= self.margin
            && self.margin >= 0.0;
        if ok {
            Ok(())
        } else {
            Err(MeshInputError::BadBand { band: *self })
        }
    }
}

/// One surface component of a prepared object, as handed to [`MeshPhase::query`].
#[derive(Clone, Copy, Debug)]
pub struct ComponentRef<'a, P> {
    /// The object model.
    pub object: &'a ObjectModel,
    /// What [`MeshPhase::prepare`] returned for that object.
    pub prepared: &'a P,
    /// The component of `object`.
    pub component: ComponentId,
}

/// Stage 2 of the paper (mesh phase): for one pair of surface components that Stage 1 found
/// close, decide from their meshes whether they are separated, penetrating, or in contact, and in
/// the last case hand Stage 3 one seed per contact.
///
/// # Frames and units
/// Millimetres throughout. `pose_ab` is B's pose in A's frame (`pose_ab * p_b` is a point of B in
/// A's frame). [`MeshOutput::penetration_centres`] are in A's frame; each [`geom_param::SeedPoint`]
/// of a seed carries its `local_point` in its own object's frame.
///
/// # Verdicts
/// Let e_A, e_B be the components' measured chordal errors
/// ([`geom_param::ComponentMesh::chordal_error`]).
/// - [`MeshVerdict::Separated`]: the components hold no contact within `delta2`. For convex
///   pairs, the hulls are farther apart than `delta2 + e_A + e_B` (so no exact points are within
///   `delta2`). On the triangle paths see there: with the normal cones (the default), no
///   critical pair of the solids' distance lies between the two components within `delta2` and
///   no tested triangles intersect; with the proxy regions, no point of the two meshes is within
///   `delta2 + e_A + e_B` of the other.
/// - [`MeshVerdict::Penetrating`]: the two meshes intersect (exact predicates);
///   [`MeshOutput::penetrating_pairs`] lists intersecting (triangle of A, triangle of B) pairs
///   (every one with the proxy regions; those where the normal-cone traversal reached triangles
///   with the normal cones, see there) and [`MeshOutput::penetration_centres`] one witness point
///   per connected region of them. [`MeshOutput::seeds`] also gets one seed per region (the
///   centre projected onto both meshes) so that the caller can confirm the penetration on the
///   exact surfaces: a mesh of a concave surface lies up to its chordal error *outside* the
///   exact surface (its chords bridge the hollow), so intersecting meshes prove an exact
///   penetration only deeper than e_A + e_B. The seeds of the pair's contacts are added too, so
///   that they are not lost when the overlap turns out to be a shallow contact.
///   Stage 2 reports penetration only from intersecting meshes: a mesh distance in
///   (0, δ1) is passed on as seeds, and Stage 3 classifies the exact distance against δ1.
/// - [`MeshVerdict::Seeds`]: the meshes do not intersect where tested and may hold a contact;
///   [`MeshOutput::seeds`] has at least one seed. Each seed names on each side a point on the
///   mesh, and the exact feature and parameters that point corresponds to (interpolated
///   linearly from the triangle's corner parameters, which are unwrapped per triangle across the
///   periodic seam, so u may lie outside [0, 2π); a mesh vertex on a vertex of the solid, a pole
///   or apex, is that vertex).
/// - [`MeshVerdict::InvalidInput`]: the band or pose is unusable (non-finite, or
///   `margin < delta2`) or a component id is out of range; `out` is left empty.
///
/// # Convex pairs
/// Both components convex with hulls: GJK between the hulls (a support map that hill-climbs over
/// the hull's vertex adjacency, warm-started from the scratch's last answer for this pair).
/// Hulls farther apart than `delta2 + e_A + e_B`: separated. Hulls apart by less: one seed from
/// the closest points p1, p2. GJK stops at about 4e-8 relative; Stage 3 makes the answer exact.
/// A hull is not its surface: a GJK closest point may lie on a hull facet that is no part of
/// the component (a "cap", e.g. over the opening of a bowl's outer wall); such a point is mapped
/// to the mesh vertex of the nearest hull vertex of the simplex, and Stage 3 moves it. And when
/// the hulls overlap, the surfaces need not intersect (the bowl's outer hull contains its
/// cavity), so the pair falls back to the triangle path below. A pair whose GJK does not
/// converge within its iteration cap falls back to the triangle path as well.
///
/// # Triangle path: normal cones ([`crate::ConcavePath::NormalCones`], the default)
/// A simultaneous traversal of the two components' patch trees ([`crate::cones::patch_tree`]):
/// every node bounds the exact surface of its mesh pieces by a ball and a slab along its normal
/// cone's axis (the pieces grown by a bound on their distance to the surface, at most the chordal
/// error), and all its outward normals, crease normals included, by a cap and a band
/// ([`crate::cones::normal_cone`]). A node pair is dropped when its volumes are farther apart than
/// `max(delta2, 0)` (plus a rounding allowance of 1e-9 of the components' sizes), or when they do
/// not overlap and the cones rule out both kinds of critical pair of the distance (a separated
/// local minimum has opposite normals along the connecting direction, a penetration witness the
/// reverse; Johnson & Cohen). A pair whose two patches are smooth, narrow-coned and whose curvature
/// tensors make the gap between them strictly convex is *certified*: it holds one minimum at most,
/// and stops there ([`crate::cones::cone_traversal::certificate`]; two leaves, which stop there
/// anyway, take the leaf path). The rest descend to leaf pairs.
/// Apexes (points where a face has no tangent plane) are traversed as points against the other
/// tree. Then
/// 1. leaf pairs whose volumes overlap get the exact triangle-triangle test (intersecting
///    meshes, as above);
/// 2. each certified pair gives a candidate where the second-order models of its two patches
///    (an exact point and normal, the mean curvature tensor) are closest; each leaf pair that may
///    hold a critical pair, the closest points of its two mesh pieces (or of an apex and a
///    piece);
/// 3. candidates standing for the same minimum are merged (within a quarter of the certified
///    pair's smaller ball, or the leaf's ball), and each one left becomes a seed: its predicted
///    points moved to the nearest mesh points, closest first.
///
/// Minima, not collision regions, are what is searched: two minima close together get a seed each
/// (no pair holding both is certified), and the cost follows the geometry of the contacts rather
/// than the number of triangles. The scratch keeps each component pair's traversal front
/// ([`crate::cones::cone_front`]): the next query re-tests only the node pairs whose margins the
/// motion of B since then may have used up, and the others not dropped by distance. What a pair of
/// components reports is a critical pair of the solids' distance: a component pair's own closest
/// points on the boundary between components, where the solids are not at a minimum, are no seed
/// (the neighbouring component pair holds the solids' minimum).
///
/// # Triangle path: proxy regions ([`crate::ConcavePath::ProxyRegions`], the paper's)
/// 1. Every intersecting triangle pair between the two meshes, by a simultaneous traversal of
///    the components' triangle BVHs and an exact triangle-triangle test: any pair means
///    penetrating meshes (one seed per region; see the verdicts).
/// 2. Otherwise every intersecting pair between the proxy of one component (the concave one; A
///    when both or neither are) and the other's mesh. The proxy is that component's mesh offset
///    outwards by `max(delta2, 0) + e_A + e_B + 1e-9 · size` (size: the component's largest
///    coordinate), standing at least that far above each of its triangles' planes (vertices on
///    creases move further; see [`crate::proxy::proxy_mesh::ProxyMesh`]). That offset suffices: two
///    exact points within `delta2` have mesh points within `delta2 + e_A + e_B`, so the other
///    mesh, unless it intersects this one (step 1), reaches into the proxy shell and, unless it
///    lies wholly inside the shell (see the limitations), crosses the proxy. A wider offset (e.g.
///    the broad phase's margin) would only widen the overlap regions, cost triangle tests, and
///    could merge two nearby distinct minima into one region (one seed, one contact lost).
///    The colliding pairs are grouped into
///    connected regions: pieces of intersection line joined end to end (mesh adjacency is not
///    used, because one long triangle, e.g. of a cylinder's side, can reach into several
///    contacts). For each region, p_ci is the centre of the area its intersection lines bound
///    (area-weighted centroid of the loop, or the segments' centroid when the loop encloses no
///    area). p_ci is projected onto both meshes (nearest point), giving one seed per region.
///
/// Proxies are built lazily (once per component and offset) and only on this path: a convex
/// pair whose hulls are disjoint never builds or touches a proxy.
///
/// # Limitations
/// As in the paper (section IV), a component completely inside the other solid without surface
/// intersection is not reported as penetrating. Likewise a component lying entirely inside the
/// proxy shell (between a mesh and its proxy, `max(delta2, 0) + e_A + e_B` thick) without
/// crossing the proxy is not seen on the triangle path. Where a concave radius of curvature is
/// below the offset the proxy folds over itself; it is still a valid collision target. Where it
/// is concave with radius R above the offset, the proxy can stand closer to the mesh than the
/// offset by about `offset · e / R` (second order in the mesh error), so a pair whose mesh
/// distance lies within that of `delta2 + e_A + e_B` may be missed.
///
/// # Panics
/// Never on any input values; `out` is cleared first and every output is finite.
pub trait MeshPhase {
    /// Per-object preprocessing (triangle BVHs, patch trees; lazily built proxy meshes behind
    /// OnceLock, keyed by offset).
    type Prepared: Send + Sync;
    /// Caller-owned scratch and warm-start state (e.g. last GJK support vertices and traversal
    /// fronts per component pair).
    type Scratch: Default + Send;

    /// Builds the per-object data (done once per object, shared by all queries).
    fn prepare(&self, object: &ObjectModel) -> Self::Prepared;

    /// `pose_ab`: B's pose in A's frame. Clears and fills `out`; returns the verdict.
    fn query(
        &self,
        a: ComponentRef<'_, Self::Prepared>,
        b: ComponentRef<'_, Self::Prepared>,
        pose_ab: &DPose3,
        band: &ContactBand,
        scratch: &mut Self::Scratch,
        out: &mut MeshOutput,
    ) -> MeshVerdict;

    /// The point of the object's meshes (all components: its whole boundary) nearest to
    /// `local_point` (the object's own frame, mm), with a bound on how far the exact boundary's
    /// distance can differ ([`MeshBoundaryPoint::error_bound`]: the largest chordal error of
    /// the components, a Hausdorff bound). Only points within `reach` + that bound are sought
    /// (`reach` in mm, +∞ for all): where the meshes have none, the answer has `distance` =
    /// +∞, `point` = `local_point` and no component. `None` for a non-finite point or an
    /// object without triangles.
    ///
    /// Not used by [`Self::query`]: the pipeline hands it to Stage 3, which needs the whole
    /// boundary to tell a penetration witness from a critical pair measured through the
    /// material (`exact_refine::Refiner::check_witness`); a nearest-point query on the meshes
    /// Stage 2 prepared anyway is the cheapest such knowledge (a stage never depends on
    /// another, so the pipeline adapts one to the other).
    fn nearest_boundary_point(
        &self,
        object: &ObjectModel,
        prepared: &Self::Prepared,
        local_point: DVec3,
        reach: f64,
    ) -> Option<MeshBoundaryPoint>;

    /// Every face of the object whose mesh comes within `radius` (mm) of `local_point` (the
    /// object's own frame), each once, at the exact parameters of its mesh's point nearest to
    /// `local_point` ([`geom_param::ComponentMesh::locate`]): the starts from which Stage 3
    /// finds the exact boundary's distance where the meshes cannot tell (a witness's segment
    /// passing closer to a mesh than its chordal error). Empty when unknown; the default knows
    /// nothing, and Stage 3 then keeps to the meshes' answer.
    fn faces_near(
        &self,
        _object: &ObjectModel,
        _prepared: &Self::Prepared,
        _local_point: DVec3,
        _radius: f64,
    ) -> Vec<FeatureLocation> {
        Vec::new()
    }
}

/// What [`MeshPhase::nearest_boundary_point`] returns (the object's frame, mm).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeshBoundaryPoint {
    /// The nearest mesh point (the query point when none is within reach).
    pub point: DVec3,
    /// Its distance to the query point (+∞ when none is within reach).
    pub distance: f64,
    /// The component whose mesh holds it (`None` when none is within reach).
    pub component: Option<ComponentId>,
    /// Bound on |exact boundary distance − `distance`| (mm): the largest chordal error of the
    /// object's component meshes.
    pub error_bound: f64,
}

/// The outcome of one [`MeshPhase::query`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum MeshVerdict {
    /// Farther apart than the band plus the chordal errors.
    Separated,
    /// The meshes intersect; see [`MeshOutput::penetrating_pairs`].
    Penetrating,
    /// In contact range; see [`MeshOutput::seeds`].
    Seeds,
    /// The inputs cannot be used; nothing was computed.
    InvalidInput(MeshInputError),
}

/// Inputs that a query refuses.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum MeshInputError {
    /// A band value is not finite, or `delta1 <= delta2 <= margin` with `margin >= 0` fails.
    #[error(
        "unusable contact band {band:?} (needs finite delta1 <= delta2 <= margin, margin >= 0)"
    )]
    BadBand {
        /// The band given.
        band: ContactBand,
    },
    /// The pose has a non-finite or non-unit rotation or a non-finite translation.
    #[error("the pose of B in A's frame is not a finite rigid motion")]
    BadPose,
    /// A component id is not one of its object's components.
    #[error("component {component:?} is not in its object (which has {count} components)")]
    NoSuchComponent {
        /// The id given.
        component: ComponentId,
        /// How many components the object has.
        count: usize,
    },
    /// The prepared data was built for an object with another number of components.
    #[error("the prepared data does not belong to this object")]
    PreparedMismatch,
}

/// Counters for statistics of one query.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct MeshStats {
    /// Exact triangle-triangle tests run (mesh-mesh and proxy-mesh).
    pub triangle_pairs_tested: u32,
    /// Connected regions found (penetration or contact).
    pub regions: u32,
    /// Whether this query built a proxy mesh.
    pub proxy_built: bool,
    /// Support-map evaluations made by GJK (0 when GJK did not run).
    pub gjk_iterations: u32,
    /// Whether the convex pair fell back to the general path (hulls overlapping, GJK not
    /// converged, or a closest hull point off the surface).
    pub convex_fallback: bool,
    /// Patch-tree node pairs examined ([`crate::ConcavePath::NormalCones`]).
    pub node_pairs_visited: u32,
    /// Patch-tree node pairs certified to hold one minimum at most, each seeded from its
    /// models ([`crate::ConcavePath::NormalCones`]).
    pub certified_pairs: u32,
    /// Patch-tree leaf pairs left for their triangles' closest points or intersection tests,
    /// whether the traversal tested them in this query or the carried front kept them
    /// ([`crate::ConcavePath::NormalCones`]).
    pub leaf_pairs: u32,
    /// Whether this query built a patch tree (convex components build theirs on first use).
    pub patches_built: bool,
}

/// What a query produces besides its verdict. Reuse one across queries: it is cleared, not
/// reallocated.
#[derive(Clone, Debug, Default)]
pub struct MeshOutput {
    /// Seeds for Stage 3 (each SeedPoint in its own object's frame; see geom_param::Seed).
    pub seeds: Vec<Seed>,
    /// Intersecting (triangle of A, triangle of B) mesh pairs, when penetrating.
    pub penetrating_pairs: Vec<(u32, u32)>,
    /// Centre of each connected penetration region, in A's frame (witness points).
    pub penetration_centres: Vec<DVec3>,
    /// For contact regions whose centre seed is in `seeds`: the region's extent and two more
    /// seeds at the ends of its loop, for the caller to refine when the centre seed does not
    /// account for the whole region (see [`RegionProbes`]). Empty on the convex path.
    pub probes: Vec<RegionProbes>,
    /// Counters for statistics: triangle pairs tested, regions found, whether a proxy was built,
    /// GJK iterations.
    pub stats: MeshStats,
}

/// The extent of one contact region (a connected piece of proxy-mesh intersection loop) and
/// seeds at its far ends. A region holds every pair of mesh points closer than the proxy
/// offset h there; one isolated minimum of distance (at p*, with d*) makes it about an
/// ellipse centred on p*, so the region's centre seed converges near the centre. When the
/// refined contact lies far from the centre (a sizeable fraction of `radius`), the region
/// holds more than that minimum (two minima in one valley, for instance) and the end seed
/// farther from the refined contact starts the search for another one.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RegionProbes {
    /// Index in [`MeshOutput::seeds`] of the region's centre seed.
    pub centre_seed: usize,
    /// The region's centre p_c (A's frame, mm), the point the centre seed was projected from.
    pub centre: DVec3,
    /// Largest distance from `centre` to the region's loop (mm).
    pub radius: f64,
    /// Seeds at the two ends of the loop's (approximate) diameter: the loop point farthest from
    /// the centre, and the loop point farthest from that one.
    pub ends: [Seed; 2],
}

impl MeshOutput {
    /// Empties every list and zeroes the counters, keeping the allocations.
    pub fn clear(&mut self) {
        self.seeds.clear();
        self.penetrating_pairs.clear();
        self.penetration_centres.clear();
        self.probes.clear();
        self.stats = MeshStats::default();
    }
}
