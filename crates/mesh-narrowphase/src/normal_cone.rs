//! Normal cones: spherical caps that bound a set of unit vectors (a patch's outward normals,
//! or the directions from one bounding volume to another), and the cap-overlap tests that tell
//! whether two patches can hold a critical pair of the distance between them (Johnson & Cohen,
//! "Spatialized normal cone hierarchies", 2001).

use glam::{DQuat, DVec3};

/// A spherical cap `{n : angle(n, axis) <= θ}` on the unit sphere, stored as its unit axis and
/// `(cos θ, sin θ)`, θ in [0, π]. θ = π is the whole sphere ([`NormalCone::ALL`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NormalCone {
    /// Unit axis (any unit vector when the cap is the whole sphere).
    pub axis: DVec3,
    /// cos θ.
    pub cos: f64,
    /// sin θ (>= 0).
    pub sin: f64,
}

/// Slack on the cosine comparisons of [`NormalCone::meets`] (rounding of unit vectors and of
/// the angle sums, about 1e-15, with a wide margin): a cap test never prunes a pair that the
/// exact caps would keep.
const COSINE_SLACK: f64 = 1e-12;

impl NormalCone {
    /// The whole sphere: every direction.
    pub const ALL: Self = Self {
        axis: DVec3::Z,
        cos: -1.0,
        sin: 0.0,
    };

    /// The cap of half-angle `angle` (radians, clamped to [0, π]) about `axis` (normalised;
    /// a zero or non-finite axis gives [`NormalCone::ALL`]).
    #[must_use]
    pub fn new(axis: DVec3, angle: f64) -> Self {
        let Some(axis) = axis.try_normalize() else {
            return Self::ALL;
        };
        if angle >= std::f64::consts::PI || angle.is_nan() {
            return Self::ALL;
        }
        let angle = angle.max(0.0);
        Self {
            axis,
            cos: angle.cos(),
            sin: angle.sin(),
        }
    }

    /// Whether the cap is the whole sphere.
    #[must_use]
    pub fn is_all(&self) -> bool {
        self.cos <= -1.0
    }

    /// The half-angle θ (radians).
    #[must_use]
    pub fn half_angle(&self) -> f64 {
        self.cos.clamp(-1.0, 1.0).acos()
    }

    /// A cap containing every vector of `normals` (unit vectors; non-finite ones are skipped):
    /// about their normalised mean, with the largest angle to any of them. No vectors, or a mean
    /// that vanishes (normals spread over the sphere), gives [`NormalCone::ALL`].
    #[must_use]
    pub fn bounding(normals: &[DVec3]) -> Self {
        let sum: DVec3 = normals.iter().filter(|n| n.is_finite()).sum();
        let Some(axis) = sum.try_normalize() else {
            return Self::ALL;
        };
        let angle = normals
            .iter()
            .filter(|n| n.is_finite())
            .map(|n| axis.angle_between(*n))
            .fold(0.0, f64::max);
        Self::new(axis, angle)
    }

    /// The cap widened by `angle` radians (>= 0).
    #[must_use]
    pub fn widened(&self, angle: f64) -> Self {
        if self.is_all() {
            return *self;
        }
        Self::new(self.axis, self.half_angle() + angle.max(0.0))
    }

    /// The smallest cap containing both caps.
    #[must_use]
    pub fn merged(&self, other: &Self) -> Self {
        if self.is_all() || other.is_all() {
            return Self::ALL;
        }
        let (t1, t2) = (self.half_angle(), other.half_angle());
        let phi = self.axis.angle_between(other.axis);
        if phi + t2 <= t1 {
            return *self;
        }
        if phi + t1 <= t2 {
            return *other;
        }
        let theta = 0.5 * (phi + t1 + t2);
        if theta >= std::f64::consts::PI {
            return Self::ALL;
        }
        // Turn self's axis towards other's by theta - t1 in their common plane.
        let side = other.axis - self.axis * self.axis.dot(other.axis);
        let Some(side) = side.try_normalize() else {
            // Opposite axes (phi = π): any great circle will do; the cap is nearly everything.
            return Self::ALL;
        };
        let turn = theta - t1;
        let axis = self.axis * turn.cos() + side * turn.sin();
        Self::new(axis, theta)
    }

    /// The cap of the opposite directions.
    #[must_use]
    pub fn negated(&self) -> Self {
        Self {
            axis: -self.axis,
            ..*self
        }
    }

