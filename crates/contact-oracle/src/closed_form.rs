//! Scenes with contacts known in closed form, built from profiles, for testing the oracle (and,
//! through it, anything compared with the oracle).
//!
//! Every builder is parametrised by the signed gap (mm; negative: overlap depth) and returns
//! the exact contacts. A scene can be moved rigidly as a whole ([`ClosedFormScene::moved`]) so
//! tests need not rely on axis-aligned poses.

use geom_param::{
    DPose3, DQuat, DVec3, LoadError, MeshOptions, ObjectDescription, SegmentSpec, Solid,
};

/// One exact contact, world frame: point_b = point_a + distance · normal, normal = A's outward
/// normal at point_a.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ExpectedContact {
    /// On A (mm).
    pub point_a: DVec3,
    /// On B (mm).
    pub point_b: DVec3,
    /// Signed distance (mm).
    pub distance: f64,
    /// A's unit outward normal at point_a.
    pub normal: DVec3,
}

/// Two posed objects and their exact contacts.
#[derive(Clone, Debug, PartialEq)]
pub struct ClosedFormScene {
    /// Name for messages, with the parameters.
    pub name: String,
    /// Object A.
    pub a: ObjectDescription,
    /// A's pose (object to world).
    pub pose_a: DPose3,
    /// Object B.
    pub b: ObjectDescription,
    /// B's pose.
    pub pose_b: DPose3,
    /// Every local minimum of distance (or penetration witness) within the scene's reach of
    /// interest (1 mm), in no particular order.
    pub expected: Vec<ExpectedContact>,
}

impl ClosedFormScene {
    /// The scene after the rigid motion `motion` of the whole world.
    #[must_use]
    pub fn moved(&self, motion: &DPose3) -> Self {
        let compose = |p: &DPose3| DPose3 {
            rotation: (motion.rotation * p.rotation).normalize(),
            translation: motion.rotation * p.translation + motion.translation,
        };
        Self {
            name: self.name.clone(),
            a: self.a.clone(),
            pose_a: compose(&self.pose_a),
            b: self.b.clone(),
            pose_b: compose(&self.pose_b),
            expected: self
                .expected
                .iter()
                .map(|e| ExpectedContact {
                    point_a: motion.rotation * e.point_a + motion.translation,
                    point_b: motion.rotation * e.point_b + motion.translation,
                    distance: e.distance,
                    normal: motion.rotation * e.normal,
                })
                .collect(),
        }
    }

    /// The exact solids of A and B (built with a coarse mesh, which the oracle does not use).
    ///
    /// # Errors
    /// A [`LoadError`] if a profile is invalid (the builders' tests check they are not).
    pub fn solids(&self) -> Result<(Solid, Solid), LoadError> {
        Ok((build(&self.a)?, build(&self.b)?))
    }
}

fn build(d: &ObjectDescription) -> Result<Solid, LoadError> {
    let scale = d
        .profile
        .iter()
        .flat_map(|s| match *s {
            SegmentSpec::Line { from, to } => vec![from, to],
            SegmentSpec::Arc {
                center, from, to, ..
            } => vec![center, from, to],
            SegmentSpec::Bezier { points } => points.to_vec(),
        })
        .flatten()
        .fold(0.0_f64, |m, c| m.max(c.abs()));
    Ok(d.build(&MeshOptions {
        chordal_tolerance: 0.05 * scale,
    })?
    .solid)
}

fn object(name: &str, profile: Vec<SegmentSpec>) -> ObjectDescription {
    ObjectDescription {
        name: name.into(),
        note: Some("closed-form test object (contact-oracle)".into()),
        profile,
    }
}

fn pose(rotation: DQuat, translation: DVec3) -> DPose3 {
    DPose3 {
        rotation,
        translation,
    }
}

/// Sphere of radius r about the origin (poles on the z axis).
fn sphere(r: f64) -> ObjectDescription {
    object(
        "sphere",
        vec![SegmentSpec::Arc {
            center: [0.0, 0.0],
            from: [0.0, -r],
            to: [0.0, r],
            ccw: true,
        }],
    )
}

/// Capped cylinder of radius r and length `length` along z, centred at the origin.
fn cylinder(r: f64, length: f64) -> ObjectDescription {
    let h = 0.5 * length;
    object(
        "cylinder",
        vec![
            SegmentSpec::Line {
                from: [0.0, -h],
                to: [r, -h],
            },
            SegmentSpec::Line {
                from: [r, -h],
                to: [r, h],
            },
            SegmentSpec::Line {
                from: [r, h],
                to: [0.0, h],
            },
        ],
    )
}

