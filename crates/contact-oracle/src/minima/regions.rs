//! One answer per region of near-minimal distance: oracle points joined by a path along which
//! the distance never rises above the higher of the two by more than the oracle's distance
//! resolution are not distinct minima, and are reported once.
//!
//! Why: the polish accepts a pair where the tangential residual (the components of
//! r = S_a − S_b along the parameter directions) is below its tolerance, an absolute length.
//! Where |r| itself is tiny (a touch, or next to a shallow crossing) every component is tiny
//! too, whatever the slope of the distance: a rim circle touching a plane at one point leaves
//! "minima" 3e-3 mm along the rim at 1.2e-7 mm, where the distance still rises as ½κs²
//! towards them; a body lying almost flat on a face leaves them along its length; a surface
//! crossing a fillet leaves them on the smooth edge next to the crossing. And a continuous
//! contact (a flat face on a flat face) has no isolated minimum at all: the polish stops
//! anywhere on the set. In every case the points belong to the region of the lowest one.
//!
//! The test (a mountain-pass argument): two minima at distances d_i <= d_j are distinct only if
//! every path between them rises above d_j by more than the resolution η; a path that does not
//! proves that j is no separate minimum at resolution η. The path walks one point along an edge
//! that holds both points of that side, or straight in the parameters of a face that holds
//! both (a point on an edge is on both its faces; u wrapped the short way round where periodic,
//! every step inside the face's trim),
//! on either solid, and the distance along it is the
//! signed distance of the walking point to the other solid (its foot followed from step to
//! step, [`penetration::signed_distance`]), which is never below the distance between the
//! two surfaces along the path of pairs (point, foot). Minima with neither a common edge nor a
//! common face on either solid are not compared (kept apart), nor are they when a step's
//! projection does not converge.

use crate::minima::penetration;
use crate::polishing::pair::Pair;
use crate::polishing::polish::Limits;
use crate::report::{OracleContact, RegionMember};
use crate::solids::held::Held;
use crate::solids::posed::PosedSolid;
use geom_param::{FaceId, FeatureLocation};

/// Steps of a connecting path.
const PATH_STEPS: usize = 64;

/// `contacts` (sorted by distance) grouped into regions: the lowest point of each region is
/// kept in the returned list (still sorted), every other point joined to it (directly or
/// through another member) becomes a [`RegionMember`] naming it. `resolution` (mm) is the
/// barrier height below which two minima are not told apart.
pub(crate) fn group(
    a: &PosedSolid,
    b: &PosedSolid,
    contacts: Vec<OracleContact>,
    limits: &Limits,
    resolution: f64,
) -> (Vec<OracleContact>, Vec<RegionMember>) {
    let mut kept: Vec<OracleContact> = Vec::new();
    let mut members: Vec<RegionMember> = Vec::new();
    for c in contacts {
        let region = (0..kept.len()).find(|&r| {
            std::iter::once(&kept[r])
                .chain(members.iter().filter(|m| m.region == r).map(|m| &m.contact))
                .any(|lower| joined(a, b, lower, &c, limits, resolution))
        });
        match region {
            Some(region) => members.push(RegionMember { region, contact: c }),
            None => kept.push(c),
        }
    }
    (kept, members)
}

/// Whether a path from `lower` to `higher` keeps the distance at or below
/// `higher.distance + resolution`, with the path's ends reproducing both distances to
/// `resolution`. The paths tried, on either solid: along an edge that holds both points of that
/// side (a rim touching a plane has its flank on the rim, where a straight path in a face's
/// parameters cuts across and climbs), and straight in the parameters of a face that holds
/// both. One path that stays low is enough.
fn joined(
    a: &PosedSolid,
    b: &PosedSolid,
    lower: &OracleContact,
    higher: &OracleContact,
    limits: &Limits,
    resolution: f64,
) -> bool {
    [true, false].into_iter().any(|on_a| {
        let (x, y) = if on_a { (a, b) } else { (b, a) };
        let ends = [lower, higher].map(|c| Ends::of(c, on_a));
        let along_edge =
            edge_path(x, &ends).is_some_and(|path| walk(x, y, &ends, path, limits, resolution));
        along_edge
            || face_paths(x, &ends)
                .into_iter()
                .any(|path| walk(x, y, &ends, path, limits, resolution))
    })
}

/// One contact seen from the walking side x: x's face, parameters and feature, the other
/// side's face and parameters (where the foot starts), and the contact's distance (mm).
struct Ends {
    face: FaceId,
    params: [f64; 2],
    location: FeatureLocation,
    foot_face: FaceId,
    foot: [f64; 2],
    distance: f64,
}

