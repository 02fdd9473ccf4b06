//! What the oracle returns.

use geom_param::{DVec3, FaceId, FeatureLocation};

/// One local minimum of distance (distance >= 0) or one penetration witness (distance < 0),
/// in the world frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OracleContact {
    /// Point on A's surface (world, mm).
    pub point_a: DVec3,
    /// Point on B's surface (world, mm): `point_a + distance * normal`.
    pub point_b: DVec3,
    /// Signed distance (mm): positive apart, negative for a penetration witness (the depth).
    pub distance: f64,
    /// A's unit outward normal at `point_a` (world); where `point_a` is on an edge or at a
    /// vertex of A (a cone of normals), the direction from `point_a` to `point_b` (sign
    /// included), which lies in that cone.
    pub normal: DVec3,
    /// A's face holding `point_a` (on an edge or at a vertex: a face it bounds).
    pub face_a: FaceId,
    /// (u, v) of `point_a` on `face_a`.
    pub params_a: [f64; 2],
    /// B's face holding `point_b` (on an edge or at a vertex: a face it bounds).
    pub face_b: FaceId,
    /// (u, v) of `point_b` on `face_b`.
    pub params_b: [f64; 2],
    /// The exact feature of A that `point_a` is on: a face (where the point is inside the
    /// face's region), an edge with its t, or a vertex.
    pub location_a: FeatureLocation,
    /// The exact feature of B that `point_b` is on.
    pub location_b: FeatureLocation,
    /// Stationarity residual (mm): the largest tangential component of `point_b - point_a`
    /// along the free parameter directions of either face.
    pub residual: f64,
    /// Newton iterations spent in the final polish.
    pub iterations: u32,
    /// The oracle's own bound on the error of `point_a` and `point_b` (mm), from the
    /// conditioning of its polished pair: the residual over the smallest eigenvalue of the
    /// Hessian of ½|S_a − S_b|² in arc-length variables, or near touch, where that eigenvalue
    /// vanishes, (2 residual / κ²)^⅓ with κ the gap's smallest curvature (1/mm), whichever is
    /// smaller, plus the coordinates' rounding, and at least the distance from each point to
    /// the edge or vertex it is reported on (snapped within the oracle's snap distance). Infinite for a continuous contact (the gap flat
    /// along some direction: any point of the set is an answer).
    pub point_error_estimate: f64,
}

/// A point the oracle's polish accepted that is no separate minimum: a path joins it to a
/// lower point of the same region (its report entry) along which the distance never rises
/// above it by more than the oracle's resolution (see [`OracleReport::members`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RegionMember {
    /// Index in [`OracleReport::contacts`] of the region's lowest point.
    pub region: usize,
    /// The point, as it was polished.
    pub contact: OracleContact,
}

/// How the pair stands against a contact band [delta1, delta2].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OracleState {
    /// Nothing at distance <= delta2.
    Separated,
    /// The smallest distance lies in [delta1, delta2].
    Contact,
    /// The smallest distance is below delta1.
    Penetration,
}

/// Agreement between the runs at two sample spacings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CrossCheck {
    /// Contacts of either run with no partner in the other (points within 1e-6 x size).
    pub unmatched: usize,
    /// Largest |distance difference| over matched pairs (mm).
    pub max_distance_difference: f64,
    /// Largest point difference (either side) over matched pairs (mm).
    pub max_point_difference: f64,
}

/// Everything the oracle found between two posed solids.
#[derive(Clone, Debug, PartialEq)]
pub struct OracleReport {
    /// All local minima and penetration witnesses with distance <= reach, sorted by distance:
    /// one per region of near-minimal distance (its lowest point), where a region holds the
    /// points joined by a path along which the distance rises by no more than the oracle's
    /// resolution (5 x its stationarity tolerance) above the higher end.
    pub contacts: Vec<OracleContact>,
    /// The other points of those regions that the polish accepted (stationary to its
    /// tolerance but no separate minimum: points on the slope next to a touch or a shallow
    /// crossing, or anywhere on a continuous contact), each naming its region.
    pub members: Vec<RegionMember>,
    /// Smallest signed distance among `contacts`; +inf when there is none.
    pub min_distance: f64,
    /// Samples used on both surfaces in the primary run.
    pub samples: usize,
    /// How well the primary run agrees with the run at the finer spacing.
    pub cross_check: CrossCheck,
}

impl OracleReport {
    /// Penetration when `min_distance < delta1`, contact when it lies in [delta1, delta2],
    /// separated otherwise.
    #[must_use]
    pub fn state(&self, delta1: f64, delta2: f64) -> OracleState {
        if self.min_distance < delta1 {
            OracleState::Penetration
        } else if self.min_distance <= delta2 {
            OracleState::Contact
        } else {
            OracleState::Separated
        }
    }

    /// Contact `index` and the members of its region.
    pub fn region(&self, index: usize) -> impl Iterator<Item = &OracleContact> {
        self.contacts.get(index).into_iter().chain(
            self.members
                .iter()
                .filter(move |m| m.region == index)
                .map(|m| &m.contact),
        )
    }

    /// The contacts with delta1 <= distance <= delta2.
    pub fn in_band(&self, delta1: f64, delta2: f64) -> impl Iterator<Item = &OracleContact> {
        self.contacts
            .iter()
            .filter(move |c| c.distance >= delta1 && c.distance <= delta2)
    }
}
