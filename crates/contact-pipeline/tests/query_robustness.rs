//! Bad and extreme poses through `ContactPipeline::query` on three paper objects (pencil, bowl,
//! vase at a 0.1 mm chordal tolerance): random poses near the fixture contacts, random poses
//! anywhere, far translations (1e6 and 1e12 mm), tiny rotations, non-finite and non-unit
//! rotations. Every call must return `Ok` or `Err(QueryError)` (a panic fails the test); every
//! `Ok` report must be free of NaN, its contacts must satisfy point_b = point_a + distance x
//! normal, and its state must agree with its contacts. Deterministic: a seeded SplitMix64.

use contact_pipeline::{
    ContactOptions, ContactPipeline, PairReport, PairState, PreparedObject, QueryError,
    QueryScratch,
};
use geom_param::{DPose3, DQuat, DVec3, ObjectDescription};
use std::path::Path;

/// SplitMix64 (Steele, Lea, Flood 2014): small, seedable, good enough to pick cases.
struct SplitMix64(u64);

impl SplitMix64 {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1).
    fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Uniform in [-1, 1).
    fn signed(&mut self) -> f64 {
        2.0 * self.unit() - 1.0
    }

    /// A uniformly distributed direction.
    fn direction(&mut self) -> DVec3 {
        loop {
            let v = DVec3::new(self.signed(), self.signed(), self.signed());
            let l = v.length();
            if l > 0.1 && l <= 1.0 {
                return v / l;
            }
        }
    }

    /// A uniformly distributed rotation (Shoemake's method).
    fn rotation(&mut self) -> DQuat {
        let (u1, u2, u3) = (self.unit(), self.unit(), self.unit());
        let tau = std::f64::consts::TAU;
        let (a, b) = ((1.0 - u1).sqrt(), u1.sqrt());
        DQuat::from_xyzw(
            a * (tau * u2).sin(),
            a * (tau * u2).cos(),
            b * (tau * u3).sin(),
            b * (tau * u3).cos(),
        )
    }
}

fn pose(rotation: DQuat, translation: DVec3) -> DPose3 {
    DPose3 {
        rotation,
        translation,
    }
}

const DELTA1: f64 = -0.001;
const DELTA2: f64 = 0.1;

struct Fixture {
    pipeline: ContactPipeline,
    pencil: PreparedObject,
    bowl: PreparedObject,
    vase: PreparedObject,
}

fn fixture() -> Fixture {
    let pipeline = ContactPipeline::new(ContactOptions {
        chordal_tolerance: 0.1,
        delta1: DELTA1,
        delta2: DELTA2,
        ..ContactOptions::default()
    })
    .expect("options");
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/objects");
    let load = |name: &str| {
        let text = std::fs::read_to_string(dir.join(format!("{name}.json"))).expect("fixture");
        let description = ObjectDescription::from_json(&text).expect("object file");
        pipeline
            .prepare_description(&description)
            .expect("paper object")
    };
    Fixture {
        pencil: load("pencil"),
        bowl: load("bowl"),
        vase: load("vase"),
        pipeline,
    }
}

