//! The mutual-nearest test of a penetration witness: its two points must be nearest boundary
//! points of each other, not a critical pair measured through the material.
//!
//! A penetration witness (p_a on A, p_b on B, depth δ = |p_b − p_a|, opposed normals) is a
//! critical pair of ½|P_a − P_b|² on two *features*; Stage 3 sees only those features, so it
//! cannot tell a true witness from a critical pair that passes through other parts of the two
//! solids (a goblet's rim against the other goblet's inner cup, 127.5 mm "deep" through its
//! outer wall: `xtask/tests/soak_regressions.rs`). What tells them apart is the rest of the
//! boundary, which only a global query knows: [`NearestBoundary`] (in the pipeline, Stage 2's
//! meshes with their chordal error bound).
//!
//! The rule: p_b must be the nearest point of B's boundary to p_a *along the witness*, and
//! p_a the nearest point of A's boundary to p_b: the segment p_a p_b meets B's boundary only
//! at p_b and A's only at p_a (it lies in both solids, inside the lens of the overlap). That
//! is certified by sphere tracing: from x = p_a, a nearest-boundary query bounds the distance
//! from x to B's boundary below by r = d_mesh − e (e the mesh's error bound); no point of B's
//! boundary lies in the ball of radius r around x, so x advances by r towards p_b. The witness
//! passes when a ball reaches within 2e + τ of p_b (τ: rounding, 1e-9 of the coordinates), and
//! fails when the trace stalls farther away (B's mesh within 2e of the segment: B's exact
//! boundary within 3e of it, away from p_b). Then the same from p_b towards p_a against A.
//! For a witness whose p_b is B's globally nearest boundary point to p_a (spheres, any convex
//! B within its focal distance) the first ball already reaches p_b: one query per side.
//!
//! A side whose point is on an edge or at a vertex is not traced: the segment leaves such a
//! point along a direction of its normal cone, not along a face normal, so that side's own
//! boundary grazes the segment next to the point (a pencil's apex poking 0.48 mm into the
//! bowl's bottom, its cone at 45° to the segment: the cone's side passes within
//! ρ sin 25° of the segment ρ from the apex), which a trace with a 0.05 mm mesh cannot tell
//! from a wall. Such a point is certified by the refiner's normal-cone test, and the other
//! point, on a face, by the trace from it. (The through-material goblet pair has A's point on
//! A's rim edge and B's on B's inner cup, a face: the trace against B rejects it.)
//!
//! Why not "globally nearest": a pencil pushed more than half-way into a bowl's wall has the
//! wall's far side nearer to its tip than the side it entered through, yet the entry side is
//! the depth a physics engine must undo; the segment rule accepts that witness (the segment
//! crosses no boundary) and still rejects the through-material pair (it crosses B's outer wall
//! and the cavity).

use crate::refiner::RefinedContact;
use geom_param::{DPose3, DVec3, FeatureLocation};

/// The nearest point of one object's boundary to a query point, as a global representation of
/// the object (for instance Stage 2's meshes) knows it.
///
/// # Contract
/// For `local_point` in the object's own frame (mm), [`BoundaryDistance::distance`] is the
/// distance from it to *some* representation of the whole boundary (every face of the solid),
/// and the exact distance to the solid's boundary lies within
/// [`BoundaryDistance::error_bound`] of it. `None` when the query cannot answer (a non-finite
/// point, an object without a boundary representation).
pub trait NearestBoundary {
    /// The nearest boundary point to `local_point` (object frame, mm) with its distance and
    /// error bound; `None` when unknown.
    fn nearest_boundary(&self, local_point: DVec3) -> Option<BoundaryDistance>;
}

/// What a [`NearestBoundary`] query returns (object frame, mm).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BoundaryDistance {
    /// The nearest point of the representation (object frame, mm).
    pub point: DVec3,
    /// Its distance to the query point (mm).
    pub distance: f64,
    /// Bound (mm) on |exact boundary distance − `distance`| (for a mesh: its chordal error).
    pub error_bound: f64,
}

/// Which side's boundary a [`WitnessCheck::ThroughMaterial`] trace ran into.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WitnessSide {
    /// The segment from `point_a` towards `point_b` met B's boundary before `point_b`.
    B,
    /// The segment from `point_b` towards `point_a` met A's boundary before `point_a`.
    A,
}

