//! The only random source of the generated poses (soak, report): SplitMix64 (Steele, Lea and
//! Flood 2014), small and seedable, so that every pose is reproduced from its seed alone.

use geom_param::{DQuat, DVec3};

/// A SplitMix64 generator. The same seed gives the same sequence on every platform.
#[derive(Clone, Debug)]
pub struct SplitMix64(u64);

impl SplitMix64 {
    /// A generator started at `seed`.
    #[must_use]
    pub fn new(seed: u64) -> Self {
        Self(seed)
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1), with 53 random bits.
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }

    /// Uniform in [lo, hi).
    pub fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }

    /// Uniform index in 0..n (0 when n is 0); the modulo bias is below n / 2^64.
    pub fn index(&mut self, n: usize) -> usize {
        if n == 0 {
            return 0;
        }
        usize::try_from(self.next_u64() % n as u64).unwrap_or(0)
    }

    /// A direction uniform on the unit sphere (Marsaglia's z / azimuth method).
    pub fn direction(&mut self) -> DVec3 {
        let z = self.uniform(-1.0, 1.0);
        let phi = self.uniform(0.0, std::f64::consts::TAU);
        let r = (1.0 - z * z).max(0.0).sqrt();
        DVec3::new(r * phi.cos(), r * phi.sin(), z)
    }

    /// A rotation uniform over SO(3) (Shoemake's subgroup algorithm), as a unit quaternion.
    pub fn rotation(&mut self) -> DQuat {
        let (u1, u2, u3) = (
            self.unit(),
            self.uniform(0.0, std::f64::consts::TAU),
            self.uniform(0.0, std::f64::consts::TAU),
        );
        let (a, b) = ((1.0 - u1).sqrt(), u1.sqrt());
        DQuat::from_xyzw(a * u2.sin(), a * u2.cos(), b * u3.sin(), b * u3.cos()).normalize()
    }
}

#[cfg(test)]
mod tests {
    use super::SplitMix64;

    #[test]
    fn matches_the_reference_sequence() {
        // First outputs for seed 1234567 from the reference C implementation (Vigna's
        // splitmix64.c).
        let mut rng = SplitMix64::new(1_234_567);
        assert_eq!(rng.next_u64(), 6_457_827_717_110_365_317);
        assert_eq!(rng.next_u64(), 3_203_168_211_198_807_973);
    }

    #[test]
    fn directions_and_rotations_are_unit() {
        let mut rng = SplitMix64::new(7);
        for _ in 0..1000 {
            assert!((rng.direction().length() - 1.0).abs() < 1e-12);
            assert!((rng.rotation().length() - 1.0).abs() < 1e-12);
        }
    }
}
