//! Seeded randomness for generated poses (SplitMix64: small, fast, reproducible from a seed).

use geom_param::{DPose3, DQuat, DVec3, ObjectModel};

/// SplitMix64 (Steele, Lea, Flood 2014): the state is the seed, advanced by a Weyl step.
#[derive(Clone, Debug)]
pub struct SplitMix64(pub u64);

impl SplitMix64 {
    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1).
    pub fn uniform(&mut self) -> f64 {
        // 53 random bits scaled into [0, 1): exact in f64.
        #[allow(clippy::cast_precision_loss)]
        let unit = (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
        unit
    }

    /// Uniform in [lo, hi).
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.uniform()
    }

    /// Uniform index in 0..n; 0 when n is 0.
    pub fn index(&mut self, n: usize) -> usize {
        if n == 0 {
            return 0;
        }
        usize::try_from(self.next_u64() % n as u64).unwrap_or(0)
    }

    /// Uniform direction on the unit sphere (rejection sampling in the cube).
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

    /// Uniformly distributed rotation (rejection sampling of quaternions in the 4-ball).
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

    /// A pose of B in A's frame that brings a random mesh vertex of B near a random mesh vertex
    /// of A: B's point lands on A's point moved along A's outward normal by a uniform amount in
    /// [−spread, 2·spread] (mm; so some poses penetrate) plus a sideways jitter of up to
    /// `spread`, under a uniformly random rotation.
    pub fn near_contact_pose(&mut self, a: &ObjectModel, b: &ObjectModel, spread: f64) -> DPose3 {
        let (pa, na) = self.surface_point(a);
        let (pb, _) = self.surface_point(b);
        let rotation = self.rotation();
        let target = pa
            + na * self.range(-spread, 2.0 * spread)
            + self.unit_vector() * self.range(0.0, spread);
        DPose3::from_parts(target - rotation * pb, rotation)
    }

    /// A random mesh vertex of a random component, with its outward normal.
    fn surface_point(&mut self, object: &ObjectModel) -> (DVec3, DVec3) {
        let mesh = &object.meshes[self.index(object.meshes.len())];
        let k = self.index(mesh.positions.len());
        (mesh.positions[k], mesh.normals[k])
    }
}
