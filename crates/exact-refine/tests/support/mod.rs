//! Shared test scaffolding: closed-form solids built from profiles, general solids with NURBS
//! and trimmed analytic faces (sewn or built by geom-param's builders), seeds, a seeded PRNG
//! and the checks every converged contact must pass.
#![allow(dead_code)] // each test binary uses a different subset

use exact_refine::{NewtonRefiner, RefineStatus, RefinedContact, Refiner};
use geom_param::{
    ComponentId, DPose3, DQuat, DVec2, DVec3, FeatureLocation, MeshOptions, NurbsCurve,
    NurbsCurve2, NurbsSurface, ObjectModel, Placement, PlanarProfile, PlanarSegment, Profile, Seed,
    SeedPoint, SegmentSpec, Solid, Surface, extrude, sew_rectangles,
};
use std::f64::consts::{FRAC_1_SQRT_2, FRAC_PI_2, PI, TAU};
use std::sync::Arc;

/// Builds a solid from profile segments (the mesh is coarse: only the exact solid is used).
pub fn solid(specs: &[SegmentSpec]) -> Solid {
    let profile = Profile::new(specs).expect("valid test profile");
    let chordal = 0.05 * profile.scale();
    ObjectModel::from_profile(
        "test",
        profile,
        &MeshOptions {
            chordal_tolerance: chordal,
        },
    )
    .expect("model")
    .solid
}

/// Sphere of radius r about the origin: face 0, south pole vertex 0, north pole vertex 1.
/// Face 0 has v from the south pole (v = 0) to the north pole (v = 1), u the longitude.
pub fn sphere(r: f64) -> Solid {
    solid(&[SegmentSpec::Arc {
        center: [0.0, 0.0],
        from: [0.0, -r],
        to: [0.0, r],
        ccw: true,
    }])
}

/// Cylinder of radius r from z = 0 to z = h: face 0 bottom disk, face 1 side, face 2 top disk;
/// edge 0 the bottom rim, edge 1 the top rim.
pub fn cylinder(r: f64, h: f64) -> Solid {
    solid(&[
        SegmentSpec::Line {
            from: [0.0, 0.0],
            to: [r, 0.0],
        },
        SegmentSpec::Line {
            from: [r, 0.0],
            to: [r, h],
        },
        SegmentSpec::Line {
            from: [r, h],
            to: [0.0, h],
        },
    ])
}

/// Torus ring with core radius rc and tube radius a: faces 0 (outer half, v from bottom to
/// top) and 1 (inner half).
pub fn torus(rc: f64, a: f64) -> Solid {
    solid(&[
        SegmentSpec::Arc {
            center: [rc, 0.0],
            from: [rc, -a],
            to: [rc, a],
            ccw: true,
        },
        SegmentSpec::Arc {
            center: [rc, 0.0],
            from: [rc, a],
            to: [rc, -a],
            ccw: true,
        },
    ])
}

/// Cone with base radius r at z = 0 and apex at (0, 0, h): face 0 base, face 1 mantle, vertex 1
/// the apex.
pub fn cone(r: f64, h: f64) -> Solid {
    solid(&[
        SegmentSpec::Line {
            from: [0.0, 0.0],
            to: [r, 0.0],
        },
        SegmentSpec::Line {
            from: [r, 0.0],
            to: [0.0, h],
        },
    ])
}

/// A block with a spherical socket of radius r centred at the origin, opening upwards
/// (z = 0 rim), outer radius w, bottom at z = -r - t. Face 3 is the (concave) socket, its
/// v = 1 end the bottom pole (vertex 1).
pub fn socket(r: f64, w: f64, t: f64) -> Solid {
    solid(&[
        SegmentSpec::Line {
            from: [0.0, -r - t],
            to: [w, -r - t],
        },
        SegmentSpec::Line {
            from: [w, -r - t],
            to: [w, 0.0],
        },
        SegmentSpec::Line {
            from: [w, 0.0],
            to: [r, 0.0],
        },
        SegmentSpec::Arc {
            center: [0.0, 0.0],
            from: [r, 0.0],
            to: [0.0, -r],
            ccw: false,
        },
    ])
}

// ---------------------------------------------------------------------------------------------
// General solids: NURBS faces sewn into solids, builders' solids with trimmed faces.

/// The xz half-plane as a placement: x = +x, y = +z (axis −y), for meridians revolved about z.
fn meridian_plane(centre: DVec3) -> Placement {
    Placement::new(centre, DVec3::NEG_Y, DVec3::X).expect("placement")
}

