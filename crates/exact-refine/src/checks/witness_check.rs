//! The nearest-boundary test of a penetration witness: one of its points must lie inside the
//! other solid with the other point as its nearest boundary point, so that the pair's distance
//! is that point's depth, not a critical pair measured through the material.
//!
//! A penetration witness (p_a on A, p_b on B, depth δ = |p_b − p_a|, opposed normals) is a
//! critical pair of ½|P_a − P_b|² on two *features*; Stage 3 sees only those features, so it
//! cannot tell a true witness from a critical pair that passes other parts of the two solids
//! (a goblet's rim against the other goblet's inner cup, 127.5 mm "deep" through its outer
//! wall: `xtask/tests/soak_regressions.rs`). What tells them apart is the rest of the
//! boundary, which only a global query knows: [`NearestBoundary`] (in the pipeline, Stage 2's
//! meshes with their chordal error bound, and the exact solid behind them).
//!
//! The rule: the pair is a witness when, for one side x with the other side y, no point of
//! y's boundary is nearer to p_x than δ (less τ: rounding, 1e-9 of the coordinates) and p_x
//! lies inside y (behind y's outward direction at p_y: the face normal, or the mean around an
//! edge, corner or apex). Then δ is the depth of p_x in y, and the pair, a critical pair, a
//! local extreme of that depth over x's boundary: the signed distance field of y sampled on
//! x's boundary, as a physics engine pushes the solids apart. Where both points lie on edges
//! or at vertices, the faces that hold p_y are left out: p_x lies in p_y's cone of normals
//! (Stage 3's critical-pair condition), and the flank beside an edge passes nearer to a point
//! inside the wedge than the edge does (two sharp rims crossing 1e-3 mm deep: the depth is the
//! edges' distance, the translation that separates them). Two crossing wedges hold each
//! other's points, so there the rule must hold both ways: each point inside the other solid,
//! with no boundary point but the other's flanks nearer. A tube's inner rim point 0.3 mm
//! inside a loft's side face, 15.4 mm from the loft's end ellipse, is no witness: the side
//! face, which holds the ellipse, is left out, but the ellipse's point has the tube's outer
//! wall nearer than the rim (`contact-pipeline`'s fast-trajectory coherence test). A point on
//! a face inside the other
//! solid's wedge is measured to the flanks: a goblet rim's corner inside the other goblet's
//! rim, against its outer wall 0.76 mm away, is no witness, the rim's top being nearer. The
//! other direction need not hold, and often does not: a pencil's apex
//! 4.7e-4 mm inside a goblet's wall has the wall point as its nearest, while the cone's flank
//! is nearer to the wall point than the apex; a pencil's ferrule point 0.159 mm inside a
//! goblet's wall has the goblet's point as its nearest, while that point, inside the pencil
//! under the ferrule's step, is nearer to the step's edge. The oracle applies the same rule
//! (`contact_oracle`'s `found::through_material`), whose witnesses always have a point on a
//! face.
//!
//! How it is decided: the representation's nearest distance d_r with error bound e settles
//! what it can (d_r − e >= δ − τ: nothing nearer; for p_y on a face, d_r + e < δ − τ: a nearer
//! point). Otherwise, since δ is a distance to the boundary itself, a bound cannot certify it,
//! and the exact distance is measured where the representation knows its solid and the faces
//! near a point ([`NearestBoundary::solid`], [`NearestBoundary::faces_near`]): a Newton
//! projection onto each face whose representation comes within δ + e, from the
//! representation's nearest parameters on it (skipping the flanks left out, and any
//! projection that slides onto one).
//!
//! A pair that fails may still have a point inside the other solid: a bracket's corner pushed
//! 2 µm into a tube's top rim had its one critical pair (the rim against the bracket's edge, √2
//! times the depth) measured past the cap and the wall, while that edge point lay 1.12 µm inside
//! the tube. Where the exact solid is known, such a point is measured to its exact nearest
//! boundary point over every face that comes that near (flanks included), and the verdict is
//! [`WitnessCheck::Overlapping`] with that depth: the solids overlap at least so deep, though
//! the pair is no witness of it.
//!
//! Until session 14 the test traced the segment p_a p_b against the meshes instead (it had to
//! meet B's boundary only at p_b and A's only at p_a). That stalled within the meshes' error of
//! boundaries the segment only grazes (a goblet's wall 0.0135 mm under a pencil's ferrule
//! step), and accepted pairs measured past a nearer face that the segment runs beside (the
//! apex above against the goblet rim's top face, 0.114 mm up, the vertical being in the apex's
//! cone of normals). What it kept and this rule gives up: a pencil pushed more than half-way
//! through a bowl's wall is measured to the wall's far side, the nearer one.

