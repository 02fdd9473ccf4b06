//! A polished pair turned into a contact: signed distance, normal, and merging of duplicates.

use crate::polishing::conditioning::point_error_bound;
use crate::polishing::pair::Pair;
use crate::polishing::polish::{self, Limits, Polished};
use crate::report::OracleContact;
use crate::samples::kdtree::KdTree;
use crate::samples::sampling::Sample;
use crate::solids::held::Held;
use crate::solids::posed::PosedSolid;
use geom_param::FeatureLocation;

/// Builds the contact for a polished pair. The distance is |S_b − S_a|, negative when
/// `negative`; the normal is the unit connecting vector oriented so that
/// point_b = point_a + distance · normal (A's face normal when the points coincide, which is
/// also A's outward normal wherever the connecting vector is normal to A). Where A's point is
/// on an edge or vertex, A has a cone of normals: the normal is minus B's face normal (for two
/// edges, their common normal) where the connecting vector lies along it (to the residual) or
/// the points coincide (within `snap`), otherwise the connecting vector, and for two
/// coinciding points otherwise placed A's outward direction there
/// ([`PosedSolid::sign_normal`]). Locations within `snap` (mm) of an edge or
/// vertex of a trimmed face are reported on it ([`PosedSolid::location`]). The point error
/// bound is the oracle's own, from the pair's conditioning and the stationarity `tolerance`
/// (mm) it was polished to ([`point_error_bound`]), and at least the distance from each
/// point to the feature it is reported on (a point snapped to an edge lies up to `snap` from
/// it).
pub(crate) fn contact(
    a: &PosedSolid,
    b: &PosedSolid,
    polished: &Polished,
    negative: bool,
    snap: f64,
    tolerance: f64,
) -> OracleContact {
    let Polished {
        pair,
        eval,
        residual,
        iterations,
        ..
    } = polished;
    let (residual, iterations) = (*residual, *iterations);
    let (pa, pb) = (eval.pa.point, eval.pb.point);
    let gap = pb - pa;
    // The normal the connecting vector must lie along (to the residual) to be replaced by it:
    // A's face normal, or minus B's where A's point is on an edge or vertex and B's inside a
    // face.
    let location_a = a.location(pair.fa, pair.a, pair.held_a, snap);
    let location_b = b.location(pair.fb, pair.b, pair.held_b, snap);
    let outward_a = a.sign_normal(pair.fa, pair.a, pair.held_a);
    let (face_normal, touching_normal) = match (location_a, location_b) {
        (FeatureLocation::Face { .. }, _) => (a.normal(pair.fa, pair.a[0], pair.a[1]), None),
        (_, FeatureLocation::Face { .. }) => (
            b.normal(pair.fb, pair.b[0], pair.b[1]).map(|n| -n),
            outward_a,
        ),
        // Two edges: their common normal, on A's outer side.
        (FeatureLocation::Edge { id: ea, t: ta }, FeatureLocation::Edge { id: eb, t: tb }) => {
            let common = a.eval_edge(ea, ta).d1.cross(b.eval_edge(eb, tb).d1);
            let oriented = common
                .try_normalize()
                .zip(outward_a)
                .map(|(n, o)| if n.dot(o) < 0.0 { -n } else { n });
            (oriented, outward_a)
        }
        _ => (None, outward_a),
    };
    let length = gap.length();
    let sign = if negative { -1.0 } else { 1.0 };
    let distance = sign * length;
    // A's face normal where the connecting vector is normal to A (interior points, to the
    // residual); the connecting vector itself at an edge, where A has a cone of normals.
    let along =
        |n: glam::DVec3| (gap - n * gap.dot(n)).length() <= 1e3 * residual.max(1e-15 * length);
    let on_face = matches!(location_a, FeatureLocation::Face { .. });
    let normal = match face_normal {
        Some(n) if length == 0.0 || along(n) || (!on_face && length <= snap) => n,
        _ => (gap / distance)
            .try_normalize()
            .or(face_normal)
            .or(touching_normal)
            .unwrap_or(glam::DVec3::Z),
    };
    // A point reported on an edge or vertex it was snapped to (within `snap`) is that far
    // from the feature it names.
    let snapped = snap_offset(a, location_a, pa).max(snap_offset(b, location_b, pb));
    let point_error_estimate = point_error_bound(polished, distance, normal, tolerance, snapped);
    OracleContact {
        point_a: pa,
        point_b: pb,
        distance,
        normal,
        face_a: pair.fa,
        params_a: pair.a,
        face_b: pair.fb,
        params_b: pair.b,
        location_a,
        location_b,
        residual,
        iterations,
        point_error_estimate,
    }
}

