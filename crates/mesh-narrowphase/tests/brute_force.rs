//! Every colliding triangle pair is found: the BVH traversals against brute force over all
//! triangle pairs, on random poses; and refused inputs.

mod common;

use common::*;
use geom_param::{ComponentId, DPose3, DQuat, DVec3, ObjectModel};
use mesh_narrowphase::triangle_intersection::triangles_intersect;
use mesh_narrowphase::{ContactBand, MeshInputError, MeshScratch, MeshVerdict};

fn band() -> ContactBand {
    ContactBand {
        margin: 1.0,
        delta1: -0.05,
        delta2: 0.3,
    }
}

/// All intersecting pairs by testing every triangle of `a` against every triangle of `b`
/// (B's positions moved by `pose`).
fn brute_force(
    positions_a: &[DVec3],
    triangles_a: &[[u32; 3]],
    positions_b: &[DVec3],
    triangles_b: &[[u32; 3]],
    pose: &DPose3,
) -> Vec<(u32, u32)> {
    let moved: Vec<DVec3> = positions_b.iter().map(|p| *pose * *p).collect();
    let mut out = Vec::new();
    for (i, ta) in triangles_a.iter().enumerate() {
        let t1 = ta.map(|k| positions_a[k as usize]);
        for (j, tb) in triangles_b.iter().enumerate() {
            let t2 = tb.map(|k| moved[k as usize]);
            if triangles_intersect(&t1, &t2) {
                out.push((i as u32, j as u32));
            }
        }
    }
    out
}

/// A random rotation, and a translation that puts a random vertex of B within `reach` of a
/// random vertex of A (so that the meshes often meet).
fn random_pose(rng: &mut Rng, a: &[DVec3], b: &[DVec3], reach: f64) -> DPose3 {
    let rotation = rng.rotation();
    let pa = a[(rng.next_u64() % a.len() as u64) as usize];
    let pb = b[(rng.next_u64() % b.len() as u64) as usize];
    let offset = rng.rotation() * DVec3::new(rng.range(0.0, reach), 0.0, 0.0);
    pose(rotation, pa - rotation * pb + offset)
}

fn check_pairs(
    a: &Prepared,
    ca: ComponentId,
    b: &Prepared,
    cb: ComponentId,
    seed: u64,
    reach: f64,
) {
    let mut rng = Rng(seed);
    let mut scratch = MeshScratch::default();
    let (ma, mb): (&ObjectModel, &ObjectModel) = (&a.object, &b.object);
    let (mesh_a, mesh_b) = (ma.mesh(ca), mb.mesh(cb));
    let mut penetrating = 0;
    let mut proxy_hits = 0;
    for _ in 0..8 {
        let pose = random_pose(&mut rng, &mesh_a.positions, &mesh_b.positions, reach);
        // Mesh against mesh, through the query.
        let truth = brute_force(
            &mesh_a.positions,
            &mesh_a.triangles,
            &mesh_b.positions,
            &mesh_b.triangles,
            &pose,
        );
        let (verdict, out) = query(a, ca, b, cb, &pose, &band(), &mut scratch);
        if truth.is_empty() {
            assert_ne!(verdict, MeshVerdict::Penetrating);
        } else {
            assert_eq!(verdict, MeshVerdict::Penetrating);
            let mut got = out.penetrating_pairs.clone();
            got.sort_unstable();
            got.dedup();
            assert_eq!(got, truth);
            penetrating += 1;
        }
        // Each side's proxy against the other's mesh, through the public tree API.
        let offset = 0.7;
        let (tree_a, tree_b) = (
            &a.prepared.components[ca.0 as usize].bvh,
            &b.prepared.components[cb.0 as usize].bvh,
        );
        let (proxy_a, _) = a.prepared.components[ca.0 as usize]
            .proxies
            .get_or_build(mesh_a, offset);
        let (proxy_b, _) = b.prepared.components[cb.0 as usize]
            .proxies
            .get_or_build(mesh_b, offset);
        let mut any = false;
        for (positions_a, positions_b, tree_a, tree_b) in [
            (&proxy_a.positions, &mesh_b.positions, &proxy_a.bvh, tree_b),
            (&mesh_a.positions, &proxy_b.positions, tree_a, &proxy_b.bvh),
        ] {
            let truth = brute_force(
                positions_a,
                &mesh_a.triangles,
                positions_b,
                &mesh_b.triangles,
                &pose,
            );
            let mut candidates = Vec::new();
            tree_a.overlapping_pairs(tree_b, &pose, (0.0, 0.0), &mut candidates);
            let moved: Vec<DVec3> = positions_b.iter().map(|p| pose * *p).collect();
            let mut got: Vec<(u32, u32)> = candidates
                .into_iter()
                .filter(|&(i, j)| {
                    let t1 = mesh_a.triangles[i as usize].map(|k| positions_a[k as usize]);
                    let t2 = mesh_b.triangles[j as usize].map(|k| moved[k as usize]);
                    triangles_intersect(&t1, &t2)
                })
                .collect();
            got.sort_unstable();
            assert_eq!(got, truth);
            any |= !truth.is_empty();
        }
        proxy_hits += usize::from(any);
    }
    println!("penetrating poses {penetrating}, proxy-hit poses {proxy_hits}");
    assert!(
        penetrating >= 3 && proxy_hits >= 3,
        "too few colliding poses to be a test"
    );
}

