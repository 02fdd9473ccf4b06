//! Penetration claims that were wrong both ways, found as generator failures of
//! `soak 10000 --seed 9102` and `soak 2000 --general --seed 9202` (the touch's bisection ended
//! where the pipeline's state jumped over the band):
//!
//! - vase-bracket 5445097807480181339: a bracket corner 0.51 mm inside the vase was reported
//!   separated. The penetration solve cycled between the bracket's corner vertex and its faces
//!   to its switch limit, and the polish that followed ended on the surfaces' crossing
//!   (d = 0, no minimum). Re-entry now prefers a way off a vertex not yet taken.
//! - goblet-pencil 13642981489842291113: a pencil near a goblet's rim, 0.2 mm or more away,
//!   was reported penetrating 10.95 mm: an edge-edge pair measured through both solids. Its
//!   seed came from GJK's closest point on a hull facet that is no part of the surface,
//!   replaced by the nearest hull vertex; such a pair now takes the general path, which finds
//!   nothing within the band (session 12). The witness check still traces only from points on
//!   faces (an edge's own faces graze the segment next to it), so a pair of two edges would
//!   pass unchecked. Dropping witnesses deeper than the meshes' error where Stage 2 saw no
//!   intersecting meshes was tried and is unsound: Stage 2's normal-cone path returns seeds,
//!   not a penetrating verdict, for a 0.55 mm vase-vase penetration it did not need to test
//!   triangle by triangle.
//!
//! - paperweight-pencil (the coherence tests' fast trajectories, the pencil pushed 3.5 mm
//!   into the paperweight's dome): answered separated or as a 3.465 mm "depth", depending on
//!   the last bits of the pose. Stage 3's one seed went to the pair from the dome's pole
//!   (inside the pencil) to the pencil's far side (outside the dome): a local minimum of |d|
//!   with both outward normals pointing the same way, one point inside the other solid and
//!   one outside, so neither a contact nor a depth. On the dome's face it was judged a
//!   non-minimum above the band and dropped, and the pair came out separated although its
//!   meshes intersect; on the pole's vertex it was reported as a depth. Such a pair is now
//!   never a minimum, and intersecting meshes whose chordal errors sum to at most delta2
//!   prove the pair is not separated, so with no contact found it is penetrating.
//!
//! - goblet-tube 4922815628022674231 (`soak 2000 --general --seed 12201`): a goblet's rim
//!   0.022 and 0.012 mm inside a tube's outer cylinder, just below its end, was answered
//!   separated: the seed on the tube's end face led every start of the pair solve to a stall.
//!   Starts on the faces across the seeds' nearest edges find the witness; 0.002 mm inside it
//!   is still missed (FIXME in the test).
//!
//! - pencil-goblet 6346694554730072555 (`soak 10000 --seed 9102`, a state failure): a goblet's
//!   wall cutting a pencil's ferrule 0.0135 mm under its step, 0.159 mm deep, answered as a
//!   contact: the witness check's segment trace stalled within the mesh's error of the step.
//!   The check now measures the nearest boundary point on the exact surfaces.
//!
//! Truth, independent of the stages: whether a point is inside a solid by the parity of a
//! ray's crossings with its closed tessellation (decisive for points farther from the
//! surface than the meshes' chordal error), and the oracle.

use contact_pipeline::{ContactOptions, ContactPipeline, PairState, QueryScratch};
use geom_param::{DPose3, DQuat, DVec3, ObjectModel};
use xtask::soak::oracle_check::oracle_report;
use xtask::soak::run::prepare_objects;

/// Whether `p` (the model's frame) is inside the closed tessellation of `model`: the majority
/// of three rays' crossing parities with every triangle (Möller-Trumbore), along directions
/// no axis or face of the fixtures is aligned with (a ray through a mesh edge or vertex can
/// count one crossing twice).
fn inside_mesh(model: &ObjectModel, p: DVec3) -> bool {
    let directions = [
        DVec3::new(0.5773, 0.6139, 0.5385),
        DVec3::new(-0.3119, 0.8213, -0.4777),
        DVec3::new(0.6829, -0.1234, -0.7202),
    ];
    let votes = directions
        .iter()
        .filter(|d| ray_parity(model, p, d.normalize()))
        .count();
    votes >= 2
}