    /// The cap rotated by `rotation`.
    #[must_use]
    pub fn rotated(&self, rotation: DQuat) -> Self {
        Self {
            axis: rotation * self.axis,
            ..*self
        }
    }

    /// Whether the two caps share a direction: angle(axis1, axis2) <= θ1 + θ2.
    #[must_use]
    pub fn meets(&self, other: &Self) -> bool {
        // A whole sphere meets everything (and two of them would wrap θ1 + θ2 = 2π to 0 below).
        if self.is_all() || other.is_all() {
            return true;
        }
        // cos and sin of θ1 + θ2 in [0, 2π); a sum of π or more (negative sine, or cosine -1)
        // covers every axis angle.
        let cos_sum = self.cos * other.cos - self.sin * other.sin;
        let sin_sum = self.sin * other.cos + self.cos * other.sin;
        if sin_sum < 0.0 || cos_sum <= -1.0 {
            return true;
        }
        self.axis.dot(other.axis) >= cos_sum - COSINE_SLACK
    }

    /// The directions from any point of a ball (centre `from`, radius `r_from`) to any point of
    /// another (centre `to`, radius `r_to`): the cap about `to - from` of half-angle
    /// asin((r_from + r_to) / |to - from|), or [`NormalCone::ALL`] when the balls overlap.
    #[must_use]
    pub fn between_balls(from: DVec3, r_from: f64, to: DVec3, r_to: f64) -> Self {
        let d = to - from;
        let length = d.length();
        let reach = r_from + r_to;
        if length <= reach || !length.is_finite() || reach.is_nan() {
            return Self::ALL;
        }
        let sin = reach / length;
        Self {
            axis: d / length,
            cos: (1.0 - sin * sin).max(0.0).sqrt(),
            sin,
        }
    }
}

/// Which critical pairs of the distance two patches may hold, from their normal cones and the
/// directions between them (Johnson & Cohen's test, for both signs).
///
/// A critical pair (p on A, q on B) of the distance between two solids has opposite outward
/// normals along the connecting direction d = (q - p)/|q - p|: for a separated local minimum
/// n_A(p) = d and n_B(q) = -d; for a penetration witness (q inside A, p inside B) n_A(p) = -d
/// and n_B(q) = d. At an edge or vertex "normal" means any vector of its normal cone. So with
/// N_A, N_B caps containing every normal of the two patches and D a cap containing every
/// direction from A's patch to B's, a separated minimum needs a direction in
/// N_A ∩ (-N_B) ∩ D and a penetration witness one in (-N_A) ∩ N_B ∩ D. Pairwise overlap of the
/// three caps is necessary for that, so a pair failing it holds no critical pair of that kind.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CriticalKinds {
    /// A separated local minimum (or a touch) is possible.
    pub separated: bool,
    /// A penetration witness is possible.
    pub penetrating: bool,
}

impl CriticalKinds {
    /// The kinds possible for normal cones `a` and `b` (same frame) and direction cap
    /// `directions` (from A's patch to B's).
    #[must_use]
    pub fn of(a: &NormalCone, b: &NormalCone, directions: &NormalCone) -> Self {
        let minus_b = b.negated();
        if !a.meets(&minus_b) {
            return Self {
                separated: false,
                penetrating: false,
            };
        }
        if directions.is_all() {
            return Self {
                separated: true,
                penetrating: true,
            };
        }
        Self {
            separated: a.meets(directions) && minus_b.meets(directions),
            penetrating: a.negated().meets(directions) && b.meets(directions),
        }
    }

    /// Either kind.
    #[must_use]
    pub fn any(&self) -> bool {
        self.separated || self.penetrating
    }
}

/// A band of directions `{n : lo <= angle(n, axis) <= hi}` on the unit sphere: what bounds the
/// normals of a patch wrapped around an axis (a cylinder's or a cone's strip) far better than a
/// cap, whose axis, the normals' mean, points across them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NormalBand {
    /// Unit axis.
    pub axis: DVec3,
    /// Smallest angle (rad) from the axis.
    pub lo: f64,
    /// Largest angle (rad) from the axis.
    pub hi: f64,
}

impl NormalBand {
    /// The whole sphere.
    pub const ALL: Self = Self {
        axis: DVec3::Z,
        lo: 0.0,
        hi: std::f64::consts::PI,
    };

