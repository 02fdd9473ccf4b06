//! Contacts in the band reported as separated, found as generator failures of
//! `soak 2000 --general --seed 9202` and `--seed 9201`: the touch's bisection ended where the
//! pipeline's state jumped from Separated to a contact at mid-band.
//!
//! - A vertex where faces meet with one tangent plane (bowl-rounded-box 3846327417572710959,
//!   pencil-bracket 10733121780553108644). At the rounded box's corner vertex the best
//!   first-order way off it led into a flat face whose descent went straight back out over
//!   its edge to the same vertex; the solve took that way every time and stopped at its switch
//!   limit (not converged, dropped), while the way into the fillet led to the minimum.
//!   Re-entry now prefers a way not yet taken from that feature, and the seed-face retry's
//!   converged polish replaces an answer that did not converge.
//! - A trimmed face's boundary taken from a polyline (bracket-bracket 1902993129432262258):
//!   the nearest trim point of a (u, v) on the chord of the cap's fillet arc was the chord's
//!   own point, so a point 2e-3 mm inside the arc passed for a point of the cap; the solve
//!   stalled there at 0.03728 mm against the minimum 0.03731 mm on the arc. The nearest trim
//!   point is now always on the exact p-curve.
//! - A planar face's chordal error without its rim (loft-bracket 10941492566190232716 of
//!   `soak 2000 --general --seed 10201`): the loft's elliptic bottom cap stated a chordal
//!   error of 0 (its triangles lie on its plane) while its rim stands off the boundary chords
//!   by up to 0.016 mm, and GJK certified its hull farther than the band plus the errors from
//!   a bracket 0.0989 mm away. A face's chordal error now includes its boundary edges' chord
//!   deviation.
//! - A saddle escape at an exact touch (vase-bowl 2697845155447835510 of `soak 10000 --seed
//!   10102`, 3.5e-12 mm): rounding gave the flat direction of ½|d|² (both points sliding
//!   together) a negative eigenvalue, and the solve stepped its whole trust radius (40 mm)
//!   along it without checking that f went down, came back and jumped again to its iteration
//!   limit. The escape now has to descend, or the point is a minimum. Since the pair solve
//!   starts at the seed's own parameters (session 21) its solve stopped at 3.0e-9 mm, 2.2e-4
//!   mm along the flat valley from the touch, with f's gradient under its rounding floor: a
//!   stationary end now goes on with Newton steps on the distance while they predict a fall
//!   above that floor.
//! - The same stop before the touch flipped a state (pencil-paperweight 17897396705959179123
//!   of `soak 10000 --seed 13150`, built at -1.4e-10 mm): the first query stopped at +1.45e-8
//!   mm, 2.7e-4 mm from the minimum, so the pose moved to delta1 was not a penetration.
//!
//! Truth: the oracle's minimum (independent dense sampling, polished) at the same pose, and
//! the connecting vector along the contact normal.

use contact_pipeline::{ContactOptions, ContactPipeline, PairState, QueryScratch};
use geom_param::{DPose3, DQuat, DVec3};
use xtask::soak::oracle_check::oracle_report;
use xtask::soak::run::prepare_objects;

/// Queries (a, b) at `pose_b` and checks the one contact against the oracle's minimum.
fn agrees_with_oracle(a: &str, b: &str, t: [f64; 3], q: [f64; 4]) {
    let pipeline = ContactPipeline::new(ContactOptions::default()).expect("default options");
    let objects = prepare_objects(&pipeline).expect("fixture objects build");
    let pose_b = DPose3 {
        translation: DVec3::from_array(t),
        rotation: DQuat::from_array(q),
    };
    let (oa, ob) = (&objects[a], &objects[b]);
    let report = pipeline
        .query(
            oa,
            &DPose3::IDENTITY,
            ob,
            &pose_b,
            &mut QueryScratch::default(),
        )
        .expect("unit quaternion");
    let oracle = oracle_report(
        &oa.model.solid,
        &ob.model.solid,
        &pose_b,
        pipeline.options(),
    )
    .expect("oracle runs");
    let truth = oracle
        .contacts
        .iter()
        .min_by(|x, y| x.distance.total_cmp(&y.distance))
        .expect("the oracle finds the touch");
    let options = pipeline.options();
    assert!(
        truth.distance > options.delta1 && truth.distance < options.delta2,
        "{truth:?}"
    );
    assert_eq!(report.state, PairState::Contact, "{a}-{b}: {report:?}");
    let nearest = report
        .contacts
        .iter()
        .min_by(|x, y| x.distance.total_cmp(&y.distance))
        .expect("a contact");
    assert!(
        (nearest.distance - truth.distance).abs() <= 1e-9,
        "{a}-{b}: pipeline {} oracle {}",
        nearest.distance,
        truth.distance
    );
    // Points within the pipeline's own conditioning bound (large at a touch, docs/STABILITY.md).
    assert!(
        nearest.point_a.distance(truth.point_a) <= 1e-5 + nearest.diagnostics.point_error_estimate,
        "{nearest:?} {truth:?}"
    );
    // The connecting vector along the normal, where it is more than rounding.
    if nearest.distance > 1e-9 {
        let along = (nearest.point_b - nearest.point_a).normalize();
        assert!(along.angle_between(nearest.normal) <= 1e-6, "{nearest:?}");
    }
}

