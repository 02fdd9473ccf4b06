//! The normal-cone triangle path ([`crate::ConcavePath::NormalCones`]): one traversal of the two
//! components' patch trees (and of each apex against the other tree), then one seed per
//! minimum: certified pairs seeded from second-order models of the exact faces, the leaf pairs
//! left from their closest points, and exact triangle tests where the meshes may intersect.

use crate::cones::cone_front::{ApexFront, ConeFront};
use crate::cones::cone_traversal::{PairFrame, TraversalOutput, traverse, traverse_point};
use crate::cones::normal_cone::{CriticalKinds, NormalCone};
use crate::cones::patch_tree::{self, Apex, PIECE_SIDES, PatchLeaf, PatchNode, PatchTree, Piece};
use crate::mesh_phase::{MeshOutput, MeshVerdict};
use crate::pair_key::PairKey;
use crate::query_side::Side;
use crate::triangles::mesh_intersections::{TriangleBuffers, none_apart};
use crate::triangles::triangle_distance::{
    TrianglePoint, boxes_gap, closest_between_segment_and_triangle, closest_between_triangles,
    closest_on_triangle, normals_gap,
};
use geom_param::{DPose3, EdgeId, FeatureLocation, Seed, SeedPoint};
use glam::{DMat2, DVec2, DVec3};
use std::collections::HashMap;

/// Buffers of the normal-cone path, kept across queries.
#[derive(Clone, Debug, Default)]
pub struct ConeScratch {
    traversal: TraversalOutput,
    found: Vec<Found>,
    /// The critical leaf pairs' lower bounds (the upper half of [`ordered_bits`]) and indices,
    /// nearest first.
    nearest_first: Vec<u64>,
    /// The candidates' ranks ([`Found::rank`], its distance as [`ordered_bits`]) and indices
    /// into `found`, as sorting keys.
    ranked: Vec<u128>,
    /// The points of the candidates so far that cover the pairs after them (certified pairs'
    /// predictions inside their balls, leaf pairs' closest points), A's in A's frame and B's in
    /// B's, for the covering test (a compact copy of theirs in `found`).
    covering_points: Vec<(DVec3, DVec3)>,
    /// Indices into `found`, closest first (a candidate is too large to sort by moving it).
    order: Vec<usize>,
    kept: Vec<usize>,
    made: Vec<(f64, Seed)>,
    /// A dropped candidate's ridge candidates ([`ridge_seeds`]), before they are judged.
    on_ridges: Vec<Found>,
    /// The triangles holding a candidate's points ([`mesh_local_minimum`]), A's and B's.
    rings: (Vec<u32>, Vec<u32>),
    /// Per candidate of `found`, its [`seed_distance`] once asked for (NaN before; ∞ for none).
    seed_distances: Vec<f64>,
    /// The last traversal's front per component pair.
    pub(crate) fronts: HashMap<PairKey, ConeFront>,
}

/// Where a seed candidate comes from.
#[derive(Clone, Copy, Debug)]
enum Source {
    /// A certified pair (A's and B's nodes); its seed is made once kept ([`node_seed`]).
    Certified([u32; 2]),
    /// A leaf pair or an apex: the seed is already made.
    Made(Seed),
}

/// A seed candidate before duplicates are merged.
#[derive(Clone, Copy, Debug)]
struct Found {
    /// Order of preference (smaller first): certified pairs by their models' gap, then leaf
    /// pairs by mesh distance, then certified pairs whose models' minimum lies outside them.
    rank: (u8, f64),
    /// A's point (A's frame).
    point_a: DVec3,
    /// B's point (A's frame).
    point_b: DVec3,
    /// Two candidates whose points are both within the smaller of their radii (mm) stand for
    /// the same minimum.
    radius: f64,
    /// For a certified pair whose models' minimum lies outside its balls: the smaller ball
    /// radius (mm). Such a pair's own minimum, if it has one, lies in it; when an earlier
    /// candidate's points lie within this radius of the candidate's, they are taken for the
    /// same minimum (the models of a pair holding a minimum predict it within its ball up to
    /// their third-order error, which the factor of four between this radius and
    /// [`MODEL_MERGE`]'s covers).
    outside: Option<f64>,
    /// For a leaf pair's candidate, where its points lie on the meshes and the error bound of
    /// its mesh distance ([`LeafPair`]); `None` for other candidates.
    leaf: Option<LeafPair>,
    source: Source,
}

/// Where a leaf pair's candidate lies on the two meshes.
#[derive(Clone, Copy, Debug)]
struct LeafPair {
    /// The error bound (mm) of the mesh distance as the distance of the exact surfaces there:
    /// the sum of the two pieces' deviation bounds. Such a candidate is superseded by a
    /// certainly lower one of a neighbouring leaf pair ([`superseded`]).
    error: f64,
    /// A's and B's leaf nodes.
    nodes: [u32; 2],
    /// A's and B's mesh triangles.
    triangles: [u32; 2],
    /// The points' barycentric coordinates in those triangles.
    barycentric: [[f64; 3]; 2],
    /// The convex edges the points lie on ([`ridges`]).
    ridges: [Option<EdgeId>; 2],
}

/// Fraction of a certified pair's smaller ball radius within which two model seeds are the same
/// minimum. A certified pair holds at most one minimum and the models of neighbouring pairs
/// predict it to second order, far closer than this; two distinct minima closer than this
/// would make the gap non-convex within one ball, which no certified pair allows.
const MODEL_MERGE: f64 = 0.25;

