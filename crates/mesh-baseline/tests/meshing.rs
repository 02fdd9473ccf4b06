//! Baseline meshes: triangle counts near the target, closed, outward, and a measured chordal
//! error that agrees with the exact deviation of a sphere mesh.

mod common;

use common::{is_watertight, signed_volume, sphere, sphere_deviation};
use geom_param::ObjectDescription;
use mesh_baseline::{BaselineError, BaselineMesh};
use std::f64::consts::PI;
use std::path::Path;

const TARGETS: [usize; 4] = [1_000, 5_000, 20_000, 80_000];

fn within_quarter(count: usize, target: usize) -> bool {
    (count as f64 - target as f64).abs() <= 0.25 * target as f64
}

#[test]
fn sphere_meshes_hit_the_target_are_closed_and_inscribed() {
    let r = 10.0;
    let model = sphere(r);
    for target in TARGETS {
        let mesh = BaselineMesh::new(&model.solid, target).expect("sphere meshes");
        let (v, t) = (mesh.vertices(), mesh.indices());
        assert!(
            within_quarter(mesh.triangle_count(), target),
            "{} triangles for target {target}",
            mesh.triangle_count()
        );
        assert!(is_watertight(t), "target {target}: not watertight");
        // Every vertex is on the sphere (the mesh is inscribed).
        for p in v {
            assert!(
                (p.length() - r).abs() <= 1e-12 * r,
                "vertex {p} off the sphere"
            );
        }
        let exact = sphere_deviation(v, t, r);
        // The measured error samples a grid of each triangle, so it may fall a little short of
        // the exact maximum (at the circumcentre) but never exceeds it.
        assert!(
            mesh.chordal_error() <= exact * (1.0 + 1e-9) && mesh.chordal_error() >= 0.9 * exact,
            "target {target}: measured {} vs exact {exact}",
            mesh.chordal_error()
        );
        // Inscribed and convex: the mesh lies between the spheres of radius r - exact and r.
        let volume = signed_volume(v, t);
        let ball = |radius: f64| 4.0 / 3.0 * PI * radius.powi(3);
        assert!(
            volume > ball(r - exact) && volume < ball(r),
            "target {target}: volume {volume}"
        );
        println!(
            "sphere r={r}: target {target}: {} triangles, {} vertices, chordal error measured {:.3e} exact {:.3e} mm",
            mesh.triangle_count(),
            mesh.vertex_count(),
            mesh.chordal_error(),
            exact
        );
    }
}

#[test]
fn paper_objects_mesh_to_the_target_closed_and_outward() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/objects");
    for name in ["paperweight", "goblet", "bowl", "pencil", "vase"] {
        let text = std::fs::read_to_string(dir.join(format!("{name}.json"))).expect("fixture");
        let description = ObjectDescription::from_json(&text).expect("valid object");
        for target in TARGETS {
            let mesh = BaselineMesh::from_description(&description, target).expect("meshes");
            assert!(
                within_quarter(mesh.triangle_count(), target),
                "{name}: {} triangles for target {target}",
                mesh.triangle_count()
            );
            assert!(
                is_watertight(mesh.indices()),
                "{name} {target}: not watertight"
            );
            assert!(signed_volume(mesh.vertices(), mesh.indices()) > 0.0);
            println!(
                "{name}: target {target}: {} triangles, chordal error {:.3e} mm",
                mesh.triangle_count(),
                mesh.chordal_error()
            );
        }
    }
}

#[test]
fn unusable_targets_are_refused() {
    let model = sphere(1.0);
    for target in [0, 5, BaselineMesh::MAX_TRIANGLES + 1] {
        assert!(
            matches!(
                BaselineMesh::new(&model.solid, target),
                Err(BaselineError::BadTarget { .. })
            ),
            "target {target}"
        );
    }
}
