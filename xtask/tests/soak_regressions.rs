//! Failures found by `cargo xtask soak`, each kept with its literal pose (A at the identity,
//! B at the pose given, default `ContactOptions`) and a comment on what failed. The ones still
//! failing are `#[ignore]`d with the reason; see docs/ROBUSTNESS.md ("Soak").

use contact_pipeline::{
    ContactOptions, ContactPipeline, PairReport, PairState, PreparedObject, QueryScratch,
};
use geom_param::{DPose3, DQuat, DVec3};
use std::collections::BTreeMap;
use xtask::soak::normal_cone::normal_cone;
use xtask::soak::run::prepare_objects;

fn pose(t: [f64; 3], q: [f64; 4]) -> DPose3 {
    DPose3 {
        translation: DVec3::from_array(t),
        rotation: DQuat::from_array(q),
    }
}

fn setup() -> (ContactPipeline, BTreeMap<String, PreparedObject>) {
    let pipeline = ContactPipeline::new(ContactOptions::default()).expect("default options");
    let objects = prepare_objects(&pipeline).expect("paper objects build");
    (pipeline, objects)
}

fn query(
    pipeline: &ContactPipeline,
    a: &PreparedObject,
    pose_a: &DPose3,
    b: &PreparedObject,
    pose_b: &DPose3,
    scratch: &mut QueryScratch,
) -> PairReport {
    pipeline
        .query(a, pose_a, b, pose_b, scratch)
        .expect("unit quaternions")
}

/// The pair queried as (A at the identity, B at `pose_b`) and swapped, with one scratch (so the
/// second query is warm-started by the first, as in the soak).
fn both_orders(
    pipeline: &ContactPipeline,
    objects: &BTreeMap<String, PreparedObject>,
    a: &str,
    b: &str,
    pose_b: &DPose3,
) -> (PairReport, PairReport) {
    let (a, b) = (&objects[a], &objects[b]);
    let mut scratch = QueryScratch::default();
    let ab = query(pipeline, a, &DPose3::IDENTITY, b, pose_b, &mut scratch);
    let ba = query(pipeline, b, pose_b, a, &DPose3::IDENTITY, &mut scratch);
    (ab, ba)
}

/// Found by the flip property (paperweight-pencil, seed 4415940930031423605 of
/// `cargo xtask soak 36 --seed 1`): B was set 1.672e-3 mm into A along the normal of a
/// face-face contact, and the pipeline reported a single contact at distance 2.5e-15 between
/// the paperweight's face 1 and the pencil's edge 0 (a smooth edge). The surfaces cross there:
/// the face's normal is 0.17 rad off the pencil's normal, so the point is on the intersection
/// curve, not a touch. Stage 3 restarted into the penetration solve from a crossing of two
/// faces but not from an edge crossing a face, and the zero-distance point passed as a local
/// minimum of |P_a - P_b|. Fixed in `exact_refine::newton::crossing_restart`: an edge's point
/// is a touch only when the other face's normal, negated, lies in the arc of its two faces'
/// normals; otherwise the solve restarts on the steeper face. Now both orders find the
/// penetration the pose was built with.
#[test]
fn an_edge_crossing_a_face_is_not_a_contact() {
    let (pipeline, objects) = setup();
    let pose_b = pose(
        [30.948056502505978, -1.4369350602541915, -1.0424243677758185],
        [
            0.6554801473691044,
            -0.711486880226767,
            0.16213254946615502,
            -0.19453851051594917,
        ],
    );
    let (ab, ba) = both_orders(&pipeline, &objects, "paperweight", "pencil", &pose_b);
    let (a, b) = (&objects["paperweight"], &objects["pencil"]);
    for (report, first, pose_first, second, pose_second) in [
        (&ab, a, DPose3::IDENTITY, b, pose_b),
        (&ba, b, pose_b, a, DPose3::IDENTITY),
    ] {
        assert_eq!(report.state, PairState::Penetration, "{report:?}");
        for c in &report.contacts {
            // Any contact kept must be a touch: the normal in both normal cones.
            let cone_a = normal_cone(&first.model.solid, &c.location_a)
                .expect("cone at A")
                .rotated(pose_first.rotation);
            let cone_b = normal_cone(&second.model.solid, &c.location_b)
                .expect("cone at B")
                .rotated(pose_second.rotation);
            assert!(cone_a.excess(c.normal) < 1e-6, "{c:?}");
            assert!(cone_b.excess(-c.normal) < 1e-6, "{c:?}");
        }
    }
}