/// The normal-cone triangle path: see [`crate::ConcavePath::NormalCones`] and the contract on
/// [`crate::MeshPhase`].
pub(crate) fn cone_path(
    (side_a, side_b): (&Side<'_>, &Side<'_>),
    key: PairKey,
    pose_ab: &DPose3,
    delta2: f64,
    errors: f64,
    (path, scratch): (&mut ConeScratch, &mut TriangleBuffers),
    out: &mut MeshOutput,
) -> MeshVerdict {
    let (tree_a, built_a) = side_a.patches();
    let (tree_b, built_b) = side_b.patches();
    out.stats.patches_built = built_a || built_b;
    // Rounding of coordinates of magnitude `size`, far below any tolerance (see
    // `proxy_path::proxy_offset` for the same allowance).
    let allowance = 1e-9 * (side_a.size + side_b.size);
    let reach = delta2.max(0.0) + allowance;
    let frame = PairFrame::new(pose_ab);
    let traversal = &mut path.traversal;
    traversal.clear();
    let front = path.fronts.entry(key).or_default();
    let moved = front.start((tree_a, tree_b), pose_ab, reach, traversal);
    traverse(tree_a, tree_b, &frame, (reach, moved), traversal);
    front.finish(traversal);
    let inverse = pose_ab.inverse();
    // Each apex against the other tree, from its own front.
    let [fronts_a, fronts_b] = &mut front.apexes;
    traverse_apexes(
        &tree_a.apexes,
        fronts_a,
        (tree_b, &inverse),
        true,
        reach,
        traversal,
    );
    traverse_apexes(
        &tree_b.apexes,
        fronts_b,
        (tree_a, pose_ab),
        false,
        reach,
        traversal,
    );
    out.stats.node_pairs_visited = traversal.visited;
    out.stats.certified_pairs = u32::try_from(traversal.certified.len()).unwrap_or(u32::MAX);
    out.stats.leaf_pairs = u32::try_from(traversal.leaves.len()).unwrap_or(u32::MAX);

    // 1. Triangles whose volumes overlap: exact intersection tests (penetrating meshes).
    scratch.candidates.clear();
    scratch.candidates.extend(
        traversal
            .leaves
            .iter()
            .filter(|l| l.meshes_may_meet)
            .filter_map(|l| triangle_pair(tree_a, tree_b, l.a, l.b)),
    );
    scratch.candidates.sort_unstable();
    scratch.candidates.dedup();
    // The leaf pairs' triangles have passed the traversal's separating-axis test (their
    // `meshes_may_meet`; for a pair the front carries, at the pose it was tested at, less the
    // motion since) and mostly meet: a floating-point filter in front of the exact test only
    // repeats its first step (the planes' filter was 4% of a pencil through a bowl's wall, and
    // spared no exact test there).
    let meshes_intersect = scratch.report_intersecting((side_a, side_b), pose_ab, none_apart, out);

    // 2. Seed candidates.
    let ConeScratch {
        traversal,
        found,
        nearest_first,
        covering_points,
        ranked,
        order,
        kept,
        made,
        on_ridges,
        rings: (rings_a, rings_b),
        seed_distances,
        ..
    } = path;
    found.clear();
    covering_points.clear();
    // A certified pair holds at most one minimum (its gap is strictly convex): one whose two
    // balls hold the points of an earlier prediction that lies inside that pair's own balls
    // (an unclamped one, accurate to third order) stands for the same minimum and is skipped
    // before its models are evaluated. A ball is larger than its patch, so this is bolder than
    // the quarter radius that merges two certified candidates (`MODEL_MERGE`); the soaks
    // check it (ROBUSTNESS, session 35). A pencil resting in a bowl at chordal tolerance
    // 0.01 mm: 13 of 31 certified pairs predicted, 47.6k instructions of Stage 2 against 57.1k.
    for stop in &traversal.certified {
        let (na, nb) = (
            &tree_a.nodes[stop.a as usize],
            &tree_b.nodes[stop.b as usize],
        );
        let (ra, rb) = (na.radius * na.radius, nb.radius * nb.radius);
        let covered = covering_points.iter().rev().any(|(pa, pb)| {
            pa.distance_squared(na.centre) <= ra && pb.distance_squared(nb.centre) <= rb
        });
        if covered {
            continue;
        }
        if let Some(f) = predict((na, nb), [stop.a, stop.b], &frame) {
            if f.outside.is_none() {
                covering_points.push((f.point_a, inverse * f.point_b));
            }
            found.push(f);
        }
    }
    let mesh_reach = delta2.max(0.0) + errors + allowance;
    // A leaf pair whose two balls already hold a covering candidate's points is skipped before
    // its closest points are computed: a leaf pair's candidate there would be merged with its
    // own below (its radius is at least its balls'); a certified pair's unclamped prediction
    // there is a minimum found to third order, which its closest points would only find again
    // (the bolder rule, as for certified pairs above). The test runs on compact copies of
    // those points (`covering_points`, B's in B's frame so that the pair's B ball needs no
    // move): over the candidates in `found` it was 6% of a pencil leaning in a tube (171 leaf
    // pairs, 16 candidates).
    // Nearest pairs first: their candidates, made first, cover the pairs around them. Sorted as
    // 64-bit integer keys, the lower bound's order to 20 bits of mantissa (a relative 1e-6;
    // nearer ties only keep the traversal's order) above the pair's index: sorting the pairs
    // themselves by `total_cmp` was a tenth of a pencil-on-tube query, and 128-bit keys with the
    // whole bound a twentieth.
    nearest_first.clear();
    nearest_first.extend(
        (traversal.leaves.iter().enumerate())
            .filter(|(_, l)| l.critical)
            .map(|(k, l)| {
                // Each leaf pair holds two nodes' worth of memory: far fewer than 2^32 fit.
                let index = u32::try_from(k).expect("fewer than 2^32 leaf pairs");
                (ordered_bits(l.lower) >> 32 << 32) | u64::from(index)
            }),
    );
    nearest_first.sort_unstable();
    for leaf in nearest_first
        .iter()
        .map(|&key| &traversal.leaves[key as u32 as usize])
    {
        if leaf.meshes_may_meet
            && triangle_pair(tree_a, tree_b, leaf.a, leaf.b)
                .is_some_and(|pair| out.penetrating_pairs.contains(&pair))
        {
            continue;
        }
        let (na, nb) = (
            &tree_a.nodes[leaf.a as usize],
            &tree_b.nodes[leaf.b as usize],
        );
        let (ra, rb) = (na.radius * na.radius, nb.radius * nb.radius);
        // The latest candidates first: made nearest first, they lie nearest the pairs to come.
        let covered = covering_points.iter().rev().any(|(pa, pb)| {
            pa.distance_squared(na.centre) <= ra && pb.distance_squared(nb.centre) <= rb
        });
        if covered {
            continue;
        }
        if let Some(f) = leaf_seed(
            (side_a, tree_a, leaf.a),
            (side_b, tree_b, leaf.b),
            &frame,
            mesh_reach,
        ) {
            covering_points.push((f.point_a, inverse * f.point_b));
            found.push(f);
        }
    }
    let mut keep = |f: Option<Found>| {
        if let Some(f) = f.filter(|f| f.rank.1 <= mesh_reach) {
            found.push(f);
        }
    };
    for &(k, node) in &traversal.apex_a_leaves {
        keep(apex_seed(
            (side_a, tree_a, k),
            (side_b, tree_b, node),
            &frame,
            true,
        ));
    }
    for &(k, node) in &traversal.apex_b_leaves {
        keep(apex_seed(
            (side_b, tree_b, k),
            (side_a, tree_a, node),
            &frame,
            false,
        ));
    }
    for (ka, apex_a) in tree_a.apexes.iter().enumerate() {
        for (kb, apex_b) in tree_b.apexes.iter().enumerate() {
            keep(apex_pair(
                (side_a, ka, apex_a),
                (side_b, kb, apex_b),
                pose_ab,
                reach,
            ));
        }
    }

    // 3. One seed per minimum, closest first.
    // Sorted as integer keys (rank, then index), as the leaf pairs above: comparing the
    // candidates through their indices was a fifth of a ball-in-a-cavity query (179 certified
    // pairs).
    ranked.clear();
    ranked.extend(found.iter().enumerate().map(|(k, f)| {
        (u128::from(f.rank.0) << 96) | (u128::from(ordered_bits(f.rank.1)) << 32) | k as u128
    }));
    ranked.sort_unstable();
    order.clear();
    order.extend(ranked.iter().map(|&key| key as u32 as usize));
    kept.clear();
    made.clear();
    seed_distances.clear();
    let mut rings = (rings_a, rings_b);
    // Keeps `found[k]` as a seed (a certified pair's is made now).
    let take = |k: usize, found: &[Found], kept: &mut Vec<usize>, made: &mut Vec<_>| {
        let f = &found[k];
        let seed = match f.source {
            Source::Made(seed) => Some(seed),
            Source::Certified([na, nb]) => {
                // The other certified pairs' nodes: where a prediction falls beyond its own
                // node, it mostly falls on theirs.
                let (certified_a, certified_b) = (
                    traversal.certified.iter().map(|c| c.a),
                    traversal.certified.iter().map(|c| c.b),
                );
                node_seed((side_a, tree_a, na), certified_a, f.point_a, f.radius)
                    .zip(node_seed(
                        (side_b, tree_b, nb),
                        certified_b,
                        inverse * f.point_b,
                        f.radius,
                    ))
                    .map(|(a, b)| Seed { a, b })
            }
        };
        if let Some(seed) = seed {
            kept.push(k);
            made.push((f.rank.1, seed));
        }
    };
    for (position, &i) in order.iter().enumerate() {
        let context = (&found[..], &kept[..], &order[..position]);
        let judged = judge(
            &found[i],
            context,
            (side_a, side_b),
            pose_ab,
            allowance,
            (&mut rings, seed_distances),
        );
        match judged {
            Judged::Kept => take(i, found, kept, made),
            Judged::Superseded => {}
            Judged::DuplicateOf(k) => {
                // The leaf pair's own candidates on a ridge of its pieces that neither it nor
                // the kept candidate lies on ([`ridge_seeds`]), judged in turn. One is no
                // nearer than the pair's own candidate (its side is part of the piece): where
                // the kept one is certainly lower than that, none would be held apart from it.
                let (f, g) = (&found[i], &found[k]);
                let Some(leaf) = f.leaf.filter(|_| !certainly_lower(g, f)) else {
                    continue;
                };
                let taken = [ridges(f), ridges(g)];
                on_ridges.clear();
                ridge_seeds(
                    (side_a, tree_a, leaf.nodes[0]),
                    (side_b, tree_b, leaf.nodes[1]),
                    &frame,
                    |k, edge| taken.iter().any(|t| t[k] == Some(edge)),
                    |r| {
                        if r.rank.1 <= mesh_reach {
                            on_ridges.push(r);
                        }
                    },
                );
                for r in on_ridges.drain(..) {
                    let context = (&found[..], &kept[..], &order[..position]);
                    if judge(
                        &r,
                        context,
                        (side_a, side_b),
                        pose_ab,
                        allowance,
                        (&mut rings, seed_distances),
                    ) == Judged::Kept
                    {
                        found.push(r);
                        take(found.len() - 1, found, kept, made);
                    }
                }
            }
        }
    }
    made.sort_unstable_by(|x, y| x.0.total_cmp(&y.0));
    out.seeds.extend(made.iter().map(|m| m.1));
    out.stats.regions += u32::try_from(made.len()).unwrap_or(u32::MAX);
    if meshes_intersect {
        MeshVerdict::Penetrating
    } else if out.seeds.is_empty() {
        MeshVerdict::Separated
    } else {
        MeshVerdict::Seeds
    }
}

