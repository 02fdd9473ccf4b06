//! Literal poses of `cargo xtask soak` where the oracle, not the pipeline, was wrong (see
//! docs/ROBUSTNESS.md, "Oracle caveats"), each checked against a truth computed here from the
//! fixtures' profiles (closed forms in the meridian plane, or brute-force sampling of an exact
//! curve), not by the oracle.

use contact_oracle::{OracleOptions, OracleReport, find_contacts};
use geom_param::{DPose3, DQuat, DVec3, MeshOptions, ObjectFile, Solid};

fn solid(name: &str) -> Solid {
    let path = format!(
        "{}/../../fixtures/objects/{name}.json",
        env!("CARGO_MANIFEST_DIR")
    );
    let text = std::fs::read_to_string(&path).expect("fixture file");
    ObjectFile::from_json(&text)
        .expect("object JSON")
        .build(&MeshOptions::default())
        .expect("object builds")
        .solid
}

fn pose(t: [f64; 3], q: [f64; 4]) -> DPose3 {
    DPose3 {
        translation: DVec3::from_array(t),
        rotation: DQuat::from_array(q),
    }
}

/// The oracle with A at the identity and B at `pose_b`, reaching 0.2 mm (2 x delta2 of the
/// pipeline's default band, as in the soak).
fn oracle(a: &str, b: &str, pose_b: &DPose3) -> OracleReport {
    let (a, b) = (solid(a), solid(b));
    let options = OracleOptions::for_solids(&a, &b, 0.2);
    find_contacts(&a, &DPose3::IDENTITY, &b, pose_b, &options).expect("oracle runs")
}

/// goblet-pencil 17338580586634746102 of `soak 10000 --seed 14`, built as a contact at
/// 3.002e-2 mm between the goblet's outer wall (face 7, the Bézier) and the pencil. The oracle
/// reported a penetration of -3.099 mm: the pencil's point against the goblet's inner wall
/// (face 9, the sphere of radius 37 about (0, 0, 150)), a local minimum of the distance between
/// the two boundaries measured through the 3 mm wall and signed by the inner wall's normal.
/// The pencil's point is outside the goblet: in the meridian plane it lies beyond the outer
/// profile at its height.
#[test]
fn a_body_outside_a_cup_wall_is_not_inside_it() {
    let pose_b = pose(
        [5.704420256306768, -95.38081053065643, -13.363565054820784],
        [
            -0.091844371385434,
            0.1716812468330789,
            0.6863697070573868,
            0.7007044927532655,
        ],
    );
    // The formerly reported pencil point (world = goblet frame): outside the outer wall.
    let old = DVec3::new(24.96966473258399, -31.260827602949846, 147.3115723327087);
    let (rho, z) = (old.truncate().length(), old.z);
    assert!(rho > bezier_radius_at(z), "{rho} {}", bezier_radius_at(z));
    let report = oracle("goblet", "pencil", &pose_b);
    assert!(
        report.contacts.iter().all(|c| c.distance > 0.0),
        "{report:?}"
    );
    // The gap the pose was built with, quoted to 4 digits.
    assert!((report.min_distance - 3.002e-2).abs() < 1e-5, "{report:?}");
}