/// Torus with core radius `core` and tube radius `tube` about the z axis, core in z = 0.
fn torus(core: f64, tube: f64) -> ObjectDescription {
    object(
        "torus",
        vec![
            SegmentSpec::Arc {
                center: [core, 0.0],
                from: [core, -tube],
                to: [core, tube],
                ccw: true,
            },
            SegmentSpec::Arc {
                center: [core, 0.0],
                from: [core, tube],
                to: [core, -tube],
                ccw: true,
            },
        ],
    )
}

/// Two spheres (A radius `r1` at the origin, B radius `r2`) whose centres lie along the unit
/// `direction` from A's, `gap` apart along it; `spins` rotate each sphere about its centre (they
/// move the poles, not the geometry). One contact: point_a = r1 · direction.
#[must_use]
pub fn sphere_on_sphere(
    r1: f64,
    r2: f64,
    gap: f64,
    direction: DVec3,
    spins: [DQuat; 2],
) -> ClosedFormScene {
    let d = direction.normalize();
    let point_a = d * r1;
    ClosedFormScene {
        name: format!("sphere_on_sphere(r1 {r1}, r2 {r2}, gap {gap})"),
        a: sphere(r1),
        pose_a: pose(spins[0], DVec3::ZERO),
        b: sphere(r2),
        pose_b: pose(spins[1], d * (r1 + r2 + gap)),
        expected: vec![ExpectedContact {
            point_a,
            point_b: point_a + d * gap,
            distance: gap,
            normal: d,
        }],
    }
}

/// A ball (A, radius `r`, spun by `spin`) inside a spherical cavity of radius `bowl_radius`
/// (B: a block 1.5 R wide and 0.3 R thick below the cavity, cavity centre at the origin,
/// opening upwards). The ball's centre lies at R − r − gap from the cavity centre along the
/// direction `tilt` (rad, from straight down, keep <= 0.5) and `azimuth` (rad). One contact,
/// distance R − |c − o| − r = gap, for balls with r <= 0.6 R (so the rim stays > 1 mm away for
/// R >= 10).
#[must_use]
pub fn sphere_in_bowl(
    r: f64,
    bowl_radius: f64,
    gap: f64,
    tilt: f64,
    azimuth: f64,
    spin: DQuat,
) -> ClosedFormScene {
    let big = bowl_radius;
    let (w, t) = (1.5 * big, 0.3 * big);
    let bowl = object(
        "bowl",
        vec![
            SegmentSpec::Line {
                from: [0.0, -big - t],
                to: [w, -big - t],
            },
            SegmentSpec::Line {
                from: [w, -big - t],
                to: [w, 0.0],
            },
            SegmentSpec::Line {
                from: [w, 0.0],
                to: [big, 0.0],
            },
            SegmentSpec::Arc {
                center: [0.0, 0.0],
                from: [big, 0.0],
                to: [0.0, -big],
                ccw: false,
            },
        ],
    );
    let d = DVec3::new(
        tilt.sin() * azimuth.cos(),
        tilt.sin() * azimuth.sin(),
        -tilt.cos(),
    );
    let centre = d * (big - r - gap);
    let point_a = centre + d * r;
    ClosedFormScene {
        name: format!("sphere_in_bowl(r {r}, R {big}, gap {gap}, tilt {tilt})"),
        a: sphere(r),
        pose_a: pose(spin, centre),
        b: bowl,
        pose_b: DPose3::IDENTITY,
        expected: vec![ExpectedContact {
            point_a,
            point_b: point_a + d * gap,
            distance: gap,
            normal: d,
        }],
    }
}

/// A ball (A, radius `r`, spun by `spin`) beside the outer wall of a cylindrical cup (B: inner
/// radius `inner`, wall thickness `wall`, 8 r tall with a floor r thick, axis z, standing on
/// z = 0). The ball's centre lies at height 4 r and radius inner + wall + r + gap in the
/// direction `azimuth` (rad) from the x axis. One contact, on the radial line: distance `gap`
/// to the outer wall. The inner wall is a local minimum of the distance between the two
/// boundaries too (wall + gap, measured through the wall, with the ball behind the inner
/// wall's normal), but no contact: the ball is outside the cup. Requires r > 1 mm, so the rim
/// and floor stay beyond a 1 mm reach.
#[must_use]
pub fn ball_beside_cup(
    r: f64,
    inner: f64,
    wall: f64,
    gap: f64,
    azimuth: f64,
    spin: DQuat,
) -> ClosedFormScene {
    let outer = inner + wall;
    let (height, floor) = (8.0 * r, r);
    let line = |from: [f64; 2], to: [f64; 2]| SegmentSpec::Line { from, to };
    let cup = object(
        "cup",
        vec![
            line([0.0, 0.0], [outer, 0.0]),
            line([outer, 0.0], [outer, height]),
            line([outer, height], [inner, height]),
            line([inner, height], [inner, floor]),
            line([inner, floor], [0.0, floor]),
        ],
    );
    let d = DVec3::new(azimuth.cos(), azimuth.sin(), 0.0);
    let centre = d * (outer + r + gap) + DVec3::Z * (0.5 * height);
    let point_a = centre - d * r;
    ClosedFormScene {
        name: format!("ball_beside_cup(r {r}, inner {inner}, wall {wall}, gap {gap})"),
        a: sphere(r),
        pose_a: pose(spin, centre),
        b: cup,
        pose_b: DPose3::IDENTITY,
        expected: vec![ExpectedContact {
            point_a,
            point_b: point_a - d * gap,
            distance: gap,
            normal: -d,
        }],
    }
}