/// Traverses `tree` by each of the other component's `apexes` (of A when `point_is_a`), moved
/// into the tree's frame by `to_tree`, each from its own front (`fronts`, one per apex, made
/// on first use), within `reach` (mm).
fn traverse_apexes(
    apexes: &[Apex],
    fronts: &mut Vec<ApexFront>,
    (tree, to_tree): (&PatchTree, &DPose3),
    point_is_a: bool,
    reach: f64,
    traversal: &mut TraversalOutput,
) {
    fronts.resize_with(apexes.len(), ApexFront::default);
    for ((k, apex), front) in apexes.iter().enumerate().zip(fronts) {
        let k = u32::try_from(k).expect("fewer than 2^32 apexes");
        let cone = apex.cone.rotated(to_tree.rotation);
        let point = *to_tree * apex.point;
        let moved = front.start(tree, (k, point, point_is_a), reach, traversal);
        traverse_point(
            tree,
            (k, point, &cone),
            point_is_a,
            (reach, moved),
            traversal,
        );
        front.finish(traversal);
    }
}

/// The bits of `x` as an unsigned integer in the order of [`f64::total_cmp`].
fn ordered_bits(x: f64) -> u64 {
    let bits = x.to_bits();
    if bits >> 63 == 1 {
        !bits
    } else {
        bits | 1 << 63
    }
}

/// What the selection does with a candidate.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Judged {
    /// It is a minimum of its own: it becomes a seed.
    Kept,
    /// It stands for the same minimum as kept candidate `found[k]` (the radius rule).
    DuplicateOf(usize),
    /// A certainly lower earlier candidate nearby supersedes it ([`superseded`]).
    Superseded,
}