use crate::features::feature_eval::{Body, Frame};
use crate::options::NewtonOptions;
use crate::refined_contact::RefinedContact;
use crate::solver::newton::{Outcome, Reentry, minimize_projection};
use geom_param::{DPose3, DVec3, FeatureLocation, Solid};

/// The nearest point of one object's boundary to a query point, as a global representation of
/// the object (for instance Stage 2's meshes) knows it.
///
/// # Contract
/// For `local_point` in the object's own frame (mm), [`BoundaryDistance::distance`] is the
/// distance from it to *some* representation of the whole boundary (every face of the solid),
/// and the exact distance to the solid's boundary lies within
/// [`BoundaryDistance::error_bound`] of it. Only boundary points within `reach` (mm) are
/// asked for: where the representation has no point within `reach` + its error bound, the
/// answer may say so with `distance` = +∞ (and `point` = `local_point`); then the exact
/// boundary is farther than `reach`. `None` when the query cannot answer (a non-finite point,
/// an object without a boundary representation).
pub trait NearestBoundary {
    /// The nearest boundary point to `local_point` (object frame, mm) with its distance and
    /// error bound, or +∞ where none is within `reach` (see the contract); `None` when
    /// unknown.
    fn nearest_boundary(&self, local_point: DVec3, reach: f64) -> Option<BoundaryDistance>;

    /// The exact solid the representation stands for, in the same (object) frame, when known.
    /// With [`Self::faces_near`] it lets [`check_witness`] measure the exact boundary's
    /// distance where the representation's error bound cannot decide. Default: unknown.
    fn solid(&self) -> Option<&Solid> {
        None
    }

    /// Every face of [`Self::solid`] whose representation comes within `radius` (mm) of
    /// `local_point` (object frame), each once, at the parameters of its representation's point
    /// nearest to `local_point`: a face whose exact surface is within `radius` − e of the point
    /// (e: [`BoundaryDistance::error_bound`]) must be among them. Default: none known.
    fn faces_near(&self, _local_point: DVec3, _radius: f64) -> Vec<FeatureLocation> {
        Vec::new()
    }

    /// The unit outward direction (object frame) of the boundary at `location`, whose point is
    /// `local_point`: what tells a point inside from one outside where that boundary point is
    /// its nearest. Default: from [`Self::solid`] ([`Body::outward`]: the face normal, the
    /// normalised mean of the face normals around an edge or corner, the axis of an apex);
    /// `None` without a solid.
    fn outward(&self, _local_point: DVec3, location: FeatureLocation) -> Option<DVec3> {
        let body = Body::Solid {
            solid: self.solid()?,
            frame: Frame::identity(),
            within: None,
        };
        body.outward(&Some(location))
    }
}

/// What a [`NearestBoundary`] query returns (object frame, mm).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BoundaryDistance {
    /// The nearest point of the representation (object frame, mm).
    pub point: DVec3,
    /// Its distance to the query point (mm); +∞ when no point lies within the query's reach
    /// (then `point` is the query point).
    pub distance: f64,
    /// Bound (mm) on |exact boundary distance − `distance`| (for a mesh: its chordal error).
    pub error_bound: f64,
}

/// Which side of a [`WitnessCheck::ThroughMaterial`] pair is reported.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WitnessSide {
    /// B's boundary passes nearer to `point_a` than `point_b` does (or `point_a` is outside
    /// B).
    B,
    /// A's boundary passes nearer to `point_b` than `point_a` does (or `point_b` is outside
    /// A).
    A,
}