/// How far `point` (world frame, mm) lies from the feature `location` names: 0 on a face
/// (the point is the face's at its parameters), else the distance to the edge's curve point
/// at t or to the vertex.
fn snap_offset(solid: &PosedSolid, location: FeatureLocation, point: glam::DVec3) -> f64 {
    match location {
        FeatureLocation::Face { .. } => 0.0,
        FeatureLocation::Edge { id, t } => solid.eval_edge(id, t).point.distance(point),
        FeatureLocation::Vertex { id } => solid.vertex_point(id).distance(point),
    }
}

/// Adds `c` unless a contact with both points within `radius` is already there. Of the two,
/// the one with fewer points on an edge or vertex is kept, then the one with the smaller
/// residual: a pair held on a face's boundary is stationary only along the boundary (its
/// residual leaves out the parameter held), and where the pair of the face beyond it is
/// stationary within `radius`, the distance still falls across the boundary (pencil-bowl
/// 8005091783543006122: held on the rim's top circle, the seam between the bowl's faces 3
/// and 4, 2.5e-6 mm from the minimum inside face 3 and 1.6e-12 mm above it).
pub(crate) fn merge(into: &mut Vec<OracleContact>, c: OracleContact, radius: f64) {
    let held = |o: &OracleContact| {
        [o.location_a, o.location_b]
            .iter()
            .filter(|l| !matches!(l, FeatureLocation::Face { .. }))
            .count()
    };
    if let Some(old) = into.iter_mut().find(|o| {
        o.point_a.distance(c.point_a) <= radius && o.point_b.distance(c.point_b) <= radius
    }) {
        if (held(&c), c.residual) < (held(old), old.residual) {
            *old = c;
        }
    } else {
        into.push(c);
    }
}