/// The selection's verdict on candidate `f` given the candidates `found`, the indices of those
/// `kept` so far and of those `earlier` in rank order: a duplicate of a kept candidate whose
/// points lie within the smaller radius of its own (or within its `outside` radius), unless a
/// ridge holds it apart or it is a mesh local minimum below a certainly lower one; superseded;
/// or kept. `rings` are the buffers of [`mesh_local_minimum`], `seed_distances` the candidates'
/// [`seed_distance`]s as far as asked for.
fn judge(
    f: &Found,
    (found, kept, earlier): (&[Found], &[usize], &[usize]),
    (side_a, side_b): (&Side<'_>, &Side<'_>),
    pose_ab: &DPose3,
    allowance: f64,
    (rings, seed_distances): (&mut (&mut Vec<u32>, &mut Vec<u32>), &mut Vec<f64>),
) -> Judged {
    let near = |k: &Found| {
        let r = k.radius.min(f.radius);
        let near = k.point_a.distance(f.point_a) <= r && k.point_b.distance(f.point_b) <= r;
        let inside = f.outside.is_some_and(|r| {
            k.point_a.distance(f.point_a) <= r && k.point_b.distance(f.point_b) <= r
        });
        near || inside
    };
    // A certified pair's or an apex's candidate is only ever a duplicate of a kept one or
    // kept: the ridge, mesh-minimum and superseding rules below are a leaf pair's.
    if f.leaf.is_none() {
        return kept
            .iter()
            .copied()
            .find(|&k| near(&found[k]))
            .map_or(Judged::Kept, Judged::DuplicateOf);
    }
    // A leaf pair's candidate that a certainly lower one would drop (by the radius rule or as
    // superseded) is kept when it is a local minimum of the mesh distance.
    let mut minimum = None;
    let mut kept_apart = |g: &Found| {
        certainly_lower(g, f)
            && *minimum.get_or_insert_with(|| {
                mesh_local_minimum((side_a, side_b), pose_ab, f, allowance, (rings.0, rings.1))
            })
    };
    // A candidate on a ridge that the mesh cannot tell from a neighbour off it (neither
    // certainly lower) may be a minimum of its own: the edge's, beside the face's.
    let ridges_f = ridges(f);
    let off_its_ridge = |g: &Found| {
        let ridges_g = ridges(g);
        let apart = (0..2).any(|s| ridges_f[s].is_some() && ridges_f[s] != ridges_g[s]);
        apart && !certainly_lower(g, f)
    };
    let duplicate_of = kept.iter().copied().find(|&k| {
        let g = &found[k];
        near(g) && !off_its_ridge(g) && !kept_apart(g)
    });
    if let Some(k) = duplicate_of {
        return Judged::DuplicateOf(k);
    }
    // Lower than `f` by the meshes, or by the exact surfaces at its seed ([`seed_distance`])
    // where `f` lies on no ridge that `g` does not: a ridge has minima of its own, which the
    // ridge rule above keeps apart from a neighbour off the ridge unless the meshes alone
    // tell the two apart.
    let lower = |k: usize| {
        let g = &found[k];
        if certainly_lower(g, f) {
            return true;
        }
        let (Some(_), Some(f_leaf)) = (g.leaf, f.leaf) else {
            return false;
        };
        let ridges_g = ridges(g);
        if (0..2).any(|s| ridges_f[s].is_some() && ridges_f[s] != ridges_g[s]) {
            return false;
        }
        if seed_distances.len() <= k {
            seed_distances.resize(k + 1, f64::NAN);
        }
        if seed_distances[k].is_nan() {
            seed_distances[k] =
                seed_distance(g, (side_a, side_b), pose_ab).unwrap_or(f64::INFINITY);
        }
        seed_distances[k] + allowance < f.rank.1 - f_leaf.error
    };
    let is_minimum = || {
        *minimum.get_or_insert_with(|| {
            mesh_local_minimum((side_a, side_b), pose_ab, f, allowance, (rings.0, rings.1))
        })
    };
    if superseded(
        earlier.iter().map(|&k| (k, &found[k])),
        f,
        lower,
        is_minimum,
    ) {
        Judged::Superseded
    } else {
        Judged::Kept
    }
}

/// Whether the leaf pair's candidate `f` is not a local minimum of the distance between leaf
/// pairs: an earlier candidate of `earlier` (closest first, with its index) from a neighbouring
/// leaf pair (points within the sum of the two candidates' radii on both sides, so that the
/// pairs' balls meet on both sides) is certainly closer (`lower`), while `f` is no local
/// minimum of the mesh distance (`is_minimum`). Along a valley of the distance that falls
/// faster than the meshes' error, every candidate but the lowest has such a neighbour, so the
/// valley gets one seed; two minima keep a seed each, as the distance rises between them (up
/// to the leaves' resolution, as for [`Found::radius`]).
///
/// Certainly closer: the neighbour's mesh distance plus its error bound, or the exact distance
/// between its seed's surface points ([`seed_distance`], a distance the solids attain there),
/// lies below `f`'s mesh distance less its error bound, the least distance of the exact
/// surfaces over `f`'s pieces. Why the error bounds: two minima of the exact distance in
/// neighbouring leaf pairs whose mesh distances are ordered the other way round (a
/// paperweight's rim 1e-3 mm into a goblet's lip beside a second minimum at 3.3e-2 mm, with the
/// lip's mesh 5e-2 mm off) lost the deeper one when any lower neighbour superseded. Why the
/// exact distance: in a conformal contact (a pencil tilted in a tube, 0.05 mm of clearance on
/// radii of 5 mm) the distance along the contact line varies by less than the meshes' error,
/// and with mesh bounds alone each of the line's leaf pairs kept a seed of its own (seven seeds
/// for two contacts, each a Newton run).
fn superseded<'f>(
    mut earlier: impl Iterator<Item = (usize, &'f Found)>,
    f: &Found,
    mut lower: impl FnMut(usize) -> bool,
    mut is_minimum: impl FnMut() -> bool,
) -> bool {
    if f.leaf.is_none() {
        return false;
    }
    earlier.any(|(k, g)| {
        let r = f.radius + g.radius;
        g.point_a.distance(f.point_a) <= r
            && g.point_b.distance(f.point_b) <= r
            && lower(k)
            && !is_minimum()
    })
}

/// The distance (mm) between the exact surface points of a made seed's two locations (B's
/// moved into A's frame): a distance the two solids attain near the candidate. `None` for a
/// candidate without a made seed, and where a seed point on a trimmed face lies outside its
/// trim (parameters interpolated across a triangle along a curved trim can fall a hair beyond
/// it, onto the surface's extension) or is not finite.
fn seed_distance(
    f: &Found,
    (side_a, side_b): (&Side<'_>, &Side<'_>),
    pose_ab: &DPose3,
) -> Option<f64> {
    let Source::Made(seed) = f.source else {
        return None;
    };
    let on_solid = |side: &Side<'_>, p: &SeedPoint| {
        let solid = &side.object.solid;
        if let FeatureLocation::Face { id, u, v } = p.location {
            let trim = solid.face(id).trim.as_ref();
            if trim.is_some_and(|t| !t.contains(DVec2::new(u, v), 0.0)) {
                return None;
            }
        }
        let x = solid.point_at(&p.location);
        x.is_finite().then_some(x)
    };
    let (a, b) = (on_solid(side_a, &seed.a)?, on_solid(side_b, &seed.b)?);
    Some(a.distance(*pose_ab * b))
}

