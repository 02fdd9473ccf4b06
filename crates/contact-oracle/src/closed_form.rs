//! Scenes with contacts known in closed form, built from profiles, for testing the oracle (and,
//! through it, anything compared with the oracle).
//!
//! Every builder is parametrised by the signed gap (mm; negative: overlap depth) and returns
//! the exact contacts. A scene can be moved rigidly as a whole ([`ClosedFormScene::moved`]) so
//! tests need not rely on axis-aligned poses.
//!
//! [`ClosedFormScene`]s pair two solids of revolution (profiles); [`BrepScene`]s pair a sphere
//! with a general solid ([`brep`]: a block with trimmed planar faces, straight edges and
//! corners; geom-param's extrusions: a plate with a cylindrical hole, an L-shaped bracket), so
//! that contacts on a face, on an edge (the distance to a line), at a corner (the distance to
//! a point), inside a hole (the distance to a cylinder) and in a concave corner have exact
//! answers.

pub mod brep;

use geom_param::{
    BuildError, DPose3, DQuat, DVec2, DVec3, LoadError, MeshOptions, ObjectDescription,
    PlanarProfile, PlanarSegment, SegmentSpec, Solid, extrude,
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

/// `motion` after `pose`.
fn compose(motion: &DPose3, pose: &DPose3) -> DPose3 {
    DPose3 {
        rotation: (motion.rotation * pose.rotation).normalize(),
        translation: motion.rotation * pose.translation + motion.translation,
    }
}

/// The expected contacts after the rigid motion `motion` of the whole world.
fn moved_contacts(expected: &[ExpectedContact], motion: &DPose3) -> Vec<ExpectedContact> {
    expected
        .iter()
        .map(|e| ExpectedContact {
            point_a: motion.rotation * e.point_a + motion.translation,
            point_b: motion.rotation * e.point_b + motion.translation,
            distance: e.distance,
            normal: motion.rotation * e.normal,
        })
        .collect()
}

impl ClosedFormScene {
    /// The scene after the rigid motion `motion` of the whole world.
    #[must_use]
    pub fn moved(&self, motion: &DPose3) -> Self {
        Self {
            name: self.name.clone(),
            a: self.a.clone(),
            pose_a: compose(motion, &self.pose_a),
            b: self.b.clone(),
            pose_b: compose(motion, &self.pose_b),
            expected: moved_contacts(&self.expected, motion),
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

/// An object of a [`BrepScene`]: a solid of revolution from its profile, or a solid built face
/// by face.
#[derive(Clone, Debug, PartialEq)]
pub enum SceneObject {
    /// The solid revolved from this description.
    Profile(ObjectDescription),
    /// [`brep::block`]: sides `size` (mm), centred at the origin, edges along the axes.
    Block {
        /// Side lengths along x, y, z (mm).
        size: DVec3,
    },
    /// geom-param's [`extrude`] of a planar profile (xy plane) from z0 to z1 (mm).
    Extrusion {
        /// The profile, holes included.
        profile: PlanarProfile,
        /// Bottom (mm).
        z0: f64,
        /// Top (mm).
        z1: f64,
    },
}

/// Why a closed-form scene's object could not be built.
#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    /// A solid of revolution's profile is invalid.
    #[error(transparent)]
    Profile(#[from] LoadError),
    /// A general solid could not be built or fails validation.
    #[error(transparent)]
    Build(#[from] BuildError),
}

impl SceneObject {
    /// The exact solid.
    ///
    /// # Errors
    /// A [`SceneError`] if a profile or a dimension is invalid (the builders' tests check
    /// they are not).
    pub fn solid(&self) -> Result<Solid, SceneError> {
        Ok(match self {
            Self::Profile(d) => build(d)?,
            Self::Block { size } => brep::block(*size)?,
            Self::Extrusion { profile, z0, z1 } => extrude(profile, *z0, *z1)?,
        })
    }
}

/// The plate of [`sphere_in_hole`] and [`sphere_on_hole_rim`]: [`brep::holed_plate`] as a
/// scene object.
fn holed_plate(width: f64, thickness: f64, radius: f64) -> SceneObject {
    SceneObject::Extrusion {
        profile: brep::holed_square(width, radius),
        z0: -0.5 * thickness,
        z1: 0.5 * thickness,
    }
}

/// Two posed objects, at least one of them built face by face, and their exact contacts.
#[derive(Clone, Debug, PartialEq)]
pub struct BrepScene {
    /// Name for messages, with the parameters.
    pub name: String,
    /// Object A.
    pub a: SceneObject,
    /// A's pose (object to world).
    pub pose_a: DPose3,
    /// Object B.
    pub b: SceneObject,
    /// B's pose.
    pub pose_b: DPose3,
    /// Every local minimum of distance (or penetration witness) within 1 mm, in no order.
    pub expected: Vec<ExpectedContact>,
}

impl BrepScene {
    /// The scene after the rigid motion `motion` of the whole world.
    #[must_use]
    pub fn moved(&self, motion: &DPose3) -> Self {
        Self {
            name: self.name.clone(),
            a: self.a.clone(),
            pose_a: compose(motion, &self.pose_a),
            b: self.b.clone(),
            pose_b: compose(motion, &self.pose_b),
            expected: moved_contacts(&self.expected, motion),
        }
    }

    /// The same scene with A and B exchanged: each contact's points exchanged and its normal
    /// reversed (B's outward normal is minus A's at a contact).
    #[must_use]
    pub fn swapped(&self) -> Self {
        Self {
            name: format!("{} (swapped)", self.name),
            a: self.b.clone(),
            pose_a: self.pose_b,
            b: self.a.clone(),
            pose_b: self.pose_a,
            expected: self
                .expected
                .iter()
                .map(|e| ExpectedContact {
                    point_a: e.point_b,
                    point_b: e.point_a,
                    distance: e.distance,
                    normal: -e.normal,
                })
                .collect(),
        }
    }

    /// The exact solids of A and B.
    ///
    /// # Errors
    /// A [`SceneError`] if an object cannot be built.
    pub fn solids(&self) -> Result<(Solid, Solid), SceneError> {
        Ok((self.a.solid()?, self.b.solid()?))
    }
}

/// A sphere (A, radius `r`, spun by `spin`) whose centre is `r + gap` from the point `foot` of
/// B along B's outward direction `away` there (unit), with B the block `size`: one contact,
/// point_b = foot, normal = −away.
fn sphere_at_block(
    name: String,
    r: f64,
    size: DVec3,
    gap: f64,
    foot: DVec3,
    away: DVec3,
    spin: DQuat,
) -> BrepScene {
    let centre = foot + away * (r + gap);
    BrepScene {
        name,
        a: SceneObject::Profile(sphere(r)),
        pose_a: pose(spin, centre),
        b: SceneObject::Block { size },
        pose_b: DPose3::IDENTITY,
        expected: vec![ExpectedContact {
            point_a: centre - away * r,
            point_b: foot,
            distance: gap,
            normal: -away,
        }],
    }
}

/// A sphere (A, radius `r`, spun by `spin`) above the top face (z = size.z / 2) of a block (B,
/// sides `size`, centred at the origin), its centre over (offset.x, offset.y) at height
/// size.z / 2 + r + gap. One contact, at the face's point below the centre; requires the
/// offset at least 1 mm inside the face, so that the face's edges are no nearer minima.
#[must_use]
pub fn sphere_on_block_face(
    r: f64,
    size: DVec3,
    gap: f64,
    offset: DVec2,
    spin: DQuat,
) -> BrepScene {
    let foot = DVec3::new(offset.x, offset.y, 0.5 * size.z);
    sphere_at_block(
        format!("sphere_on_block_face(r {r}, size {size}, gap {gap}, offset {offset})"),
        r,
        size,
        gap,
        foot,
        DVec3::Z,
        spin,
    )
}

/// A sphere (A, radius `r`, spun by `spin`) beside the block's edge x = size.x / 2,
/// z = size.z / 2 (B, sides `size`, centred at the origin): its centre lies r + gap from the
/// edge point (size.x / 2, along, size.z / 2) in the direction (cos angle, 0, sin angle),
/// `angle` in (0, π/2) so that the edge point is the block's nearest point (the distance to a
/// line). One contact at that edge point; |along| <= size.y / 2 − 1 keeps the corners beyond
/// 1 mm of it.
#[must_use]
pub fn sphere_near_block_edge(
    r: f64,
    size: DVec3,
    gap: f64,
    angle: f64,
    along: f64,
    spin: DQuat,
) -> BrepScene {
    let foot = DVec3::new(0.5 * size.x, along, 0.5 * size.z);
    sphere_at_block(
        format!("sphere_near_block_edge(r {r}, size {size}, gap {gap}, angle {angle})"),
        r,
        size,
        gap,
        foot,
        DVec3::new(angle.cos(), 0.0, angle.sin()),
        spin,
    )
}

/// A sphere (A, radius `r`, spun by `spin`) off the block's corner size / 2 (B, sides `size`,
/// centred at the origin): its centre lies r + gap from the corner along `direction`, whose
/// components must all be positive so that the corner is the block's nearest point (the
/// distance to a point). One contact, at the corner.
#[must_use]
pub fn sphere_near_block_corner(
    r: f64,
    size: DVec3,
    gap: f64,
    direction: DVec3,
    spin: DQuat,
) -> BrepScene {
    sphere_at_block(
        format!("sphere_near_block_corner(r {r}, size {size}, gap {gap}, dir {direction})"),
        r,
        size,
        gap,
        0.5 * size,
        direction.normalize(),
        spin,
    )
}

/// A sphere (A, radius `r` < `radius`, spun by `spin`) inside the cylindrical hole (radius
/// `radius`, axis z) of a square plate (B, 4 radius wide, `thickness` thick along z, centred
/// at the origin). The centre lies at height `height` and at `radius − r − gap` from the axis
/// in the direction `azimuth` (rad) from x: one contact, on that radial line at the hole's
/// wall, distance `gap` (the distance to a cylinder from inside). Requires
/// |height| + r + 1 <= thickness / 2, so that the rims and faces stay beyond 1 mm.
#[must_use]
pub fn sphere_in_hole(
    r: f64,
    radius: f64,
    thickness: f64,
    gap: f64,
    height: f64,
    azimuth: f64,
    spin: DQuat,
) -> BrepScene {
    let d = DVec3::new(azimuth.cos(), azimuth.sin(), 0.0);
    let centre = d * (radius - r - gap) + DVec3::Z * height;
    let point_a = centre + d * r;
    BrepScene {
        name: format!(
            "sphere_in_hole(r {r}, R {radius}, thickness {thickness}, gap {gap}, height {height})"
        ),
        a: SceneObject::Profile(sphere(r)),
        pose_a: pose(spin, centre),
        b: holed_plate(4.0 * radius, thickness, radius),
        pose_b: DPose3::IDENTITY,
        expected: vec![ExpectedContact {
            point_a,
            point_b: point_a + d * gap,
            distance: gap,
            normal: d,
        }],
    }
}

/// A sphere (A, radius `r`, spun by `spin`) resting on the rim of the cylindrical hole (radius
/// `radius`, axis z) of a square plate (B, 4 radius wide, `thickness` thick, centred at the
/// origin): the rim is the circle where the plate's top face (z = thickness / 2, trimmed by
/// the hole) meets the hole's wall. The centre lies r + gap from the rim point P at `azimuth`
/// (rad, from x) along cos(tilt) (towards the axis) + sin(tilt) z, `tilt` in (0, π/2), a
/// direction between the two faces' normals, so that P is the plate's nearest point (the
/// distance to a circle edge). One contact at P; requires r + gap < radius.
#[must_use]
pub fn sphere_on_hole_rim(
    r: f64,
    radius: f64,
    thickness: f64,
    gap: f64,
    tilt: f64,
    azimuth: f64,
    spin: DQuat,
) -> BrepScene {
    let radial = DVec3::new(azimuth.cos(), azimuth.sin(), 0.0);
    let rim = radial * radius + DVec3::Z * (0.5 * thickness);
    let away = -radial * tilt.cos() + DVec3::Z * tilt.sin();
    let centre = rim + away * (r + gap);
    BrepScene {
        name: format!(
            "sphere_on_hole_rim(r {r}, R {radius}, thickness {thickness}, gap {gap}, tilt {tilt})"
        ),
        a: SceneObject::Profile(sphere(r)),
        pose_a: pose(spin, centre),
        b: holed_plate(4.0 * radius, thickness, radius),
        pose_b: DPose3::IDENTITY,
        expected: vec![ExpectedContact {
            point_a: centre - away * r,
            point_b: rim,
            distance: gap,
            normal: -away,
        }],
    }
}

/// A sphere (A, radius `r`, spun by `spin`) nestled in the concave corner of an L-shaped
/// bracket (B: geom-param's extrusion of the L with outer corner at the origin, arms 4 mm
/// thick and 2 r + 10 long along x and y, from z = −(r + 3) to r + 3). The inner faces are the
/// planes y = 4 (for x >= 4) and x = 4 (for y >= 4), meeting in a concave edge along z; the
/// centre lies at (4 + r + gap, 4 + r + gap, `height`). Two contacts, one on each inner face,
/// each at distance `gap`; the concave edge (√2 (r + gap) − r from the sphere) is no minimum.
/// Requires |height| <= 2.
#[must_use]
pub fn sphere_in_l_corner(r: f64, gap: f64, height: f64, spin: DQuat) -> BrepScene {
    let (t, a, h) = (4.0, 2.0 * r + 10.0, r + 3.0);
    let line = |from: [f64; 2], to: [f64; 2]| PlanarSegment::Line {
        from: DVec2::from(from),
        to: DVec2::from(to),
    };
    let profile = PlanarProfile {
        outer: vec![
            line([0.0, 0.0], [a, 0.0]),
            line([a, 0.0], [a, t]),
            line([a, t], [t, t]),
            line([t, t], [t, a]),
            line([t, a], [0.0, a]),
            line([0.0, a], [0.0, 0.0]),
        ],
        holes: Vec::new(),
    };
    let centre = DVec3::new(t + r + gap, t + r + gap, height);
    let expected = [DVec3::X, DVec3::Y]
        .map(|axis| {
            let point_a = centre - axis * r;
            ExpectedContact {
                point_a,
                point_b: point_a - axis * gap,
                distance: gap,
                normal: -axis,
            }
        })
        .to_vec();
    BrepScene {
        name: format!("sphere_in_l_corner(r {r}, gap {gap}, height {height})"),
        a: SceneObject::Profile(sphere(r)),
        pose_a: pose(spin, centre),
        b: SceneObject::Extrusion {
            profile,
            z0: -h,
            z1: h,
        },
        pose_b: DPose3::IDENTITY,
        expected,
    }
}