/// Radius of the goblet's outer wall at height `z` in [112, 150]: the cubic Bézier of the
/// profile, (30, 112), (36, 112), (40, 130), (40, 150) in (r, z), solved for z by bisection
/// (z(t) is increasing).
fn bezier_radius_at(z: f64) -> f64 {
    let cubic = |p: [f64; 4], t: f64| {
        let s = 1.0 - t;
        p[0] * s * s * s + 3.0 * p[1] * t * s * s + 3.0 * p[2] * t * t * s + p[3] * t * t * t
    };
    let (mut lo, mut hi) = (0.0, 1.0);
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if cubic([112.0, 112.0, 130.0, 150.0], mid) < z {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    cubic([30.0, 36.0, 40.0, 40.0], 0.5 * (lo + hi))
}

/// paperweight-goblet 16100062523339980813 of `soak 10000 --seed 14`, built as an overlap of
/// -5.956e-5 mm: the goblet's rim (edge 7, the circle r = 40 at z = 150) dips into the
/// paperweight's flat bottom (z = 0, material above). The oracle reported six minima at
/// 1.3e-6 to 1.2e-5 mm on the rim just outside the two points where it crosses the plane;
/// along the rim the distance to the plane falls to zero at the crossing, so none is a local
/// minimum (a damped polish had stopped next to the crossing). Brute force over the exact
/// rim: it is 5.9557e-5 mm deep at its deepest and crosses z = 0 within 1e-3 mm of each old
/// point.
#[test]
fn points_next_to_a_shallow_crossing_are_no_minima() {
    let q = DQuat::from_array([
        0.4816721975207381,
        0.1991805213538251,
        0.27005416255691045,
        -0.8095614635927573,
    ]);
    let t = DVec3::new(11.630430484643616, -113.96317353141464, -104.08174781687997);
    let rim = |theta: f64| q * DVec3::new(40.0 * theta.cos(), 40.0 * theta.sin(), 150.0) + t;
    let steps = 2_000_000;
    let mut deepest = f64::NEG_INFINITY;
    let mut crossings = Vec::new();
    let mut previous = rim(0.0);
    for k in 1..=steps {
        let p = rim(std::f64::consts::TAU * f64::from(k) / f64::from(steps));
        deepest = deepest.max(p.z);
        if (p.z > 0.0) != (previous.z > 0.0) {
            crossings.push(p - p.z / (p.z - previous.z) * (p - previous));
        }
        previous = p;
    }
    assert!((deepest - 5.9557e-5).abs() < 1e-9, "{deepest:e}");
    assert_eq!(crossings.len(), 2, "{crossings:?}");
    for old in [
        DVec3::new(3.485177581252019, 0.9308859635237039, 0.0),
        DVec3::new(3.632890089674294, 0.9412625122758386, 0.0),
    ] {
        let near = crossings
            .iter()
            .map(|c| c.distance(old))
            .fold(f64::INFINITY, f64::min);
        assert!(near < 1e-3, "{near:e}");
    }
    let report = oracle(
        "paperweight",
        "goblet",
        &DPose3 {
            rotation: q,
            translation: t,
        },
    );
    assert!(
        report
            .contacts
            .iter()
            .all(|c| !(c.distance > 0.0 && c.distance < 1e-4)),
        "{report:?}"
    );
}

/// pencil-goblet 7302112096488778657 of `soak 1000 --seed 11`, built as an overlap of
/// -7.239e-5 mm with the pencil's apex (0, 0, 177.5) inside the goblet's face 2 (the profile
/// arc of radius 27 about (r, z) = (35, 33), material on the side away from the centre). The
/// witness is the apex at depth 27 - |(r, z) - (35, 33)| in the goblet's meridian plane; the
/// oracle used to polish it onto the crossing curve (contacts at -6.5e-10 mm 2.8e-5 mm from the
/// apex, no touch).
#[test]
fn an_apex_inside_a_surface_is_witnessed_at_the_apex() {
    let pose_b = pose(
        [-7.129217804605351, 31.678192586920083, 168.7026926745926],
        [
            -0.1914257699959785,
            0.9329799519694516,
            -0.20974367287186252,
            0.22116097190677222,
        ],
    );
    let apex = DVec3::new(0.0, 0.0, 177.5);
    let local = pose_b.rotation.inverse() * (apex - pose_b.translation);
    let meridian = glam::DVec2::new(local.truncate().length(), local.z);
    let from_centre = meridian - glam::DVec2::new(35.0, 33.0);
    // On the arc's span: the angle from the centre lies between the arc's ends (35, 6), (8, 33).
    assert!(from_centre.x < 0.0 && from_centre.y < 0.0, "{meridian:?}");
    let depth = 27.0 - from_centre.length();
    assert!((depth + 7.239e-5).abs() < 1e-8, "{depth:e}");
    let report = oracle("pencil", "goblet", &pose_b);
    let witness = report
        .contacts
        .iter()
        .find(|c| c.point_a.distance(apex) < 1e-9)
        .unwrap_or_else(|| panic!("{report:?}"));
    assert!(
        (witness.distance - depth).abs() < 1e-9,
        "{witness:?} {depth:e}"
    );
    assert!(
        report.contacts.iter().all(|c| c.distance.abs() > 1e-6),
        "{report:?}"
    );
}

/// vase-paperweight 9674568083999433558 of `soak 10000 --seed 4002`, built as a touch at
/// 3.3e-10 mm: the vase's bottom rim (edge 0, the circle r = 26 at z = 0) touches the
/// paperweight's flat bottom (face 0, the plane z = 0 of B, material above it). The oracle
/// listed six minima along the rim, the touch and five more at 1.2e-7 to 6.0e-7 mm up to
/// 6e-3 mm from it, which the soak counted as missed. Closed form: with n B's outward normal
/// (−z of B) and p0 B's origin, a rim point at angle θ is (q(θ) − p0) · n from the plane,
/// = −p0 · n + 26 (n_x cos θ + n_y sin θ): a single minimum on the circle, at
/// θ* = atan2(−n_y, −n_x), rising as 26 |n_xy| (1 − cos(θ − θ*)) on both sides. So the five are
/// no minima: the polish accepted them because its residual (the tangential part of a
/// connecting vector 1e-7 mm long) is below its absolute tolerance whatever the slope. Now
/// they are members of the touch's region (the distance rises monotonically from the touch
/// to each of them along the rim) and the report has one contact.
#[test]
fn a_rim_touching_a_plane_is_one_minimum() {
    let pose_b = pose(
        [39.23675798667718, 10.268181967326449, 10.60503555006201],
        [
            -0.8272766063050112,
            0.3787005894505797,
            -0.409280350089375,
            0.06847536229159813,
        ],
    );
    let n = pose_b.rotation * -DVec3::Z;
    let p0 = pose_b.translation;
    let rim = |theta: f64| DVec3::new(26.0 * theta.cos(), 26.0 * theta.sin(), 0.0);
    let plane = |q: DVec3| (q - p0).dot(n);
    let touch_angle = (-n.y).atan2(-n.x);
    let touch = rim(touch_angle);
    let lowest = plane(touch);
    // The foot of the touch lies on B's bottom disk (radius 32).
    let foot = pose_b.rotation.inverse() * (touch - lowest * n - p0);
    assert!(
        foot.z.abs() < 1e-9 && foot.truncate().length() < 32.0,
        "{foot:?}"
    );
    let report = oracle("vase", "paperweight", &pose_b);
    let tolerance = OracleOptions::for_solids(&solid("vase"), &solid("paperweight"), 0.2).tolerance;
    assert_eq!(report.contacts.len(), 1, "{report:?}");
    let c = &report.contacts[0];
    assert!((c.distance - lowest).abs() < 1e-12, "{c:?} {lowest:e}");
    assert!(
        c.point_a.distance(touch) <= c.point_error_estimate,
        "{c:?} {touch:?}"
    );
    assert!(report.members.len() >= 5, "{report:?}");
    for m in &report.members {
        let p = m.contact.point_a;
        assert!(
            p.z.abs() < 1e-12 && (p.truncate().length() - 26.0).abs() < 1e-9,
            "{p:?}"
        );
        let rise = plane(p) - lowest;
        // A member is a point of the rim and a point of the plane whose connecting vector has
        // a tangential part e of at most the oracle's `tolerance`: its distance is
        // √(h² + e²) for the rim point's height h over the plane, so it exceeds h by
        // e² / (distance + h), and never falls below it.
        let excess = m.contact.distance - plane(p);
        let bound = tolerance * tolerance / (m.contact.distance + plane(p)) + 1e-14;
        assert!(
            excess > -1e-14 && excess <= bound,
            "{m:?}: {excess:e} over {bound:e}"
        );
        assert!(rise > 1e-8, "{m:?}: a member is no minimum, rise {rise:e}");
    }
}

/// bracket-paperweight 4792506523713132914 of `soak 300 --general --seed 2026`, built as a
/// touch at −9.3e-10 mm: the bracket's corner at its origin (vertex 0) pokes a hair into the
/// paperweight's flat bottom (face 0, the plane z = 0 of B, material above it). The oracle
/// reported +1.3e-10 mm on the bracket's edge 0, 1.6e-9 mm from the corner: a point of the
/// curve where the corner's edges cross the plane (f = ½|r|² vanishes there and the cone test
/// calls it a touch). Closed form: the corner is (p0 − 0) · n below the plane, n = B's outward
/// normal −z_B, p0 = B's origin; that is the witness, and the oracle now reports it.
#[test]
fn a_corner_a_hair_inside_a_plane_is_witnessed_at_the_corner() {
    let pose_b = pose(
        [-6.20324367429038, 1.0766358227045587, 7.716520569669497],
        [
            0.5704223424291541,
            0.6602469039450488,
            -0.4653729731888312,
            -0.14872919321371214,
        ],
    );
    let n = pose_b.rotation * -DVec3::Z;
    let depth = (DVec3::ZERO - pose_b.translation).dot(n);
    // The corner's foot lies on B's bottom disk (radius 32).
    let foot = pose_b.rotation.inverse() * (-depth * n - pose_b.translation);
    assert!(foot.truncate().length() < 32.0, "{foot:?}");
    assert!(depth < -9e-10 && depth > -1.1e-9, "{depth:e}");
    let report = oracle("bracket", "paperweight", &pose_b);
    let c = report
        .contacts
        .iter()
        .min_by(|x, y| x.distance.total_cmp(&y.distance))
        .unwrap_or_else(|| panic!("{report:?}"));
    assert!((c.distance - depth).abs() < 1e-13, "{c:?} {depth:e}");
    assert!(c.point_a.length() < 1e-12, "{c:?}");
}
