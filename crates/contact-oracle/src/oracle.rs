//! The oracle: sample both solids, polish every discrete local minimum and every penetration
//! start, merge, and cross-check against a second run at a finer, shifted grid.

use crate::cross_check::compare;
use crate::error::OracleError;
use crate::minima::found::{contact, merge, separated_through_material, through_material};
use crate::minima::local_minima::{self, NEIGHBOURHOOD, Outcome};
use crate::minima::penetration;
use crate::minima::regions;
use crate::options::OracleOptions;
use crate::polishing::pair::Pair;
use crate::polishing::polish::{self, Limits, Polished};
use crate::report::{OracleContact, OracleReport, RegionMember};
use crate::samples::kdtree::KdTree;
use crate::samples::sampling::{self, Sample};
use crate::solids::held::Held;
use crate::solids::posed::PosedSolid;
use geom_param::{DPose3, FeatureLocation, Solid};

/// Most samples of one solid in one run (a `Sample` is 72 bytes: at most ~72 MB per solid).
pub const SAMPLE_BUDGET: usize = 1_000_000;
/// Extra sampled margin beyond `reach`, in spacings.
const MARGIN: f64 = 3.0;
/// The oracle's distance resolution, in stationarity tolerances: minima separated by a barrier
/// lower than this are one region (`regions`).
const RESOLUTION: f64 = 5.0;
/// Most penetration starts taken from crossings, per side.
const MAX_CROSSING_STARTS: usize = 64;

/// All local minima of distance and penetration witnesses between `a` under `pose_a` and `b`
/// under `pose_b` with signed distance <= `options.reach`, in the world frame.
///
/// # Errors
/// [`OracleError::BadPose`], [`OracleError::BadOptions`], [`OracleError::BadSolid`], or
/// [`OracleError::TooManySamples`] when the spacing is too fine for [`SAMPLE_BUDGET`].
pub fn find_contacts(
    a: &Solid,
    pose_a: &DPose3,
    b: &Solid,
    pose_b: &DPose3,
    options: &OracleOptions,
) -> Result<OracleReport, OracleError> {
    let OracleOptions {
        spacing,
        reach,
        tolerance,
    } = *options;
    let usable = spacing.is_finite()
        && spacing > 0.0
        && tolerance.is_finite()
        && tolerance > 0.0
        && reach.is_finite()
        && reach >= 0.0;
    if !usable {
        return Err(OracleError::BadOptions {
            spacing,
            reach,
            tolerance,
        });
    }
    let pose_a = checked_pose(pose_a, "a")?;
    let pose_b = checked_pose(pose_b, "b")?;
    if a.faces.is_empty() {
        return Err(OracleError::BadSolid { which: "a" });
    }
    if b.faces.is_empty() {
        return Err(OracleError::BadSolid { which: "b" });
    }
    let (pa, pb) = (PosedSolid::new(a, &pose_a), PosedSolid::new(b, &pose_b));
    let primary = run(&pa, &pb, options, spacing, 0.0)?;
    let secondary = run(&pa, &pb, options, spacing / std::f64::consts::SQRT_2, 0.5)?;
    let size = primary.size;
    let cross_check = compare(&primary.contacts, &secondary.contacts, 1e-6 * size);
    let min_distance = primary
        .contacts
        .first()
        .map_or(f64::INFINITY, |c| c.distance);
    Ok(OracleReport {
        contacts: primary.contacts,
        members: primary.members,
        min_distance,
        samples: primary.samples,
        cross_check,
    })
}

fn checked_pose(pose: &DPose3, which: &'static str) -> Result<DPose3, OracleError> {
    let q = pose.rotation;
    if !(q.is_finite() && pose.translation.is_finite() && (q.length() - 1.0).abs() <= 1e-6) {
        return Err(OracleError::BadPose { which });
    }
    Ok(DPose3 {
        rotation: q.normalize(),
        translation: pose.translation,
    })
}