/// The ridges (convex edges) that a leaf pair's candidate's mesh points lie on, A's and B's:
/// `None` for a point on a face, on a smooth or concave edge or at a vertex, and for other
/// candidates (certified pairs lie on smooth nodes; an apex is a vertex).
///
/// Why: the radius rule takes candidates within a leaf's ball for one minimum, and a leaf
/// spans the mesh's chordal error. A pencil's tip (a cone of radius 1 mm meeting the taper at
/// a ridge, meshed with 8 segments, chordal error 0.077 mm) in a goblet's bowl has three
/// minima within 1.1 mm: the apex at 0.0415 mm, the ridge at 0.0692 and the taper at 0.0661.
/// The ridge's candidate (mesh distance 0.124) was merged into one on the tip cone 0.9 mm away
/// (0.075, not certainly lower), whose Newton run went to the apex, and the ridge's minimum
/// was missed. On a ridge the distance has minima of its own (the edge's, point-curve and
/// curve-surface in the paper's list), which a face's seed beside it does not reach.
fn ridges(f: &Found) -> [Option<EdgeId>; 2] {
    f.leaf.map_or([None, None], |leaf| leaf.ridges)
}

/// [`patch_tree::ridge_at`] on `side`'s mesh and solid.
fn ridge_at(side: &Side<'_>, triangle: u32, barycentric: [f64; 3]) -> Option<EdgeId> {
    patch_tree::ridge_at(side.mesh, &side.object.solid, triangle, barycentric)
}

/// Whether leaf pairs' candidates `g` and `f` have mesh distances that put `g` lower by more
/// than both error bounds, so that the exact surfaces are certainly closer at `g` too. False
/// unless both are leaf pairs' candidates.
fn certainly_lower(g: &Found, f: &Found) -> bool {
    match (g.leaf, f.leaf) {
        (Some(g_leaf), Some(f_leaf)) => g.rank.1 + g_leaf.error < f.rank.1 - f_leaf.error,
        _ => false,
    }
}

/// Whether a leaf pair's candidate `f` is a local minimum of the distance between the two
/// meshes: no pair of triangles holding its points' features (the triangle for a point inside
/// it, both triangles of an edge, a vertex's ring: together a neighbourhood of each point on
/// its mesh) is closer than its own distance by more than `allowance` (mm, rounding). False for
/// any other candidate. `rings` are buffers.
///
/// Such a candidate is kept where a certainly lower one ([`certainly_lower`]) would drop it by
/// the radius rule or as [`superseded`]: a leaf's radius is its piece's ball, which on a flat
/// face's few large triangles spans millimetres, and two plates' top corners 1.04 mm apart (two
/// copies of a SolidWorks box of plates, edge against edge at 0.05 mm and at 0.0936 mm) were
/// taken as one minimum, the second missed. A candidate on a slope of the mesh distance has a
/// closer pair next to it and is dropped as before; candidates whose distances agree within the
/// errors (a valley flatter than the meshes' error, where the faceting makes local minima of
/// its own) merge by the radius rule as before.
fn mesh_local_minimum(
    (side_a, side_b): (&Side<'_>, &Side<'_>),
    pose_ab: &DPose3,
    f: &Found,
    allowance: f64,
    (rings_a, rings_b): (&mut Vec<u32>, &mut Vec<u32>),
) -> bool {
    let Some(leaf) = f.leaf else {
        return false;
    };
    let (ma, mb) = (side_a.mesh, side_b.mesh);
    let ([ta, tb], [ba, bb]) = (leaf.triangles, leaf.barycentric);
    let (Some(&ca), Some(&cb)) = (ma.triangles.get(ta as usize), mb.triangles.get(tb as usize))
    else {
        return false;
    };
    const ZERO: f64 = 1e-12;
    side_a.prepared.rings.holding(ta, ca, ba, ZERO, rings_a);
    side_b.prepared.rings.holding(tb, cb, bb, ZERO, rings_b);
    // A few triangles a side (one to a vertex's ring): B's are moved per pair, not stored.
    let threshold = f.rank.1 - allowance;
    rings_a.iter().all(|&t| {
        let corners_a = ma.triangle(t as usize);
        rings_b.iter().all(|&u| {
            let corners_b = mb.triangle(u as usize).map(|p| *pose_ab * p);
            normals_gap(&corners_a, &corners_b) >= threshold
                || closest_between_triangles(&corners_a, &corners_b).distance >= threshold
        })
    })
}

/// The mesh triangles of a leaf pair.
fn triangle_pair(tree_a: &PatchTree, tree_b: &PatchTree, a: u32, b: u32) -> Option<(u32, u32)> {
    match (tree_a.nodes[a as usize].leaf, tree_b.nodes[b as usize].leaf) {
        (PatchLeaf::Piece(pa), PatchLeaf::Piece(pb)) => Some((
            tree_a.pieces.get(pa as usize)?.triangle,
            tree_b.pieces.get(pb as usize)?.triangle,
        )),
        _ => None,
    }
}

/// One side of a certified pair as a height function over the plane normal to w (lateral
/// coordinates x in the basis e1, e2): h(x) ≈ h0 + g · (x - x0) + ½ (x - x0)ᵀ H (x - x0).
struct Height {
    x0: DVec2,
    h0: f64,
    g: DVec2,
    hessian: DMat2,
    radius: f64,
}

impl Height {
    /// From a point with its outward normal and the patch's curvature tensor evaluated on the
    /// lateral basis (`form(e_i, e_j)`); `None` when the normal is nearly parallel to the plane.
    /// The graph's gradient is -n_lateral / (n · w) for either orientation, and a patch bends
    /// away from its outward normal where convex: H = -sign(n · w) C restricted.
    fn new(
        point: DVec3,
        normal: DVec3,
        form: impl Fn(usize, usize) -> f64,
        (w, e1, e2): (DVec3, DVec3, DVec3),
        radius: f64,
    ) -> Option<Self> {
        let nw = normal.dot(w);
        if nw.abs() <= 0.2 || nw.is_nan() {
            return None;
        }
        let sign = -nw.signum();
        Some(Self {
            x0: DVec2::new(e1.dot(point), e2.dot(point)),
            h0: w.dot(point),
            g: -DVec2::new(e1.dot(normal), e2.dot(normal)) / nw,
            hessian: DMat2::from_cols(
                DVec2::new(form(0, 0), form(0, 1)),
                DVec2::new(form(0, 1), form(1, 1)),
            ) * sign,
            radius,
        })
    }

    fn at(&self, x: DVec2) -> f64 {
        let d = x - self.x0;
        self.h0 + self.g.dot(d) + 0.5 * d.dot(self.hessian * d)
    }
}

