//! Contact manifolds through parry's `PersistentQueryDispatcher` trait: the paper's
//! two-contact fixture scenes against the pipeline's own query (what `contacts query` prints),
//! both argument orders, a ball on a parry cuboid, ids and solver data kept over a small
//! motion, and what is beyond reach.

mod support;

use contact_parry::{BeyondReach, DispatcherOptions, ExactDispatcher, exact_ball, packed_feature};
use contact_pipeline::QueryScratch;
use parry3d_f64::math::{Pose, Vector};
use parry3d_f64::query::{ContactManifold, PersistentQueryDispatcher, Unsupported};
use parry3d_f64::shape::Cuboid;
use std::sync::Arc;
use support::fixtures::scene;

/// Solver data a physics engine keeps per manifold and per point (rapier keeps impulses).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct Mark(u32);

type Manifold = ContactManifold<Mark, Mark>;

#[test]
fn paper_scenes_give_one_manifold_per_pipeline_contact_in_both_orders() {
    for name in [
        "pencil-bowl-two-contacts",
        "vase-vase-two-contacts",
        "pencil-paperweight-two-contacts",
        "pencil-tube-two-contacts",
    ] {
        let s = scene(name);
        let report = s
            .pipeline
            .query(
                s.a.object(),
                &s.pose_a,
                s.b.object(),
                &s.pose_b,
                &mut QueryScratch::default(),
            )
            .expect("query");
        assert_eq!(report.contacts.len(), 2, "{name}");
        let dispatcher = ExactDispatcher::new(DispatcherOptions::default());
        let pos12 = s.pose_a.inverse() * s.pose_b;
        let mut manifolds: Vec<Manifold> = Vec::new();
        let mut workspace = None;
        dispatcher
            .contact_manifolds(&pos12, &s.a, &s.b, 0.1, &mut manifolds, &mut workspace)
            .expect("exact");
        assert_eq!(manifolds.len(), 2, "{name}");
        for c in &report.contacts {
            let local_a = s.pose_a.inverse_transform_point(c.point_a);
            let m = manifolds
                .iter()
                .find(|m| m.points[0].local_p1.distance(local_a) < 1e-6)
                .unwrap_or_else(|| panic!("{name}: no manifold at {local_a}"));
            let p = &m.points[0];
            assert_eq!(m.points.len(), 1);
            assert!((p.dist - c.distance).abs() < 1e-9, "{name}");
            assert!(
                p.local_p2
                    .distance(s.pose_b.inverse_transform_point(c.point_b))
                    < 1e-6
            );
            assert!(m.local_n1.distance(s.pose_a.rotation.inverse() * c.normal) < 1e-6);
            assert!(
                m.local_n2
                    .distance(-(s.pose_b.rotation.inverse() * c.normal))
                    < 1e-6
            );
            assert_eq!(p.fid1, packed_feature(&c.location_a));
            assert_eq!(p.fid2, packed_feature(&c.location_b));
        }
        // Swapped: the same minima, points swapped and normals flipped.
        let mut swapped: Vec<Manifold> = Vec::new();
        let mut workspace = None;
        dispatcher
            .contact_manifolds(
                &pos12.inverse(),
                &s.b,
                &s.a,
                0.1,
                &mut swapped,
                &mut workspace,
            )
            .expect("exact");
        assert_eq!(swapped.len(), 2, "{name}");
        for m in &manifolds {
            let twin = swapped
                .iter()
                .find(|t| t.points[0].local_p2.distance(m.points[0].local_p1) < 1e-6)
                .unwrap_or_else(|| panic!("{name}: swapped order lost a contact"));
            assert!(twin.points[0].local_p1.distance(m.points[0].local_p2) < 1e-6);
            assert!((twin.points[0].dist - m.points[0].dist).abs() < 1e-9);
            assert!(twin.local_n1.distance(m.local_n2) < 1e-6);
            assert!(twin.local_n2.distance(m.local_n1) < 1e-6);
            assert_eq!(twin.points[0].fid1, m.points[0].fid2);
        }
        // A prediction below a contact's distance leaves that contact out.
        let nearest = manifolds
            .iter()
            .map(|m| m.points[0].dist)
            .fold(f64::INFINITY, f64::min);
        let mut fewer: Vec<Manifold> = Vec::new();
        dispatcher
            .contact_manifolds(&pos12, &s.a, &s.b, nearest, &mut fewer, &mut None)
            .expect("exact");
        assert_eq!(fewer.len(), 1, "{name}");
    }
}