impl Ends {
    fn of(c: &OracleContact, on_a: bool) -> Self {
        if on_a {
            Self {
                face: c.face_a,
                params: c.params_a,
                location: c.location_a,
                foot_face: c.face_b,
                foot: c.params_b,
                distance: c.distance,
            }
        } else {
            Self {
                face: c.face_b,
                params: c.params_b,
                location: c.location_b,
                foot_face: c.face_a,
                foot: c.params_a,
                distance: c.distance,
            }
        }
    }
}

/// A path's point at fraction s in [0, 1]: face, parameters and feature, `None` where it
/// leaves the face's region.
type Path<'p> = Box<dyn Fn(f64) -> Option<(FaceId, [f64; 2], Held)> + 'p>;

/// Along the edge that holds both points, its t running the short way round a closed edge.
fn edge_path<'p>(x: &'p PosedSolid, ends: &[Ends; 2]) -> Option<Path<'p>> {
    let (FeatureLocation::Edge { id: edge, t: from }, FeatureLocation::Edge { id: to_edge, t: to }) =
        (ends[0].location, ends[1].location)
    else {
        return None;
    };
    if edge != to_edge {
        return None;
    }
    let domain = x.solid.edge(edge).curve.domain();
    let mut step = to - from;
    if domain.periodic {
        let span = domain.max - domain.min;
        step -= span * (step / span).round();
    }
    let use_index = x.use_on(edge, ends[0].face);
    let use_ = x.solid.edge(edge).uses[use_index];
    Some(Box::new(move |s| {
        let t = domain.normalize(from + s * step);
        let held = Held::Edge { edge, t, use_index };
        Some((use_.face, x.use_params(&use_, t), held))
    }))
}

/// Straight in the parameters of each face that holds both points (u wrapped the short way
/// round where periodic, every point inside the face's trim). A point on an edge is on both of
/// the edge's faces (at the use's parameters): a touch's flank point that the polish left on
/// a smooth edge (a goblet foot's flat bottom meeting its bead) shares the bead with the touch
/// only that way.
fn face_paths<'p>(x: &'p PosedSolid, ends: &[Ends; 2]) -> Vec<Path<'p>> {
    let [from_faces, to_faces] = ends.each_ref().map(|e| faces_holding(x, e));
    let mut paths: Vec<Path<'p>> = Vec::new();
    for &(face, from) in &from_faces {
        let Some(&(_, to)) = to_faces.iter().find(|(f, _)| *f == face) else {
            continue;
        };
        let step = parameter_step(x, face, from, to);
        paths.push(Box::new(move |s| {
            let uv = x.normalize(face, [from[0] + s * step[0], from[1] + s * step[1]]);
            x.inside(face, uv).then_some((face, uv, Held::Face))
        }));
    }
    paths
}

/// The faces a contact's point of side x lies on, with its parameters on each: its own face,
/// and on an edge the edge's other face too.
fn faces_holding(x: &PosedSolid, end: &Ends) -> Vec<(FaceId, [f64; 2])> {
    let mut faces = vec![(end.face, end.params)];
    if let FeatureLocation::Edge { id, t } = end.location {
        for use_ in &x.solid.edge(id).uses {
            if use_.face != end.face {
                faces.push((use_.face, x.use_params(use_, t)));
            }
        }
    }
    faces
}

/// Walks x's point along `path`, its foot on y followed from step to step: true when the
/// signed distance at the path's ends reproduces both contacts' distances and never rises
/// above the higher one by more than `resolution`.
fn walk(
    x: &PosedSolid,
    y: &PosedSolid,
    ends: &[Ends; 2],
    path: Path,
    limits: &Limits,
    resolution: f64,
) -> bool {
    let [lower, higher] = ends;
    let mut pair = Pair::faces(lower.face, lower.params, lower.foot_face, lower.foot);
    let mut highest = f64::NEG_INFINITY;
    for k in 0..=PATH_STEPS {
        let Some((face, uv, held)) = path(k as f64 / PATH_STEPS as f64) else {
            return false;
        };
        (pair.fa, pair.a, pair.held_a) = (face, uv, held);
        let Some((value, foot)) = penetration::signed_distance(x, y, pair, limits) else {
            return false;
        };
        pair = foot;
        let expected = match k {
            0 => Some(lower.distance),
            PATH_STEPS => Some(higher.distance),
            _ => None,
        };
        if expected.is_some_and(|d| (value - d).abs() > resolution) {
            return false;
        }
        highest = highest.max(value);
    }
    highest <= higher.distance + resolution
}

/// `to − from` in `face`'s parameters, a periodic parameter's difference taken the short way.
fn parameter_step(x: &PosedSolid, face: FaceId, from: [f64; 2], to: [f64; 2]) -> [f64; 2] {
    std::array::from_fn(|i| {
        let range = x.range(face, i);
        let d = to[i] - from[i];
        if range.periodic {
            let span = range.span();
            d - span * (d / span).round()
        } else {
            d
        }
    })
}
