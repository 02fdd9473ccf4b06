//! Shared by the tests and benches: a seeded generator, the paper objects, closed-form test
//! objects built in code, and random relative poses biased towards contact. Lengths in mm.
#![allow(dead_code)] // each test binary uses a different subset

use geom_param::{DPose3, MeshOptions, ObjectDescription, ObjectModel, Profile, SegmentSpec};
use glam::{DQuat, DVec3};
use std::path::PathBuf;

/// The six paper objects, in the paper's order.
pub const NAMES: [&str; 6] = ["paperweight", "goblet", "bowl", "pencil", "jar", "vase"];

/// SplitMix64: a small seeded generator, so every test is reproducible.
pub struct Rng(pub u64);

impl Rng {
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1).
    pub fn uniform(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.uniform()
    }

    /// Uniform index in 0..n (n > 0).
    pub fn index(&mut self, n: usize) -> usize {
        (self.next_u64() % n as u64) as usize
    }

    pub fn unit_vector(&mut self) -> DVec3 {
        loop {
            let v = DVec3::new(
                self.range(-1.0, 1.0),
                self.range(-1.0, 1.0),
                self.range(-1.0, 1.0),
            );
            let l2 = v.length_squared();
            if l2 > 1e-4 && l2 <= 1.0 {
                return v / l2.sqrt();
            }
        }
    }

    /// Uniformly distributed rotation.
    pub fn rotation(&mut self) -> DQuat {
        loop {
            let q = DQuat::from_xyzw(
                self.range(-1.0, 1.0),
                self.range(-1.0, 1.0),
                self.range(-1.0, 1.0),
                self.range(-1.0, 1.0),
            );
            let l2 = q.length_squared();
            if l2 > 1e-4 && l2 <= 1.0 {
                return q.normalize();
            }
        }
    }
}

/// A paper object from `fixtures/objects/`, meshed with `chordal_tolerance` (mm).
pub fn paper(name: &str, chordal_tolerance: f64) -> ObjectModel {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join(format!("../../fixtures/objects/{name}.json"));
    let text = std::fs::read_to_string(&path).expect("fixture exists");
    ObjectDescription::from_json(&text)
        .expect("fixture parses")
        .build(&MeshOptions { chordal_tolerance })
        .expect("fixture builds")
}

/// A sphere of radius `r` about the origin: one ccw arc from (0, -r) to (0, r).
pub fn sphere(r: f64, chordal_tolerance: f64) -> ObjectModel {
    let arc = SegmentSpec::Arc {
        center: [0.0, 0.0],
        from: [0.0, -r],
        to: [0.0, r],
        ccw: true,
    };
    model("sphere", &[arc], chordal_tolerance)
}

/// A column of `n` bumps along z, one convex surface component per bump: the profile climbs
/// the outer side as `n` convex arcs of radius 1 about (5, 1.2 i), each spanning +-30 degrees
/// about the outward direction, consecutive arcs meeting at concave edges; flat disks close
/// the bottom and top (each joins its neighbouring bump at a convex edge). Bump `i` bulges
/// out to r = 6 at z = 1.2 i.
pub fn bumpy_column(n: usize, chordal_tolerance: f64) -> ObjectModel {
    let (r0, a, half) = (5.0, 1.0, 30f64.to_radians());
    let (dr, dz) = (a * half.cos(), a * half.sin());
    let pitch = 2.0 * dz;
    let mut specs = Vec::with_capacity(n + 2);
    let bottom = -dz;
    specs.push(SegmentSpec::Line {
        from: [0.0, bottom],
        to: [r0 + dr, bottom],
    });
    for i in 0..n {
        let z = pitch * i as f64;
        specs.push(SegmentSpec::Arc {
            center: [r0, z],
            from: [r0 + dr, z - dz],
            to: [r0 + dr, z + dz],
            ccw: true,
        });
    }
    let top = pitch * (n as f64 - 1.0) + dz;
    specs.push(SegmentSpec::Line {
        from: [r0 + dr, top],
        to: [0.0, top],
    });
    model("bumpy column", &specs, chordal_tolerance)
}

/// Centre height (mm) of bump `i` of [`bumpy_column`] and its outer radius.
pub fn bump_tip(i: usize) -> (f64, f64) {
    (2.0 * 30f64.to_radians().sin() * i as f64, 6.0)
}

fn model(name: &str, specs: &[SegmentSpec], chordal_tolerance: f64) -> ObjectModel {
    let profile = Profile::new(specs).expect("valid profile");
    ObjectModel::from_profile(name, profile, &MeshOptions { chordal_tolerance })
        .expect("model builds")
}

/// A random pose of B in A's frame that brings a random point of B's surface near a random
/// point of A's surface: B's point lands at A's point moved along A's outward normal by a
/// random amount in [-spread, 2 spread] (so some poses penetrate) plus a random sideways jitter
/// of up to `spread`, under a uniformly random rotation.
pub fn near_contact_pose(rng: &mut Rng, a: &ObjectModel, b: &ObjectModel, spread: f64) -> DPose3 {
    let (pa, na) = random_surface_point(rng, a);
    let (pb, _) = random_surface_point(rng, b);
    let rotation = rng.rotation();
    let target =
        pa + na * rng.range(-spread, 2.0 * spread) + rng.unit_vector() * rng.range(0.0, spread);
    DPose3::from_parts(target - rotation * pb, rotation)
}

/// A random mesh vertex of a random component, with its outward normal.
pub fn random_surface_point(rng: &mut Rng, object: &ObjectModel) -> (DVec3, DVec3) {
    let mesh = &object.meshes[rng.index(object.meshes.len())];
    let k = rng.index(mesh.positions.len());
    (mesh.positions[k], mesh.normals[k])
}