/// Whether a negative pair (a penetration witness, or a minimum signed negative) measures its
/// depth past a nearer part of a surface (through material) rather than from a point of one
/// solid inside the other to that solid's nearest boundary point. The pair stands when one of
/// its points, S_x, has no point of the other solid y nearer than d = |S_a − S_b| (so S_y is
/// y's nearest boundary point to S_x and d is S_x's depth) and lies inside y (behind y's
/// outward side at S_y, [`PosedSolid::sign_normal`]): d is then the depth of S_x, and the pair
/// a local maximum of that depth. The other direction need not hold. A pencil's apex 4.7e-4
/// mm inside a goblet's wall has the wall point as its nearest, while the cone's flank is
/// nearer than the apex to the wall point; a pencil's ferrule point 0.159 mm inside a goblet's
/// wall has the goblet's point as its nearest, while that point, inside the pencil under its
/// ferrule's step, is nearer to the step's edge (pencil-goblet 6346694554730072555, a test in
/// `xtask/tests/penetration_claim_regressions.rs`).
///
/// The cases it rejects: the inner wall of a cup and a body just outside its outer wall are a
/// local minimum of the distance between the two boundaries at the wall's thickness plus the
/// gap, signed negative when the cup is A; the outer wall is nearer to the body's point, and
/// the inner wall's point is outside the body. A pencil's apex 4.7e-4 mm inside a goblet's
/// wall and 0.114 mm below its rim's top face is a critical pair with that face (the vertical
/// lies in the apex's cone of normals), but the wall is nearer to the apex
/// (goblet-pencil 15938213170571082673 of `soak 10000 --seed 13115`).
///
/// A nearer point is a sample of the other solid (samples lie on the exact surfaces) or, since
/// a sample is up to about a spacing from the surface point it stands for, S_x projected onto
/// the other solid from the nearest sample of each of its faces within d plus two spacings
/// (`spacing`, mm; [`nearer_point`]). A margin of 10 x the stationarity tolerance (mm) keeps
/// the pair's own points from counting, so a touching pair (d within it) is never dropped.
///
/// Fine samples exist only within `keep` (mm) of the other solid, so a nearer point beyond
/// that band can go unseen: a pair deeper than `keep` less two spacings must pass the strict
/// test instead, no sample of either solid nearer than d (a tube's rim point taken for a point
/// 21.6 mm inside a loft, tube-loft 7912923848273877506 of `soak 2000 --general --seed 13206`).
pub(crate) fn through_material(
    (a, b): (&PosedSolid, &PosedSolid),
    pair: &Pair,
    (tree_a, tree_b): (&KdTree, &KdTree),
    (samples_a, samples_b): (&[Sample], &[Sample]),
    (spacing, keep): (f64, f64),
    limits: &Limits,
) -> bool {
    let e = polish::evaluate(a, b, pair);
    let limit = e.r.length() - 10.0 * limits.tolerance;
    if limit <= 0.0 {
        return false;
    }
    if limit > keep - 2.0 * spacing {
        // Deeper than the sampled band: a nearer point may lie where nothing was sampled, so
        // the pair must pass the strict test, no sample of either solid nearer.
        return tree_a.nearest_within(e.pb.point, limit).is_some()
            || tree_b.nearest_within(e.pa.point, limit).is_some();
    }
    // S_b inside A at depth d: r = S_a − S_b points out of A at S_a.
    let b_inside_a = a
        .sign_normal(pair.fa, pair.a, pair.held_a)
        .is_none_or(|n| e.r.dot(n) >= 0.0)
        && !nearer_point((a, b), pair, (tree_a, samples_a), limit, spacing, limits);
    let a_inside_b = || {
        b.sign_normal(pair.fb, pair.b, pair.held_b)
            .is_none_or(|n| e.r.dot(n) <= 0.0)
            && !nearer_point(
                (b, a),
                &pair.swapped(),
                (tree_b, samples_b),
                limit,
                spacing,
                limits,
            )
    };
    !(b_inside_a || a_inside_b())
}

/// Whether x (`solids.0`, its point first in `pair`) has a point nearer than `limit` (mm) to
/// y's point of `pair`: a sample of x ([`KdTree::nearest_within`]), or y's point projected
/// onto x from the nearest sample of each face of x within `limit` + 2 x `spacing` (the
/// nearest samples overall may all lie on one face, farther than another face's foot).
fn nearer_point(
    (x, y): (&PosedSolid, &PosedSolid),
    pair: &Pair,
    (tree, samples): (&KdTree, &[Sample]),
    limit: f64,
    spacing: f64,
    limits: &Limits,
) -> bool {
    let target = polish::evaluate(x, y, pair).pb.point;
    if tree.nearest_within(target, limit).is_some() {
        return true;
    }
    let mut per_face: Vec<(f64, usize)> = Vec::new();
    tree.within(target, limit + 2.0 * spacing, &mut |k| {
        let d = samples[k].point.distance(target);
        match per_face
            .iter_mut()
            .find(|(_, j)| samples[*j].face == samples[k].face)
        {
            Some(best) if d < best.0 => *best = (d, k),
            Some(_) => {}
            None => per_face.push((d, k)),
        }
    });
    per_face.iter().any(|&(_, k)| {
        let projected = project_from((x, y), pair, &samples[k], limits);
        projected.converged && projected.eval.r.length() < limit
    })
}