/// A certified pair's candidate from the nodes' own second-order models (anchor point and
/// normal on the exact surface, mean curvature tensor): where the gap between the two height
/// functions over the plane normal to w (the bisector of A's axis and the reverse of B's) is
/// least, solved from their 2x2 Hessians (which the certificate makes positive definite; where
/// the models disagree, the midpoint of the two anchors). No surface is evaluated, so that
/// duplicates are merged before seeds are made ([`node_seed`]).
fn predict(
    (na, nb): (&PatchNode, &PatchNode),
    nodes: [u32; 2],
    frame: &PairFrame,
) -> Option<Found> {
    let axis_b = frame.rotation * nb.cone.axis;
    let w = (na.cone.axis - axis_b).try_normalize()?;
    let (e1, e2) = w.any_orthonormal_pair();
    let basis = [e1, e2];
    let local = [frame.inverse * e1, frame.inverse * e2];
    let ha = Height::new(
        na.anchor,
        na.anchor_normal,
        |i, j| na.curvature.form(basis[i], basis[j]),
        (w, e1, e2),
        na.radius,
    )?;
    let hb = Height::new(
        frame.rotation * nb.anchor + frame.translation,
        frame.rotation * nb.anchor_normal,
        |i, j| nb.curvature.form(local[i], local[j]),
        (w, e1, e2),
        nb.radius,
    )?;
    let x = lowest_gap(&ha, &hb);
    let clamped = x.distance(ha.x0) > ha.radius || x.distance(hb.x0) > hb.radius;
    let lift = |h: &Height| e1 * x.x + e2 * x.y + w * h.at(x);
    Some(Found {
        rank: (if clamped { 2 } else { 0 }, hb.at(x) - ha.at(x)),
        point_a: lift(&ha),
        point_b: lift(&hb),
        radius: MODEL_MERGE * na.radius.min(nb.radius),
        outside: clamped.then_some(na.radius.min(nb.radius)),
        leaf: None,
        source: Source::Certified(nodes),
    })
}

/// The lateral point where h_B - h_A is least: (H_B - H_A) x = g_A - g_B + H_B x0_B - H_A x0_A
/// when that Hessian is positive definite, else the midpoint of the two centres.
fn lowest_gap(ha: &Height, hb: &Height) -> DVec2 {
    let k = hb.hessian - ha.hessian;
    let rhs = ha.g - hb.g + hb.hessian * hb.x0 - ha.hessian * ha.x0;
    let det = k.determinant();
    let scale = k
        .x_axis
        .abs()
        .max_element()
        .max(k.y_axis.abs().max_element());
    let midpoint = 0.5 * (ha.x0 + hb.x0);
    if det > 1e-12 * scale * scale && k.x_axis.x + k.y_axis.y > 0.0 {
        let x = k.inverse() * rhs;
        if x.is_finite() { x } else { midpoint }
    } else {
        midpoint
    }
}

/// The seed point of a kept certified pair's side: the predicted point (`point`, in its own
/// object's frame) moved to the nearest point of the component's mesh, and located on the
/// exact surface through its triangle's corner parameters. On the mesh, like every other seed,
/// and unaffected by singular parametrisations (a sphere's pole), which an expansion in the
/// face's parameters is not. The point is the nearest of the pair's node's pieces when that
/// lies within `snap` (mm; the candidate's merge radius, within which the models place the
/// minimum, or the mesh's chordal error where that is more): a start that close stands for the
/// same minimum as the prediction. Otherwise, where the prediction fell farther beyond the
/// node, the nearest piece of whichever `nearby` node (the other certified pairs' nodes on this
/// side) has its centre nearest the prediction, when that piece lies within `snap`; failing
/// that, the nearest piece of the whole component. Searching the whole component whenever
/// the prediction lay beyond the node by more than the chordal error was a sixth of Stage 2 for
/// a pencil resting in a bowl at chordal tolerance 0.01 mm (33 certified pairs), and grew as
/// the tolerance shrank; the start now lies up to `snap` from the prediction rather than the
/// chordal error, which cost one more Newton step on three of the fixtures' contacts. The same
/// pencil's kept prediction lay 0.39 mm beyond its node and 0.0026 mm from the pieces of the
/// certified node nearest it: searching that node first spared the component's search (71
/// nodes visited), 35.4k instructions of Stage 2 against 32.0k.
///
/// Where that point lies within `snap` of a mesh vertex on a vertex of the solid (a
/// pole or an apex), the seed is that vertex: a seed a hair beside a pole makes Newton crawl
/// through the pole's singular parametrisation, one on it starts from the vertex itself, and
/// Stage 3 moves off it onto a face when the minimum lies beside it.
fn node_seed(
    (side, tree, node): (&Side<'_>, &PatchTree, u32),
    nearby: impl Iterator<Item = u32>,
    point: DVec3,
    snap: f64,
) -> Option<SeedPoint> {
    let snap = snap.max(side.chordal_error()) + 1e-12 * side.size;
    let mut near = nearest_piece(tree, node, point, None);
    if near.is_none_or(|n| n.2 > snap) {
        let nearest = nearby
            .filter(|&k| k != node)
            .filter_map(|k| {
                Some((
                    tree.nodes.get(k as usize)?.centre.distance_squared(point),
                    k,
                ))
            })
            .min_by(|x, y| x.0.total_cmp(&y.0));
        if let Some((_, k)) = nearest {
            near = nearest_piece(tree, k, point, near);
        }
    }
    let (piece, on_piece, _) = match near {
        Some(near) if near.2 <= snap => near,
        beyond => nearest_piece(tree, 0, point, beyond)?,
    };
    let corner = (0..3).find(|&k| {
        let b = piece.barycentric[k];
        let tri = side.mesh.triangles.get(piece.triangle as usize);
        let vertex = tri.and_then(|t| {
            let m = (0..3).find(|&m| b[m] == 1.0)?;
            Some(t[m])
        });
        let on_vertex = vertex.and_then(|v| side.mesh.vertex_locations.get(v as usize));
        matches!(on_vertex, Some(FeatureLocation::Vertex { .. }))
            && piece.corners[k].distance(on_piece.point) <= snap
    });
    let barycentric = match corner {
        Some(k) => {
            let mut unit = [0.0; 3];
            unit[k] = 1.0;
            unit
        }
        None => on_piece.barycentric,
    };
    piece_point(side, piece, barycentric).map(|(point, _)| point)
}

/// The point of the pieces under `node` nearest to `point` (the tree's frame), with its
/// distance (mm): a depth-first search, nearer child first, that skips subtrees whose balls lie
/// farther than the best distance so far, starting from `known` (a piece point already found
/// and its distance, which only a strictly nearer one replaces).
fn nearest_piece<'t>(
    tree: &'t PatchTree,
    node: u32,
    point: DVec3,
    known: Option<(&'t Piece, TrianglePoint, f64)>,
) -> Option<(&'t Piece, TrianglePoint, f64)> {
    let mut best = known;
    // The tree is balanced: depth below 64 for any mesh that fits in memory.
    let mut stack = [0_u32; 64];
    let mut depth = 1;
    stack[0] = node;
    while depth > 0 {
        depth -= 1;
        let i = stack[depth];
        let Some(n) = tree.nodes.get(i as usize) else {
            continue;
        };
        let bound = best.as_ref().map_or(f64::INFINITY, |b| b.2);
        if n.centre.distance(point) - n.radius > bound {
            continue;
        }
        match n.leaf {
            PatchLeaf::Piece(k) => {
                if let Some(piece) = tree.pieces.get(k as usize) {
                    let p = closest_on_triangle(point, &piece.corners);
                    let d = p.point.distance(point);
                    if d < bound {
                        best = Some((piece, p, d));
                    }
                }
            }
            PatchLeaf::Inner => {
                if depth + 2 <= stack.len() {
                    // The nearer child on top, so that the first leaves reached bound the rest.
                    let (near, far) = match (
                        tree.nodes.get(i as usize + 1),
                        tree.nodes.get(n.right as usize),
                    ) {
                        (Some(l), Some(r))
                            if l.centre.distance_squared(point)
                                > r.centre.distance_squared(point) =>
                        {
                            (n.right, i + 1)
                        }
                        _ => (i + 1, n.right),
                    };
                    stack[depth] = far;
                    stack[depth + 1] = near;
                    depth += 2;
                }
            }
        }
    }
    best
}

/// A leaf's piece with its corners in A's frame: moved by `to_a` (B's frame in A's) for a piece
/// of B's, as they are (`None`) for one of A's.
fn piece_of<'t>(
    tree: &'t PatchTree,
    node: u32,
    to_a: Option<&PairFrame>,
) -> Option<(&'t Piece, [DVec3; 3])> {
    let PatchLeaf::Piece(k) = tree.nodes.get(node as usize)?.leaf else {
        return None;
    };
    let piece = tree.pieces.get(k as usize)?;
    let corners = match to_a {
        // The rotation as a matrix: a quaternion's rotation of a point costs twice as much.
        Some(f) => piece.corners.map(|p| f.rotation * p + f.translation),
        None => piece.corners,
    };
    Some((piece, corners))
}