/// Found by the swap property (goblet-jar, seed 14010951826386768336 of
/// `cargo xtask soak 36 --seed 1`). Goblet first: Stage 3 refines the single seed to a
/// penetration of -0.0227 mm between the goblet's rim edge (edge 7, z = 150) and the jar's
/// face 1. Jar first: the same seed, with the goblet's point at v = 0.9999999999999994 instead
/// of v = 1 (the face boundary at the rim) after the change of frame, makes the Newton
/// iteration wander 56 mm away and stop at the iteration limit (223 iterations), and the pair
/// is reported separated: the pair solve started the goblet's point as a face point, reached a
/// face-face penetrating pair whose witness is on the rim edge, and the face-face penetration
/// solve had nothing to converge to. Fixed in `exact_refine::feature_switch::settle_start`: a
/// start within coordinate rounding of a face's side is put on the side (the edge).
#[test]
fn swapping_goblet_and_jar_keeps_the_state() {
    let (pipeline, objects) = setup();
    let pose_b = pose(
        [9.017570918688739, 64.52225739926473, 157.21971540504506],
        [
            -0.5323539114746471,
            0.27750465959971143,
            -0.5881057060936296,
            0.5419613965018225,
        ],
    );
    let (ab, ba) = both_orders(&pipeline, &objects, "goblet", "jar", &pose_b);
    assert_eq!(ab.state, ba.state);
}

/// Two paperweights touching (the pose the pose generator's touch reached for
/// paperweight-paperweight seed 2092789425003139053 of `cargo xtask soak 720 --seed 2`): the
/// base's flat bottom (face 0) of one against the base's upper fillet (face 3) of the other at
/// distance -1.5e-9 mm. A fresh query reports the contact; a query after one at B moved by
/// 3.2 mm (which changes the GJK warm start, hence the seed) reports separated: the refined
/// minimum is the same pair at -1.1e-9 mm but `is_local_minimum` is false, because at a
/// penetration of 1e-9 mm the second-order test (exactly two negative eigenvalues of the
/// sliding directions, of size |d| x curvature ~ 1e-11) is decided by rounding. The same pair
/// queried in the other order is also reported separated. Fixed in
/// `exact_refine::diagnostics::diagnose`: a converged pair with |d| within its distance error
/// estimate (here 4e-3 and 1.2e-6 mm: one relative curvature is nearly zero) is judged as at
/// d = 0, a touch when the normals are opposed, whatever the eigenvalues' signs.
#[test]
fn a_touch_does_not_depend_on_the_previous_query_or_the_order() {
    let (pipeline, objects) = setup();
    let pose_b = pose(
        [42.32213345196685, 18.48019303646614, -7.520722805550621],
        [
            -0.4736673641827512,
            -0.4269739948233737,
            -0.741315105691558,
            0.2092471025516212,
        ],
    );
    let before = DPose3 {
        translation: pose_b.translation
            + DVec3::new(0.34612635021871063, 1.6170244361474273, -2.7175171385536165),
        ..pose_b
    };
    let p = &objects["paperweight"];
    let fresh = query(
        &pipeline,
        p,
        &DPose3::IDENTITY,
        p,
        &pose_b,
        &mut QueryScratch::default(),
    );
    let mut scratch = QueryScratch::default();
    let _ = query(&pipeline, p, &DPose3::IDENTITY, p, &before, &mut scratch);
    let after = query(&pipeline, p, &DPose3::IDENTITY, p, &pose_b, &mut scratch);
    let swapped = query(
        &pipeline,
        p,
        &pose_b,
        p,
        &DPose3::IDENTITY,
        &mut QueryScratch::default(),
    );
    assert_eq!(fresh.state, after.state, "after a query 3.2 mm away");
    assert_eq!(fresh.state, swapped.state, "objects swapped");
}