/// One NURBS face revolved about z and sewn into a solid (its poles become vertices).
fn sewn(surface: NurbsSurface) -> Solid {
    let size = (0..surface.count()[0])
        .flat_map(|i| (0..surface.count()[1]).map(move |j| (i, j)))
        .map(|(i, j)| surface.control_point(i, j).abs().max_element())
        .fold(0.0, f64::max);
    sew_rectangles(vec![Arc::new(surface)], 1e-9 * size).expect("sewn NURBS solid")
}

/// The NURBS sphere of radius r about the origin (The NURBS Book A8.1): the rational quadratic
/// semicircle from the south pole through +x to the north pole, revolved about z. Face 0:
/// u in [0, 2π] periodic (the angle about z at multiples of π/2), v in [−π/2, π/2] (the
/// latitude at −π/2, 0, π/2, not between); vertices at the poles.
pub fn nurbs_sphere(r: f64) -> Solid {
    let meridian =
        NurbsCurve::circle_arc(&meridian_plane(DVec3::ZERO), r, -FRAC_PI_2, PI).expect("arc");
    sewn(NurbsSurface::revolution(&meridian, DVec3::ZERO, DVec3::Z, TAU).expect("revolved"))
}

/// The same sphere with the meridian's weights `weights` (5 of them; knots [0, 0, 0, 1, 1, 2,
/// 2, 2], control points (0, −r), (r, −r), (r, 0), (r, r), (0, r) in the xz plane). The
/// weights (1, c √½, c², ...) with any c > 0 reparametrise a quarter arc without changing it
/// (The NURBS Book eq. 6.4), and scaling all weights changes nothing, so many weight sets
/// give the exact sphere. Face 0: u as [`nurbs_sphere`], v in [0, 2] from south to north.
pub fn nurbs_sphere_weighted(r: f64, weights: [f64; 5]) -> Solid {
    let points = [(0.0, -r), (r, -r), (r, 0.0), (r, r), (0.0, r)]
        .map(|(x, z)| DVec3::new(x, 0.0, z))
        .to_vec();
    let meridian = NurbsCurve::new(
        2,
        vec![0.0, 0.0, 0.0, 1.0, 1.0, 2.0, 2.0, 2.0],
        points,
        weights.to_vec(),
        false,
    )
    .expect("meridian");
    sewn(NurbsSurface::revolution(&meridian, DVec3::ZERO, DVec3::Z, TAU).expect("revolved"))
}

/// The meridian weights of the exact semicircle: 1 at the joints, √½ at the corners.
pub const SEMICIRCLE_WEIGHTS: [f64; 5] = [1.0, FRAC_1_SQRT_2, 1.0, FRAC_1_SQRT_2, 1.0];

/// The NURBS torus: the rational quadratic circle of radius `a` about (rc, 0, 0) in the xz
/// plane (from its outer equator, counter-clockwise towards +z), revolved about z. Face 0,
/// periodic in u (about z) and v (around the tube, the angle from the outer equator at
/// multiples of π/2); no edges or vertices.
pub fn nurbs_torus(rc: f64, a: f64) -> Solid {
    let tube = NurbsCurve::circle_arc(&meridian_plane(DVec3::new(rc, 0.0, 0.0)), a, 0.0, TAU)
        .expect("circle");
    sewn(NurbsSurface::revolution(&tube, DVec3::ZERO, DVec3::Z, TAU).expect("revolved"))
}

/// The NURBS cone of base radius r at z = 0 with apex (0, 0, h): a disk (the segment from the
/// centre to (r, 0, 0), revolved) and the mantle (from (r, 0, 0) to the apex, revolved), both
/// degree 1 along the meridian; the apex and the disk's centre are collapsed rows (poles).
/// Face 0 the disk, face 1 the mantle (v from the rim, 0, to the apex, 1).
pub fn nurbs_cone(r: f64, h: f64) -> Solid {
    let line = |a: DVec3, b: DVec3| {
        NurbsCurve::new(
            1,
            vec![0.0, 0.0, 1.0, 1.0],
            vec![a, b],
            vec![1.0, 1.0],
            false,
        )
        .expect("line")
    };
    let revolve = |c: NurbsCurve| -> Arc<dyn Surface> {
        Arc::new(NurbsSurface::revolution(&c, DVec3::ZERO, DVec3::Z, TAU).expect("revolved"))
    };
    let rim = DVec3::new(r, 0.0, 0.0);
    sew_rectangles(
        vec![
            revolve(line(DVec3::ZERO, rim)),
            revolve(line(rim, DVec3::new(0.0, 0.0, h))),
        ],
        1e-9 * r.max(h),
    )
    .expect("sewn cone")
}

