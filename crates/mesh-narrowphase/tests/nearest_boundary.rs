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
    let chordal = bowl
        .object
        .meshes
        .iter()
        .map(|m| m.chordal_error)
        .fold(0.0, f64::max);
    let mut rng = Rng(7);
    let mut worst: f64 = 0.0;
    for _ in 0..400 {
        let q = DVec3::new(
            rng.range(-45.0, 45.0),
            rng.range(-45.0, 45.0),
            rng.range(-5.0, 55.0),
        );
        let found = phase
            .nearest_boundary_point(&bowl.object, &bowl.prepared, q)
            .expect("a finite point has a nearest mesh point");
        let exact = bowl_distance(q, inner, outer, zc);
        assert!(found.error_bound >= chordal, "{found:?}");
        assert!(
            (found.distance - exact).abs() <= found.error_bound + 1e-9,
            "at {q}: mesh {} vs exact {exact} (bound {})",
            found.distance,
            found.error_bound
        );
        assert!((found.point.distance(q) - found.distance).abs() <= 1e-9 * (1.0 + exact));
        assert!((found.component.0 as usize) < bowl.object.components.len());
        worst = worst.max((found.distance - exact).abs());
    }
    // The bound is not vacuous: the mesh is that far off somewhere.
    assert!(worst > 0.1 * chordal, "{worst} vs {chordal}");
    assert!(
        phase
            .nearest_boundary_point(&bowl.object, &bowl.prepared, DVec3::NAN)
            .is_none()
    );
}