/// Found by the flip property (jar-goblet, seed 17719967120687397067 of the CI soak, 252 poses
/// with seed 2026): the closest pair was the jar's face 2 against the goblet's smooth edge 8 at
/// 0.0524 mm; B moved along that contact's normal to delta1 - 1.5e-7 mm (the pose below, where
/// that pair is a critical pair at -1.00015e-3 mm) was reported separated. Stage 3 reached the
/// goblet's face 8 at v = 1 - 4.4e-14 instead of the edge, where the depth's curvature jumps,
/// and the face-face penetration solve stalled 1.7e-7 mm short of the witness (214
/// iterations). Fixed in `exact_refine::newton::retry_on_sides`: a penetration solve that does
/// not converge restarts once from the sides its points are within √ε x |P| of.
#[test]
fn a_penetration_witness_on_a_smooth_edge_is_found() {
    let (pipeline, objects) = setup();
    let pose_b = pose(
        [34.24561959685395, -181.88555030453102, 70.96868033865229],
        [
            0.07691737494688769,
            0.7060464618347572,
            0.6588184346860593,
            -0.24807333851043178,
        ],
    );
    let (ab, ba) = both_orders(&pipeline, &objects, "jar", "goblet", &pose_b);
    assert_eq!(ab.state, PairState::Penetration, "{ab:?}");
    assert_eq!(ba.state, PairState::Penetration, "{ba:?}");
}

/// Found by the flip property (bowl-pencil, seed 16094712877817274496 of the CI soak): the
/// closest pair was the bowl's face 2 (at v = 0.0053, next to its edge 1) against the pencil's
/// face 6 at 0.094 mm; B moved along that contact's normal to delta1 - 1.5e-7 mm (the pose
/// below, where that pair is a critical pair at -1.00015e-3 mm) was reported as a contact at
/// -1.04e-4 mm between the bowl's edge 1 and the pencil's face 6. The seed was on the edge,
/// and the fast Newton solve for the witness accepted the edge's critical pair, whose depth
/// rises into the adjacent face 2. Fixed in `exact_refine::penetration::saddle_newton`: a
/// witness on an edge or vertex from which the depth rises into a face is left to the nested
/// solver, which re-enters the face.
#[test]
fn a_penetration_witness_next_to_an_edge_is_found() {
    let (pipeline, objects) = setup();
    let pose_b = pose(
        [-30.4729301434057, -66.4134743156096, -41.19557851074387],
        [
            0.4846298069860689,
            0.21577152880886474,
            0.3291179911282738,
            -0.781190082791519,
        ],
    );
    let (ab, ba) = both_orders(&pipeline, &objects, "bowl", "pencil", &pose_b);
    assert_eq!(ab.state, PairState::Penetration, "{ab:?}");
    assert_eq!(ba.state, PairState::Penetration, "{ba:?}");
}

/// Found by the swap property (bowl-goblet, seed 6952665423583246700 of the CI soak; built
/// 2.571e-3 mm deep). Bowl first, the seed lands exactly on the side v = 0.6 of the bowl's
/// face 1, hence on its edge 1, and the nested penetration solve between that edge and the
/// goblet's edge 7 stalled (208 iterations): reported separated. Goblet first, the seed is at
/// v = 0.5999999999999999, stays on the face, and the witness (goblet edge 7 against bowl
/// face 1) is found. Fixed in `exact_refine::newton::retry_on_sides`: a penetration solve that
/// does not converge on an edge restarts just inside each adjacent face.
#[test]
fn a_seed_on_a_face_side_finds_the_penetration() {
    let (pipeline, objects) = setup();
    let pose_b = pose(
        [161.67400547464732, 55.69067779307774, -52.10341642649432],
        [
            0.2786519068333151,
            -0.609436580074842,
            0.09381709396166919,
            0.7363005653708448,
        ],
    );
    let (ab, ba) = both_orders(&pipeline, &objects, "bowl", "goblet", &pose_b);
    assert_eq!(ab.state, PairState::Penetration, "{ab:?}");
    assert_eq!(ba.state, PairState::Penetration, "{ba:?}");
}