/// The v at which face `face`'s meridian (u fixed) reaches latitude `latitude` (rad, about the
/// origin), by bisection: for the revolved NURBS spheres, whose latitude grows with v.
pub fn v_at_latitude(solid: &Solid, face: u32, u: f64, latitude: f64) -> f64 {
    let surface = &solid.faces[face as usize].surface;
    let range = surface.domain()[1];
    let lat = |v: f64| {
        let p = surface.eval(u, v).point;
        p.z.atan2(p.truncate().length())
    };
    let (mut lo, mut hi) = (range.min, range.max);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if lat(mid) < latitude {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// A square block [0, 20]² x [0, 10] extruded from four lines: faces 0-3 the sides (face k on
/// the segment from corner k), 4 the bottom cap, 5 the top cap (trimmed planes); per segment k
/// edges 3k (bottom), 3k + 1 (top), 3k + 2 (vertical, at corner k); vertices 2k (bottom) and
/// 2k + 1 (top) at corner k. Corners: (0, 0), (20, 0), (20, 20), (0, 20).
pub fn block() -> Solid {
    let corners =
        [(0.0, 0.0), (20.0, 0.0), (20.0, 20.0), (0.0, 20.0)].map(|(x, y)| DVec2::new(x, y));
    let outer = (0..4)
        .map(|k| PlanarSegment::Line {
            from: corners[k],
            to: corners[(k + 1) % 4],
        })
        .collect();
    extrude(
        &PlanarProfile {
            outer,
            holes: Vec::new(),
        },
        0.0,
        10.0,
    )
    .expect("block")
}

/// The block [0, 20]² x [0, 10] with its side x = 20 pushed out into a roof: a quadratic NURBS
/// segment from (20, 0) through the control points (22.5, 5), (25, 10) [a knot of multiplicity
/// 2 = the degree: a crease], (22.5, 15) to (20, 20). Each piece is a straight segment
/// parametrised uniformly (its middle control point is its midpoint), so face 1 is two planes
/// meeting at a convex crease along the vertical line x = 25, y = 10, at u = 1 inside the
/// face. Faces: 0 (y = 0), 1 (the roof), 2, 3, caps 4 and 5.
pub fn creased_block() -> Solid {
    let p = |x: f64, y: f64| DVec2::new(x, y);
    let roof = NurbsCurve2::new(
        2,
        vec![0.0, 0.0, 0.0, 1.0, 1.0, 2.0, 2.0, 2.0],
        vec![
            p(20.0, 0.0),
            p(22.5, 5.0),
            p(25.0, 10.0),
            p(22.5, 15.0),
            p(20.0, 20.0),
        ],
        vec![1.0; 5],
        false,
    )
    .expect("roof");
    extrude(
        &PlanarProfile {
            outer: vec![
                PlanarSegment::Line {
                    from: p(0.0, 0.0),
                    to: p(20.0, 0.0),
                },
                PlanarSegment::Nurbs(roof),
                PlanarSegment::Line {
                    from: p(20.0, 20.0),
                    to: p(0.0, 20.0),
                },
                PlanarSegment::Line {
                    from: p(0.0, 20.0),
                    to: p(0.0, 0.0),
                },
            ],
            holes: Vec::new(),
        },
        0.0,
        10.0,
    )
    .expect("creased block")
}

/// The parameters (u, v) on a [`sphere`] (face 0) of the point in direction `w` from its
/// centre.
pub fn sphere_params(w: DVec3) -> (f64, f64) {
    (
        w.y.atan2(w.x).rem_euclid(2.0 * PI),
        (w.z.clamp(-1.0, 1.0).asin() + FRAC_PI_2) / PI,
    )
}

/// A seed point at `location` on `solid`, with its point offset by `offset` (object frame).
pub fn seed_point(solid: &Solid, location: FeatureLocation, offset: DVec3) -> SeedPoint {
    SeedPoint {
        component: ComponentId(0),
        local_point: solid.point_at(&location) + offset,
        location,
    }
}

/// Shorthand for a face location.
pub fn face(id: u32, u: f64, v: f64) -> FeatureLocation {
    FeatureLocation::Face {
        id: geom_param::FaceId(id),
        u,
        v,
    }
}

/// Shorthand for an edge location.
pub fn edge(id: u32, t: f64) -> FeatureLocation {
    FeatureLocation::Edge {
        id: geom_param::EdgeId(id),
        t,
    }
}

/// Shorthand for a vertex location.
pub fn vertex(id: u32) -> FeatureLocation {
    FeatureLocation::Vertex {
        id: geom_param::VertexId(id),
    }
}

/// A pose from a rotation and translation.
pub fn pose(rotation: DQuat, translation: DVec3) -> DPose3 {
    DPose3 {
        rotation,
        translation,
    }
}

/// Runs the default refiner.
pub fn refine(a: &Solid, b: &Solid, pose_ab: &DPose3, seed: &Seed) -> RefinedContact {
    NewtonRefiner::default().refine(a, b, pose_ab, seed, &mut ())
}

/// SplitMix64 (Steele, Lea, Flood 2014): a tiny, seedable PRNG.
pub struct Rng(pub u64);

impl Rng {
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * ((self.next_u64() >> 11) as f64 / (1u64 << 53) as f64)
    }

    pub fn unit_vector(&mut self) -> DVec3 {
        loop {
            let v = DVec3::new(
                self.range(-1.0, 1.0),
                self.range(-1.0, 1.0),
                self.range(-1.0, 1.0),
            );
            if let Some(u) = v
                .try_normalize()
                .filter(|_| v.length() <= 1.0 && v.length() > 0.1)
            {
                return u;
            }
        }
    }

    pub fn rotation(&mut self) -> DQuat {
        DQuat::from_axis_angle(self.unit_vector(), self.range(0.0, std::f64::consts::TAU))
    }
}

/// Every output finite, the normal a unit vector.
pub fn assert_finite(c: &RefinedContact, what: &str) {
    let d = &c.diagnostics;
    assert!(
        c.point_a.is_finite() && c.point_b.is_finite(),
        "{what}: points {c:?}"
    );
    assert!(
        !c.distance.is_nan() && c.normal.is_finite(),
        "{what}: {c:?}"
    );
    assert!(
        (c.normal.length() - 1.0).abs() < 1e-12,
        "{what}: normal {:?}",
        c.normal
    );
    assert!(
        !d.gradient_norm.is_nan() && !d.condition.is_nan(),
        "{what}: {d:?}"
    );
    assert!(
        !d.error_estimate.is_nan() && !d.point_error_estimate.is_nan(),
        "{what}: {d:?}"
    );
    for p in c
        .location_a
        .params()
        .into_iter()
        .chain(c.location_b.params())
    {
        assert!(p.is_finite(), "{what}: params {c:?}");
    }
}

/// A converged, isolated answer: status, consistency of distance with the points, and the
/// connecting vector parallel to the normal to 1e-12 relative (plus rounding of the coordinates).
pub fn assert_converged(c: &RefinedContact, what: &str) {
    assert_converged_at(c, c.point_a.length().max(c.point_b.length()), what);
}

/// [`assert_converged`] where the coordinates that entered the computation were as large as
/// `scale` (mm), e.g. B's own coordinates before its pose moved them next to A.
pub fn assert_converged_at(c: &RefinedContact, scale: f64, what: &str) {
    assert_finite(c, what);
    assert_eq!(
        c.diagnostics.status,
        RefineStatus::Converged,
        "{what}: {c:?}"
    );
    assert!(
        c.diagnostics.converged && c.diagnostics.is_local_minimum,
        "{what}: {c:?}"
    );
    let gap = c.point_b - c.point_a;
    let scale = scale.max(c.point_a.length()).max(c.point_b.length());
    let rounding = 64.0 * f64::EPSILON * scale;
    assert!(
        gap.cross(c.normal).length() <= 1e-12 * gap.length() + rounding,
        "{what}: connecting vector {gap:?} not along normal {:?}",
        c.normal
    );
    assert!(
        (gap.dot(c.normal) - c.distance).abs() <= rounding,
        "{what}: distance {c:?}"
    );
}

/// The closed-form check: distance and points within the result's own error estimates (which
/// near touch grow like 1 / (gap x curvature), see the crate docs); where the gap is not small
/// (|gap| >= 1e-3 mm) the distance estimate must itself be at rounding level (1e-12 x scale).
/// Returns the actual (distance, point) errors.
pub fn assert_answer(
    c: &RefinedContact,
    distance: f64,
    pa: DVec3,
    pb: DVec3,
    what: &str,
) -> (f64, f64) {
    let d = &c.diagnostics;
    let scale = pa.length().max(pb.length()).max(1.0);
    let rounding = 64.0 * f64::EPSILON * scale;
    let distance_error = (c.distance - distance).abs();
    assert!(
        distance_error <= d.error_estimate.max(rounding),
        "{what}: distance {} vs {distance} (estimate {})",
        c.distance,
        d.error_estimate
    );
    if distance.abs() >= 1e-3 {
        assert!(
            d.error_estimate <= 1e-12 * scale,
            "{what}: distance estimate {d:?}"
        );
    }
    let tol = d.point_error_estimate.max(rounding);
    let point_error = c.point_a.distance(pa).max(c.point_b.distance(pb));
    assert!(
        c.point_a.distance(pa) <= tol,
        "{what}: point_a {:?} vs {pa:?} (tol {tol})",
        c.point_a
    );
    assert!(
        c.point_b.distance(pb) <= tol,
        "{what}: point_b {:?} vs {pb:?} (tol {tol})",
        c.point_b
    );
    (distance_error, point_error)
}