/// The verdict of [`check_witness`] on a penetration witness.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum WitnessCheck {
    /// Certified: the segment `point_a` `point_b` meets B's boundary only within
    /// 2e_B + τ of `point_b` and A's only within 2e_A + τ of `point_a` (e: the error bounds of
    /// the [`NearestBoundary`] queries, τ = 1e-9 of the coordinates), each side traced where
    /// its point is on a face (see the module docs). Also for a pair that does not penetrate
    /// (nothing to check).
    MutuallyNearest,
    /// Not a witness: the boundary of `side` passes within 3e of the segment, farther than
    /// 2e + τ from the segment's end on that side: the pair is measured through the material.
    ThroughMaterial {
        /// Whose boundary the trace met.
        side: WitnessSide,
        /// Distance (mm) from the trace's start to where it stalled.
        at: f64,
    },
    /// The queries could not decide: one answered `None` (non-finite points included), or the
    /// trace took more than [`MAX_TRACE_STEPS`] balls (a segment grazing a boundary).
    Undecided,
}

/// Sphere-tracing steps per side before [`WitnessCheck::Undecided`]: a ball per step, each at
/// least e wide, and a segment well inside the solid is covered by one or two.
pub const MAX_TRACE_STEPS: u32 = 64;

/// Checks that `witness` (A's frame, B posed by `pose_ab`: point_in_a = pose_ab * point_in_b)
/// is a pair of mutually nearest boundary points, as described in the module docs: the trace
/// against B when `location_b` is a face, against A when `location_a` is. `near_a`
/// answers in A's frame, `near_b` in B's own frame. A witness with `distance >= 0` (not
/// penetrating) or with non-finite points is returned as [`WitnessCheck::MutuallyNearest`]
/// and [`WitnessCheck::Undecided`] respectively.
#[must_use]
pub fn check_witness(
    pose_ab: &DPose3,
    witness: &RefinedContact,
    near_a: &dyn NearestBoundary,
    near_b: &dyn NearestBoundary,
) -> WitnessCheck {
    let (pa, pb) = (witness.point_a, witness.point_b);
    if !(pa.is_finite() && pb.is_finite() && witness.distance.is_finite()) {
        return WitnessCheck::Undecided;
    }
    if witness.distance >= 0.0 {
        return WitnessCheck::MutuallyNearest;
    }
    let rounding = 1e-9 * (pa.length() + pb.length() + pa.distance(pb));
    let b_from_a = pose_ab.inverse();
    let to_b = |x: DVec3| near_b.nearest_boundary(b_from_a * x);
    let to_a = |x: DVec3| near_a.nearest_boundary(x);
    let on_face = |l: &FeatureLocation| matches!(l, FeatureLocation::Face { .. });
    let reached = |start, end, query: &dyn Fn(DVec3) -> Option<BoundaryDistance>, end_on_face| {
        if end_on_face {
            trace(start, end, rounding, query)
        } else {
            Trace::Reached
        }
    };
    match reached(pa, pb, &to_b, on_face(&witness.location_b)) {
        Trace::Reached => {}
        Trace::Stalled(at) => {
            return WitnessCheck::ThroughMaterial {
                side: WitnessSide::B,
                at,
            };
        }
        Trace::Unknown => return WitnessCheck::Undecided,
    }
    match reached(pb, pa, &to_a, on_face(&witness.location_a)) {
        Trace::Reached => WitnessCheck::MutuallyNearest,
        Trace::Stalled(at) => WitnessCheck::ThroughMaterial {
            side: WitnessSide::A,
            at,
        },
        Trace::Unknown => WitnessCheck::Undecided,
    }
}

/// How one sphere trace ended.
enum Trace {
    /// A certified ball reached within 2e + τ of the end.
    Reached,
    /// The boundary came within 2e of the segment at this distance from the start (mm).
    Stalled(f64),
    /// A query answered `None`, or the step cap was hit.
    Unknown,
}

