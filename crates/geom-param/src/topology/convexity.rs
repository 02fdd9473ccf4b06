//! Convexity of revolved faces and of the edges between them, decided from the geometry.
//!
//! A revolved face has principal curvatures κ_meridian = (r'z'' - z'r'')/|t|³ and
//! κ_parallel = z'/(r |t|) (see [`crate::RevolvedSurface`]). Both are sign-checked over the whole
//! segment at the points where either can change sign ([`ProfileSegment::sign_breakpoints`]) and
//! between them, so a thin concave band is never missed.

use crate::revolution::profile_segment::ProfileSegment;
use crate::topology::solid::{EdgeConvexity, FaceConvexity};

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