/// Capped cylinders of length `length` with perpendicular axes: A (radius `r1`) along x through
/// the origin, B (radius `r2`) along y at height r1 + r2 + gap. One contact on the common
/// perpendicular (the z axis), provided length / 2 > r1 + r2 + 1.
#[must_use]
pub fn crossed_cylinders(r1: f64, r2: f64, gap: f64, length: f64) -> ClosedFormScene {
    let point_a = DVec3::new(0.0, 0.0, r1);
    ClosedFormScene {
        name: format!("crossed_cylinders(r1 {r1}, r2 {r2}, gap {gap})"),
        a: cylinder(r1, length),
        pose_a: pose(
            DQuat::from_rotation_y(std::f64::consts::FRAC_PI_2),
            DVec3::ZERO,
        ),
        b: cylinder(r2, length),
        pose_b: pose(
            DQuat::from_rotation_x(-std::f64::consts::FRAC_PI_2),
            DVec3::new(0.0, 0.0, r1 + r2 + gap),
        ),
        expected: vec![ExpectedContact {
            point_a,
            point_b: point_a + DVec3::Z * gap,
            distance: gap,
            normal: DVec3::Z,
        }],
    }
}

/// A torus (A: core radius `core`, tube radius `tube`) tilted by `tilt` (rad, > 0) about x,
/// above a wide thin disk (B, radius 2 (core + tube) + 10, 5 thick) whose top is the plane
/// z = 0. One contact, below the lowest point of the core circle, distance `gap`.
#[must_use]
pub fn torus_on_plane(core: f64, tube: f64, tilt: f64, gap: f64) -> ClosedFormScene {
    let w = 2.0 * (core + tube) + 10.0;
    let plate = object(
        "plate",
        vec![
            SegmentSpec::Line {
                from: [0.0, -5.0],
                to: [w, -5.0],
            },
            SegmentSpec::Line {
                from: [w, -5.0],
                to: [w, 0.0],
            },
            SegmentSpec::Line {
                from: [w, 0.0],
                to: [0.0, 0.0],
            },
        ],
    );
    let height = core * tilt.sin() + tube + gap;
    let point_a = DVec3::new(0.0, -core * tilt.cos(), gap);
    ClosedFormScene {
        name: format!("torus_on_plane(R {core}, a {tube}, tilt {tilt}, gap {gap})"),
        a: torus(core, tube),
        pose_a: pose(DQuat::from_rotation_x(tilt), DVec3::new(0.0, 0.0, height)),
        b: plate,
        pose_b: DPose3::IDENTITY,
        expected: vec![ExpectedContact {
            point_a,
            point_b: point_a - DVec3::Z * gap,
            distance: gap,
            normal: -DVec3::Z,
        }],
    }
}

/// A rod (A: capped cylinder of radius `rod`, along x, 2 (core + tube) + 4 rod + 4 long) lying
/// across a torus (B: core radius `core`, tube radius `tube`, core in z = 0) through its axis,
/// `gap` above the tube tops. Two contacts, at x = ±core.
#[must_use]
pub fn rod_across_torus(core: f64, tube: f64, rod: f64, gap: f64) -> ClosedFormScene {
    let length = 2.0 * (core + tube) + 4.0 * rod + 4.0;
    let expected = [-1.0, 1.0]
        .map(|s| {
            let point_a = DVec3::new(s * core, 0.0, tube + gap);
            ExpectedContact {
                point_a,
                point_b: point_a - DVec3::Z * gap,
                distance: gap,
                normal: -DVec3::Z,
            }
        })
        .to_vec();
    ClosedFormScene {
        name: format!("rod_across_torus(R {core}, a {tube}, rod {rod}, gap {gap})"),
        a: cylinder(rod, length),
        pose_a: pose(
            DQuat::from_rotation_y(std::f64::consts::FRAC_PI_2),
            DVec3::new(0.0, 0.0, tube + rod + gap),
        ),
        b: torus(core, tube),
        pose_b: DPose3::IDENTITY,
        expected,
    }
}
