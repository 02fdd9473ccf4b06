//! The six paper objects from `fixtures/objects/`: topology and components (snapshot), the
//! paper's component counts, and the dual representation's guarantees (every mesh vertex on its
//! exact feature, measured chordal error within tolerance, watertight and outward meshes).

use geom_param::{
    Boundary, ComponentKind, FeatureLocation, MeshOptions, ObjectDescription, ObjectModel,
};
use glam::DVec3;
use serde_json::{Value, json};
use std::collections::HashMap;
use std::path::PathBuf;

const NAMES: [&str; 6] = ["paperweight", "goblet", "bowl", "pencil", "jar", "vase"];

fn fixture(name: &str) -> ObjectDescription {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join(format!("../../fixtures/objects/{name}.json"));
    let text = std::fs::read_to_string(&path).expect("fixture exists");
    ObjectDescription::from_json(&text).expect("fixture parses")
}

fn model(name: &str, tolerance: f64) -> ObjectModel {
    fixture(name)
        .build(&MeshOptions {
            chordal_tolerance: tolerance,
        })
        .expect("fixture builds")
}

fn round(x: f64) -> f64 {
    let r = (x * 1e6).round() / 1e6;
    if r == 0.0 { 0.0 } else { r }
}

#[test]
fn component_counts_match_the_paper() {
    let expected = [3, 8, 2, 3, 3, 3];
    for (name, count) in NAMES.iter().zip(expected) {
        let m = model(name, 0.1);
        assert_eq!(m.components.len(), count, "{name}");
        let concave = m
            .components
            .iter()
            .filter(|c| c.kind == ComponentKind::Concave)
            .count();
        match *name {
            "paperweight" | "pencil" => assert_eq!(concave, 0, "{name} is all convex"),
            _ => assert!(concave >= 1, "{name} has a concave component"),
        }
    }
}

#[test]
fn topology_and_components_snapshot() {
    for name in NAMES {
        let m = model(name, 0.1);
        let faces: Vec<Value> = m
            .solid
            .faces
            .iter()
            .zip(
                m.profile
                    .as_ref()
                    .expect("a paper object is revolved")
                    .segments(),
            )
            .map(|(f, s)| {
                let side = |b: Boundary| match b {
                    Boundary::Periodic => json!("periodic"),
                    Boundary::Edge(e) => json!({"edge": e.0}),
                    Boundary::Vertex(v) => json!({"vertex": v.0}),
                    Boundary::Trimmed => json!("trimmed"),
                };
                json!({
                    "kind": s.kind_name(),
                    "convexity": format!("{:?}", f.convexity),
                    "v_min": side(f.boundary[2]),
                    "v_max": side(f.boundary[3]),
                })
            })
            .collect();
        let edges: Vec<Value> = m
            .solid
            .edges
            .iter()
            .map(|e| {
                let p = e.curve.eval(0.0).point;
                json!({
                    "faces": [e.uses[0].face.0, e.uses[1].face.0],
                    "radius": round(p.x), "z": round(p.z),
                    "convexity": format!("{:?}", e.convexity),
                })
            })
            .collect();
        let vertices: Vec<Value> = m
            .solid
            .vertices
            .iter()
            .map(|v| {
                json!({"point": [round(v.point.x), round(v.point.y), round(v.point.z)],
                            "faces": v.faces.iter().map(|f| f.0).collect::<Vec<_>>()})
            })
            .collect();
        let components: Vec<Value> = m
            .components
            .iter()
            .map(|c| {
                json!({
                    "kind": format!("{:?}", c.kind),
                    "faces": c.faces.iter().map(|f| f.0).collect::<Vec<_>>(),
                    "edges": c.edges.iter().map(|e| e.0).collect::<Vec<_>>(),
                    "vertices": c.vertices.iter().map(|v| v.0).collect::<Vec<_>>(),
                })
            })
            .collect();
        let snapshot = json!({"name": name, "faces": faces, "edges": edges, "vertices": vertices,
                              "components": components});
        insta::assert_json_snapshot!(format!("topology_{name}"), snapshot);
    }
}

#[test]
fn every_mesh_vertex_evaluates_back_to_its_position() {
    for name in NAMES {
        let m = model(name, 0.05);
        for mesh in &m.meshes {
            for (p, loc) in mesh.positions.iter().zip(&mesh.vertex_locations) {
                let exact = m.solid.point_at(loc);
                let scale = p.length().max(1.0);
                assert!(
                    exact.distance(*p) <= 1e-12 * scale,
                    "{name}: {loc:?} at {p} vs {exact}"
                );
            }
            // Corner parameters of each triangle evaluate to its corners too.
            for ((t, params), face) in mesh
                .triangles
                .iter()
                .zip(&mesh.triangle_params)
                .zip(&mesh.triangle_faces)
            {
                for k in 0..3 {
                    let q = mesh.positions[t[k] as usize];
                    let p = m.solid.eval_face(*face, params[k][0], params[k][1]).point;
                    assert!(
                        p.distance(q) <= 1e-12 * q.length().max(1.0),
                        "{name}: corner {k} of a triangle on {face:?}"
                    );
                }
            }
        }
    }
}