#[test]
fn torus_and_cylinder_pairs_match_brute_force() {
    let ring = Prepared::new(torus(20.0, 5.0, 0.1));
    let rod = Prepared::new(cylinder(4.0, 50.0, 0.1));
    let (cr, cc) = (ring.object.components[0].id, rod.object.components[0].id);
    check_pairs(&ring, cr, &rod, cc, 11, 3.0);
}

#[test]
fn vase_pairs_match_brute_force() {
    let vase = Prepared::new(paper_object("vase", 0.2));
    let bowl = Prepared::new(paper_object("bowl", 0.2));
    for (ca, cb) in [(1, 0), (0, 1), (2, 1)] {
        let (ca, cb) = (ComponentId(ca), ComponentId(cb));
        check_pairs(&vase, ca, &bowl, cb, 5 + u64::from(ca.0), 3.0);
    }
}

#[test]
fn unusable_inputs_are_refused() {
    let a = Prepared::new(sphere(10.0, 0.1));
    let c = a.object.components[0].id;
    let mut scratch = MeshScratch::default();
    let ok = pose(DQuat::IDENTITY, DVec3::new(20.1, 0.0, 0.0));
    let nan = pose(DQuat::IDENTITY, DVec3::new(f64::NAN, 0.0, 0.0));
    let (verdict, out) = query(&a, c, &a, c, &nan, &band(), &mut scratch);
    assert_eq!(verdict, MeshVerdict::InvalidInput(MeshInputError::BadPose));
    assert!(out.seeds.is_empty());
    let scaled = pose(DQuat::from_xyzw(0.0, 0.0, 0.0, 2.0), DVec3::X * 30.0);
    let (verdict, _) = query(&a, c, &a, c, &scaled, &band(), &mut scratch);
    assert_eq!(verdict, MeshVerdict::InvalidInput(MeshInputError::BadPose));
    let bad = ContactBand {
        margin: 0.1,
        delta1: 0.0,
        delta2: 0.3,
    };
    let (verdict, _) = query(&a, c, &a, c, &ok, &bad, &mut scratch);
    assert_eq!(
        verdict,
        MeshVerdict::InvalidInput(MeshInputError::BadBand { band: bad })
    );
    let (verdict, _) = query(&a, ComponentId(7), &a, c, &ok, &band(), &mut scratch);
    assert_eq!(
        verdict,
        MeshVerdict::InvalidInput(MeshInputError::NoSuchComponent {
            component: ComponentId(7),
            count: 1
        })
    );
    let (verdict, _) = query(&a, c, &a, c, &ok, &band(), &mut scratch);
    assert_eq!(verdict, MeshVerdict::Seeds);
}

#[test]
fn plane_filter_never_contradicts_the_exact_test() {
    use mesh_narrowphase::plane_filter::clearly_apart;
    let mut rng = Rng(99);
    let mut apart = 0;
    for k in 0..200_000 {
        // Triangles around a shared random point, scaled from 1e-3 to 1e3, many of them touching
        // or nearly touching (a corner of one on or just off the other's plane).
        let scale = 10f64.powf(rng.range(-3.0, 3.0));
        let centre = DVec3::new(
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
        ) * 100.0;
        let mut corner = || centre + rng.rotation() * DVec3::X * scale * rng.unit();
        let t1 = [corner(), corner(), corner()];
        let mut t2 = [corner(), corner(), corner()];
        if k % 2 == 0 {
            // Put a corner of t2 (almost) on t1's plane.
            let n = (t1[1] - t1[0]).cross(t1[2] - t1[0]).normalize_or_zero();
            let d = n.dot(t2[0] - t1[0]);
            t2[0] -= n * d * (1.0 - 1e-13 * f64::from(k % 7));
        }
        if clearly_apart(&t1, &t2) {
            apart += 1;
            assert!(
                !triangles_intersect(&t1, &t2),
                "filter says apart: {t1:?} {t2:?}"
            );
        }
    }
    assert!(apart > 10_000, "the filter never fired: {apart}");
}