/// Whether the ray from `p` along `dir` crosses the model's triangles an odd number of times.
fn ray_parity(model: &ObjectModel, p: DVec3, dir: DVec3) -> bool {
    let mut crossings = 0;
    for mesh in &model.meshes {
        for t in &mesh.triangles {
            let [a, b, c] = t.map(|i| mesh.positions[i as usize]);
            let (e1, e2) = (b - a, c - a);
            let h = dir.cross(e2);
            let det = e1.dot(h);
            if det.abs() < 1e-14 {
                continue;
            }
            let s = p - a;
            let u = s.dot(h) / det;
            let q = s.cross(e1);
            let v = dir.dot(q) / det;
            if u < 0.0 || v < 0.0 || u + v > 1.0 {
                continue;
            }
            if e2.dot(q) / det > 0.0 {
                crossings += 1;
            }
        }
    }
    crossings % 2 == 1
}

fn pose(t: [f64; 3], q: [f64; 4]) -> DPose3 {
    DPose3 {
        translation: DVec3::from_array(t),
        rotation: DQuat::from_array(q),
    }
}

#[test]
fn a_bracket_corner_inside_the_vase_is_a_penetration() {
    let pipeline = ContactPipeline::new(ContactOptions::default()).expect("default options");
    let objects = prepare_objects(&pipeline).expect("fixture objects build");
    let (vase, bracket) = (&objects["vase"], &objects["bracket"]);
    // The generator's touched pose moved 0.01 mm back along its line of approach.
    let touched = pose(
        [-2.0110853144985184, 50.79799566475438, 73.08386243211953],
        [
            -0.6694823330914138,
            0.4608751127779044,
            -0.3750314494635806,
            -0.4458014670384984,
        ],
    );
    let approach = DVec3::new(0.08781783656467584, -0.2916161585463662, -0.952495692198007);
    let pose_b = DPose3 {
        translation: touched.translation - approach * 0.01,
        ..touched
    };
    let report = pipeline
        .query(
            vase,
            &DPose3::IDENTITY,
            bracket,
            &pose_b,
            &mut QueryScratch::default(),
        )
        .expect("unit quaternion");
    assert_eq!(report.state, PairState::Penetration, "{report:?}");
    let deepest = report
        .contacts
        .iter()
        .min_by(|x, y| x.distance.total_cmp(&y.distance))
        .expect("a penetration contact");
    // Each point is inside the other solid (the witness spans the lens), by far more than the
    // meshes' error.
    let error = vase
        .model
        .meshes
        .iter()
        .map(|m| m.chordal_error)
        .fold(0.0, f64::max);
    assert!(deepest.distance < -10.0 * error, "{deepest:?}");
    assert!(inside_mesh(&vase.model, deepest.point_b), "{deepest:?}");
    assert!(
        inside_mesh(&bracket.model, pose_b.inverse() * deepest.point_a),
        "{deepest:?}"
    );
    assert!(
        (deepest.point_a.distance(deepest.point_b) + deepest.distance).abs() <= 1e-9,
        "{deepest:?}"
    );
}

#[test]
fn a_pencil_by_the_goblet_rim_is_not_taken_for_10_mm_deep() {
    let pipeline = ContactPipeline::new(ContactOptions::default()).expect("default options");
    let objects = prepare_objects(&pipeline).expect("fixture objects build");
    let (goblet, pencil) = (&objects["goblet"], &objects["pencil"]);
    let touched = pose(
        [2.38575511971254, 15.796616161241587, 153.01213495786146],
        [
            -0.5232096120517146,
            0.20718271205449357,
            -0.018866324781560476,
            0.8264206480187171,
        ],
    );
    let approach = DVec3::new(
        0.02694253032059672,
        -0.5883638100027788,
        -0.8081473424685239,
    );
    let pose_b = DPose3 {
        translation: touched.translation + approach * 1e-9,
        ..touched
    };
    let report = pipeline
        .query(
            goblet,
            &DPose3::IDENTITY,
            pencil,
            &pose_b,
            &mut QueryScratch::default(),
        )
        .expect("unit quaternion");
    // No vertex of either mesh is inside the other object's mesh: nothing penetrates by more
    // than the meshes' error.
    let b_in_a = pencil
        .model
        .meshes
        .iter()
        .flat_map(|m| &m.positions)
        .any(|p| inside_mesh(&goblet.model, pose_b * *p));
    let a_in_b = goblet
        .model
        .meshes
        .iter()
        .flat_map(|m| &m.positions)
        .any(|p| inside_mesh(&pencil.model, pose_b.inverse() * *p));
    assert!(!b_in_a && !a_in_b);
    let oracle = oracle_report(
        &goblet.model.solid,
        &pencil.model.solid,
        &pose_b,
        pipeline.options(),
    )
    .expect("oracle runs");
    assert!(
        oracle.min_distance > 2.0 * pipeline.options().delta2,
        "{oracle:?}"
    );
    assert_eq!(report.state, PairState::Separated, "{report:?}");
    assert!(report.contacts.is_empty(), "{report:?}");
}

