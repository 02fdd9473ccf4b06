//! Planted answers on general solids: spheres placed at random around a block, so that the
//! nearest point of the block is on a face, an edge or a corner as chance has it, the gap
//! (or overlap) drawn at random; the truth is the closest point of the box to the sphere's
//! centre (coordinates clamped to the box), computed here without the oracle.

mod support;

use contact_oracle::ExpectedContact;
use contact_oracle::closed_form::SceneObject;
use contact_oracle::closed_form::brep::block;
use geom_param::{DPose3, DVec3, FeatureLocation, SegmentSpec};
use support::{Errors, Rng, check_solids};

const DISTANCE_TOLERANCE: f64 = 1e-9 * 40.0;
const POINT_TOLERANCE: f64 = 1e-7 * 40.0;

#[test]
fn spheres_around_a_block_match_the_clamped_closest_point() {
    let half = DVec3::new(10.0, 7.0, 5.0);
    let r = 4.0;
    let box_solid = block(2.0 * half).expect("builds");
    let sphere = SceneObject::Profile(geom_param::ObjectDescription {
        name: "sphere".into(),
        note: None,
        profile: vec![SegmentSpec::Arc {
            center: [0.0, 0.0],
            from: [0.0, -r],
            to: [0.0, r],
            ccw: true,
        }],
    })
    .solid()
    .expect("valid profile");
    let mut rng = Rng(2024);
    let mut worst = Errors::default();
    let mut kinds = [0; 3];
    let mut placed = 0;
    while placed < 24 {
        let reach = half + DVec3::splat(r + 0.5);
        let c = DVec3::new(
            rng.range(-reach.x, reach.x),
            rng.range(-reach.y, reach.y),
            rng.range(-reach.z, reach.z),
        );
        let q = c.clamp(-half, half);
        let gap = q.distance(c) - r;
        if !(-0.005..=0.3).contains(&gap) {
            continue;
        }
        placed += 1;
        let clamped = (0..3).filter(|&i| q[i].abs() == half[i]).count();
        let point_a = c + (q - c).normalize() * r;
        let expected = [ExpectedContact {
            point_a,
            point_b: q,
            distance: gap,
            normal: (q - c).normalize(),
        }];
        let motion = rng.motion();
        let moved = |p: DVec3| motion.rotation * p + motion.translation;
        let expected = expected.map(|e| ExpectedContact {
            point_a: moved(e.point_a),
            point_b: moved(e.point_b),
            distance: e.distance,
            normal: motion.rotation * e.normal,
        });
        let pose_a = DPose3 {
            rotation: (motion.rotation * rng.rotation()).normalize(),
            translation: moved(c),
        };
        let what = format!("sphere at {c} (gap {gap:.3e}, {clamped} coordinates clamped)");
        let (report, errors) = check_solids(
            &what,
            (&sphere, &pose_a),
            (&box_solid, &motion),
            &expected,
            DISTANCE_TOLERANCE,
            POINT_TOLERANCE,
        );
        let location = report.contacts[0].location_b;
        let kind = match location {
            FeatureLocation::Face { .. } => 1,
            FeatureLocation::Edge { .. } => 2,
            FeatureLocation::Vertex { .. } => 3,
        };
        assert_eq!(kind, clamped, "{what}: {location:?}");
        kinds[clamped - 1] += 1;
        worst = worst.max(errors);
    }
    println!("faces, edges, corners: {kinds:?}; worst errors {worst:?}");
    assert!(kinds.iter().all(|&k| k > 0), "{kinds:?}");
}

