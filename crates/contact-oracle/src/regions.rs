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
//! proves that j is no separate minimum at resolution η. The path walks one point straight in
//! the parameters of a face that holds both points of that side (u wrapped the short way
//! round where periodic, every step inside the face's trim), and the distance along it is the
//! signed distance of the walking point to the other solid (its foot followed from step to
//! step, [`penetration::signed_distance`]), which is never below the distance between the
//! two surfaces along the path of pairs (point, foot). Minima on different faces of both solids
//! are not compared (kept apart), nor are they when a step's projection does not converge.

use crate::penetration;
use crate::polish::{Limits, Pair};
use crate::posed::PosedSolid;
use crate::report::{OracleContact, RegionMember};
use geom_param::FaceId;

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

/// Whether the straight path from `lower` to `higher` (on a face holding both points of one
/// side) keeps the distance at or below `higher.distance + resolution`, with the path's ends
/// reproducing both distances to `resolution`.
fn joined(
    a: &PosedSolid,
    b: &PosedSolid,
    lower: &OracleContact,
    higher: &OracleContact,
    limits: &Limits,
    resolution: f64,
) -> bool {
    let on_a = lower.face_a == higher.face_a;
    if !on_a && lower.face_b != higher.face_b {
        return false;
    }
    // The walking side x and the other side y; the pair is (x's point, y's foot).
    let (x, y, face, from, to, foot_face, foot) = if on_a {
        (
            a,
            b,
            lower.face_a,
            lower.params_a,
            higher.params_a,
            lower.face_b,
            lower.params_b,
        )
    } else {
        (
            b,
            a,
            lower.face_b,
            lower.params_b,
            higher.params_b,
            lower.face_a,
            lower.params_a,
        )
    };
    let step = parameter_step(x, face, from, to);
    let mut pair = Pair::faces(face, from, foot_face, foot);
    let mut highest = f64::NEG_INFINITY;
    for k in 0..=PATH_STEPS {
        let t = k as f64 / PATH_STEPS as f64;
        let uv = x.normalize(face, [from[0] + t * step[0], from[1] + t * step[1]]);
        if !x.inside(face, uv) {
            return false;
        }
        (pair.fa, pair.a) = (face, uv);
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