#[test]
fn a_pencil_pressed_into_the_paperweight_dome_is_a_penetration() {
    let pipeline = ContactPipeline::new(ContactOptions::default()).expect("default options");
    let objects = prepare_objects(&pipeline).expect("fixture objects build");
    let (paperweight, pencil) = (&objects["paperweight"], &objects["pencil"]);
    // The dome's pole, on the paperweight's axis (its profile's last arc ends there).
    let pole = DVec3::new(0.0, 0.0, 54.1245154965971);
    // Two poses 2e-16 mm apart that used to get the two different wrong answers.
    for y in [-4.0281981562277135e-15, -4.202923375831177e-15] {
        let pose_b = pose(
            [-60.0, y, 54.08951549667865],
            [
                0.0,
                0.7071067811865475,
                0.0,
                std::f64::consts::FRAC_1_SQRT_2,
            ],
        );
        // The pole is inside the pencil, 3.4 mm or more from every vertex of its mesh.
        let pole_in_b = pose_b.inverse() * pole;
        assert!(inside_mesh(&pencil.model, pole_in_b));
        let nearest_vertex = pencil
            .model
            .meshes
            .iter()
            .flat_map(|m| &m.positions)
            .map(|p| p.distance(pole_in_b))
            .fold(f64::INFINITY, f64::min);
        assert!(nearest_vertex > 3.4, "{nearest_vertex}");
        let report = pipeline
            .query(
                paperweight,
                &DPose3::IDENTITY,
                pencil,
                &pose_b,
                &mut QueryScratch::default(),
            )
            .expect("unit quaternion");
        assert_eq!(report.state, PairState::Penetration, "y {y}: {report:?}");
        // A depth, if any, is a pair of points each inside the other solid.
        for depth in &report.contacts {
            assert!(depth.distance < 0.0, "y {y}: {depth:?}");
            assert!(
                inside_mesh(&paperweight.model, depth.point_b),
                "y {y}: {depth:?}"
            );
            assert!(
                inside_mesh(&pencil.model, pose_b.inverse() * depth.point_a),
                "y {y}: {depth:?}"
            );
        }
    }
}

/// Found as a generator failure of `soak 2000 --general --seed 12201` (goblet-tube
/// 4922815628022674231: the state jumped from separated to separated over the band). The
/// goblet's rim pokes into the tube's outer cylinder (radius 9 mm) 0.19 mm below the tube's end
/// face. Stage 2 seeded the pair on the end face; the penetration solve from there, and from
/// the end's outer edge, went down the rim to a stall 1.1 mm "deep" and the seed was dropped.
/// A pair solve that does not converge is now also tried from the faces across the seeds'
/// nearest edges, and from the cylinder it converges to the witness.
///
/// Truth, independent of the stages: the rim point is inside the tube by ray parity, and its
/// depth is 9 mm less its distance from the tube's axis (the closed form of a cylinder).
#[test]
fn a_goblet_rim_inside_a_tube_below_its_end_is_a_penetration() {
    let pipeline = ContactPipeline::new(ContactOptions::default()).expect("default options");
    let objects = prepare_objects(&pipeline).expect("fixture objects build");
    let (goblet, tube) = (&objects["goblet"], &objects["tube"]);
    let touched = pose(
        [56.246822699252256, -49.95915758014042, 162.2051263072105],
        [
            -0.26676891347872084,
            -0.7192151017007293,
            -0.5648845008327364,
            0.3040879560356553,
        ],
    );
    let away = DVec3::new(0.9689932103458647, 0.16807592415284897, 0.18111499668382114);
    for shift in [0.0, 0.01] {
        let pose_b = DPose3 {
            translation: touched.translation + away * shift,
            ..touched
        };
        let report = pipeline
            .query(
                goblet,
                &DPose3::IDENTITY,
                tube,
                &pose_b,
                &mut QueryScratch::default(),
            )
            .expect("unit quaternion");
        assert_eq!(report.state, PairState::Penetration, "{shift}: {report:?}");
        let witness = &report.contacts[0];
        let rim = pose_b.inverse() * witness.point_a;
        assert!(inside_mesh(&tube.model, rim), "{witness:?}");
        let depth = 9.0 - rim.truncate().length();
        assert!(rim.z < 60.0 - 0.1, "{rim}");
        assert!(
            (witness.distance + depth).abs() < 1e-9,
            "{shift}: {witness:?}, {depth}"
        );
        assert!(
            (depth - (0.022_087_871 - shift)).abs() < 1e-6,
            "{shift}: {depth}"
        );
    }
    // FIXME: 0.01 mm farther out (the rim 2.1e-3 mm inside the cylinder, past delta1) every
    // start of the pair solve still ends unconverged and the pair is answered separated.
    let pose_b = DPose3 {
        translation: touched.translation + away * 0.02,
        ..touched
    };
    let report = pipeline
        .query(
            goblet,
            &DPose3::IDENTITY,
            tube,
            &pose_b,
            &mut QueryScratch::default(),
        )
        .expect("unit quaternion");
    assert_eq!(report.state, PairState::Separated, "{report:?}");
}

