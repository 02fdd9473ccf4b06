//! Shared test scaffolding: a seeded PRNG, random rigid motions, and the comparison of an
//! oracle report with a closed-form scene.
#![allow(dead_code)] // each test binary uses a different subset

use contact_oracle::closed_form::BrepScene;
use contact_oracle::{
    ClosedFormScene, ExpectedContact, OracleContact, OracleOptions, OracleReport, find_contacts,
};
use geom_param::{DPose3, DQuat, DVec3, Solid};

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
            if v.length() <= 1.0 && v.length() > 0.1 {
                return v.normalize();
            }
        }
    }

    pub fn rotation(&mut self) -> DQuat {
        DQuat::from_axis_angle(self.unit_vector(), self.range(0.0, std::f64::consts::TAU))
    }

    pub fn motion(&mut self) -> DPose3 {
        DPose3 {
            rotation: self.rotation(),
            translation: DVec3::new(
                self.range(-50.0, 50.0),
                self.range(-50.0, 50.0),
                self.range(-50.0, 50.0),
            ),
        }
    }
}

/// Worst errors of one comparison.
#[derive(Clone, Copy, Debug, Default)]
pub struct Errors {
    pub distance: f64,
    pub point: f64,
    pub normal: f64,
}

impl Errors {
    pub fn max(self, o: Self) -> Self {
        Self {
            distance: self.distance.max(o.distance),
            point: self.point.max(o.point),
            normal: self.normal.max(o.normal),
        }
    }
}

/// Runs the oracle on `scene` with reach 1 mm and checks it reports exactly the expected
/// contacts: same count, each expected contact matched by distance within `distance_tol` and
/// both points within `point_tol` and within the contact's own `point_error_estimate`, clean
/// cross-check. Returns the report and the errors.
pub fn check_scene(
    scene: &ClosedFormScene,
    distance_tol: f64,
    point_tol: f64,
) -> (OracleReport, Errors) {
    let (a, b) = scene.solids().expect("closed-form profiles are valid");
    check_solids(
        &scene.name,
        (&a, &scene.pose_a),
        (&b, &scene.pose_b),
        &scene.expected,
        distance_tol,
        point_tol,
    )
}

/// [`check_scene`] for a scene with solids built face by face.
pub fn check_brep_scene(
    scene: &BrepScene,
    distance_tol: f64,
    point_tol: f64,
) -> (OracleReport, Errors) {
    let (a, b) = scene.solids().expect("closed-form solids are valid");
    check_solids(
        &scene.name,
        (&a, &scene.pose_a),
        (&b, &scene.pose_b),
        &scene.expected,
        distance_tol,
        point_tol,
    )
}

/// The oracle with reach 1 mm on two posed solids against the `expected` contacts (see
/// [`check_scene`]).
pub fn check_solids(
    what: &str,
    (a, pose_a): (&Solid, &DPose3),
    (b, pose_b): (&Solid, &DPose3),
    expected: &[ExpectedContact],
    distance_tol: f64,
    point_tol: f64,
) -> (OracleReport, Errors) {
    let options = OracleOptions::for_solids(a, b, 1.0);
    let report = find_contacts(a, pose_a, b, pose_b, &options).expect("oracle runs");
    assert_eq!(
        report.contacts.len(),
        expected.len(),
        "{what}: contacts {:#?}",
        report.contacts
    );
    assert_eq!(
        report.cross_check.unmatched, 0,
        "{what}: {:?}",
        report.cross_check
    );
    let mut errors = Errors::default();
    for e in expected {
        let c: &OracleContact = report
            .contacts
            .iter()
            .min_by(|p, q| {
                p.point_a
                    .distance(e.point_a)
                    .total_cmp(&q.point_a.distance(e.point_a))
            })
            .expect("at least one contact");
        let err = Errors {
            distance: (c.distance - e.distance).abs(),
            point: c
                .point_a
                .distance(e.point_a)
                .max(c.point_b.distance(e.point_b)),
            normal: (c.normal - e.normal).length(),
        };
        assert!(
            err.distance <= distance_tol,
            "{what}: distance {} vs {} ({c:?})",
            c.distance,
            e.distance
        );
        assert!(err.point <= point_tol, "{what}: points {c:?} vs {e:?}");
        // The oracle's own bound on its points (from its conditioning) covers the error.
        assert!(
            err.point <= c.point_error_estimate,
            "{what}: point error {:e} above the bound {:e}: {c:?} vs {e:?}",
            err.point,
            c.point_error_estimate
        );
        // Exact up to the stationarity residual (the tangential part of the connecting vector).
        assert!(
            (c.point_b - (c.point_a + c.normal * c.distance)).length()
                <= 2.0 * c.residual + 1e-12 * (1.0 + c.point_a.length()),
            "{what}: point_b != point_a + distance normal: {c:?}"
        );
        errors = errors.max(err);
    }
    (report, errors)
}