/// Found by the flip property (bowl-vase, seed 1078096001492731885 of `cargo xtask soak 1000
/// --seed 11`): the closest pair was the bowl's face 3 against the vase's edge 0 at 0.0784 mm;
/// B moved along that contact's normal to delta1 - 9.8e-8 mm (the pose below) was reported
/// separated. The nested penetration solve projected the outer point onto the vase's face 0,
/// whose closest point converged towards its side (v = 1 - 2.4e-15) without reaching it, and
/// stalled there (228 iterations, the depth's curvature jumping at the side). Fixed in
/// `exact_refine::penetration::solve_penetration`: an inner projection within √ε x |P| of a
/// side is put on the side (the edge), which makes the inner side the edge.
#[test]
fn an_inner_projection_onto_a_face_side_becomes_the_edge() {
    let (pipeline, objects) = setup();
    let pose_b = pose(
        [41.58557740542648, -31.262216804295907, 41.47861929862172],
        [
            -0.32948587782287037,
            0.6185992447106525,
            -0.40701611633072193,
            0.5857575537760986,
        ],
    );
    let (ab, ba) = both_orders(&pipeline, &objects, "bowl", "vase", &pose_b);
    assert_eq!(ab.state, PairState::Penetration, "{ab:?}");
    assert_eq!(ba.state, PairState::Penetration, "{ba:?}");
}

/// Found by the flip property (goblet-goblet, seed 10541403850172320131 of
/// `cargo xtask soak 1000 --seed 11`): the closest pair is the two rims (edge 7 of each, z = 150)
/// crossing at 0.0488355 mm; B moved along that contact's normal to delta1 - 1.5e-7 mm (the first
/// pose below, where that pair is a critical pair at -1.00015e-3 mm by construction) is reported
/// separated in both orders, and moved to delta1 + 1.5e-7 mm (the second pose) separated goblet
/// first, penetration the other way round, instead of the contact at -9.9985e-4 mm. Not fixed:
/// the penetration solve stalls (135 iterations) on edge 7 against the other goblet's face 7 at
/// v = 1 - 3.9e-8, 0.0122 mm off; `retry_on_sides` restarting from just inside edge 7's faces
/// reaches the iteration limit at the same place. (Restarting edge 7 against edge 7, tried while
/// analysing, stalls too, on face 8 at v = 7.7e-7 with |d| = 1.0033e-3 mm, near the witness.)
#[test]
#[ignore = "not fixed: the rim-rim penetration solve stalls on edge 7 against face 7 at v = 1 - 3.9e-8, and its restarts from the sides do not converge either"]
fn crossing_rims_moved_to_delta1_flip_the_state() {
    let (pipeline, objects) = setup();
    let rotation = [
        0.7271627999377562,
        -0.4611155181494053,
        -0.5085101361234947,
        -0.004917597803121201,
    ];
    let into = pose(
        [125.23732727900044, -131.22055754520457, 212.89332930055457],
        rotation,
    );
    let kept = pose(
        [125.23732748862051, -131.22055770914412, 212.89332943905814],
        rotation,
    );
    let g = &objects["goblet"];
    let delta1 = pipeline.options().delta1;
    let mut scratch = QueryScratch::default();
    let r = query(&pipeline, g, &DPose3::IDENTITY, g, &into, &mut scratch);
    assert_eq!(r.state, PairState::Penetration, "{r:?}");
    let r = query(&pipeline, g, &DPose3::IDENTITY, g, &kept, &mut scratch);
    assert_eq!(r.state, PairState::Contact, "{r:?}");
    let rim_point = DVec3::new(31.508290134558084, -24.6419896273923, 150.0);
    assert!(
        r.contacts
            .iter()
            .any(|c| (c.distance - (delta1 + 1.5e-7)).abs() < 1e-7
                && c.point_a.distance(rim_point) < 1e-4),
        "{r:?}"
    );
}