/// y's point of `pair` projected onto x (`solids.0`, its point first in `pair`) from `sample`
/// of x: the polish with y's parameters held.
fn project_from(
    (x, y): (&PosedSolid, &PosedSolid),
    pair: &Pair,
    sample: &Sample,
    limits: &Limits,
) -> Polished {
    let mut start = *pair;
    (start.fa, start.a, start.held_a) = (sample.face, sample.uv, Held::Face);
    polish::minimise(x, y, start, [true, true, false, false], limits)
}

/// [`through_material`] for a separated minimum `pair`: a nearer part of a surface disproves it
/// only where the segment between the two points passes behind that part
/// ([`behind_nearer_part`]), the rule Stage 3 applies to depths (the segment meets neither
/// boundary between its ends). A pencil's body cylinder 0.08 mm above its ferrule's step is
/// 0.0992 mm from a goblet's bead, a local minimum of the distance whose segment is free,
/// while the ferrule's edge is 0.081 mm from the bead's point: that edge lies beside the
/// segment, not across it (pencil-goblet 3730177810009156855 of `soak 10000 --seed 13108`).
/// The cup's wall above still counts: the body's point is behind the outer wall.
pub(crate) fn separated_through_material(
    (a, b): (&PosedSolid, &PosedSolid),
    pair: &Pair,
    (tree_a, tree_b): (&KdTree, &KdTree),
    (samples_a, samples_b): (&[Sample], &[Sample]),
    limits: &Limits,
) -> bool {
    let e = polish::evaluate(a, b, pair);
    let limit = e.r.length() - 10.0 * limits.tolerance;
    if limit <= 0.0 {
        return false;
    }
    let behind_a = tree_a.nearest_within(e.pb.point, limit).is_some()
        && behind_nearer_part((a, b), pair, (tree_a, samples_a), limit, limits);
    behind_a
        || (tree_b.nearest_within(e.pa.point, limit).is_some()
            && behind_nearer_part((b, a), &pair.swapped(), (tree_b, samples_b), limit, limits))
}

/// Most samples nearer than the pair's distance that [`behind_nearer_part`] projects from.
const NEARER_STARTS: usize = 8;

/// Whether x's point of `pair` (x = `solids.0`, its point first in `pair`) lies behind the
/// tangent plane of a part of x nearer than `limit` to y's point: y's point projected onto x
/// from each of the [`NEARER_STARTS`] nearest such samples of x (`samples`, `tree`) gives a
/// point q of x and the direction n between q and y's point, turned to x's outer side at q
/// (y's point may be inside x, overlapping that part); x's own point
/// behind q, (S_x − q) · n below −10 x tolerance, puts the segment across the plane there,
/// into x's material. A projection that does not converge counts as behind (the nearer part
/// stands, as before this test).
fn behind_nearer_part(
    (x, y): (&PosedSolid, &PosedSolid),
    pair: &Pair,
    (tree, samples): (&KdTree, &[Sample]),
    limit: f64,
    limits: &Limits,
) -> bool {
    let own = polish::evaluate(x, y, pair);
    let target = own.pb.point;
    let mut nearer: Vec<(f64, usize)> = Vec::new();
    tree.within(target, limit, &mut |k| {
        nearer.push((samples[k].point.distance(target), k));
    });
    nearer.sort_by(|p, q| p.0.total_cmp(&q.0));
    nearer.iter().take(NEARER_STARTS).any(|&(_, k)| {
        let projected = project_from((x, y), pair, &samples[k], limits);
        if !projected.converged {
            return true;
        }
        let q = projected.eval.pa.point;
        let (Some(n), Some(outward)) = (
            (target - q).try_normalize(),
            x.sign_normal(projected.pair.fa, projected.pair.a, projected.pair.held_a),
        ) else {
            return true;
        };
        // Oriented outwards: y's point may be inside x (overlapping the nearer part).
        let n = if n.dot(outward) < 0.0 { -n } else { n };
        (own.pa.point - q).dot(n) < -10.0 * limits.tolerance
    })
}