/// Sphere tracing from `start` to `end` (both in A's frame) against the boundary `query`
/// answers for (a point in A's frame in, its nearest boundary point out).
fn trace(
    start: DVec3,
    end: DVec3,
    rounding: f64,
    query: &dyn Fn(DVec3) -> Option<BoundaryDistance>,
) -> Trace {
    let length = start.distance(end);
    let Some(direction) = ((end - start) / length).try_normalize() else {
        return Trace::Reached;
    };
    let mut s = 0.0;
    for _ in 0..MAX_TRACE_STEPS {
        let Some(near) = query(start + direction * s) else {
            return Trace::Unknown;
        };
        let e = near.error_bound.max(0.0);
        if !(near.distance.is_finite() && e.is_finite()) {
            return Trace::Unknown;
        }
        // No exact boundary point within `free` of the current point.
        let free = near.distance - e;
        let remaining = length - s;
        // The ball covers the segment up to 2e + τ before its end (where the end's own surface
        // may be within the bound).
        if free + 2.0 * e + rounding >= remaining {
            return Trace::Reached;
        }
        // The mesh within 2e of the segment (the exact boundary within 3e), more than
        // 2e + τ + free from the end: the segment meets another part of the boundary.
        if free <= e {
            return Trace::Stalled(s);
        }
        s += free;
    }
    Trace::Unknown
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::refiner::{RefineDiagnostics, RefineStatus};
    use geom_param::{FaceId, FeatureLocation};

    /// The exact nearest boundary point of a ball (centre, radius) in its own frame, with a
    /// pretended error bound.
    struct Ball {
        centre: DVec3,
        radius: f64,
        error: f64,
    }

    impl NearestBoundary for Ball {
        fn nearest_boundary(&self, p: DVec3) -> Option<BoundaryDistance> {
            let r = p - self.centre;
            let n = r.try_normalize()?;
            Some(BoundaryDistance {
                point: self.centre + n * self.radius,
                distance: (r.length() - self.radius).abs(),
                error_bound: self.error,
            })
        }
    }

    /// A hollow ball (a shell between two radii): the nearest of its two spheres.
    struct Shell {
        inner: f64,
        outer: f64,
    }

    impl NearestBoundary for Shell {
        fn nearest_boundary(&self, p: DVec3) -> Option<BoundaryDistance> {
            let n = p.try_normalize()?;
            let (di, dout) = (
                (p.length() - self.inner).abs(),
                (p.length() - self.outer).abs(),
            );
            let (radius, distance) = if di < dout {
                (self.inner, di)
            } else {
                (self.outer, dout)
            };
            Some(BoundaryDistance {
                point: n * radius,
                distance,
                error_bound: 1e-3,
            })
        }
    }

    fn witness(point_a: DVec3, point_b: DVec3, distance: f64) -> RefinedContact {
        let location = FeatureLocation::Face {
            id: FaceId(0),
            u: 0.0,
            v: 0.0,
        };
        RefinedContact {
            point_a,
            point_b,
            location_a: location,
            location_b: location,
            distance,
            normal: DVec3::X,
            diagnostics: RefineDiagnostics {
                iterations: 0,
                gradient_norm: 0.0,
                condition: 1.0,
                converged: true,
                is_local_minimum: true,
                error_estimate: 0.0,
                point_error_estimate: 0.0,
                gap_curvature: f64::INFINITY,
                status: RefineStatus::Converged,
            },
        }
    }

    /// Two overlapping balls (radii 10 and 4, centres 12 apart, 2 mm deep): the closed-form
    /// witness (10, 0, 0) / (8, 0, 0) is certified by one ball per side.
    #[test]
    fn overlapping_balls_certify_their_witness() {
        let pose_ab = DPose3 {
            translation: DVec3::new(12.0, 0.0, 0.0),
            rotation: geom_param::DQuat::from_rotation_z(0.7),
        };
        let a = Ball {
            centre: DVec3::ZERO,
            radius: 10.0,
            error: 1e-3,
        };
        let b = Ball {
            centre: DVec3::ZERO,
            radius: 4.0,
            error: 1e-3,
        };
        let good = witness(DVec3::new(10.0, 0.0, 0.0), DVec3::new(8.0, 0.0, 0.0), -2.0);
        assert_eq!(
            check_witness(&pose_ab, &good, &a, &b),
            WitnessCheck::MutuallyNearest
        );
    }

    /// A ball of radius 3 at the origin against a shell (radii 10 and 12) centred at
    /// (-8, 0, 0): A's cap near (3, 0, 0) lies in the shell's wall. Its witness against the
    /// inner sphere, (3, 0, 0) / (2, 0, 0) (normals +x and −x, 1 mm deep), is certified; the
    /// pair from A's (−3, 0, 0), in the cavity, to the outer sphere's (4, 0, 0) crosses the
    /// inner sphere at (2, 0, 0), 5 mm along: through the material. With the roles swapped
    /// the witness is certified again, and a pair crossing the shell's wall fails on A's side.
    #[test]
    fn a_pair_across_a_shell_wall_is_through_material() {
        let shell_at = DVec3::new(-8.0, 0.0, 0.0);
        let ball = Ball {
            centre: DVec3::ZERO,
            radius: 3.0,
            error: 1e-3,
        };
        let shell = Shell {
            inner: 10.0,
            outer: 12.0,
        };
        let pose_ab = DPose3 {
            translation: shell_at,
            rotation: geom_param::DQuat::IDENTITY,
        };
        let real = witness(DVec3::new(3.0, 0.0, 0.0), DVec3::new(2.0, 0.0, 0.0), -1.0);
        assert_eq!(
            check_witness(&pose_ab, &real, &ball, &shell),
            WitnessCheck::MutuallyNearest
        );
        let through = witness(DVec3::new(-3.0, 0.0, 0.0), DVec3::new(4.0, 0.0, 0.0), -7.0);
        match check_witness(&pose_ab, &through, &ball, &shell) {
            WitnessCheck::ThroughMaterial {
                side: WitnessSide::B,
                at,
            } => assert!((at - 5.0).abs() < 2e-3, "{at}"),
            other => panic!("{other:?}"),
        }
        // Swapped: the shell is A (at the origin), the ball B at +8 along x.
        let swapped = DPose3 {
            translation: -shell_at,
            rotation: geom_param::DQuat::IDENTITY,
        };
        let moved = |p: DVec3| p - shell_at;
        let real = witness(
            moved(DVec3::new(2.0, 0.0, 0.0)),
            moved(DVec3::X * 3.0),
            -1.0,
        );
        assert_eq!(
            check_witness(&swapped, &real, &shell, &ball),
            WitnessCheck::MutuallyNearest
        );
        // The shell's outer point (−12, 0, 0) against the ball's near pole (5, 0, 0): the
        // segment runs outside the ball, but crosses the shell's inner sphere at (−10, 0, 0),
        // 15 mm from the ball's point.
        let through = witness(
            DVec3::new(-12.0, 0.0, 0.0),
            DVec3::new(5.0, 0.0, 0.0),
            -17.0,
        );
        match check_witness(&swapped, &through, &shell, &ball) {
            WitnessCheck::ThroughMaterial {
                side: WitnessSide::A,
                at,
            } => assert!((at - 15.0).abs() < 2e-3, "{at}"),
            other => panic!("{other:?}"),
        }
    }

    /// The through-material pair of the shell test with one point at a vertex: that side is
    /// not traced (its boundary grazes the segment at an apex), the other still is.
    #[test]
    fn a_side_on_a_vertex_is_not_traced() {
        let pose_ab = DPose3 {
            translation: DVec3::new(-8.0, 0.0, 0.0),
            rotation: geom_param::DQuat::IDENTITY,
        };
        let ball = Ball {
            centre: DVec3::ZERO,
            radius: 3.0,
            error: 1e-3,
        };
        let shell = Shell {
            inner: 10.0,
            outer: 12.0,
        };
        let mut through = witness(DVec3::new(-3.0, 0.0, 0.0), DVec3::new(4.0, 0.0, 0.0), -7.0);
        through.location_b = FeatureLocation::Vertex {
            id: geom_param::VertexId(0),
        };
        // B's side (the shell's inner sphere 5 mm along) is skipped; A's is traced: from B's
        // point (4, 0, 0) towards A's (−3, 0, 0) the ball is entered at (3, 0, 0), 1 mm along.
        match check_witness(&pose_ab, &through, &ball, &shell) {
            WitnessCheck::ThroughMaterial {
                side: WitnessSide::A,
                at,
            } => assert!((at - 1.0).abs() < 2e-3, "{at}"),
            other => panic!("{other:?}"),
        }
        // With B's point on a face again and A's at a vertex, B's side is traced and fails.
        through.location_b = FeatureLocation::Face {
            id: FaceId(0),
            u: 0.0,
            v: 0.0,
        };
        through.location_a = FeatureLocation::Vertex {
            id: geom_param::VertexId(0),
        };
        match check_witness(&pose_ab, &through, &ball, &shell) {
            WitnessCheck::ThroughMaterial {
                side: WitnessSide::B,
                ..
            } => {}
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn non_finite_or_separated_pairs_are_not_traced() {
        let ball = Ball {
            centre: DVec3::ZERO,
            radius: 1.0,
            error: 0.0,
        };
        let nan = witness(DVec3::NAN, DVec3::ZERO, -1.0);
        assert_eq!(
            check_witness(&DPose3::IDENTITY, &nan, &ball, &ball),
            WitnessCheck::Undecided
        );
        let apart = witness(DVec3::X, DVec3::X * 2.0, 1.0);
        assert_eq!(
            check_witness(&DPose3::IDENTITY, &apart, &ball, &ball),
            WitnessCheck::MutuallyNearest
        );
    }
}