/// Found by the swap property (goblet-goblet, seed 15738302282556059162 of
/// `cargo xtask soak 1000 --seed 11`; built 1.953e-3 mm deep, with the witness on the first
/// goblet's rim, z = 150). First goblet first, Stage 3 finds the penetration; the other order was
/// reported separated: the pair solve converged on a crossing (face 4 against face 8 at
/// v = 1.8e-4, d = 5.6e-14 mm), and the crossing restart's step (angle / curvature) left both
/// faces, was clamped onto edges 4 and 7, and the penetration solve from there converged to a
/// critical pair 6.07 mm deep between edges 3 and 7, no witness. Fixed in
/// `exact_refine::newton::crossing_restart`: a restart step that would leave its face stops
/// half-way to the side it would cross (`inside_fraction`).
#[test]
fn swapping_two_goblets_keeps_a_rim_penetration() {
    let (pipeline, objects) = setup();
    let pose_b = pose(
        [-19.46896617651577, 34.89126569712594, 213.01867389136282],
        [
            0.23567868608686526,
            -0.9502039254552238,
            -0.0857382736246507,
            -0.18497839173729785,
        ],
    );
    let g = &objects["goblet"];
    let mut scratch = QueryScratch::default();
    let ab = query(&pipeline, g, &DPose3::IDENTITY, g, &pose_b, &mut scratch);
    let ba = query(&pipeline, g, &pose_b, g, &DPose3::IDENTITY, &mut scratch);
    assert_eq!(ab.state, PairState::Penetration, "{ab:?}");
    assert_eq!(ba.state, PairState::Penetration, "{ba:?}");
}

/// Found by the swap property and the oracle (goblet-bowl, seed 8595849821463493159 of
/// `cargo xtask soak 1000 --seed 11`; built as a touch at 2.239e-10 mm, the oracle's minimum is
/// 2.668e-10 mm between the bowl's face 0 and the goblet's face 7). Bowl first, the pipeline
/// reports that contact at 2.668e-10 mm (converged in 62 iterations); goblet first, the pair
/// solve reaches the same pair (|d| = 2.7e-10 mm, parameters within 1e-6) but stops at the
/// iteration limit (64) unconverged, and the pair was reported separated. At an exact touch the
/// gap is quartic in the offset along the flattest direction, so Newton converges only linearly.
/// Fixed in `exact_refine::newton::solve`: a pair solve stopped by the iteration limit continues
/// once from where it stopped.
#[test]
fn a_goblet_touching_a_bowl_is_a_contact_in_both_orders() {
    let (pipeline, objects) = setup();
    let pose_b = pose(
        [-29.865116491822945, 18.441587790055102, 115.3702398746137],
        [
            -0.8042717060156233,
            -0.43254816648853933,
            0.13997185104104728,
            0.3826969917392409,
        ],
    );
    let (ab, ba) = both_orders(&pipeline, &objects, "goblet", "bowl", &pose_b);
    for report in [&ab, &ba] {
        assert_eq!(report.state, PairState::Contact, "{report:?}");
        assert!(
            report.contacts.iter().any(|c| c.distance.abs() < 1e-9),
            "{report:?}"
        );
    }
}

/// Found by the oracle (bowl-paperweight, seed 5618258536318199318 of
/// `cargo xtask soak 1000 --seed 11`): besides the contact the pose was built with (bowl face 4
/// against the paperweight's face 1 at 0.03326 mm, reported), the oracle finds a second local
/// minimum 4.6 mm away, the bowl's face 4 against the paperweight's face 3 at 0.0730838 mm,
/// inside the band; the pipeline does not report it. Not analysed (Stage 1/2 may not have seeded
/// it).
#[test]
#[ignore = "not fixed, not analysed: a second minimum at 0.0731 mm (bowl face 4 / paperweight face 3) is not reported"]
fn a_second_contact_in_the_band_is_reported() {
    let (pipeline, objects) = setup();
    let pose_b = pose(
        [-14.13872657433006, -20.735789749114346, 72.12623322873607],
        [
            -0.25871576848907074,
            -0.5949659295245138,
            -0.08637166352349065,
            0.7560566311992282,
        ],
    );
    let (a, b) = (&objects["bowl"], &objects["paperweight"]);
    let report = query(
        &pipeline,
        a,
        &DPose3::IDENTITY,
        b,
        &pose_b,
        &mut QueryScratch::default(),
    );
    let oracle_a = DVec3::new(-33.28678828500792, -25.838393333200578, 41.804827385957026);
    assert!(
        report
            .contacts
            .iter()
            .any(|c| (c.distance - 7.308380531285347e-2).abs() < 1e-7
                && c.point_a.distance(oracle_a) < 1e-3),
        "{report:?}"
    );
}

