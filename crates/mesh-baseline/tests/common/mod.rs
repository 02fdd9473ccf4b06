//! Test helpers computed independently of the crate: spheres, random rotations, exact
//! mesh-to-sphere deviations and topology checks.
#![allow(dead_code)]

use geom_param::{DPose3, DQuat, DVec3, MeshOptions, ObjectModel, Profile, SegmentSpec};
use std::collections::HashMap;

/// A sphere of radius `r` centred at the origin, as an exact model (one arc face, two poles).
pub fn sphere(r: f64) -> ObjectModel {
    let profile = Profile::new(&[SegmentSpec::Arc {
        center: [0.0, 0.0],
        from: [0.0, -r],
        to: [0.0, r],
        ccw: true,
    }])
    .expect("a sphere profile is valid");
    ObjectModel::from_profile(
        "sphere",
        profile,
        &MeshOptions {
            chordal_tolerance: 0.1 * r,
        },
    )
    .expect("tolerance is valid")
}

/// Deterministic generator (64-bit LCG, top 53 bits) of uniform numbers in [0, 1).
pub struct Lcg(pub u64);

impl Lcg {
    pub fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Uniform random rotation (Shoemake's method).
    pub fn rotation(&mut self) -> DQuat {
        let (u1, u2, u3) = (self.next(), self.next(), self.next());
        let tau = std::f64::consts::TAU;
        let (a, b) = ((1.0 - u1).sqrt(), u1.sqrt());
        DQuat::from_xyzw(
            a * (tau * u2).sin(),
            a * (tau * u2).cos(),
            b * (tau * u3).sin(),
            b * (tau * u3).cos(),
        )
        .normalize()
    }

    /// Uniform random unit vector.
    pub fn direction(&mut self) -> DVec3 {
        let z = 2.0 * self.next() - 1.0;
        let phi = std::f64::consts::TAU * self.next();
        let s = (1.0 - z * z).sqrt();
        DVec3::new(s * phi.cos(), s * phi.sin(), z)
    }
}

pub fn pose(rotation: DQuat, translation: DVec3) -> DPose3 {
    DPose3 {
        rotation,
        translation,
    }
}

/// Closest point of triangle (a, b, c) to p (Ericson, Real-Time Collision Detection 5.1.5).
pub fn closest_on_triangle(p: DVec3, a: DVec3, b: DVec3, c: DVec3) -> DVec3 {
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return a;
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(bp), ac.dot(bp));
    if d3 >= 0.0 && d4 <= d3 {
        return b;
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return a + ab * (d1 / (d1 - d3));
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(cp), ac.dot(cp));
    if d6 >= 0.0 && d5 <= d6 {
        return c;
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return a + ac * (d2 / (d2 - d6));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    }
    let denom = 1.0 / (va + vb + vc);
    a + ab * (vb * denom) + ac * (vc * denom)
}

/// Exact largest distance between a mesh whose vertices lie on the sphere |x| = r and that
/// sphere: r minus the smallest distance from the centre to a triangle.
pub fn sphere_deviation(vertices: &[DVec3], indices: &[[u32; 3]], r: f64) -> f64 {
    indices
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|k| vertices[k as usize]);
            r - closest_on_triangle(DVec3::ZERO, a, b, c).length()
        })
        .fold(0.0, f64::max)
}

/// Largest circumradius of the mesh's triangles (mm).
pub fn max_circumradius(vertices: &[DVec3], indices: &[[u32; 3]]) -> f64 {
    indices
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|k| vertices[k as usize]);
            let area2 = (b - a).cross(c - a).length();
            a.distance(b) * b.distance(c) * c.distance(a) / (2.0 * area2)
        })
        .fold(0.0, f64::max)
}

/// Every undirected edge is used by exactly two triangles, once in each direction.
pub fn is_watertight(indices: &[[u32; 3]]) -> bool {
    let mut uses: HashMap<(u32, u32), (u32, u32)> = HashMap::new();
    for t in indices {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            let entry = uses.entry((a.min(b), a.max(b))).or_default();
            if a < b {
                entry.0 += 1;
            } else {
                entry.1 += 1;
            }
        }
    }
    uses.values().all(|&u| u == (1, 1))
}

/// Signed volume (mm³): positive for an outward closed mesh.
pub fn signed_volume(vertices: &[DVec3], indices: &[[u32; 3]]) -> f64 {
    indices
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|k| vertices[k as usize]);
            a.dot(b.cross(c)) / 6.0
        })
        .sum()
}