struct Run {
    contacts: Vec<OracleContact>,
    members: Vec<RegionMember>,
    samples: usize,
    size: f64,
}

fn run(
    a: &PosedSolid,
    b: &PosedSolid,
    options: &OracleOptions,
    spacing: f64,
    offset: f64,
) -> Result<Run, OracleError> {
    let ca = sampling::coarse(a, spacing).ok_or(OracleError::BadSolid { which: "a" })?;
    let cb = sampling::coarse(b, spacing).ok_or(OracleError::BadSolid { which: "b" })?;
    let size = ca.bounds.extent().max(cb.bounds.extent());
    let keep = options.reach + MARGIN * spacing;
    let too_many = |needed| OracleError::TooManySamples {
        spacing,
        needed,
        budget: SAMPLE_BUDGET,
    };
    let sa = sampling::fine(a, &ca, &cb, keep, spacing, offset, SAMPLE_BUDGET).map_err(too_many)?;
    let sb = sampling::fine(b, &cb, &ca, keep, spacing, offset, SAMPLE_BUDGET).map_err(too_many)?;
    let samples = sa.len() + sb.len();
    let mut contacts = Vec::new();
    if sa.is_empty() || sb.is_empty() {
        return Ok(Run {
            contacts,
            members: Vec::new(),
            samples,
            size,
        });
    }
    let (ta, tb) = (KdTree::new(&points(&sa)), KdTree::new(&points(&sb)));
    let limits = Limits {
        tolerance: options.tolerance,
        step: 4.0 * spacing,
        iterations: 300,
    };
    let radius = NEIGHBOURHOOD * spacing;
    let merge_radius = 1e3 * options.tolerance;

    // Separated and touching minima, from both sides.
    let near_ab = local_minima::nearest(&sa, &tb, keep);
    let near_ba = local_minima::nearest(&sb, &ta, keep);
    let mut starts = Vec::new();
    for i in local_minima::candidates(&sa, &ta, &near_ab, radius) {
        let (j, _) = near_ab[i].expect("candidates have a nearest sample");
        starts.push(pair(&sa[i], &sb[j]));
    }
    for j in local_minima::candidates(&sb, &tb, &near_ba, radius) {
        let (i, _) = near_ba[j].expect("candidates have a nearest sample");
        starts.push(pair(&sa[i], &sb[j]));
    }
    let mut crossings = Vec::new();
    for start in starts {
        let outcome = local_minima::polish(a, b, start, spacing, &limits);
        match outcome {
            Outcome::Minimum(p) => {
                let signed = |p: &Polished| {
                    let negative = is_negative(a, p, options.tolerance);
                    p.eval.r.length() * if negative { -1.0 } else { 1.0 }
                };
                let p = local_minima::deeper_corner(a, b, *p, &limits, signed);
                let negative = is_negative(a, &p, options.tolerance);
                let through = if negative {
                    through_material(
                        (a, b),
                        &p.pair,
                        (&ta, &tb),
                        (&sa, &sb),
                        (spacing, keep),
                        &limits,
                    )
                } else {
                    separated_through_material((a, b), &p.pair, (&ta, &tb), (&sa, &sb), &limits)
                };
                if through {
                    continue;
                }
                let c = to_contact(a, b, &p, negative, options.tolerance);
                merge(&mut contacts, c, merge_radius);
            }
            Outcome::Crossing(q) => crossings.push(q),
            Outcome::Rejected => {}
        }
    }

    // Penetration witnesses, from A inside B and from B inside A.
    for swapped in [false, true] {
        let (own, other, own_tree, near, x, y) = if swapped {
            (&sb, &sa, &tb, &near_ba, b, a)
        } else {
            (&sa, &sb, &ta, &near_ab, a, b)
        };
        let phis = penetration::signed_distances(
            x, y, own, own_tree, other, near, spacing, radius, &limits,
        );
        let mut starts: Vec<Pair> = penetration::deepest_per_region(own, own_tree, &phis, radius)
            .into_iter()
            .map(|(_, p)| p)
            .collect();
        let mut taken: Vec<glam::DVec3> = Vec::new();
        for c in &crossings {
            let c = if swapped { swap(c) } else { *c };
            let at = x.eval(c.fa, c.a[0], c.a[1]).point;
            if taken.len() < MAX_CROSSING_STARTS && taken.iter().all(|t| t.distance(at) > spacing) {
                taken.push(at);
                starts.push(c);
            }
        }
        for start in starts {
            let Some(w) = penetration::witness(x, y, start, spacing, &limits) else {
                continue;
            };
            let pair = if swapped { swap(&w.pair) } else { w.pair };
            let e = polish::evaluate(a, b, &pair);
            let residual = polish::residual(&e, pair.dims(), [false; 4]);
            // A witness has one point inside the other solid with the other point as its
            // nearest boundary point; otherwise it is a depth through the material.
            if through_material(
                (a, b),
                &pair,
                (&ta, &tb),
                (&sa, &sb),
                (spacing, keep),
                &limits,
            ) {
                continue;
            }
            // And a witness overlaps: A's point behind B's outward side and B's behind A's
            // (S_a − S_b against both sides' normals; a pair on the outer sides is a separated
            // pair that the polish reached from the descent, not a penetration).
            let behind = |na: Option<glam::DVec3>, nb: Option<glam::DVec3>| {
                na.is_none_or(|n| e.r.dot(n) >= 0.0) && nb.is_none_or(|n| e.r.dot(n) <= 0.0)
            };
            if !behind(
                a.sign_normal(pair.fa, pair.a, pair.held_a),
                b.sign_normal(pair.fb, pair.b, pair.held_b),
            ) {
                continue;
            }
            let w = Polished {
                pair,
                eval: e,
                residual,
                ..w
            };
            let c = to_contact(a, b, &w, true, options.tolerance);
            merge(&mut contacts, c, merge_radius);
        }
    }
    contacts.retain(|c| c.distance <= options.reach);
    contacts.sort_by(|p, q| p.distance.total_cmp(&q.distance));
    let (contacts, members) =
        regions::group(a, b, contacts, &limits, RESOLUTION * options.tolerance);
    Ok(Run {
        contacts,
        members,
        samples,
        size,
    })
}

