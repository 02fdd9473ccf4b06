//! Shared test scaffolding: closed-form solids built from profiles, seeds, a seeded PRNG and
//! the checks every converged contact must pass.
#![allow(dead_code)] // each test binary uses a different subset

use exact_refine::{NewtonRefiner, RefineStatus, RefinedContact, Refiner};
use geom_param::{
    ComponentId, DPose3, DQuat, DVec3, FeatureLocation, MeshOptions, ObjectModel, Profile, Seed,
    SeedPoint, SegmentSpec, Solid,
};

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