    /// The band about `axis` containing every cap of `cones` (each cap's axis at its angle from
    /// `axis`, widened by the cap's half-angle). [`NormalBand::ALL`] for a zero axis or a cap
    /// that is the whole sphere.
    #[must_use]
    pub fn around(axis: DVec3, cones: impl Iterator<Item = NormalCone>) -> Self {
        let Some(axis) = axis.try_normalize() else {
            return Self::ALL;
        };
        let (mut lo, mut hi) = (std::f64::consts::PI, 0.0_f64);
        for c in cones {
            if c.is_all() {
                return Self::ALL;
            }
            let angle = axis.dot(c.axis).clamp(-1.0, 1.0).acos();
            let width = c.half_angle();
            lo = lo.min(angle - width);
            hi = hi.max(angle + width);
        }
        Self {
            axis,
            lo: lo.max(0.0),
            hi: hi.min(std::f64::consts::PI),
        }
    }

    /// Whether the band says nothing (it covers every direction).
    #[must_use]
    pub fn is_all(&self) -> bool {
        self.lo <= 0.0 && self.hi >= std::f64::consts::PI
    }

    /// The band of the opposite directions.
    #[must_use]
    pub fn negated(&self) -> Self {
        Self {
            axis: -self.axis,
            ..*self
        }
    }

    /// The band rotated by `rotation`.
    #[must_use]
    pub fn rotated(&self, rotation: DQuat) -> Self {
        Self {
            axis: rotation * self.axis,
            ..*self
        }
    }

    /// The band rotated by the matrix `rotation`.
    #[must_use]
    pub fn rotated_by(&self, rotation: &glam::DMat3) -> Self {
        Self {
            axis: *rotation * self.axis,
            ..*self
        }
    }

    /// Whether the band shares a direction with the cap: the angles from the band's axis within
    /// the cap, [φ - θ, φ + θ] with φ the angle between the axes, meet [lo, hi].
    #[must_use]
    pub fn meets(&self, cap: &NormalCone) -> bool {
        if self.is_all() || cap.is_all() {
            return true;
        }
        let phi = self.axis.dot(cap.axis).clamp(-1.0, 1.0).acos();
        let theta = cap.half_angle();
        // The slack covers the rounding of the two acos (about 1e-16 rad each).
        phi - theta <= self.hi + 1e-12 && phi + theta >= self.lo - 1e-12
    }
}

impl CriticalKinds {
    /// [`CriticalKinds::of`] refined by the bands of the two patches' normals (`band_a`,
    /// `band_b`, same frame; a normal lies in both its cap and its band): each band must meet
    /// the other patch's reversed cap and the directions.
    #[must_use]
    pub fn with_bands(
        self,
        (a, band_a): (&NormalCone, &NormalBand),
        (b, band_b): (&NormalCone, &NormalBand),
        directions: &NormalCone,
    ) -> Self {
        if !self.any() {
            return self;
        }
        let minus_b = b.negated();
        let (minus_band_a, minus_band_b) = (band_a.negated(), band_b.negated());
        let shared = band_a.meets(&minus_b) && minus_band_b.meets(a);
        Self {
            separated: self.separated
                && shared
                && band_a.meets(directions)
                && minus_band_b.meets(directions),
            penetrating: self.penetrating
                && shared
                && minus_band_a.meets(directions)
                && band_b.meets(directions),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Caps against their definition: two caps meet when the angle between their axes is at
    /// most the sum of their half-angles (whole spheres included), and do not when it exceeds
    /// it by more than the test's slack (1e-12 on the cosine, about 1.4e-6 rad next to
    /// opposite axes), which may only err towards meeting.
    #[test]
    fn caps_meet_as_their_angles_say() {
        let angles = [0.0, 0.3, 1.2, 1.5, 2.0, 3.0, std::f64::consts::PI];
        let axes = [
            DVec3::Z,
            DVec3::X,
            -DVec3::Z,
            DVec3::new(1.0, 1.0, 0.3).normalize(),
        ];
        for &t1 in &angles {
            for &t2 in &angles {
                for &a1 in &axes {
                    for &a2 in &axes {
                        let (c1, c2) = (NormalCone::new(a1, t1), NormalCone::new(a2, t2));
                        let gap = a1.angle_between(a2) - (t1 + t2);
                        if gap <= 0.0 {
                            assert!(c1.meets(&c2), "{t1} {t2} {a1} {a2}");
                        } else if gap > 1e-5 {
                            assert!(!c1.meets(&c2), "{t1} {t2} {a1} {a2}");
                        }
                    }
                }
            }
        }
    }
}