/// The poses of B (A at the identity) in the fixture scenes, copied from
/// `fixtures/scenes/{pencil-bowl,vase-vase}-{one,two}-contact(s).json`.
fn contact_poses() -> [(&'static str, DPose3); 4] {
    [
        (
            "pencil-bowl-one-contact",
            pose(
                DQuat::from_xyzw(0.0, 0.9238795325112867, 0.0, 0.38268343236508984),
                DVec3::new(-115.5, 0.0, 131.5314536606893),
            ),
        ),
        (
            "pencil-bowl-two-contacts",
            pose(
                DQuat::from_xyzw(0.0, 0.8977059759571835, 0.0, 0.44059503030647196),
                DVec3::new(-130.3998473869082, 0.0, 114.60598684057987),
            ),
        ),
        (
            "vase-vase-one-contact",
            pose(DQuat::IDENTITY, DVec3::new(69.7210017493926, 0.0, 0.0)),
        ),
        (
            "vase-vase-two-contacts",
            pose(
                DQuat::from_xyzw(0.0, -0.39018610922003333, 0.0, 0.9207360100331323),
                DVec3::new(87.63647781006527, 1.8645304127143176e-26, 37.12955634852105),
            ),
        ),
    ]
}

#[derive(Default, Debug)]
struct Tally {
    queries: usize,
    errors: usize,
    separated: usize,
    contact: usize,
    penetration: usize,
    contacts: usize,
}

/// Runs one query and checks the report; returns it (or the error) for further checks.
fn run(
    f: &Fixture,
    scratch: &mut QueryScratch,
    (a, pose_a): (&PreparedObject, DPose3),
    (b, pose_b): (&PreparedObject, DPose3),
    tally: &mut Tally,
    what: &str,
) -> Result<PairReport, QueryError> {
    tally.queries += 1;
    let result = f.pipeline.query(a, &pose_a, b, &pose_b, scratch);
    match &result {
        Err(e) => {
            tally.errors += 1;
            assert!(!e.to_string().is_empty(), "{what}");
        }
        Ok(report) => {
            check_report(report, &pose_a, &pose_b, what);
            tally.contacts += report.contacts.len();
            match report.state {
                PairState::Separated => tally.separated += 1,
                PairState::Contact => tally.contact += 1,
                PairState::Penetration => tally.penetration += 1,
            }
        }
    }
    result
}

fn check_report(report: &PairReport, pose_a: &DPose3, pose_b: &DPose3, what: &str) {
    let what = format!("{what} (pose_a {pose_a:?}, pose_b {pose_b:?})");
    let scale =
        200.0 + pose_a.translation.abs().max_element() + pose_b.translation.abs().max_element();
    for w in &report.penetration_witnesses {
        assert!(w.is_finite(), "{what}: witness {w}");
    }
    for (i, c) in report.contacts.iter().enumerate() {
        assert!(
            c.point_a.is_finite() && c.point_b.is_finite() && c.normal.is_finite(),
            "{what}: contact {i} {c:?}"
        );
        assert!(c.distance.is_finite(), "{what}: contact {i} {c:?}");
        // In the band, or below it as a penetration region's depth (only when penetrating).
        assert!(
            c.distance <= DELTA2
                && (c.distance >= DELTA1 || report.state == PairState::Penetration),
            "{what}: contact {i} outside the band: {c:?}"
        );
        assert!(
            (c.normal.length() - 1.0).abs() < 1e-9,
            "{what}: contact {i} normal length {}",
            c.normal.length()
        );
        let gap = c.point_b - (c.point_a + c.distance * c.normal);
        assert!(
            gap.length() <= 1e-9 * scale,
            "{what}: contact {i} point_b - (point_a + d n) = {gap} (scale {scale}): {c:?}"
        );
        let d = &c.diagnostics;
        // Documented: `condition` is +inf when the smallest eigenvalue is zero and
        // `point_error_estimate` is +inf for a continuous contact. Nothing may be NaN.
        assert!(d.gradient_norm.is_finite(), "{what}: contact {i} {d:?}");
        assert!(!d.condition.is_nan(), "{what}: contact {i} {d:?}");
        assert!(d.error_estimate.is_finite(), "{what}: contact {i} {d:?}");
        assert!(
            !d.point_error_estimate.is_nan(),
            "{what}: contact {i} {d:?}"
        );
    }
    match report.state {
        PairState::Separated => {
            assert!(
                report.contacts.is_empty(),
                "{what}: separated with contacts"
            );
            assert!(
                report.penetration_witnesses.is_empty(),
                "{what}: separated with penetration witnesses"
            );
        }
        PairState::Contact => {
            assert!(
                !report.contacts.is_empty(),
                "{what}: contact without contacts"
            );
            assert!(
                report.penetration_witnesses.is_empty(),
                "{what}: contact with penetration witnesses"
            );
        }
        PairState::Penetration => {}
    }
}

#[test]
fn random_poses_near_contact_and_anywhere() {
    let f = fixture();
    let mut scratch = QueryScratch::default();
    let mut rng = SplitMix64(0xC0_47AC7);
    let mut tally = Tally::default();
    let objects = |name: &str| match name.split('-').next() {
        Some("pencil") => (&f.pencil, &f.bowl),
        _ => (&f.vase, &f.vase),
    };
    // Near the fixture contacts: B jittered by 1e-6..1 mm and up to 0.02 rad, then the whole
    // pair moved by a random rigid motion.
    for (name, pose_b) in contact_poses() {
        let (b, a) = objects(name);
        for _ in 0..40 {
            let shift = 10f64.powf(-6.0 + 6.0 * rng.unit()) * rng.direction();
            let turn = DQuat::from_scaled_axis(0.02 * rng.unit() * rng.direction());
            let local_b = pose(turn * pose_b.rotation, pose_b.translation + shift);
            let world = pose(rng.rotation(), 300.0 * rng.direction());
            let result = run(
                &f,
                &mut scratch,
                (a, world),
                (b, world * local_b),
                &mut tally,
                name,
            );
            assert!(result.is_ok(), "{name}: {result:?}");
        }
    }
    // Anywhere: random rotations, B's origin within 150 mm of A's.
    let pairs = [
        ("pencil-bowl", &f.bowl, &f.pencil),
        ("vase-pencil", &f.vase, &f.pencil),
        ("bowl-vase", &f.bowl, &f.vase),
        ("vase-vase", &f.vase, &f.vase),
    ];
    for (name, a, b) in pairs {
        for _ in 0..15 {
            let pose_a = pose(rng.rotation(), 50.0 * rng.signed() * rng.direction());
            let pose_b = pose(rng.rotation(), 150.0 * rng.unit() * rng.direction());
            let result = run(&f, &mut scratch, (a, pose_a), (b, pose_b), &mut tally, name);
            assert!(result.is_ok(), "{name}: {result:?}");
        }
    }
    println!("{tally:?}");
    assert_eq!(tally.queries, 220);
}

#[test]
fn far_translations_and_tiny_rotations() {
    let f = fixture();
    let mut scratch = QueryScratch::default();
    let mut rng = SplitMix64(0xFA2);
    let mut tally = Tally::default();
    for (name, pose_b) in contact_poses() {
        let (b, a) = match name.split('-').next() {
            Some("pencil") => (&f.pencil, &f.bowl),
            _ => (&f.vase, &f.vase),
        };
        for far in [1e6, 1e12, -1e12] {
            // Both objects far from the origin (the pair itself unchanged) ...
            let offset = far * rng.direction();
            let world = pose(DQuat::IDENTITY, offset);
            let _ = run(
                &f,
                &mut scratch,
                (a, world),
                (b, world * pose_b),
                &mut tally,
                &format!("{name} moved by {far:e}"),
            );
            // ... and B alone sent far away: separated.
            let away = pose(pose_b.rotation, pose_b.translation + offset);
            let report = run(
                &f,
                &mut scratch,
                (a, DPose3::IDENTITY),
                (b, away),
                &mut tally,
                &format!("{name} B at {far:e}"),
            )
            .expect("a far pose is a rigid motion");
            assert_eq!(report.state, PairState::Separated, "{name} B at {far:e}");
        }
        // Tiny rotations of B about its fixture pose, and of the whole pair.
        for angle in [5e-324, 1e-300, 1e-200, 1e-16, 1e-12, 1e-8] {
            let turn = DQuat::from_axis_angle(rng.direction(), angle);
            let what = format!("{name} turned by {angle:e}");
            let local = pose(turn * pose_b.rotation, pose_b.translation);
            let result = run(
                &f,
                &mut scratch,
                (a, DPose3::IDENTITY),
                (b, local),
                &mut tally,
                &what,
            );
            assert!(result.is_ok(), "{what}: {result:?}");
            let world = pose(turn, DVec3::ZERO);
            let result = run(
                &f,
                &mut scratch,
                (a, world),
                (b, world * pose_b),
                &mut tally,
                &what,
            );
            assert!(result.is_ok(), "{what}: {result:?}");
        }
    }
    println!("{tally:?}");
    assert_eq!(tally.queries, 4 * (3 * 2 + 6 * 2));
}

#[test]
fn non_finite_and_non_unit_poses_are_errors_or_rigid() {
    let f = fixture();
    let mut scratch = QueryScratch::default();
    let mut tally = Tally::default();
    let (_, pose_b) = contact_poses()[0];
    let (a, b) = (&f.bowl, &f.pencil);
    // Each of the seven components of either pose made non-finite: always `BadPose`.
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        for k in 0..7 {
            for which in ["a", "b"] {
                let mut p = if which == "a" {
                    DPose3::IDENTITY
                } else {
                    pose_b
                };
                let mut q = p.rotation.to_array();
                let mut t = p.translation.to_array();
                if k < 4 {
                    q[k] = bad;
                } else {
                    t[k - 4] = bad;
                }
                p = pose(DQuat::from_array(q), DVec3::from_array(t));
                let (pa, pb) = if which == "a" {
                    (p, pose_b)
                } else {
                    (DPose3::IDENTITY, p)
                };
                let what = format!("pose {which} component {k} = {bad}");
                let result = run(&f, &mut scratch, (a, pa), (b, pb), &mut tally, &what);
                assert!(
                    matches!(result, Err(QueryError::BadPose { .. })),
                    "{what}: {result:?}"
                );
            }
        }
    }
    // Rotations whose norm is off 1 by more than the documented 1e-6: `BadPose`. (Within it, see
    // `near_unit_rotation_gives_unit_normals`.)
    for (norm, accepted) in [
        (0.0, false),
        (5e-324, false),
        (0.5, false),
        (1.0 - 1e-5, false),
        (1.0 + 2e-6, false),
        (1e300, false),
    ] {
        for which in ["a", "b"] {
            let scaled = |p: DPose3| pose(p.rotation * norm, p.translation);
            let (pa, pb) = if which == "a" {
                (scaled(DPose3::IDENTITY), pose_b)
            } else {
                (DPose3::IDENTITY, scaled(pose_b))
            };
            let what = format!("rotation of {which} with norm {norm:e}");
            let result = run(&f, &mut scratch, (a, pa), (b, pb), &mut tally, &what);
            if accepted {
                assert!(result.is_ok(), "{what}: {result:?}");
            } else {
                assert!(
                    matches!(result, Err(QueryError::BadPose { .. })),
                    "{what}: {result:?}"
                );
            }
        }
    }
    println!("{tally:?}");
    assert_eq!(tally.queries, 3 * 7 * 2 + 6 * 2);
}

/// FIXME (found by `non_finite_and_non_unit_poses_are_errors_or_rigid`): `query` accepts a
/// rotation quaternion whose norm is within 1e-6 of 1 but does not normalise it, so the world
/// normal is scaled by |q|^2: with A's rotation [0, 0, 0, 1.0000009] and B at the
/// pencil-bowl-one-contact pose, contact 0 has a normal of length 1.0000018000008102 (and the
/// points are not a rigid motion of the exact ones). Expected: a unit normal (normalise the
/// accepted quaternion, as the scene loader does).
#[test]
fn near_unit_rotation_gives_unit_normals() {
    let f = fixture();
    let mut scratch = QueryScratch::default();
    let mut tally = Tally::default();
    let pose_a = pose(DQuat::from_xyzw(0.0, 0.0, 0.0, 1.0000009), DVec3::ZERO);
    let (_, pose_b) = contact_poses()[0];
    let result = run(
        &f,
        &mut scratch,
        (&f.bowl, pose_a),
        (&f.pencil, pose_b),
        &mut tally,
        "A rotated by [0, 0, 0, 1.0000009]",
    );
    assert!(result.is_ok_and(|r| r.state == PairState::Contact));
}
