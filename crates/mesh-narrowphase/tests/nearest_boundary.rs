//! `MeshPhase::nearest_boundary_point` against the closed-form distance to a spherical bowl's
//! boundary (outer and inner hemispheres and the flat rim, in more than one component).

mod common;

use common::*;
use geom_param::DVec3;
use mesh_narrowphase::{MeshNarrowphase, MeshPhase};

/// Distance from `q` to the bowl `socket(inner, outer, zc)`'s boundary: the two hemispheres
/// z <= zc of radii `inner` and `outer` about (0, 0, zc), and the annulus between them at
/// z = zc. Above the equator a hemisphere's nearest point is on its rim circle.
fn bowl_distance(q: DVec3, inner: f64, outer: f64, zc: f64) -> f64 {
    let rho = q.x.hypot(q.y);
    let dz = q.z - zc;
    let hemisphere = |r: f64| {
        if dz <= 0.0 {
            (q - DVec3::new(0.0, 0.0, zc)).length() - r
        } else {
            (rho - r).hypot(dz)
        }
        .abs()
    };
    let annulus = (rho - rho.clamp(inner, outer)).hypot(dz);
    hemisphere(inner).min(hemisphere(outer)).min(annulus)
}

#[test]
fn nearest_boundary_point_matches_the_closed_form_within_the_chordal_error() {
    let (inner, outer, zc) = (30.0, 35.0, 40.0);
    let bowl = Prepared::new(socket(inner, outer, zc, 0.02));
    assert!(bowl.object.components.len() >= 2);
    let phase = MeshNarrowphase::default();
    let chordal = largest_chordal_error(&bowl);
    let mut rng = Rng(7);
    let mut worst: f64 = 0.0;
    for _ in 0..400 {
        let q = DVec3::new(
            rng.range(-45.0, 45.0),
            rng.range(-45.0, 45.0),
            rng.range(-5.0, 55.0),
        );
        let found = phase
            .nearest_boundary_point(&bowl.object, &bowl.prepared, q, f64::INFINITY)
            .expect("a finite point has a nearest mesh point");
        // Bounded by a reach, the search finds the same point when it lies within the reach
        // and the error bound, and says that none does otherwise.
        for reach in [0.5, 2.0, 8.0] {
            let bounded = phase
                .nearest_boundary_point(&bowl.object, &bowl.prepared, q, reach)
                .expect("a finite point has an answer");
            if found.distance < reach + found.error_bound {
                assert_eq!(bounded, found, "at {q} within {reach}");
            } else {
                assert_eq!(bounded.distance, f64::INFINITY, "at {q} beyond {reach}");
                assert_eq!((bounded.point, bounded.component), (q, None));
            }
        }
        let exact = bowl_distance(q, inner, outer, zc);
        assert!(found.error_bound >= chordal, "{found:?}");
        assert!(
            (found.distance - exact).abs() <= found.error_bound + 1e-9,
            "at {q}: mesh {} vs exact {exact} (bound {})",
            found.distance,
            found.error_bound
        );
        assert!((found.point.distance(q) - found.distance).abs() <= 1e-9 * (1.0 + exact));
        assert!(
            found
                .component
                .is_some_and(|c| (c.0 as usize) < bowl.object.components.len())
        );
        worst = worst.max((found.distance - exact).abs());
    }
    // The bound is not vacuous: the mesh is that far off somewhere.
    assert!(worst > 0.1 * chordal, "{worst} vs {chordal}");
    assert!(
        phase
            .nearest_boundary_point(&bowl.object, &bowl.prepared, DVec3::NAN, f64::INFINITY)
            .is_none()
    );
}

/// `MeshPhase::faces_near` on the same bowl: every face whose exact surface comes within the
/// reach minus the chordal error is listed, once, and each listed location is an exact surface
/// point within the reach plus the chordal error. Faces are told apart by their exact points
/// (distance from the centre 30 or 35 below the equator, or on the plane z = 40), and each
/// face's exact distance is the closed form for that surface alone.
#[test]
fn faces_near_lists_every_face_within_reach() {
    let (inner, outer, zc) = (30.0, 35.0, 40.0);
    let bowl = Prepared::new(socket(inner, outer, zc, 0.02));
    let phase = MeshNarrowphase::default();
    let solid = &bowl.object.solid;
    let chordal = largest_chordal_error(&bowl);
    let centre = DVec3::new(0.0, 0.0, zc);
    // Which surface a face lies on, from its point in mid-domain.
    let kind = |face: geom_param::FaceId| {
        let [du, dv] = solid.face(face).surface.domain();
        let p = solid
            .eval_face(face, 0.5 * (du.min + du.max), 0.5 * (dv.min + dv.max))
            .point;
        if (p.z - zc).abs() < 1e-9 {
            0
        } else if ((p - centre).length() - inner).abs() < 1e-6 {
            1
        } else {
            2
        }
    };
    let face_distance = |k: usize, q: DVec3| {
        let (rho, dz) = (q.x.hypot(q.y), q.z - zc);
        let sphere = |r: f64| {
            if dz <= 0.0 {
                ((q - centre).length() - r).abs()
            } else {
                (rho - r).hypot(dz)
            }
        };
        match k {
            0 => (rho - rho.clamp(inner, outer)).hypot(dz),
            1 => sphere(inner),
            _ => sphere(outer),
        }
    };
    let mut rng = Rng(11);
    let mut required = 0;
    for _ in 0..300 {
        let q = DVec3::new(
            rng.range(-40.0, 40.0),
            rng.range(-40.0, 40.0),
            rng.range(0.0, 45.0),
        );
        let radius = rng.range(0.1, 3.0);
        let listed = phase.faces_near(&bowl.object, &bowl.prepared, q, radius);
        let ids: Vec<geom_param::FaceId> = listed
            .iter()
            .map(|l| match *l {
                geom_param::FeatureLocation::Face { id, .. } => id,
                other => panic!("not a face: {other:?}"),
            })
            .collect();
        for (i, id) in ids.iter().enumerate() {
            assert!(!ids[..i].contains(id), "{id:?} twice at {q}");
        }
        for l in &listed {
            let geom_param::FeatureLocation::Face { id, u, v } = *l else {
                unreachable!()
            };
            let p = solid.eval_face(id, u, v).point;
            assert!(p.distance(q) <= radius + chordal + 1e-9, "{l:?} at {q}");
        }
        for index in 0..solid.faces.len() {
            let id = geom_param::FaceId(u32::try_from(index).expect("few faces"));
            if face_distance(kind(id), q) <= radius - chordal {
                assert!(ids.contains(&id), "{id:?} missing at {q}, radius {radius}");
                required += 1;
            }
        }
    }
    // Not vacuous: many points have faces they must list.
    assert!(required > 30, "{required}");
}

/// The largest chordal error of the prepared object's component meshes (mm).
fn largest_chordal_error(prepared: &Prepared) -> f64 {
    prepared
        .object
        .meshes
        .iter()
        .map(|m| m.chordal_error)
        .fold(0.0, f64::max)
}