#[test]
fn a_rounded_box_corner_seed_finds_the_fillet_minimum() {
    agrees_with_oracle(
        "bowl",
        "rounded-box",
        [-32.29737214570076, -11.254283379019999, -31.516240020567817],
        [
            -0.4073696079449436,
            -0.6064707223700704,
            -0.4169153466381316,
            0.5407632191341373,
        ],
    );
}

#[test]
fn a_pencil_against_the_bracket() {
    agrees_with_oracle(
        "pencil",
        "bracket",
        [28.517353224669467, -12.087932655997893, 6.021464612966128],
        [
            0.03827654457520631,
            0.9901572924562942,
            0.038893040609348985,
            0.12888279064003214,
        ],
    );
}

#[test]
fn two_brackets_edge_to_fillet_arc() {
    // The generator's touched pose, 1e-9 mm back along its line of approach.
    let approach = DVec3::new(-0.6886403130206544, 0.5809489209546477, 0.4339042181454862);
    let t =
        DVec3::new(-19.08147745328165, -12.66343315549642, -0.7487017136830119) - approach * 1e-9;
    agrees_with_oracle(
        "bracket",
        "bracket",
        t.to_array(),
        [
            0.3569634320257414,
            0.7044537011908971,
            -0.2672846480910013,
            0.5521603100275496,
        ],
    );
}

#[test]
fn a_loft_rim_near_the_band_edge_against_the_bracket() {
    agrees_with_oracle(
        "loft",
        "bracket",
        [2.9172466964050656, 1.767954491147245, -12.094411068559324],
        [
            0.040432800108789226,
            -0.4033102216266032,
            0.9053751938722949,
            0.12649826926708277,
        ],
    );
}

#[test]
fn a_vase_touching_the_bowl_at_rounding() {
    agrees_with_oracle(
        "vase",
        "bowl",
        [-7.92449224146677, 48.25534321463631, 68.46884919489513],
        [
            -0.6733253563285265,
            -0.5247384981490811,
            -0.3688769925974093,
            0.36771216653464217,
        ],
    );
}

#[test]
fn a_pencil_touching_the_paperweight_flips_at_delta1() {
    let (pose, stats) = xtask::soak::run::replay("pencil", "paperweight", 17897396705959179123)
        .expect("the soak's objects");
    assert!(pose.is_some(), "the generator builds the pose");
    assert!(
        stats.failures.is_empty() && stats.property_failures.is_empty(),
        "{stats:?}"
    );
}

/// `soak 2400 --general --seed 13269` (concave pairs, issue 15, session 37; found on 492e5a3,
/// since taken back, and the same on 43db715 and on d33671d): a loft posed by the generator to touch the tube (aimed gap 2.9e-10
/// mm) is reported in contact, while the oracle's minimum distance is -0.0274 mm, a
/// penetration. FIXME(issue 15): not investigated yet; today's behaviour (this one state
/// failure) is asserted, so that a fix shows here.
#[test]
fn a_loft_touching_the_tube_where_the_oracle_finds_a_penetration_is_reported_in_contact() {
    let (pose, stats) =
        xtask::soak::run::replay("loft", "tube", 2513307330531289286).expect("the soak's objects");
    assert!(pose.is_some(), "the generator builds the pose");
    assert_eq!(stats.failures.len(), 1, "{stats:?}");
    assert_eq!(stats.failures[0].what, "state", "{stats:?}");
    assert!(
        stats.failures[0]
            .detail
            .starts_with("pipeline Contact, oracle Penetration"),
        "{stats:?}"
    );
}