/// pencil-goblet 6346694554730072555 of `soak 10000 --seed 9102`, a state failure (a FIXME from
/// session 9 to 14). The goblet's cup wall cuts the pencil's ferrule (the cylinder r = 3.6, z 6
/// to 14) just below the step at z = 14, where an annulus steps down to the body (r = 3.5).
/// Two witnesses: the goblet's point at r = 3.44, z = 13.9865 lies in the pencil, 0.0608 mm
/// from its nearest boundary point on the step's inner, concave edge; and the ferrule's point
/// level with it, at r = 3.6, lies in the goblet's wall, 0.159 mm from its nearest boundary
/// point, that same goblet point. The deeper one, 0.159 mm, is the pair's depth (the oracle
/// keeps a pair whose one point lies inside the other solid with the other's point as its
/// nearest; until session 14 it asked both points to be each other's nearest, which the
/// 0.159 mm pair is not, and reported the 0.0608 mm one).
///
/// Stage 3 reached the 0.159 mm pair, but its witness check rejected it: the check traced the
/// segment against the pencil's mesh (chordal error 0.05 mm), and the segment runs 0.0135 mm
/// under the step's annulus, well within the 3e where the mesh cannot tell a wall from a
/// graze, so the trace stalled and the pair was answered as a contact from minima found
/// elsewhere (the 0.0608 mm pair the oracle reported before was no critical pair: its
/// residual was 0.0135 mm, the step's height over the goblet's point). The check now asks
/// the ferrule's point for its nearest goblet point, measured on the exact faces.
///
/// Truth independent of both: each point's nearest boundary point on the other solid by the
/// meridian distance (the solids are surfaces of revolution: a point's distance to a face is
/// its distance, in its meridian half-plane, to the face's profile, minimised here by dense
/// sampling and golden section over the profile's parameter), and inside-ness by ray parity.
#[test]
fn a_goblet_wall_under_a_ferrule_step_is_a_penetration() {
    let pipeline = ContactPipeline::new(ContactOptions::default()).expect("default options");
    let objects = prepare_objects(&pipeline).expect("fixture objects build");
    let (pencil, goblet) = (&objects["pencil"], &objects["goblet"]);
    let pose_b = pose(
        [6.61148946477011, 21.406186019438177, -47.175192725469785],
        [
            -0.146864311392287,
            0.18276375934262992,
            -0.8576413467358593,
            -0.45768941726821744,
        ],
    );
    let oracle = oracle_report(
        &pencil.model.solid,
        &goblet.model.solid,
        &pose_b,
        pipeline.options(),
    )
    .expect("oracle runs");
    let deepest = oracle
        .contacts
        .iter()
        .min_by(|x, y| x.distance.total_cmp(&y.distance))
        .expect("the oracle's witness");
    // The ferrule's point in the goblet's wall, with the goblet's point as its nearest.
    let ferrule = deepest.point_a;
    assert!(
        (ferrule.truncate().length() - 3.6).abs() < 1e-9 && ferrule.z < 14.0,
        "{deepest:?}"
    );
    let in_goblet = pose_b.inverse() * ferrule;
    assert!(inside_mesh(&goblet.model, in_goblet), "{deepest:?}");
    let depth = meridian_distance(&goblet.model.solid, in_goblet);
    assert!(
        (deepest.distance + depth).abs() < 1e-9,
        "{deepest:?} {depth}"
    );
    // The goblet's point in the pencil, nearest to the step's edge circle: less deep.
    let p = deepest.point_b;
    let (r, z) = (p.truncate().length(), p.z);
    assert!(r < 3.5 && z < 14.0, "{p:?}");
    assert!(inside_mesh(&pencil.model, p), "{p:?}");
    let to_step = (r - 3.5).hypot(z - 14.0);
    assert!(
        (meridian_distance(&pencil.model.solid, p) - to_step).abs() < 1e-9,
        "{to_step}"
    );
    assert!(to_step < depth - 0.05, "{to_step} {depth}");
    assert!(deepest.distance < pipeline.options().delta1, "{deepest:?}");
    let report = pipeline
        .query(
            pencil,
            &DPose3::IDENTITY,
            goblet,
            &pose_b,
            &mut QueryScratch::default(),
        )
        .expect("unit quaternions");
    assert_eq!(report.state, PairState::Penetration, "{report:?}");
    let depth_found = report
        .contacts
        .iter()
        .min_by(|x, y| x.distance.total_cmp(&y.distance))
        .expect("the witness is reported");
    assert!(
        (depth_found.distance - deepest.distance).abs() < 1e-9
            && depth_found.point_a.distance(ferrule) < 1e-6
            && depth_found.point_b.distance(p) < 1e-6,
        "{depth_found:?} against {deepest:?}"
    );
}

