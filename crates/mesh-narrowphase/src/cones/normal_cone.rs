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

    /// [`NormalCone::meets`] for the cap and for its negation (`(self.meets(other),
    /// self.negated().meets(other))`), from one dot product: the two differ only in the sign
    /// of `axis · other.axis`, which negating a vector flips exactly.
    #[must_use]
    pub fn meets_signed(&self, other: &Self) -> (bool, bool) {
        if self.is_all() || other.is_all() {
            return (true, true);
        }
        let cos_sum = self.cos * other.cos - self.sin * other.sin;
        let sin_sum = self.sin * other.cos + self.cos * other.sin;
        if sin_sum < 0.0 || cos_sum <= -1.0 {
            return (true, true);
        }
        let (dot, limit) = (self.axis.dot(other.axis), cos_sum - COSINE_SLACK);
        (dot >= limit, -dot >= limit)
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
        let (a_meets, minus_a_meets) = a.meets_signed(directions);
        let (minus_b_meets, b_meets) = minus_b.meets_signed(directions);
        Self {
            separated: a_meets && minus_b_meets,
            penetrating: minus_a_meets && b_meets,
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
    /// cos `lo` (kept so that the tests need no trigonometry).
    pub cos_lo: f64,
    /// cos `hi`.
    pub cos_hi: f64,
}

impl NormalBand {
    /// The whole sphere.
    pub const ALL: Self = Self {
        axis: DVec3::Z,
        lo: 0.0,
        hi: std::f64::consts::PI,
        cos_lo: 1.0,
        cos_hi: -1.0,
    };

    /// The band `lo <= angle(n, axis) <= hi` (rad, clamped to [0, π]) about the unit `axis`.
    #[must_use]
    pub fn new(axis: DVec3, lo: f64, hi: f64) -> Self {
        let (lo, hi) = (lo.max(0.0), hi.min(std::f64::consts::PI));
        Self {
            axis,
            lo,
            hi,
            cos_lo: lo.cos(),
            cos_hi: hi.cos(),
        }
    }

    /// The band about `axis` containing every item of `items`, each given by a cap and a band
    /// that both contain its normals (either may be the whole sphere): the angles from `axis`
    /// within the cap, [φ - θ, φ + θ] with φ the angle between the axes, intersected with those
    /// within the band, [lo - δ, hi + δ] with δ the angle between the band's axis (turned to
    /// `axis`'s side, a band about -b being one about b with angles π - hi..π - lo) and `axis`.
    /// [`NormalBand::ALL`] for a zero axis or an item known by neither.
    #[must_use]
    pub fn around_items(
        axis: DVec3,
        items: impl Iterator<Item = (NormalCone, NormalBand)>,
    ) -> Self {
        let Some(axis) = axis.try_normalize() else {
            return Self::ALL;
        };
        let pi = std::f64::consts::PI;
        let (mut lo, mut hi) = (pi, 0.0_f64);
        for (cap, band) in items {
            let (mut item_lo, mut item_hi) = (0.0, pi);
            if !cap.is_all() {
                let phi = axis.dot(cap.axis).clamp(-1.0, 1.0).acos();
                let theta = cap.half_angle();
                (item_lo, item_hi) = (phi - theta, phi + theta);
            }
            if !band.is_all() {
                let cos = axis.dot(band.axis).clamp(-1.0, 1.0);
                let (b_lo, b_hi) = if cos >= 0.0 {
                    (band.lo, band.hi)
                } else {
                    (pi - band.hi, pi - band.lo)
                };
                let delta = cos.abs().min(1.0).acos();
                item_lo = f64::max(item_lo, b_lo - delta);
                item_hi = f64::min(item_hi, b_hi + delta);
            }
            if cap.is_all() && band.is_all() {
                return Self::ALL;
            }
            lo = lo.min(item_lo);
            hi = hi.max(item_hi);
        }
        Self::new(axis, lo, hi)
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
    /// the cap, [φ - θ, φ + θ] with φ the angle between the axes, meet [lo, hi]. Compared
    /// through cosines (cos is decreasing on [0, π]): φ - θ <= hi holds when φ <= θ or
    /// cos(φ - θ) >= cos hi, and φ + θ >= lo when φ + θ >= π (sin(φ + θ) < 0) or
    /// cos(φ + θ) <= cos lo.
    #[must_use]
    pub fn meets(&self, cap: &NormalCone) -> bool {
        if self.is_all() || cap.is_all() {
            return true;
        }
        let c = self.axis.dot(cap.axis).clamp(-1.0, 1.0);
        let s = (1.0 - c * c).sqrt();
        // Rounding of unit vectors and products (about 1e-16), with a wide margin: the test
        // may only err towards meeting.
        let slack = COSINE_SLACK;
        let below_hi = c >= cap.cos || c * cap.cos + s * cap.sin >= self.cos_hi - slack;
        let above_lo =
            s * cap.cos + c * cap.sin < 0.0 || c * cap.cos - s * cap.sin <= self.cos_lo + slack;
        below_hi && above_lo
    }

    /// [`NormalBand::meets`] for the band and for its negation (`(self.meets(cap),
    /// self.negated().meets(cap))`), from one dot product: negating the axis negates c exactly
    /// and leaves s, so the negated band's sums are the same products with c's negated.
    #[must_use]
    pub fn meets_signed(&self, cap: &NormalCone) -> (bool, bool) {
        if self.is_all() || cap.is_all() {
            return (true, true);
        }
        let c = self.axis.dot(cap.axis).clamp(-1.0, 1.0);
        let s = (1.0 - c * c).sqrt();
        let (hi, lo) = (self.cos_hi - COSINE_SLACK, self.cos_lo + COSINE_SLACK);
        let (cc, ss, sc, cs) = (c * cap.cos, s * cap.sin, s * cap.cos, c * cap.sin);
        let plus = (c >= cap.cos || cc + ss >= hi) && (sc + cs < 0.0 || cc - ss <= lo);
        let minus = (-c >= cap.cos || ss - cc >= hi) && (sc - cs < 0.0 || -cc - ss <= lo);
        (plus, minus)
    }
}

/// Where the directions shared by two bands lie ([`NormalBand::shared`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SharedDirections {
    /// The bands share no direction.
    None,
    /// Every shared direction lies in one of these two caps.
    Within([NormalCone; 2]),
    /// No useful bound: the shared directions may lie anywhere.
    Anywhere,
}

/// Largest cap half-angle (rad) worth reporting as [`SharedDirections::Within`]: wider, the two
/// caps say little beyond the bands themselves.
const SHARED_CAP_LIMIT: f64 = 1.2;

impl NormalBand {
    /// Where the directions lying in both bands are (Hanniel & Elber's single-root tests bound
    /// normals the same way: two thin bands about distinct axes meet in two small regions).
    ///
    /// With a1, a2 the axes (angle φ, c = cos φ, s = sin φ) and the orthonormal basis
    /// e1 = a1, e2 = (a2 - c a1)/s, u = a1 × a2 / s, a direction n = x e1 + y e2 + z u lies in
    /// both bands when x = n · a1 ∈ [cos hi1, cos lo1] and n · a2 = c x + s y ∈ [cos hi2,
    /// cos lo2]: (x, y) lies in a parallelogram P, inside the disc of centre p0 (P's centre)
    /// and radius ρ (its farthest corner), and z = ±√(1 - x² - y²). On that disc (when
    /// |p0| + ρ < 1) the lift p ↦ (p, ±√(1 - |p|²)) is Lipschitz with constant
    /// L = 1/√(1 - (|p0| + ρ)²) (the norm of its derivative), so n lies within the chord L ρ of
    /// n± = (p0, ±√(1 - |p0|²)): in the caps about n± of chord L ρ (half-angle
    /// 2 asin(L ρ / 2)).
    ///
    /// Axes closer to parallel than 1e-9 rad compare their angle ranges only; either band being
    /// the whole sphere, or caps wider than 1.2 rad, give [`SharedDirections::Anywhere`].
    #[must_use]
    pub fn shared(&self, other: &Self) -> SharedDirections {
        if self.is_all() || other.is_all() {
            return SharedDirections::Anywhere;
        }
        let (a1, a2) = (self.axis, other.axis);
        let c = a1.dot(a2).clamp(-1.0, 1.0);
        let cross = a1.cross(a2);
        let s = cross.length();
        // Rounding of the cosines below (about 1e-16 each) with a wide margin.
        let slack = 1e-12;
        let (x_lo, x_hi) = (self.cos_hi - slack, self.cos_lo + slack);
        let (q_lo, q_hi) = (other.cos_hi - slack, other.cos_lo + slack);
        if s <= 1e-9 || !s.is_finite() {
            // (Anti)parallel axes: n · a2 = ±n · a1 up to s; the ranges of n · a1 must meet.
            let (b_lo, b_hi) = if c >= 0.0 {
                (q_lo, q_hi)
            } else {
                (-q_hi, -q_lo)
            };
            let meet = x_lo.max(b_lo) <= x_hi.min(b_hi) + 2.0 * s;
            return if meet {
                SharedDirections::Anywhere
            } else {
                SharedDirections::None
            };
        }
        let u = cross / s;
        let e2 = (a2 - a1 * c) / s;
        let y_of = |x: f64, q: f64| (q - c * x) / s;
        let x0 = 0.5 * (x_lo + x_hi);
        let y0 = y_of(x0, 0.5 * (q_lo + q_hi));
        let rho = [(x_lo, q_lo), (x_lo, q_hi), (x_hi, q_lo), (x_hi, q_hi)]
            .into_iter()
            .map(|(x, q)| {
                let (dx, dy) = (x - x0, y_of(x, q) - y0);
                dx * dx + dy * dy
            })
            .fold(0.0, f64::max)
            .sqrt();
        let m = (x0 * x0 + y0 * y0).sqrt();
        let reach = m + rho;
        if reach >= 1.0 || reach.is_nan() {
            return SharedDirections::Anywhere;
        }
        // The cap of chord k about n±: cos = 1 - k²/2, sin = k √(1 - k²/4).
        let chord = rho / (1.0 - reach * reach).sqrt();
        let cos = 1.0 - 0.5 * chord * chord;
        if cos < SHARED_CAP_LIMIT.cos() || cos.is_nan() {
            return SharedDirections::Anywhere;
        }
        let sin = chord * (1.0 - 0.25 * chord * chord).max(0.0).sqrt();
        let z0 = (1.0 - m * m).max(0.0).sqrt();
        let p = a1 * x0 + e2 * y0;
        // p ⟂ u and |p|² + z0² = 1: both centres are unit vectors.
        SharedDirections::Within([
            NormalCone {
                axis: p + u * z0,
                cos,
                sin,
            },
            NormalCone {
                axis: p - u * z0,
                cos,
                sin,
            },
        ])
    }
}

impl CriticalKinds {
    /// [`CriticalKinds::of`] refined by the bands of the two patches' normals (`band_a`,
    /// `band_b`, same frame; a normal lies in both its cap and its band): each band must meet
    /// the other patch's reversed cap and the directions. Two whole-sphere bands add nothing:
    /// `self` as it is.
    #[must_use]
    #[inline]
    pub fn with_bands(
        self,
        (a, band_a): (&NormalCone, &NormalBand),
        (b, band_b): (&NormalCone, &NormalBand),
        directions: &NormalCone,
    ) -> Self {
        if !self.any() || (band_a.is_all() && band_b.is_all()) {
            return self;
        }
        self.refined_by_bands((a, band_a), (b, band_b), directions)
    }

    /// [`CriticalKinds::with_bands`] past its early answers, in a function of its own so that
    /// the early answers stay inline where a traversal asks for them at every node.
    fn refined_by_bands(
        self,
        (a, band_a): (&NormalCone, &NormalBand),
        (b, band_b): (&NormalCone, &NormalBand),
        directions: &NormalCone,
    ) -> Self {
        let minus_b = b.negated();
        let minus_band_b = band_b.negated();
        let shared = band_a.meets(&minus_b) && minus_band_b.meets(a);
        let (band_a_meets, minus_band_a_meets) = band_a.meets_signed(directions);
        let (minus_band_b_meets, band_b_meets) = minus_band_b.meets_signed(directions);
        let mut kinds = Self {
            separated: self.separated && shared && band_a_meets && minus_band_b_meets,
            penetrating: self.penetrating && shared && minus_band_a_meets && band_b_meets,
        };
        if !kinds.any() {
            return kinds;
        }
        // A separated minimum's direction d lies in band A and in -band B (n_B = -d); a
        // penetration witness's in -band A and band B, the opposite set. Where the two bands
        // meet only in two small caps, d must also lie in one of them: a cap C for a separated
        // minimum (with N_A and -N_B), -C for a witness (with -N_A and N_B; -C meets -N_A
        // exactly when C meets N_A).
        match band_a.shared(&minus_band_b) {
            SharedDirections::None => {
                kinds.separated = false;
                kinds.penetrating = false;
            }
            SharedDirections::Within(caps) => {
                let (mut separated, mut penetrating) = (false, false);
                for cap in &caps {
                    if cap.meets(a) && cap.meets(&minus_b) {
                        let (towards, away) = cap.meets_signed(directions);
                        separated |= towards;
                        penetrating |= away;
                    }
                }
                kinds.separated &= separated;
                kinds.penetrating &= penetrating;
            }
            SharedDirections::Anywhere => {}
        }
        kinds
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

    /// The signed tests agree bit for bit with testing the cap or band and its negation one
    /// by one, over caps and bands about axes in general position, opposite and equal, of
    /// every width (the traversal relies on that: no pair's verdict may change).
    #[test]
    fn signed_tests_agree_with_the_negated_ones() {
        let axes = [
            DVec3::Z,
            -DVec3::Z,
            DVec3::X,
            DVec3::new(1.0, 1.0, 0.3).normalize(),
            DVec3::new(-0.2, 1.0, 0.7).normalize(),
            DVec3::new(1e-9, 0.0, 1.0).normalize(),
        ];
        let angles = [
            0.0,
            1e-7,
            0.3,
            1.2,
            std::f64::consts::FRAC_PI_2,
            2.0,
            3.0,
            std::f64::consts::PI,
        ];
        let ranges = [
            (0.0, 0.3),
            (1.2, 1.9),
            (1.5, 1.5002),
            (2.5, 3.0),
            (0.0, 3.2),
        ];
        for &a1 in &axes {
            for &a2 in &axes {
                for &t1 in &angles {
                    let c1 = NormalCone::new(a1, t1);
                    for &t2 in &angles {
                        let c2 = NormalCone::new(a2, t2);
                        assert_eq!(
                            c1.meets_signed(&c2),
                            (c1.meets(&c2), c1.negated().meets(&c2)),
                            "{c1:?} {c2:?}"
                        );
                    }
                    for &(lo, hi) in &ranges {
                        let b = NormalBand::new(a2, lo, hi);
                        assert_eq!(
                            b.meets_signed(&c1),
                            (b.meets(&c1), b.negated().meets(&c1)),
                            "{b:?} {c1:?}"
                        );
                    }
                }
            }
        }
    }

    fn band(axis: DVec3, lo: f64, hi: f64) -> NormalBand {
        NormalBand::new(axis.normalize(), lo, hi)
    }

    /// Whether `n` lies in the band, by its definition (angles through acos).
    fn in_band(b: &NormalBand, n: DVec3) -> bool {
        let a = b.axis.angle_between(n);
        a >= b.lo - 1e-12 && a <= b.hi + 1e-12
    }

    /// Bands against caps by their definition (the angles from the band's axis within the cap,
    /// [φ - θ, φ + θ], meet [lo, hi]; computed here with acos, where the test uses cosines): they
    /// meet when those intervals overlap and do not when they miss by more than 1e-5 rad.
    #[test]
    fn bands_meet_caps_as_their_angles_say() {
        let ranges = [
            (0.0, 0.3),
            (1.2, 1.9),
            (1.5, 1.5002),
            (2.5, std::f64::consts::PI),
            (0.4, 0.41),
        ];
        let angles = [0.0, 0.2, 1.0, 2.0];
        let axes = [
            DVec3::Z,
            DVec3::X,
            -DVec3::Z,
            DVec3::new(1.0, 1.0, 0.3).normalize(),
            DVec3::new(-0.2, 1.0, 0.7).normalize(),
        ];
        for &(lo, hi) in &ranges {
            for &t in &angles {
                for &a1 in &axes {
                    for &a2 in &axes {
                        let (b, c) = (band(a1, lo, hi), NormalCone::new(a2, t));
                        let phi = a1.angle_between(a2);
                        let gap = (phi - t - hi).max(lo - (phi + t));
                        if gap <= 0.0 {
                            assert!(b.meets(&c), "{lo} {hi} {t} {a1} {a2}");
                        } else if gap > 1e-5 {
                            assert!(!b.meets(&c), "{lo} {hi} {t} {a1} {a2}");
                        }
                    }
                }
            }
        }
    }

    /// Every direction in both of two bands, found by brute force (a dense sampling of the
    /// first band's rings, kept where it lies in the second by the definition), lies in one of
    /// the caps [`NormalBand::shared`] returns; `None` only when no sample is shared. Thin rings
    /// about axes tilted by φ share two small caps about ±(a1 × a2) of half-angle about
    /// (w1 + w2) / sin φ, w the rings' half-widths.
    #[test]
    fn shared_directions_hold_every_direction_in_both_bands() {
        let half = std::f64::consts::FRAC_PI_2;
        let tilted = |phi: f64| DVec3::new(phi.sin(), 0.0, phi.cos());
        let cases = [
            (
                band(DVec3::Z, half - 1e-3, half + 1e-3),
                band(tilted(0.02), half - 2e-3, half + 2e-3),
            ),
            (
                band(DVec3::Z, half - 1e-6, half + 1e-6),
                band(tilted(0.3), half - 1e-6, half + 1e-6),
            ),
            (band(DVec3::Z, 0.7, 0.75), band(tilted(1.0), 1.2, 1.3)),
            (band(DVec3::Z, 0.7, 0.75), band(tilted(0.1), 1.2, 1.3)),
            (band(DVec3::Z, 0.7, 0.75), band(-DVec3::Z, 0.1, 0.2)),
            (band(DVec3::Z, 0.7, 0.75), band(-DVec3::Z, 2.3, 2.5)),
            (
                band(DVec3::new(0.3, -0.5, 0.8), 1.0, 1.6),
                band(DVec3::new(-0.6, 0.1, 0.2), 0.2, 0.9),
            ),
            (
                band(DVec3::X, half - 0.05, half + 0.05),
                band(DVec3::Y, half - 0.05, half + 0.05),
            ),
        ];
        for (k, (b1, b2)) in cases.iter().enumerate() {
            let shared = b1.shared(b2);
            let (e1, e2) = b1.axis.any_orthonormal_pair();
            let mut found = 0;
            for i in 0..=8 {
                let t = b1.lo + (b1.hi - b1.lo) * f64::from(i) / 8.0;
                for j in 0..20_000 {
                    let p = std::f64::consts::TAU * f64::from(j) / 20_000.0;
                    let n = (e1 * p.cos() + e2 * p.sin()) * t.sin() + b1.axis * t.cos();
                    if !in_band(b2, n) {
                        continue;
                    }
                    found += 1;
                    match shared {
                        SharedDirections::None => panic!("case {k}: {n} is shared"),
                        SharedDirections::Within(caps) => assert!(
                            caps.iter()
                                .any(|c| c.axis.angle_between(n) <= c.half_angle() + 1e-9),
                            "case {k}: {n} outside {caps:?}"
                        ),
                        SharedDirections::Anywhere => {}
                    }
                }
            }
            if k < 2 {
                assert!(found > 0, "case {k}");
                let (w, phi) = if k == 0 {
                    (3e-3, 0.02_f64)
                } else {
                    (2e-6, 0.3_f64)
                };
                let SharedDirections::Within(caps) = shared else {
                    panic!("case {k}: {shared:?}");
                };
                let pole = b1.axis.cross(b2.axis).normalize();
                for c in caps {
                    assert!(c.half_angle() <= 1.5 * w / phi.sin(), "case {k}: {c:?}");
                    assert!(c.axis.cross(pole).length() <= 1e-9, "case {k}: {c:?}");
                }
            }
            if k == 4 {
                assert_eq!(shared, SharedDirections::None);
            }
        }
    }
}