#[test]
fn an_exact_ball_on_a_parry_cuboid_in_both_orders() {
    let s = scene("pencil-bowl-two-contacts");
    let dispatcher = ExactDispatcher::new(DispatcherOptions::default());
    let ball = exact_ball(Arc::clone(&s.pipeline), 8.0).expect("ball");
    let ground = Cuboid::new(Vector::new(100.0, 100.0, 5.0));
    let gap = 0.02;
    let pos_ball = Pose::translation(10.0, -4.0, 5.0 + 8.0 + gap);
    for flipped in [false, true] {
        let mut manifolds: Vec<Manifold> = Vec::new();
        let result = if flipped {
            dispatcher.contact_manifolds(
                &pos_ball.inverse(),
                &ball,
                &ground,
                0.1,
                &mut manifolds,
                &mut None,
            )
        } else {
            dispatcher.contact_manifolds(&pos_ball, &ground, &ball, 0.1, &mut manifolds, &mut None)
        };
        result.expect("exact");
        assert_eq!(manifolds.len(), 1);
        let (m, p) = (&manifolds[0], &manifolds[0].points[0]);
        assert!((p.dist - gap).abs() < 1e-9);
        let (on_ground, on_ball, up) = if flipped {
            (p.local_p2, p.local_p1, -m.local_n1)
        } else {
            (p.local_p1, p.local_p2, m.local_n1)
        };
        assert!(on_ground.distance(Vector::new(10.0, -4.0, 5.0)) < 1e-8);
        assert!(on_ball.distance(Vector::new(0.0, 0.0, -8.0)) < 1e-8);
        assert!(up.distance(Vector::Z) < 1e-9);
    }
}

#[test]
fn ids_and_solver_data_persist_over_a_small_motion() {
    let s = scene("pencil-bowl-two-contacts");
    let dispatcher = ExactDispatcher::new(DispatcherOptions::default());
    let counters = dispatcher.counters();
    let mut manifolds: Vec<Manifold> = Vec::new();
    let mut workspace = None;
    let mut scratch = QueryScratch::default();
    let mut features = Vec::new();
    for frame in 0..24 {
        // The pencil turns about the bowl's axis and slides along it a little.
        let t = f64::from(frame);
        let motion = Pose::from_parts(
            Vector::new(0.0, 0.0, 2e-4 * t),
            glam::DQuat::from_rotation_z(3e-4 * t),
        );
        let pose_b = motion * s.pose_b;
        let pos12 = s.pose_a.inverse() * pose_b;
        dispatcher
            .contact_manifolds(&pos12, &s.a, &s.b, 0.1, &mut manifolds, &mut workspace)
            .expect("exact");
        let cold = s
            .pipeline
            .query(s.a.object(), &s.pose_a, s.b.object(), &pose_b, &mut scratch)
            .expect("query");
        assert_eq!(manifolds.len(), cold.contacts.len(), "frame {frame}");
        assert_eq!(manifolds.len(), 2, "frame {frame}");
        for c in &cold.contacts {
            assert!(
                manifolds
                    .iter()
                    .any(|m| (m.points[0].dist - c.distance).abs() < 1e-9),
                "frame {frame}: the warm answer differs from the cold one"
            );
        }
        if frame == 0 {
            for (k, m) in manifolds.iter_mut().enumerate() {
                let mark = Mark(k as u32 + 1);
                m.data = mark;
                m.points[0].data = mark;
                features.push((m.points[0].fid1, m.points[0].fid2));
            }
        } else {
            for (k, m) in manifolds.iter().enumerate() {
                assert_eq!(m.data, Mark(k as u32 + 1), "frame {frame}");
                assert_eq!(m.points[0].data, Mark(k as u32 + 1), "frame {frame}");
                assert_eq!((m.points[0].fid1, m.points[0].fid2), features[k]);
            }
        }
    }
    let counts = counters.snapshot();
    assert_eq!(counts.exact + counts.warm, 24);
    assert!(counts.warm >= 20, "{counts:?}");
}

#[test]
fn an_unrepresentable_partner_gets_no_manifold_or_a_mesh_one() {
    let s = scene("pencil-bowl-two-contacts");
    let ball = exact_ball(Arc::clone(&s.pipeline), 5.0).expect("ball");
    let mesh = ball.closed_mesh().trimesh.clone();
    let pos12 = Pose::translation(10.01, 0.0, 0.0);
    let strict = ExactDispatcher::new(DispatcherOptions::default());
    let mut manifolds: Vec<Manifold> = vec![ContactManifold::new()];
    assert_eq!(
        strict.contact_manifolds(&pos12, &ball, &mesh, 0.1, &mut manifolds, &mut None),
        Err(Unsupported)
    );
    assert!(manifolds.is_empty());
    let meshy = ExactDispatcher::new(DispatcherOptions {
        beyond_reach: BeyondReach::MeshApproximation,
        ..DispatcherOptions::default()
    });
    meshy
        .contact_manifolds(&pos12, &ball, &mesh, 0.1, &mut manifolds, &mut None)
        .expect("parry's trimesh manifolds");
    let nearest = manifolds
        .iter()
        .flat_map(|m| &m.points)
        .map(|p| p.dist)
        .fold(f64::INFINITY, f64::min);
    let e = ball.closed_mesh().chordal_error;
    assert!(
        (nearest - 0.01).abs() <= 2.0 * e,
        "mesh contact at {nearest}"
    );
}