/// The seed point of a point with barycentric coordinates `b` in `piece`, with the convex edge
/// it lies on ([`patch_tree::ridge_at`]): on that edge, at the parameter interpolated from its
/// triangle's corners there, and on the triangle's face otherwise.
///
/// Why on the edge: a mesh point on a ridge stands for the edge's own minimum (curve-surface),
/// and its face parameters put the start a chord's sagitta inside the face, where Newton's
/// first steps on the face pair cross the edge and are rejected. A tube lying across a loft's
/// top cap, its minima on the cap's rim: the seed on the ridge took nine iterations from the
/// cap, three of them rejected steps across the rim.
fn piece_point(side: &Side<'_>, piece: &Piece, b: [f64; 3]) -> Option<(SeedPoint, Option<EdgeId>)> {
    let t = piece.triangle as usize;
    (t < side.mesh.triangle_params.len() && t < side.mesh.triangle_faces.len()).then(|| {
        let c = piece.corners;
        let barycentric = piece.to_triangle(b);
        let ridge = ridge_at(side, piece.triangle, barycentric);
        let location = ridge
            .and_then(|edge| edge_location(side, t, barycentric, edge))
            .unwrap_or_else(|| side.mesh.locate(t, barycentric));
        let point = SeedPoint {
            component: side.component,
            local_point: c[0] * b[0] + c[1] * b[1] + c[2] * b[2],
            location,
        };
        (point, ridge)
    })
}

/// The location on `edge` of the point with `barycentric` coordinates in mesh triangle
/// `triangle`, whose weighted corners all lie on that edge: their edge parameters averaged by
/// weight (a periodic edge's unwrapped about the first one's, so that two corners across its
/// seam average to a point between them). `None` where a corner is not on the edge or the
/// parameter is not finite.
fn edge_location(
    side: &Side<'_>,
    triangle: usize,
    barycentric: [f64; 3],
    edge: EdgeId,
) -> Option<FeatureLocation> {
    let corners = side.mesh.triangles.get(triangle)?;
    let domain = side.object.solid.edges.get(edge.0 as usize)?.curve.domain();
    let period = domain.max - domain.min;
    let (mut sum, mut weights, mut reference) = (0.0, 0.0, None);
    for (&vertex, &weight) in corners.iter().zip(&barycentric) {
        if weight <= 1e-12 {
            continue;
        }
        let FeatureLocation::Edge { id, t } = *side.mesh.vertex_locations.get(vertex as usize)?
        else {
            return None;
        };
        if id != edge {
            return None;
        }
        let first = *reference.get_or_insert(t);
        let t = if domain.periodic {
            t - period * ((t - first) / period).round()
        } else {
            t
        };
        sum += weight * t;
        weights += weight;
    }
    let t = domain.normalize(sum / weights);
    t.is_finite()
        .then_some(FeatureLocation::Edge { id: edge, t })
}

