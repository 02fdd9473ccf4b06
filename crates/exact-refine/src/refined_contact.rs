//! What a refinement returns: the [`RefinedContact`] with its [`RefineDiagnostics`] and
//! [`RefineStatus`].

use geom_param::{DVec3, FeatureLocation};

/// The exact closest pair of two features, in A's frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RefinedContact {
    /// On A, in A's frame (mm).
    pub point_a: DVec3,
    /// On B, in A's frame (mm).
    pub point_b: DVec3,
    /// Final feature and parameters on A (periodic parameters wrapped into the domain).
    pub location_a: FeatureLocation,
    /// Final feature and parameters on B.
    pub location_b: FeatureLocation,
    /// Signed distance (mm): (point_b − point_a) · normal; negative when penetrating.
    pub distance: f64,
    /// Unit normal from A to B in A's frame: A's outward normal at `point_a` when that is on a
    /// face, otherwise B's outward normal at `point_b` negated when that is on a face, otherwise
    /// for two edges their common normal (tangent x tangent) turned away from A, otherwise the
    /// direction of point_b − point_a (reversed when penetrating).
    pub normal: DVec3,
    /// How far to trust the above.
    pub diagnostics: RefineDiagnostics,
}

/// How the refinement went, and how far to trust its answer.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RefineDiagnostics {
    /// Newton steps of the pair solve (the two seed projections are not counted).
    pub iterations: u32,
    /// Largest tangential component of the connecting vector at the end (mm): for each
    /// parameter x_i, |(P_a − P_b) · ∂P/∂x_i| / |∂P/∂x_i|. Zero at an exact critical point.
    pub gradient_norm: f64,
    /// Condition number of the Hessian of ½|P_a − P_b|² with each variable scaled by its speed
    /// |∂P/∂x_i| (so all variables are arc lengths in mm): largest over smallest eigenvalue
    /// magnitude. `f64::INFINITY` when the smallest is exactly zero, 1 when there are no
    /// variables (vertex against vertex). Near touch it grows like 1 / (gap x curvature).
    pub condition: f64,
    /// Stationary to tolerance (or the Newton step fell below rounding): `status` is
    /// [`RefineStatus::Converged`] or [`RefineStatus::ContinuousContact`].
    pub converged: bool,
    /// The converged point satisfies the second-order condition for a local minimum of the
    /// *signed* distance: separated, no eigenvalue of the Hessian below −(rounding floor), i.e.
    /// a local minimum of |P_a − P_b|, not a saddle or maximum; penetrating, exactly the
    /// min(n_a, n_b) relative-sliding directions are negative (the deepest pair) and the others
    /// are not, except between two edges, which share no sliding direction: there none is
    /// negative (two crossing rims, d inside both edges' normal cones). Where |distance| is within `error_estimate` and the pair penetrates, the sign of
    /// the distance and those eigenvalues (|d| x relative curvature) are rounding: the pair is
    /// then judged as at distance 0, a minimum when its outward normals are opposed (a touch;
    /// a face's normal, negated, within 4.5e-5 rad plus the residual's angle of the other
    /// face's normal or of the arc of an edge's two faces' normals). False when not converged.
    pub is_local_minimum: bool,
    /// Estimated absolute error of `distance` (mm): rounding of the coordinates
    /// (16 ε x coordinate scale) plus the change of the gap over `point_error_estimate`.
    pub error_estimate: f64,
    /// Estimated error of the points along the feature (mm): the tangential residual plus its
    /// rounding floor over the smallest Hessian eigenvalue. Near touch that eigenvalue is about
    /// gap x relative curvature, so at a 1e-9 mm gap the points are only good to roughly
    /// ε x scale / (1e-9 x curvature) while the distance stays good to rounding.
    /// `f64::INFINITY` for a continuous contact (any point of the degenerate set is an answer).
    pub point_error_estimate: f64,
    /// The gap function's smallest curvature (1/mm): to second order the distance between the
    /// features rises as `distance + ½ gap_curvature s²` when the pair slides by s (mm) along
    /// its flattest relative direction, and at least that fast along any other (the smallest
    /// eigenvalue of the Hessian of ½|P_a − P_b|² in arc-length variables at separation
    /// ℓ = max(|gap|, √ε / curvature scale), divided by ℓ; for two faces, the smallest
    /// eigenvalue of the sum of their curvature tensors in the common tangent plane, e.g.
    /// 1/R₁ + 1/R₂ for two spheres). 0 for a continuous contact (zero to rounding, see
    /// [`RefineStatus::ContinuousContact`]); `f64::INFINITY` where no parameter can slide (a
    /// vertex against a vertex) or the input was invalid. So √(2τ / gap_curvature) is the
    /// half-length (mm) of the region over which the gap stays within τ of `distance`.
    pub gap_curvature: f64,
    /// How it ended.
    pub status: RefineStatus,
}

/// How a refinement ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum RefineStatus {
    /// An isolated critical point found to tolerance.
    Converged,
    /// Converged on a degenerate set of minima (conformal spheres, parallel cylinders,
    /// flat-on-flat, paper section IV): the Hessian has an eigenvalue within rounding of zero.
    /// The distance is exact; the points are one representative pair of the set.
    ContinuousContact,
    /// `NewtonOptions::max_iterations` steps without meeting the tolerance.
    IterationLimit,
    /// The trust region shrank below rounding before the tolerance was met (the Hessian model
    /// stopped predicting the objective).
    Stalled,
    /// More than `NewtonOptions::max_feature_switches` switches between faces, edges and
    /// vertices (a minimum on a crease the iteration kept crossing).
    FeatureSwitchLimit,
    /// The input cannot be refined: a feature id that does not belong to its solid, a
    /// non-finite pose, or a seed with neither finite parameters nor a finite point. Points are
    /// zero and the distance is `f64::INFINITY`.
    InvalidInput,
}