/// Largest distance between the exact surface and the mesh, sampled on a barycentric grid of
/// 45 points per triangle (denser than, and different from, the 12 the mesher uses).
fn measured_chordal_error(m: &ObjectModel, mesh: &geom_param::ComponentMesh) -> f64 {
    const N: usize = 8;
    let mut worst = 0.0_f64;
    for ((t, params), face) in mesh
        .triangles
        .iter()
        .zip(&mesh.triangle_params)
        .zip(&mesh.triangle_faces)
    {
        let p = t.map(|i| mesh.positions[i as usize]);
        for i in 0..=N {
            for j in 0..=N - i {
                let b = [
                    i as f64 / N as f64,
                    j as f64 / N as f64,
                    (N - i - j) as f64 / N as f64,
                ];
                let u = b[0] * params[0][0] + b[1] * params[1][0] + b[2] * params[2][0];
                let v = b[0] * params[0][1] + b[1] * params[1][1] + b[2] * params[2][1];
                let exact = m.solid.eval_face(*face, u, v).point;
                let linear = p[0] * b[0] + p[1] * b[1] + p[2] * b[2];
                worst = worst.max(exact.distance(linear));
            }
        }
    }
    worst
}

#[test]
fn measured_chordal_error_is_within_the_requested_tolerance() {
    for tolerance in [0.2, 0.05, 0.01] {
        for name in NAMES {
            let m = model(name, tolerance);
            for mesh in &m.meshes {
                let measured = measured_chordal_error(&m, mesh);
                assert!(
                    measured <= tolerance,
                    "{name} at {tolerance}: measured {measured}"
                );
                assert!(
                    mesh.chordal_error <= tolerance,
                    "{name}: reported {}",
                    mesh.chordal_error
                );
            }
        }
    }
}

/// Merges the component meshes by exact vertex position; every undirected edge of the result
/// must be used by exactly two triangles, once in each direction (closed and consistently
/// oriented), and the enclosed volume must be positive (outward orientation).
#[test]
fn object_meshes_are_watertight_and_outward() {
    for name in NAMES {
        let m = model(name, 0.05);
        let mut index: HashMap<[u64; 3], usize> = HashMap::new();
        let mut directed: HashMap<(usize, usize), usize> = HashMap::new();
        let mut volume = 0.0;
        for mesh in &m.meshes {
            let ids: Vec<usize> = mesh
                .positions
                .iter()
                .map(|p| {
                    let n = index.len();
                    *index.entry(p.to_array().map(f64::to_bits)).or_insert(n)
                })
                .collect();
            for t in &mesh.triangles {
                let v = t.map(|i| ids[i as usize]);
                if v[0] == v[1] || v[1] == v[2] || v[0] == v[2] {
                    continue; // degenerate (all corners at a pole); carries no area
                }
                for k in 0..3 {
                    *directed.entry((v[k], v[(k + 1) % 3])).or_default() += 1;
                }
                let p = t.map(|i| mesh.positions[i as usize]);
                volume += p[0].dot(p[1].cross(p[2])) / 6.0;
            }
        }
        for (&(a, b), &count) in &directed {
            assert_eq!(count, 1, "{name}: edge used twice in one direction");
            assert_eq!(directed.get(&(b, a)), Some(&1), "{name}: open edge");
        }
        assert!(volume > 0.0, "{name}: inward mesh (volume {volume})");
    }
}

#[test]
fn vertex_normals_are_unit_and_outward_on_faces() {
    for name in NAMES {
        let m = model(name, 0.1);
        for mesh in &m.meshes {
            for (n, loc) in mesh.normals.iter().zip(&mesh.vertex_locations) {
                assert!((n.length() - 1.0).abs() < 1e-12, "{name}: normal not unit");
                if let FeatureLocation::Face { id, u, v } = *loc {
                    let exact = m
                        .solid
                        .face(id)
                        .surface
                        .normal(u, v)
                        .expect("regular point");
                    assert!(
                        n.distance(exact) < 1e-12,
                        "{name}: normal differs from exact"
                    );
                }
            }
            // The triangle normal agrees in sign with the vertex normals (outward triangles).
            for t in &mesh.triangles {
                let p = t.map(|i| mesh.positions[i as usize]);
                let tn = (p[1] - p[0]).cross(p[2] - p[0]);
                let vn: DVec3 = t.iter().map(|&i| mesh.normals[i as usize]).sum();
                assert!(tn.dot(vn) >= 0.0, "{name}: triangle faces inward");
            }
        }
    }
}

#[test]
fn revolved_solids_pass_the_general_validation() {
    for name in NAMES {
        let m = model(name, 0.1);
        assert_eq!(geom_param::validate(&m.solid), Ok(()), "{name}");
    }
}
