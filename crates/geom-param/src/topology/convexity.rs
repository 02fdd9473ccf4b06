//! Convexity of faces and of the edges between them, decided from the geometry.
//!
//! Any solid ([`classify_convexity`]): a face is sampled for its principal curvatures over its
//! region ([`FACE_SAMPLES`]² points of its parameter box, those inside a trim), an edge for the
//! dihedral turn between its two faces ([`EDGE_SAMPLES`] points along it). Sampling bounds what
//! is seen: a face whose curvature changes sign only between samples (a band narrower than
//! 1/[`FACE_SAMPLES`] of its parameter range) is not caught. For every analytic surface class
//! the sign is constant or changes over wide regions (a torus's inner half), so it is. An edge
//! whose turn changes sign along it is classified [`EdgeConvexity::Concave`]: the conservative
//! side, since a concave component is handled by the proxy-mesh path, which is right for convex
//! geometry too.
//!
//! Solids of revolution use the exact rules below. A revolved face has principal curvatures κ_meridian = (r'z'' - z'r'')/|t|³ and
//! κ_parallel = z'/(r |t|) (see [`crate::RevolvedSurface`]). Both are sign-checked over the whole
//! segment at the points where either can change sign ([`ProfileSegment::sign_breakpoints`]) and
//! between them, so a thin concave band is never missed.

use crate::revolution::profile_segment::ProfileSegment;
use crate::topology::feature::EdgeId;
use crate::topology::solid::{EdgeConvexity, Face, FaceConvexity, Solid};
use glam::DVec2;

/// Relative tolerance below which a curvature or slope counts as zero.
const SIGN_EPS: f64 = 1e-9;

/// Classifies the face swept by `segment`. `scale` is the profile's length scale (mm).
#[must_use]
pub fn classify_revolved_face(segment: &ProfileSegment, scale: f64) -> FaceConvexity {
    if let ProfileSegment::Line(l) = segment {
        let d = l.to - l.from;
        if d.y.abs() <= SIGN_EPS * d.length() {
            return FaceConvexity::Flat;
        }
    }
    let breaks = segment.sign_breakpoints();
    let mut samples = breaks.clone();
    samples.extend(breaks.windows(2).map(|w| 0.5 * (w[0] + w[1])));
    let concave = samples.iter().any(|&s| {
        let p = segment.eval(s);
        let slope = p.d1.y / p.d1.length(); // sign of κ_parallel where r > 0
        let meridian = p.signed_curvature() * scale;
        slope < -SIGN_EPS || meridian < -SIGN_EPS
    });
    if concave {
        FaceConvexity::Concave
    } else {
        FaceConvexity::Convex
    }
}

/// Classifies the edge circle where `before` ends and `after` starts, from the turn of the
/// profile's tangent there: turning left (towards the material) is a ridge.
#[must_use]
pub fn classify_joint(before: &ProfileSegment, after: &ProfileSegment) -> EdgeConvexity {
    let a = before.eval(1.0).d1.normalize();
    let b = after.eval(0.0).d1.normalize();
    let turn = a.perp_dot(b);
    if turn > SIGN_EPS {
        EdgeConvexity::Convex
    } else if turn < -SIGN_EPS {
        EdgeConvexity::Concave
    } else {
        EdgeConvexity::Smooth
    }
}

/// Grid size per parameter of the curvature samples of a face.
pub const FACE_SAMPLES: usize = 12;
/// Samples along an edge for its dihedral turn.
pub const EDGE_SAMPLES: usize = 17;
/// Angle (rad) between the faces' normals below which an edge is tangent-continuous: far above
/// rounding (1e-12) and far below any modelled crease.
const SMOOTH_ANGLE: f64 = 1e-6;

/// Sets every face's and edge's convexity of `solid` from its geometry (see the module doc).
pub fn classify_convexity(solid: &mut Solid) {
    let faces: Vec<FaceConvexity> = solid.faces.iter().map(classify_face).collect();
    for (face, c) in solid.faces.iter_mut().zip(faces) {
        face.convexity = c;
    }
    let edges: Vec<EdgeConvexity> = (0..solid.edges.len())
        .map(|e| {
            classify_edge(
                solid,
                EdgeId(u32::try_from(e).expect("fewer than 2^32 edges")),
            )
        })
        .collect();
    for (edge, c) in solid.edges.iter_mut().zip(edges) {
        edge.convexity = c;
    }
}