/// The verdict of [`check_witness`] on a penetration witness.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum WitnessCheck {
    /// Certified (see the module docs): one point lies inside the other solid, and no point of
    /// that solid's boundary (but, between two edges or vertices, the flanks of the other
    /// point) is nearer to it than the depth less τ = 1e-9 of the coordinates; between two
    /// edges or vertices, both ways. Also for a pair that does not penetrate (nothing to
    /// check).
    Certified,
    /// Not a witness: neither side holds, the pair is measured through the material. `side`
    /// is the first side that found a nearer boundary point (A's point against B's boundary
    /// first, unless A's point is on a face and B's is not), or B where both points are only
    /// outside.
    ThroughMaterial {
        /// Whose boundary passes nearer.
        side: WitnessSide,
        /// Distance (mm) from the other solid's point to that nearer boundary point (the depth
        /// itself where the points are only outside).
        at: f64,
    },
    /// Not a witness, as [`WitnessCheck::ThroughMaterial`], but the point whose other solid's
    /// boundary passes nearer lies inside that solid: its exact nearest boundary point (over
    /// every face of the solid that comes that near) is `depth` (mm) away, with the point behind
    /// the boundary's outward direction there. The solids then overlap at least `depth` deep
    /// (the pair's point is on its own boundary), though the pair does not measure it.
    Overlapping {
        /// Whose boundary holds the point (B: A's point lies inside B).
        side: WitnessSide,
        /// The point's exact distance (mm) to that solid's boundary.
        depth: f64,
    },
    /// The queries could not decide: one answered `None` (non-finite points included), an
    /// exact distance was needed and not had (no solid, or a projection that did not
    /// converge), or the outward direction was unknown.
    Undecided,
}

/// Checks `witness` (A's frame, B posed by `pose_ab`: point_in_a = pose_ab * point_in_b) as
/// described in the module docs: A's point against B's boundary (`near_b`, which answers in
/// B's own frame), then B's point against A's (`near_a`, in A's frame), the other way round
/// when A's point is on a face and B's is not (the order changes what is queried, not the
/// verdict, but for [`WitnessCheck::ThroughMaterial`]'s side). A witness with
/// `distance >= 0` (not penetrating) is [`WitnessCheck::Certified`]; one with non-finite
/// points [`WitnessCheck::Undecided`].
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
        return WitnessCheck::Certified;
    }
    let depth = pa.distance(pb);
    let limit = depth - 1e-9 * (pa.length() + pb.length() + depth);
    let b_from_a = pose_ab.inverse();
    // (the other solid's boundary, the point in its frame, its own point there and location)
    let mut sides = [
        (
            near_b,
            b_from_a * pa,
            b_from_a * pb,
            witness.location_b,
            WitnessSide::B,
        ),
        (near_a, pb, pa, witness.location_a, WitnessSide::A),
    ];
    // Flanks are left out only between two sharp points, and then both sides must hold (see
    // the module docs).
    let on_face = |l: &FeatureLocation| matches!(l, FeatureLocation::Face { .. });
    let sharp = !on_face(&witness.location_a) && !on_face(&witness.location_b);
    // A sharp point (edge or vertex) against a face is the one that usually lies inside (a
    // pencil's apex in a bowl's wall, whose face point has the apex's flank nearer): tested
    // first, it certifies the witness without the other side's queries.
    if on_face(&witness.location_a) && !on_face(&witness.location_b) {
        sides.swap(0, 1);
    }
    let mut undecided = false;
    let mut nearer: Option<(WitnessSide, f64)> = None;
    // Per side: whether its point lies inside the other solid with no boundary point nearer.
    let mut holds = [false; 2];
    // Per side: the distance of a boundary point of the other solid to this side's point (the
    // nearer one found, or, between two sharp points, the other point where none but its flanks
    // is nearer; elsewhere the other point is then the nearest, and `holds` decides), with the
    // representation's error bound.
    let mut nearer_at = [None; 2];
    for (k, &(near, point, own_point, own, side)) in sides.iter().enumerate() {
        // Only a boundary point nearer than `limit` matters (one farther, by the error bound,
        // answers `No` as none within reach does).
        let found = near.nearest_boundary(point, limit);
        let error = found.map_or(f64::INFINITY, |f| f.error_bound.max(0.0));
        match found.map_or(Nearer::Unknown, |f| {
            nearer_than(near, &f, point, limit, sharp.then_some(own))
        }) {
            Nearer::At(at) => {
                nearer.get_or_insert((side, at));
                nearer_at[k] = Some((at, error));
            }
            Nearer::Unknown => undecided = true,
            Nearer::No => {
                nearer_at[k] = sharp.then_some((depth, error));
                match near.outward(own_point, own) {
                    Some(n) => holds[k] = (point - own_point).dot(n) < 0.0,
                    None => undecided = true,
                }
            }
        }
        if holds[k] && !sharp {
            return WitnessCheck::Certified;
        }
    }
    if holds == [true, true] {
        return WitnessCheck::Certified;
    }
    if undecided {
        return WitnessCheck::Undecided;
    }
    // The deeper of the points that lie inside the other solid, flanks and all, if any.
    let overlapping = (sides.iter().zip(nearer_at))
        .filter_map(|(&(near, point, _, _, side), at)| {
            Some((side, depth_inside(near, point, at?)?))
        })
        .max_by(|x, y| x.1.total_cmp(&y.1));
    if let Some((side, depth)) = overlapping {
        return WitnessCheck::Overlapping { side, depth };
    }
    let (side, at) = nearer.unwrap_or((WitnessSide::B, depth));
    WitnessCheck::ThroughMaterial { side, at }
}