/// The closest points of a critical leaf pair as a seed candidate ranked by their distance,
/// when that is at most `reach` (mm).
fn leaf_seed(
    (side_a, tree_a, a): (&Side<'_>, &PatchTree, u32),
    (side_b, tree_b, b): (&Side<'_>, &PatchTree, u32),
    frame: &PairFrame,
    reach: f64,
) -> Option<Found> {
    let (pa, ta) = piece_of(tree_a, a, None)?;
    let (pb, tb) = piece_of(tree_b, b, Some(frame))?;
    // Pieces side by side (their ball spans a triangle, far wider than the gaps of a conformal
    // contact) are told apart by their boxes before their closest points are computed.
    if boxes_gap(&ta, &tb) > reach {
        return None;
    }
    let pair = closest_between_triangles(&ta, &tb);
    if pair.distance.is_nan() || pair.distance > reach {
        return None;
    }
    let (seed_a, ridge_a) = piece_point(side_a, pa, pair.a.barycentric)?;
    let (seed_b, ridge_b) = piece_point(side_b, pb, pair.b.barycentric)?;
    let (node_a, node_b) = (&tree_a.nodes[a as usize], &tree_b.nodes[b as usize]);
    let radius = node_a.radius.max(node_b.radius);
    pair.distance.is_finite().then_some(Found {
        rank: (1, pair.distance),
        point_a: pair.a.point,
        point_b: pair.b.point,
        radius,
        outside: None,
        // A leaf's inset is its one piece's deviation bound.
        leaf: Some(LeafPair {
            error: node_a.mesh_inset + node_b.mesh_inset,
            nodes: [a, b],
            triangles: [pa.triangle, pb.triangle],
            barycentric: [
                pa.to_triangle(pair.a.barycentric),
                pb.to_triangle(pair.b.barycentric),
            ],
            ridges: [ridge_a, ridge_b],
        }),
        source: Source::Made(Seed {
            a: seed_a,
            b: seed_b,
        }),
    })
}

/// The candidates of a critical leaf pair (leaf nodes `a`, `b`) on its pieces' ridges: for each
/// side of a piece along a convex edge inside its component ([`Piece::inner_ridges`]) that
/// `skip` (side index 0 for A, 1 for B, and the edge) does not exclude, the closest points of
/// that side and the other piece, handed to `push`. The selection asks for them when it drops
/// a leaf pair's candidate as standing for a kept one's minimum, skipping the ridges either
/// candidate already lies on.
///
/// Why: an edge has minima of its own (curve-surface), and the closest points of two triangles
/// need not lie on a triangle's side along the edge when the minimum does, since the other
/// mesh lies up to its chordal error off its surface. A vase's body over a goblet's flat top (an
/// annulus between radii 37 and 40 mm, meshed with triangles across its width) has minima on
/// both rims, 0.0270 and 0.0828 mm; the leaf pair at the outer rim had its closest points 0.16
/// mm inside the annulus, which the radius rule merged with a mid-annulus candidate whose seed
/// went to the inner rim, and the outer rim's minimum had no seed (goblet-vase
/// 1604628255842907462 of `soak 10000 --seed 13154`).
fn ridge_seeds(
    (side_a, tree_a, a): (&Side<'_>, &PatchTree, u32),
    (side_b, tree_b, b): (&Side<'_>, &PatchTree, u32),
    frame: &PairFrame,
    skip: impl Fn(usize, EdgeId) -> bool,
    mut push: impl FnMut(Found),
) {
    let (Some((pa, ta)), Some((pb, tb))) =
        (piece_of(tree_a, a, None), piece_of(tree_b, b, Some(frame)))
    else {
        return;
    };
    let (node_a, node_b) = (&tree_a.nodes[a as usize], &tree_b.nodes[b as usize]);
    let radius = node_a.radius.max(node_b.radius);
    let error = node_a.mesh_inset + node_b.mesh_inset;
    let sides = [(side_a, pa, &ta, &tb), (side_b, pb, &tb, &ta)];
    for (k, &(side, piece, own, other)) in sides.iter().enumerate() {
        for (bit, &(i, j)) in PIECE_SIDES.iter().enumerate() {
            if piece.inner_ridges & (1 << bit) == 0 {
                continue;
            }
            let on = ridge_at(side, piece.triangle, piece.barycentric[i].to_array());
            let Some(edge) = on.filter(|&e| !skip(k, e)) else {
                continue;
            };
            let (s, far, distance) = closest_between_segment_and_triangle(own[i], own[j], other);
            let mut along = [0.0; 3];
            along[i] = 1.0 - s;
            along[j] = s;
            let near = own[i] + (own[j] - own[i]) * s;
            let (other_side, other_piece) = if k == 0 { (side_b, pb) } else { (side_a, pa) };
            let (Some(here), Some(there)) = (
                piece_point(side, piece, along),
                piece_point(other_side, other_piece, far.barycentric),
            ) else {
                continue;
            };
            debug_assert!(here.1 == Some(edge));
            let ((seed_a, seed_b), (point_a, point_b), (bary_a, bary_b)) = if k == 0 {
                ((here, there), (near, far.point), (along, far.barycentric))
            } else {
                ((there, here), (far.point, near), (far.barycentric, along))
            };
            if distance.is_finite() {
                push(Found {
                    rank: (1, distance),
                    point_a,
                    point_b,
                    radius,
                    outside: None,
                    leaf: Some(LeafPair {
                        error,
                        nodes: [a, b],
                        triangles: [pa.triangle, pb.triangle],
                        barycentric: [pa.to_triangle(bary_a), pb.to_triangle(bary_b)],
                        ridges: [seed_a.1, seed_b.1],
                    }),
                    source: Source::Made(Seed {
                        a: seed_a.0,
                        b: seed_b.0,
                    }),
                });
            }
        }
    }
}

/// The closest point of a leaf's piece to an apex as a seed candidate. The apex is apex `k` of
/// `apex_tree` (side `apex_side`), the leaf node `node` of `tree` (side `side`);
/// `apex_is_a` says which of the two is A.
fn apex_seed(
    (apex_side, apex_tree, k): (&Side<'_>, &PatchTree, u32),
    (side, tree, node): (&Side<'_>, &PatchTree, u32),
    frame: &PairFrame,
    apex_is_a: bool,
) -> Option<Found> {
    let apex = apex_tree.apexes.get(k as usize)?;
    let (piece, corners) = piece_of(tree, node, apex_is_a.then_some(frame))?;
    let point = if apex_is_a {
        apex.point
    } else {
        frame.rotation * apex.point + frame.translation
    };
    let on_piece: TrianglePoint = closest_on_triangle(point, &corners);
    let apex_point = SeedPoint {
        component: apex_side.component,
        local_point: apex.point,
        location: apex.location,
    };
    let (piece_seed, _) = piece_point(side, piece, on_piece.barycentric)?;
    let (seed, point_a, point_b) = if apex_is_a {
        (
            Seed {
                a: apex_point,
                b: piece_seed,
            },
            point,
            on_piece.point,
        )
    } else {
        (
            Seed {
                a: piece_seed,
                b: apex_point,
            },
            on_piece.point,
            point,
        )
    };
    let distance = point.distance(on_piece.point);
    distance.is_finite().then_some(Found {
        rank: (1, distance),
        point_a,
        point_b,
        radius: tree.nodes[node as usize].radius,
        outside: None,
        leaf: None,
        source: Source::Made(seed),
    })
}

/// Two apexes within `reach` whose cones allow a critical pair, as a seed candidate.
fn apex_pair(
    (side_a, _, apex_a): (&Side<'_>, usize, &crate::cones::patch_tree::Apex),
    (side_b, _, apex_b): (&Side<'_>, usize, &crate::cones::patch_tree::Apex),
    pose_ab: &DPose3,
    reach: f64,
) -> Option<Found> {
    let (pa, pb) = (apex_a.point, *pose_ab * apex_b.point);
    let distance = pa.distance(pb);
    let cone_b = apex_b.cone.rotated(pose_ab.rotation);
    let directions = NormalCone::between_balls(pa, 0.0, pb, 0.0);
    let kinds = CriticalKinds::of(&apex_a.cone, &cone_b, &directions);
    (distance <= reach && kinds.any()).then_some(Found {
        rank: (1, distance),
        point_a: pa,
        point_b: pb,
        radius: 0.0,
        outside: None,
        leaf: None,
        source: Source::Made(Seed {
            a: SeedPoint {
                component: side_a.component,
                local_point: apex_a.point,
                location: apex_a.location,
            },
            b: SeedPoint {
                component: side_b.component,
                local_point: apex_b.point,
                location: apex_b.location,
            },
        }),
    })
}