/// The convexity of a face from its principal curvatures at the samples of its region, with a
/// curvature counted as zero below [`SIGN_EPS`] / (the face's extent).
#[must_use]
pub fn classify_face(face: &Face) -> FaceConvexity {
    let domain = face.surface.domain();
    let (lo, hi) = match &face.trim {
        Some(trim) => trim.bounds(),
        None => (
            DVec2::new(domain[0].min, domain[1].min),
            DVec2::new(domain[0].max, domain[1].max),
        ),
    };
    let n = FACE_SAMPLES;
    let mut curvatures = Vec::with_capacity(n * n);
    let mut extent_lo = glam::DVec3::splat(f64::INFINITY);
    let mut extent_hi = glam::DVec3::splat(f64::NEG_INFINITY);
    for i in 0..n {
        for j in 0..n {
            // Cell centres: the sides themselves may be poles with no curvature.
            let uv = lo
                + (hi - lo) * DVec2::new((i as f64 + 0.5) / n as f64, (j as f64 + 0.5) / n as f64);
            if let Some(trim) = &face.trim {
                if !trim.contains(uv, 0.0) {
                    continue;
                }
            }
            let p = face.surface.eval(uv.x, uv.y).point;
            extent_lo = extent_lo.min(p);
            extent_hi = extent_hi.max(p);
            if let Some(k) = face.surface.principal_curvatures(uv.x, uv.y) {
                curvatures.push(k);
            }
        }
    }
    let extent = (extent_hi - extent_lo).max_element().max(f64::MIN_POSITIVE);
    let eps = SIGN_EPS / extent;
    if curvatures.iter().any(|k| k.min < -eps) {
        FaceConvexity::Concave
    } else if curvatures
        .iter()
        .all(|k| k.max.abs() <= eps && k.min.abs() <= eps)
    {
        FaceConvexity::Flat
    } else {
        FaceConvexity::Convex
    }
}

/// The convexity of edge `id` from the turn between its faces along it: with w the direction
/// from the edge into its first face and n₂ the second face's normal, the edge is a ridge where
/// n₂ · w < 0 (the second face turns away from the first's side), a valley where > 0, smooth
/// where the normals agree within [`SMOOTH_ANGLE`] at every sample.
///
/// # Panics
/// If the id does not belong to `solid`.
#[must_use]
pub fn classify_edge(solid: &Solid, id: EdgeId) -> EdgeConvexity {
    let edge = solid.edge(id);
    let range = edge.curve.domain();
    let (mut convex, mut concave) = (false, false);
    for k in 0..EDGE_SAMPLES {
        // Inner samples only: at an edge's end a face may have no normal (an apex).
        let t = range.min + range.span() * (k as f64 + 0.5) / EDGE_SAMPLES as f64;
        let [first, second] = &edge.uses;
        let normal_of = |use_: &crate::topology::solid::EdgeUse| {
            let [u, v] = solid.use_params(use_, t);
            let [ru, rv] = solid.face(use_.face).surface.domain();
            solid
                .face(use_.face)
                .surface
                .normal(ru.normalize(u), rv.normalize(v))
        };
        let (Some(n1), Some(n2)) = (normal_of(first), normal_of(second)) else {
            continue;
        };
        if n1.cross(n2).length() <= SMOOTH_ANGLE && n1.dot(n2) > 0.0 {
            continue;
        }
        let [u, v] = solid.use_params(first, t);
        let [ru, rv] = solid.face(first.face).surface.domain();
        let s = solid
            .face(first.face)
            .surface
            .eval(ru.normalize(u), rv.normalize(v));
        let inward = solid.use_inward(first, t);
        let w = s.du * inward.x + s.dv * inward.y;
        if n2.dot(w) < 0.0 {
            convex = true;
        } else {
            concave = true;
        }
    }
    match (convex, concave) {
        (_, true) => EdgeConvexity::Concave,
        (true, false) => EdgeConvexity::Convex,
        (false, false) => EdgeConvexity::Smooth,
    }
}