/// Distance (mm) from `p` (the solid's frame) to the boundary of `solid`, a solid of
/// revolution about z: the least over its faces of the distance, in p's meridian half-plane,
/// from (|p_xy|, p_z) to the face's profile (r(v), z(v)) = (x, z) of the face at u = 0.
/// Each profile is sampled at 4096 values of v and the best sample refined by golden section
/// over its two neighbouring intervals (the distance is unimodal there at this density).
fn meridian_distance(solid: &geom_param::Solid, p: DVec3) -> f64 {
    let target = geom_param::DVec2::new(p.truncate().length(), p.z);
    let mut best = f64::INFINITY;
    for (index, face) in solid.faces.iter().enumerate() {
        let range = face.surface.domain()[1];
        let at = |v: f64| {
            let q = solid
                .eval_face(
                    geom_param::FaceId(u32::try_from(index).expect("few faces")),
                    0.0,
                    v,
                )
                .point;
            geom_param::DVec2::new(q.x, q.z).distance(target)
        };
        let samples = 4096;
        let v_of = |k: usize| range.min + range.span() * k as f64 / samples as f64;
        let k = (0..=samples)
            .min_by(|&i, &j| at(v_of(i)).total_cmp(&at(v_of(j))))
            .expect("samples");
        let (mut lo, mut hi) = (v_of(k.saturating_sub(1)), v_of((k + 1).min(samples)));
        let ratio = (5.0_f64.sqrt() - 1.0) / 2.0;
        for _ in 0..200 {
            let (x1, x2) = (hi - ratio * (hi - lo), lo + ratio * (hi - lo));
            if at(x1) < at(x2) {
                hi = x2;
            } else {
                lo = x1;
            }
        }
        best = best.min(at(0.5 * (lo + hi)));
    }
    best
}

/// `soak 2000 --general --seed 13206`, tube-loft 7912923848273877506 (built as two contacts at
/// 0.060 mm): the oracle of session 14's first rule reported a penetration 21.6 mm "deep"
/// between the tube's bottom rim (edge 0, z = 0) and the loft's side, taking the rim's point
/// for a point inside the loft with the loft's side as its nearest boundary point. The
/// oracle keeps fine samples only within its reach of the other solid, so the loft's nearer
/// boundary was not sampled there; a pair deeper than that band must now pass the strict test
/// (no sample of either solid nearer than its distance). Independent check: the rim's point is
/// outside the loft (ray parity with the loft's mesh), so the pair is no penetration, and the
/// pipeline's answer, two contacts, stands.
#[test]
fn a_rim_point_outside_a_loft_is_no_deep_witness() {
    let pipeline = ContactPipeline::new(ContactOptions::default()).expect("default options");
    let objects = prepare_objects(&pipeline).expect("fixture objects build");
    let (tube, loft) = (&objects["tube"], &objects["loft"]);
    let pose_b = pose(
        [1.1598176290315467, 20.29730369229872, 59.62031714963561],
        [
            0.4913727774911826,
            0.8426759824728876,
            -0.0009816222029540285,
            0.22011137753829374,
        ],
    );
    let rim_point = DVec3::new(8.88786990980687, 1.4162515547562915, 0.0);
    assert!(!inside_mesh(&loft.model, pose_b.inverse() * rim_point));
    let oracle = oracle_report(
        &tube.model.solid,
        &loft.model.solid,
        &pose_b,
        pipeline.options(),
    )
    .expect("oracle runs");
    assert!(oracle.min_distance > 0.0, "{:?}", oracle.contacts);
    let report = pipeline
        .query(
            tube,
            &DPose3::IDENTITY,
            loft,
            &pose_b,
            &mut QueryScratch::default(),
        )
        .expect("unit quaternion");
    assert_eq!(report.state, PairState::Contact, "{report:?}");
    assert_eq!(report.contacts.len(), 2, "{report:?}");
}