/// The closest point of triangle abc to p and how many of its barycentric coordinates vanish
/// (0: inside the triangle, 1: on an edge, 2: at a corner): Ericson, Real-Time Collision
/// Detection, 5.1.5, by Voronoi regions.
fn closest_on_triangle(p: DVec3, a: DVec3, b: DVec3, c: DVec3) -> (DVec3, usize) {
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return (a, 2);
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(bp), ac.dot(bp));
    if d3 >= 0.0 && d4 <= d3 {
        return (b, 2);
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return (a + ab * (d1 / (d1 - d3)), 1);
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(cp), ac.dot(cp));
    if d6 >= 0.0 && d5 <= d6 {
        return (c, 2);
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return (a + ac * (d2 / (d2 - d6)), 1);
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        return (b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6))), 1);
    }
    let denom = 1.0 / (va + vb + vc);
    (a + ab * (vb * denom) + ac * (vc * denom), 0)
}

/// Spheres around a tetrahedron (edges and corners far from right angles): the truth is the
/// closest of the four triangles' closest points.
#[test]
fn spheres_around_a_tetrahedron_match_the_closest_triangle_point() {
    let p = [
        DVec3::new(-8.0, -6.0, -4.0),
        DVec3::new(12.0, -3.0, -4.0),
        DVec3::new(-2.0, 11.0, -3.0),
        DVec3::new(1.0, 1.0, 10.0),
    ];
    let r = 4.0;
    let solid = contact_oracle::closed_form::brep::tetrahedron(p).expect("builds");
    let sphere = SceneObject::Profile(geom_param::ObjectDescription {
        name: "sphere".into(),
        note: None,
        profile: vec![SegmentSpec::Arc {
            center: [0.0, 0.0],
            from: [0.0, -r],
            to: [0.0, r],
            ccw: true,
        }],
    })
    .solid()
    .expect("valid profile");
    let faces = [[1, 2, 3], [0, 2, 3], [0, 1, 3], [0, 1, 2]];
    let centroid = p.iter().copied().sum::<DVec3>() / 4.0;
    let mut rng = Rng(4049);
    let mut worst = Errors::default();
    let mut kinds = [0; 3];
    let mut placed = 0;
    while placed < 24 {
        let c = centroid + rng.unit_vector() * rng.range(0.0, 16.0);
        // Outside: beyond at least one face's plane (oriented away from the centroid).
        let outside = faces.iter().any(|&[i, j, k]| {
            let n = (p[j] - p[i]).cross(p[k] - p[i]);
            let n = if n.dot(p[i] - centroid) < 0.0 { -n } else { n };
            (c - p[i]).dot(n) > 0.0
        });
        if !outside {
            continue;
        }
        let (q, zeros) = faces
            .iter()
            .map(|&[i, j, k]| closest_on_triangle(c, p[i], p[j], p[k]))
            .min_by(|x, y| x.0.distance(c).total_cmp(&y.0.distance(c)))
            .expect("four faces");
        let gap = q.distance(c) - r;
        if !(-0.005..=0.3).contains(&gap) {
            continue;
        }
        placed += 1;
        let expected = [ExpectedContact {
            point_a: c + (q - c).normalize() * r,
            point_b: q,
            distance: gap,
            normal: (q - c).normalize(),
        }];
        let pose_a = DPose3 {
            rotation: rng.rotation(),
            translation: c,
        };
        let what = format!("sphere at {c} (gap {gap:.3e}, {zeros} barycentric zeros)");
        let (report, errors) = check_solids(
            &what,
            (&sphere, &pose_a),
            (&solid, &DPose3::IDENTITY),
            &expected,
            DISTANCE_TOLERANCE,
            POINT_TOLERANCE,
        );
        let location = report.contacts[0].location_b;
        let kind = match location {
            FeatureLocation::Face { .. } => 0,
            FeatureLocation::Edge { .. } => 1,
            FeatureLocation::Vertex { .. } => 2,
        };
        assert_eq!(kind, zeros, "{what}: {location:?}");
        kinds[zeros] += 1;
        worst = worst.max(errors);
    }
    println!("faces, edges, corners: {kinds:?}; worst errors {worst:?}");
    assert!(kinds.iter().all(|&k| k > 0), "{kinds:?}");
}