/// Whether a polished minimum is a penetration: B's point behind A's outward side at the
/// feature A's point is on (a point held on a face's side, an edge of a face without trim, has
/// the edge's side, which the face's own normal there does not give).
fn is_negative(a: &PosedSolid, p: &Polished, tolerance: f64) -> bool {
    let snap = 10.0 * tolerance;
    let held = match a.location(p.pair.fa, p.pair.a, p.pair.held_a, snap) {
        FeatureLocation::Face { .. } => Held::Face,
        FeatureLocation::Edge { id, t } => Held::Edge {
            edge: id,
            t,
            use_index: 0,
        },
        FeatureLocation::Vertex { id } => Held::Vertex(id),
    };
    let na = a.sign_normal(p.pair.fa, p.pair.a, held);
    na.is_some_and(|n| (p.eval.pb.point - p.eval.pa.point).dot(n) < 0.0)
}

fn points(samples: &[Sample]) -> Vec<glam::DVec3> {
    samples.iter().map(|s| s.point).collect()
}

fn pair(sa: &Sample, sb: &Sample) -> Pair {
    Pair::faces(sa.face, sa.uv, sb.face, sb.uv)
}

fn swap(p: &Pair) -> Pair {
    p.swapped()
}

/// The contact of a polished pair; locations snap to edges and vertices within 10 x
/// `tolerance` (the stationarity tolerance, mm).
fn to_contact(
    a: &PosedSolid,
    b: &PosedSolid,
    p: &Polished,
    negative: bool,
    tolerance: f64,
) -> OracleContact {
    let snap = 10.0 * tolerance;
    contact(a, b, p, negative, snap, tolerance)
}