/// The exact distance (mm) from `local` (in `near`'s frame) to `near`'s boundary when `local`
/// lies inside the solid; `None` when it lies outside, or where that is not decided. `at` (mm)
/// is the distance of some point of the boundary, a representation's or the exact one's, and
/// `e` the representation's error bound, so the exact nearest point is within `at` + e and its
/// face is listed within `at` + 2e ([`NearestBoundary::faces_near`]). Each listed face is
/// projected onto (the flanks included: inside means inside the whole solid), and `local` is
/// inside when it lies behind the outward direction at the nearest of those points (the face
/// normal there; around an edge or corner, the mean, as [`NearestBoundary::outward`]). Any
/// projection that does not converge leaves it undecided.
fn depth_inside(near: &dyn NearestBoundary, local: DVec3, (at, e): (f64, f64)) -> Option<f64> {
    if !(e.is_finite() && at.is_finite()) {
        return None;
    }
    let solid = near.solid()?;
    let (depth, point, location) = nearest_on_faces(near, solid, local, at + 2.0 * e, None)?;
    let outward = near.outward(point, location?)?;
    ((local - point).dot(outward) < 0.0).then_some(depth)
}

/// The nearest exact boundary point to `local` (in `near`'s frame) over the faces of `solid`
/// that `near` lists within `radius` (mm, [`NearestBoundary::faces_near`]), each by Stage 3's
/// projection from the listed parameters, leaving out the faces that hold `flanked` and any
/// projection that slid onto a face beside it ([`Solid::beside`]): its distance (mm), point and
/// location (`None` for no face), or ∞ when none counts. `None` when a projection does not
/// converge.
fn nearest_on_faces(
    near: &dyn NearestBoundary,
    solid: &Solid,
    local: DVec3,
    radius: f64,
    flanked: Option<FeatureLocation>,
) -> Option<(f64, DVec3, Option<FeatureLocation>)> {
    let body = Body::Solid {
        solid,
        frame: Frame::identity(),
        within: None,
    };
    let options = NewtonOptions::default();
    let mut nearest = (f64::INFINITY, local, None);
    for start in near.faces_near(local, radius) {
        let FeatureLocation::Face { id, .. } = start else {
            continue;
        };
        if flanked.is_some_and(|own| solid.face_holds(id, &own)) {
            continue;
        }
        let solution =
            minimize_projection(&body, local, Some(start), 0.0, &options, Reentry::Allowed);
        if solution.outcome != Outcome::Converged {
            return None;
        }
        // A projection that slid onto a flank left out does not count.
        let state = &solution.state;
        let slid = |own: FeatureLocation| state.la.is_some_and(|l| solid.beside(&l, &own));
        let distance = state.d.length();
        if !flanked.is_some_and(slid) && distance < nearest.0 {
            nearest = (distance, state.ea.point, state.la);
        }
    }
    Some(nearest)
}