/// Found by the oracle (pencil-bowl, seed 16555674050705579074 of
/// `cargo xtask soak 1000 --seed 11`; built as a touch at 1.9e-12 mm): the pipeline reports one
/// contact at 2.84e-10 mm between the pencil's face 6 and the bowl's face 2 at v = 3.9e-4 (next to
/// its joint with face 1), condition 8.9e10 and point error estimate 7.3e-4 mm: a nearly flat
/// minimum. The oracle finds another local minimum 9.4e-3 mm away across that joint, face 6
/// against the bowl's face 1 at 4.127e-6 mm, which the pipeline does not report. Not analysed:
/// it may be the same flat valley of the distance, split by the smooth joint.
#[test]
#[ignore = "not fixed, not analysed: the oracle's minimum at 4.1e-6 mm on the bowl's face 1, 9.4e-3 mm from the reported flat contact on face 2, is not reported"]
fn a_flat_touch_across_a_smooth_joint_reports_both_minima() {
    let (pipeline, objects) = setup();
    let pose_b = pose(
        [-9.745112151206866, -27.525932834638805, 70.53579620995133],
        [
            0.32487827239326744,
            -0.30400308482004557,
            0.87388732255707,
            0.19584989155140667,
        ],
    );
    let (a, b) = (&objects["pencil"], &objects["bowl"]);
    let report = query(
        &pipeline,
        a,
        &DPose3::IDENTITY,
        b,
        &pose_b,
        &mut QueryScratch::default(),
    );
    let oracle_a = DVec3::new(0.40797060016420383, -3.476141537596198, 91.63791297373353);
    assert!(
        report
            .contacts
            .iter()
            .any(|c| (c.distance - 4.127391009015136e-6).abs() < 1e-7
                && c.point_a.distance(oracle_a) < 1e-3),
        "{report:?}"
    );
}

/// Two "missed" contacts of `cargo xtask soak 1000 --seed 11` that are the oracle's, not the
/// pipeline's (pencil-goblet seed 7302112096488778657 and pencil-pencil seed
/// 12710718749562303040, built as overlaps of -7.239e-5 and -8.137e-5 mm with the pencil's apex,
/// vertex 1 at z = 177.5, inside the other solid). The oracle reports contacts at -6.5e-10,
/// -6.2e-10 and -2.2e-13 mm on the pencil's cone (face 8) 2.8e-5 to 4.8e-5 mm from the apex:
/// points of the curve where the cone crosses the other surface, at distance zero trivially.
/// They are no touch: the contact normal there would be the other surface's normal, which makes
/// 38.5 deg (pencil-goblet) and 71 deg (pencil-pencil) with the pencil's axis, while the cone's
/// normals make 74 deg with it (half-angle 16 deg, from the oracle's points). The pipeline
/// reports the apex penetration alone, as it should; this keeps it from reporting the crossing.
/// (The oracle now reports the apex witness too, docs/ROBUSTNESS.md oracle fix 14.)
#[test]
fn a_pencil_apex_inside_a_surface_is_one_contact_not_a_crossing() {
    let (pipeline, objects) = setup();
    let cases = [
        (
            "goblet",
            pose(
                [-7.129217804605351, 31.678192586920083, 168.7026926745926],
                [
                    -0.1914257699959785,
                    0.9329799519694516,
                    -0.20974367287186252,
                    0.22116097190677222,
                ],
            ),
            -7.239e-5,
        ),
        (
            "pencil",
            pose(
                [56.338720810237724, -80.24909286563573, 199.89163098370508],
                [
                    0.2107172064873394,
                    -0.7492078137857953,
                    -0.5850671826055373,
                    0.22799627736105738,
                ],
            ),
            -8.137e-5,
        ),
    ];
    let pencil = &objects["pencil"];
    for (other, pose_b, built) in cases {
        let report = query(
            &pipeline,
            pencil,
            &DPose3::IDENTITY,
            &objects[other],
            &pose_b,
            &mut QueryScratch::default(),
        );
        assert_eq!(report.state, PairState::Contact, "{other}: {report:?}");
        assert_eq!(report.contacts.len(), 1, "{other}: {report:?}");
        let c = &report.contacts[0];
        // The aimed gap is quoted to 4 digits.
        assert!((c.distance - built).abs() < 1e-8, "{other}: {c:?}");
        assert!(
            c.point_a.distance(DVec3::new(0.0, 0.0, 177.5)) < 1e-9,
            "{other}: {c:?}"
        );
    }
}
