//! The proxy shell does not thin out: every proxy triangle stands at least the offset above the
//! plane of its mesh triangle, also at the creases of a cylinder's rims and the apex of a cone,
//! where a plain offset along the averaged vertex normals would stand only cos(45°) of it off.

mod common;

use common::*;
use geom_param::{ComponentMesh, SegmentSpec};
use mesh_narrowphase::proxy::proxy_mesh::{MIN_NORMAL_COSINE, ProxyMesh};

/// Checks the shell of `mesh` at `offset` by plain vector algebra on the two position lists,
/// and returns the smallest height a plain offset along the vertex normals would have had
/// (relative to `offset`).
fn check_shell(mesh: &ComponentMesh, offset: f64, what: &str) -> f64 {
    let proxy = ProxyMesh::build(mesh, offset);
    assert_eq!(proxy.positions.len(), mesh.positions.len());
    let mut plain_least = f64::INFINITY;
    for tri in &mesh.triangles {
        let p = tri.map(|i| mesh.positions[i as usize]);
        let Some(n) = (p[1] - p[0]).cross(p[2] - p[0]).try_normalize() else {
            continue;
        };
        for &i in tri {
            let i = i as usize;
            let height = (proxy.positions[i] - mesh.positions[i]).dot(n);
            assert!(
                height >= offset * (1.0 - 1e-12),
                "{what}: vertex {i} of the proxy stands {height} above its triangle's plane, \
                 below the offset {offset}"
            );
            plain_least = plain_least.min(mesh.normals[i].dot(n));
        }
    }
    for (q, p) in proxy.positions.iter().zip(&mesh.positions) {
        assert!(q.distance(*p) <= offset / MIN_NORMAL_COSINE * (1.0 + 1e-12));
    }
    plain_least
}

#[test]
fn shell_is_at_least_the_offset_on_smooth_surfaces_creases_and_apexes() {
    let rod = cylinder(4.0, 30.0, 0.05);
    let plain = check_shell(rod.mesh(rod.components[0].id), 0.2, "cylinder");
    // The rims are right-angled creases: a plain offset would thin to cos 45° there.
    assert!(plain < 0.75, "no crease in the cylinder mesh: {plain}");
    let cone = model(
        "cone",
        &[
            SegmentSpec::Line {
                from: [0.0, 0.0],
                to: [5.0, 0.0],
            },
            SegmentSpec::Line {
                from: [5.0, 0.0],
                to: [0.0, 20.0],
            },
        ],
        0.05,
    );
    for c in &cone.components {
        check_shell(cone.mesh(c.id), 0.15, "cone");
    }
    let ring = torus(20.0, 5.0, 0.02);
    let plain = check_shell(ring.mesh(ring.components[0].id), 0.3, "torus");
    assert!(
        plain > 0.99,
        "a smooth torus should need no correction: {plain}"
    );
    let bowl = paper_object("bowl", 0.05);
    for c in &bowl.components {
        check_shell(bowl.mesh(c.id), 0.25, "bowl");
    }
}