/// Whether a boundary comes nearer than some distance to a point.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Nearer {
    /// No boundary point nearer.
    No,
    /// A boundary point at this distance (mm), nearer.
    At(f64),
    /// Not decided.
    Unknown,
}

/// Whether `near`'s boundary has a point nearer than `limit` (mm) to `local` (its own frame),
/// leaving out the faces that hold `flanked` (the pair's point on this boundary, an edge or a
/// vertex) when given ([`Solid::face_holds`]): the representation's answer where its error
/// bound settles it, otherwise the exact distance to each face its representation lists
/// within `limit` + e (a face with a point nearer than `limit` has its representation within
/// `limit` + e), by Stage 3's projection from the listed parameters (a local Newton
/// minimisation on the face, its edges and vertices, back into the face where the distance
/// falls into it: the face's nearest point when the listed start is near it), not counting a
/// projection that slid onto a face left out ([`Solid::beside`]). `found` is the
/// representation's nearest point to `local`, asked for within `limit`.
fn nearer_than(
    near: &dyn NearestBoundary,
    found: &BoundaryDistance,
    local: DVec3,
    limit: f64,
    flanked: Option<FeatureLocation>,
) -> Nearer {
    let e = found.error_bound.max(0.0);
    if found.distance.is_nan() || found.distance < 0.0 || !e.is_finite() {
        return Nearer::Unknown;
    }
    if found.distance - e >= limit {
        return Nearer::No;
    }
    if flanked.is_none() && found.distance + e < limit {
        return Nearer::At(found.distance);
    }
    let Some(solid) = near.solid() else {
        return Nearer::Unknown;
    };
    match nearest_on_faces(near, solid, local, limit + e, flanked) {
        None => Nearer::Unknown,
        Some((best, ..)) if best < limit => Nearer::At(best),
        Some(_) => Nearer::No,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::refined_contact::{RefineDiagnostics, RefineStatus};
    use geom_param::{EdgeId, FaceId, FeatureLocation};

    /// The exact nearest boundary point of a ball (centre, radius) in its own frame, with a
    /// claimed error bound.
    struct Ball {
        centre: DVec3,
        radius: f64,
        error: f64,
    }

    impl NearestBoundary for Ball {
        fn nearest_boundary(&self, p: DVec3, _reach: f64) -> Option<BoundaryDistance> {
            let r = p - self.centre;
            let n = r.try_normalize()?;
            Some(BoundaryDistance {
                point: self.centre + n * self.radius,
                distance: (r.length() - self.radius).abs(),
                error_bound: self.error,
            })
        }

        fn outward(&self, p: DVec3, _location: FeatureLocation) -> Option<DVec3> {
            (p - self.centre).try_normalize()
        }
    }

    /// A hollow ball (a shell between two radii about the origin), exact.
    struct Shell {
        inner: f64,
        outer: f64,
    }

    impl NearestBoundary for Shell {
        fn nearest_boundary(&self, p: DVec3, _reach: f64) -> Option<BoundaryDistance> {
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
                error_bound: 0.0,
            })
        }

        /// Outwards on the outer sphere, towards the centre on the inner one.
        fn outward(&self, p: DVec3, _location: FeatureLocation) -> Option<DVec3> {
            let n = p.try_normalize()?;
            Some(if p.length() > 0.5 * (self.inner + self.outer) {
                n
            } else {
                -n
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
    /// witness (10, 0, 0) / (8, 0, 0) is certified, each point the other ball's nearest. With
    /// an error bound and no exact solid behind it, a distance to the boundary equal to the
    /// depth cannot be certified: undecided.
    #[test]
    fn overlapping_balls_certify_their_witness() {
        let pose_ab = DPose3 {
            translation: DVec3::new(12.0, 0.0, 0.0),
            rotation: geom_param::DQuat::from_rotation_z(0.7),
        };
        let ball = |radius: f64, error: f64| Ball {
            centre: DVec3::ZERO,
            radius,
            error,
        };
        let good = witness(DVec3::new(10.0, 0.0, 0.0), DVec3::new(8.0, 0.0, 0.0), -2.0);
        assert_eq!(
            check_witness(&pose_ab, &good, &ball(10.0, 0.0), &ball(4.0, 0.0)),
            WitnessCheck::Certified
        );
        assert_eq!(
            check_witness(&pose_ab, &good, &ball(10.0, 1e-3), &ball(4.0, 1e-3)),
            WitnessCheck::Undecided
        );
    }

    /// A ball of radius 3 at the origin against a shell (radii 10 and 12) centred at
    /// (-8, 0, 0): A's cap near (3, 0, 0) lies in the shell's wall. Its witness against the
    /// inner sphere, (3, 0, 0) / (2, 0, 0) (1 mm deep), is certified; the pair from A's
    /// (−3, 0, 0), in the cavity, to the outer sphere's (4, 0, 0), 7 mm, is not: the inner
    /// sphere passes 5 mm from A's point, and the ball 1 mm from B's. With the roles swapped
    /// the witness is certified again; in the pair from the shell's outer point (−12, 0, 0) to
    /// the ball's near pole (5, 0, 0) the shell's point is outside the ball (the pole its
    /// nearest point) and the shell's inner sphere passes 5 mm from the pole.
    #[test]
    fn a_pair_across_a_shell_wall_is_through_material() {
        let shell_at = DVec3::new(-8.0, 0.0, 0.0);
        let ball = Ball {
            centre: DVec3::ZERO,
            radius: 3.0,
            error: 0.0,
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
            WitnessCheck::Certified
        );
        let through = witness(DVec3::new(-3.0, 0.0, 0.0), DVec3::new(4.0, 0.0, 0.0), -7.0);
        match check_witness(&pose_ab, &through, &ball, &shell) {
            WitnessCheck::ThroughMaterial {
                side: WitnessSide::B,
                at,
            } => assert!((at - 5.0).abs() < 1e-12, "{at}"),
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
            WitnessCheck::Certified
        );
        let through = witness(
            DVec3::new(-12.0, 0.0, 0.0),
            DVec3::new(5.0, 0.0, 0.0),
            -17.0,
        );
        match check_witness(&swapped, &through, &shell, &ball) {
            WitnessCheck::ThroughMaterial {
                side: WitnessSide::A,
                at,
            } => assert!((at - 5.0).abs() < 1e-12, "{at}"),
            other => panic!("{other:?}"),
        }
    }

    /// The through-material pair of the shell test with B's point at a vertex: with A's point
    /// on a face, B's flanks count, and the pair fails as before (the inner sphere passes 5 mm
    /// from A's point); B's sharp point is now tested first, and the ball passes 1 mm from it.
    /// With A's point at a vertex too, B's flanks are to be left out, which needs the exact
    /// solid: without it, B's side and so the pair are undecided.
    #[test]
    fn a_side_on_a_vertex_needs_the_exact_solid() {
        let pose_ab = DPose3 {
            translation: DVec3::new(-8.0, 0.0, 0.0),
            rotation: geom_param::DQuat::IDENTITY,
        };
        let ball = Ball {
            centre: DVec3::ZERO,
            radius: 3.0,
            error: 0.0,
        };
        let shell = Shell {
            inner: 10.0,
            outer: 12.0,
        };
        let vertex = FeatureLocation::Vertex {
            id: geom_param::VertexId(0),
        };
        let mut through = witness(DVec3::new(-3.0, 0.0, 0.0), DVec3::new(4.0, 0.0, 0.0), -7.0);
        through.location_b = vertex;
        match check_witness(&pose_ab, &through, &ball, &shell) {
            WitnessCheck::ThroughMaterial {
                side: WitnessSide::A,
                at,
            } => assert!((at - 1.0).abs() < 1e-12, "{at}"),
            other => panic!("{other:?}"),
        }
        through.location_a = vertex;
        assert_eq!(
            check_witness(&pose_ab, &through, &ball, &shell),
            WitnessCheck::Undecided
        );
    }

    #[test]
    fn non_finite_or_separated_pairs_are_not_checked() {
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
            WitnessCheck::Certified
        );
    }

    /// A tube's wall (radii 8 and 10, z from 0 to 20, [`geom_param::tube`]: faces 0 outer, 1
    /// inner, 2 bottom, 3 top; edge 1 the outer top circle) as a representation that knows its
    /// exact distance but claims a mesh's error bound of 0.05 mm, and, when `exact`, its solid
    /// and the faces near a point (every face, at its nearest sample of a 64 x 64 parameter
    /// grid inside its trim).
    struct TubeWall {
        solid: Solid,
        exact: bool,
    }

    impl TubeWall {
        fn new(exact: bool) -> Self {
            Self {
                solid: geom_param::tube(10.0, 8.0, 20.0).expect("tube"),
                exact,
            }
        }
    }

    impl NearestBoundary for TubeWall {
        /// Exact for points inside the wall (every point queried below).
        fn nearest_boundary(&self, p: DVec3, _reach: f64) -> Option<BoundaryDistance> {
            let r = p.truncate().length();
            let distance = (r - 8.0).min(10.0 - r).min(p.z).min(20.0 - p.z);
            (distance >= 0.0).then_some(BoundaryDistance {
                point: p,
                distance,
                error_bound: 0.05,
            })
        }

        fn solid(&self) -> Option<&Solid> {
            self.exact.then_some(&self.solid)
        }

        /// Every face (more than the contract asks for), at its nearest grid sample.
        fn faces_near(&self, p: DVec3, _radius: f64) -> Vec<FeatureLocation> {
            let mut out = Vec::new();
            for (index, face) in self.solid.faces.iter().enumerate() {
                let id = FaceId(u32::try_from(index).expect("four faces"));
                let [du, dv] = face.surface.domain();
                let grid = |range: &geom_param::ParamRange, k: usize| {
                    range.min + range.span() * (k as f64 + 0.5) / 64.0
                };
                let nearest = (0..64 * 64)
                    .map(|k| [grid(&du, k % 64), grid(&dv, k / 64)])
                    .filter(|uv| {
                        face.trim
                            .as_ref()
                            .is_none_or(|t| t.contains(geom_param::DVec2::from(*uv), 0.0))
                    })
                    .min_by(|x, y| {
                        let at = |uv: &[f64; 2]| self.solid.eval_face(id, uv[0], uv[1]).point;
                        at(x).distance(p).total_cmp(&at(y).distance(p))
                    });
                if let Some([u, v]) = nearest {
                    out.push(FeatureLocation::Face { id, u, v });
                }
            }
            out
        }
    }

    /// Witnesses from a point inside a tube's wall (A's) to a point of its boundary (B's),
    /// with A a ball whose surface holds A's point and leaves B's point outside, at the depth
    /// (so only B's side can hold). To the outer cylinder 0.1 mm deep at mid-height: the
    /// cylinder is the nearest boundary, which the claimed bound cannot certify alone
    /// (undecided) and the exact distance does. 1 mm deep 0.01 mm under the top cap: the cap is
    /// nearer, as the bound alone shows. 0.05 mm deep there: only the exact distance shows the
    /// cap nearer. To the outer top edge, 0.05 mm along its bisector: the cylinder and the cap
    /// (the faces that hold the edge) are nearer, 0.035 mm, and count against a point on a
    /// face; against a point at a vertex they are left out, and the pair holds when B's point
    /// lies inside A with A's point its nearest (two sharp points crossing), not when A leaves
    /// it outside; from 2 mm
    /// inside the wall the inner cylinder, which does not hold the edge, is nearer either way.
    /// Where the pair is no witness, A's point inside the wall is measured to its exact nearest
    /// boundary point (flanks and all) when the exact solid is known: the pair overlaps by that
    /// depth ([`WitnessCheck::Overlapping`]); without it, the verdict stays through the material.
    #[test]
    fn a_depth_the_bound_cannot_settle_is_measured_on_the_exact_surface() {
        // A's ball leaves B's point outside, or, `crossing`, holds it (its centre beyond it).
        let check_with = |pa: DVec3,
                          pb: DVec3,
                          on: Option<[FeatureLocation; 2]>,
                          exact: bool,
                          crossing: bool| {
            let away = if crossing { -100.0 } else { 100.0 };
            let a = Ball {
                centre: pa - (pb - pa).normalize() * away,
                radius: 100.0,
                error: 0.0,
            };
            let mut w = witness(pa, pb, -pa.distance(pb));
            if let Some([a_on, b_on]) = on {
                (w.location_a, w.location_b) = (a_on, b_on);
            }
            check_witness(&DPose3::IDENTITY, &w, &a, &TubeWall::new(exact))
        };
        let check = |pa: DVec3, pb: DVec3, on: Option<[FeatureLocation; 2]>, exact: bool| {
            check_with(pa, pb, on, exact, false)
        };
        let to_cylinder = |r: f64, z: f64, exact: bool| {
            check(DVec3::new(r, 0.0, z), DVec3::new(10.0, 0.0, z), None, exact)
        };
        // With the exact solid, a point inside the wall is also measured to its nearest
        // boundary point: the pair overlaps by that depth.
        let nearer = |verdict: WitnessCheck, exact: bool, expected: f64| match verdict {
            WitnessCheck::ThroughMaterial {
                side: WitnessSide::B,
                at,
            } if !exact => (at - expected).abs() < 1e-9,
            WitnessCheck::Overlapping {
                side: WitnessSide::B,
                depth,
            } if exact => (depth - expected).abs() < 1e-9,
            _ => false,
        };
        assert_eq!(to_cylinder(9.9, 10.0, false), WitnessCheck::Undecided);
        assert_eq!(to_cylinder(9.9, 10.0, true), WitnessCheck::Certified);
        for exact in [false, true] {
            let verdict = to_cylinder(9.0, 19.99, exact);
            assert!(nearer(verdict, exact, 0.01), "{verdict:?}");
        }
        assert_eq!(to_cylinder(9.95, 19.99, false), WitnessCheck::Undecided);
        let verdict = to_cylinder(9.95, 19.99, true);
        assert!(nearer(verdict, true, 0.01), "{verdict:?}");

        let edge = FeatureLocation::Edge {
            id: EdgeId(1),
            t: 0.0,
        };
        let face = FeatureLocation::Face {
            id: FaceId(0),
            u: 0.0,
            v: 0.0,
        };
        let vertex = FeatureLocation::Vertex {
            id: geom_param::VertexId(0),
        };
        let corner = DVec3::new(10.0, 0.0, 20.0);
        let bisector = DVec3::new(1.0, 0.0, 1.0).normalize();
        let inside = corner - bisector * 0.05;
        let flank = 0.05 * 0.5_f64.sqrt();
        let verdict = check(inside, corner, Some([face, edge]), true);
        assert!(nearer(verdict, true, flank), "{verdict:?}");
        assert_eq!(
            check_with(inside, corner, Some([vertex, edge]), true, true),
            WitnessCheck::Certified
        );
        // Against a vertex the flanks are left out of the nearer test, not of the depth.
        let verdict = check(inside, corner, Some([vertex, edge]), true);
        assert!(nearer(verdict, true, flank), "{verdict:?}");
        for a_on in [face, vertex] {
            let verdict = check(DVec3::new(8.2, 0.0, 19.0), corner, Some([a_on, edge]), true);
            assert!(nearer(verdict, true, 0.2), "{verdict:?}");
        }
    }
}
