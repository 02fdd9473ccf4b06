//! A NURBS surface (STEP's B_SPLINE_SURFACE_WITH_KNOTS, rational or not).

use crate::curves::curve::ParamRange;
use crate::geometry_error::GeometryError;
use crate::nurbs::CLOSURE_RELATIVE_TOL;
use crate::nurbs::basis::BSplineBasis;
use crate::nurbs::control_point::net_extent;
use crate::nurbs::rational_bspline_curve::check_points_and_weights;
use crate::nurbs::surface_derivatives::rational_surface_derivatives;
use crate::surfaces::surface::{Surface, SurfacePoint};
use glam::DVec3;

/// Size of a first derivative, relative to the net's size over the parameter span, below which
/// it counts as zero (a collapsed row or column of control points: a pole).
const DEGENERATE_RELATIVE_EPS: f64 = 1e-10;
/// Relative cross product |S_u × S_v| / (|S_u| |S_v|) below which S_u and S_v count as parallel.
const PARALLEL_RELATIVE_EPS: f64 = 1e-12;
/// Largest distance between the unit limit normals at three points of a collapsed row (about
/// the angle between them, rad) for the row to have one tangent plane.
const POLE_NORMAL_AGREEMENT: f64 = 1e-9;

/// S(u, v) = Σ_ij N_{i,p}(u) N_{j,q}(v) w_ij P_ij / Σ_ij N_{i,p}(u) N_{j,q}(v) w_ij over
/// [u_p, u_{n+1}] × [v_q, v_{m+1}], mm: degrees p, q <= [`crate::MAX_DEGREE`], knots with
/// multiplicities, weights > 0, control net P_ij with i along u (the rows) and j along v.
///
/// Periodic in u means the surface closes across u: the homogeneous boundary curves at u_p
/// and u_{n+1} coincide (for clamped knots: the first and last rows of control points and
/// weights), and the u domain wraps; likewise in v. Parameters outside the domain are wrapped
/// (periodic) or clamped. The outward normal is S_u × S_v normalised; where a row or column
/// of the net collapses to a point (a pole, as on a NURBS sphere) it is the limit
/// ±S_uv × S_v (or ±S_u × S_uv) from inside the domain, when that limit is the same all along
/// the collapsed row (a tangent plane exists), and `None` otherwise (a cone tip).
#[derive(Clone, Debug, PartialEq)]
pub struct NurbsSurface {
    basis: [BSplineBasis; 2],
    /// Row-major: P_ij at i * count_v + j.
    control_points: Vec<DVec3>,
    weights: Vec<f64>,
    periodic: [bool; 2],
    /// Extent of the net plus the distance of its first point from the origin (mm): the scale
    /// of rounding in evaluated derivatives.
    size: f64,
}

impl NurbsSurface {
    /// The surface of degrees `degree` = [p, q] over `knots` = [U, V] with control net
    /// `control_points[i][j]` = P_ij (row i along u) and `weights[i][j]` = w_ij of the same
    /// shape, closed and wrapping in the directions flagged `periodic`.
    ///
    /// # Errors
    /// [`GeometryError::TooFewControlPoints`] for an empty net,
    /// [`GeometryError::CountMismatch`] when the rows differ in length or the weights do not
    /// match the points, every error of [`BSplineBasis::new`] in each direction,
    /// [`GeometryError::NonFinite`], [`GeometryError::NonPositiveWeight`] (index row-major),
    /// and [`GeometryError::NotClosed`] for a periodic direction whose ends differ.
    pub fn new(
        degree: [usize; 2],
        knots: [Vec<f64>; 2],
        control_points: Vec<Vec<DVec3>>,
        weights: Vec<Vec<f64>>,
        periodic: [bool; 2],
    ) -> Result<Self, GeometryError> {
        let count_u = control_points.len();
        let count_v = control_points.first().map_or(0, Vec::len);
        if count_u == 0 || count_v == 0 {
            return Err(GeometryError::TooFewControlPoints {
                count: 0,
                degree: if count_u == 0 { degree[0] } else { degree[1] },
            });
        }
        if let Some(row) = control_points.iter().find(|row| row.len() != count_v) {
            return Err(GeometryError::CountMismatch {
                what: "control net row",
                expected: count_v,
                found: row.len(),
            });
        }
        if weights.len() != count_u {
            return Err(GeometryError::CountMismatch {
                what: "weight rows",
                expected: count_u,
                found: weights.len(),
            });
        }
        if let Some(row) = weights.iter().find(|row| row.len() != count_v) {
            return Err(GeometryError::CountMismatch {
                what: "weight row",
                expected: count_v,
                found: row.len(),
            });
        }
        let [knots_u, knots_v] = knots;
        let basis = [
            BSplineBasis::new(degree[0], knots_u, count_u)?,
            BSplineBasis::new(degree[1], knots_v, count_v)?,
        ];
        let control_points: Vec<DVec3> = control_points.into_iter().flatten().collect();
        let weights: Vec<f64> = weights.into_iter().flatten().collect();
        check_points_and_weights(&control_points, &weights)?;
        let size = net_extent(&control_points) + control_points[0].length();
        let surface = Self {
            basis,
            control_points,
            weights,
            periodic,
            size,
        };
        let extent = net_extent(&surface.control_points);
        for (direction, &closed) in periodic.iter().enumerate() {
            if closed {
                let gap = surface.boundary_gap(direction, extent);
                if gap > CLOSURE_RELATIVE_TOL * extent {
                    return Err(GeometryError::NotClosed { gap });
                }
            }
        }
        Ok(surface)
    }

    /// The basis along u (`direction` 0) or v (1).
    ///
    /// # Panics
    /// If `direction` > 1.
    #[must_use]
    pub fn basis(&self, direction: usize) -> &BSplineBasis {
        &self.basis[direction]
    }

    /// Number of control points [along u, along v].
    #[must_use]
    pub fn count(&self) -> [usize; 2] {
        [self.basis[0].count(), self.basis[1].count()]
    }

    /// P_ij (mm).
    ///
    /// # Panics
    /// If i or j is not below [`NurbsSurface::count`].
    #[must_use]
    pub fn control_point(&self, i: usize, j: usize) -> DVec3 {
        self.control_points[i * self.basis[1].count() + j]
    }

    /// w_ij.
    ///
    /// # Panics
    /// If i or j is not below [`NurbsSurface::count`].
    #[must_use]
    pub fn weight(&self, i: usize, j: usize) -> f64 {
        self.weights[i * self.basis[1].count() + j]
    }

    /// Whether the surface closes and wraps [in u, in v].
    #[must_use]
    pub fn is_periodic(&self) -> [bool; 2] {
        self.periodic
    }

    /// Largest distance between the two boundary curves across `direction`, compared control
    /// point by control point on their homogeneous nets Q_k = Σ_i N_i(t) w P (projected points,
    /// plus the relative weight difference times `extent`).
    fn boundary_gap(&self, direction: usize, extent: f64) -> f64 {
        let basis = &self.basis[direction];
        let (start, end) = basis.domain();
        let [count_u, count_v] = self.count();
        let other = if direction == 0 { count_v } else { count_u };
        let index = |along: usize, across: usize| {
            if direction == 0 {
                along * count_v + across
            } else {
                across * count_v + along
            }
        };
        let boundary = |t: f64, across: usize| {
            let span = basis.find_span(t);
            let n = basis.derivatives(span, t);
            let (mut point, mut weight) = (DVec3::ZERO, 0.0);
            for (r, &value) in n[0].iter().enumerate().take(basis.degree() + 1) {
                let i = index(span - basis.degree() + r, across);
                point += self.control_points[i] * (value * self.weights[i]);
                weight += value * self.weights[i];
            }
            (point / weight, weight)
        };
        (0..other)
            .map(|across| {
                let (p0, w0) = boundary(start, across);
                let (p1, w1) = boundary(end, across);
                (p1 - p0).length() + extent * (w1 - w0).abs() / w0.max(w1)
            })
            .fold(0.0, f64::max)
    }

    /// The limit normal at a point where S_u (`collapsed` = 0) or S_v (1) vanishes, seen from
    /// the side of the domain the point is on, or `None` if the point is not on that side's
    /// boundary.
    fn pole_normal(&self, collapsed: usize, u: f64, v: f64) -> Option<DVec3> {
        let domain = self.domain();
        // S_u(u, v0 + h) ≈ h S_uv, so S_u × S_v ≈ h S_uv × S_v, h > 0 at the start of v;
        // S_v(u0 + h, v) ≈ h S_uv, so S_u × S_v ≈ h S_u × S_uv, h > 0 at the start of u.
        let across = &domain[1 - collapsed];
        let t = if collapsed == 0 { v } else { u };
        let slack = DEGENERATE_RELATIVE_EPS * across.span();
        let side = if t - across.min <= slack {
            1.0
        } else if across.max - t <= slack {
            -1.0
        } else {
            return None;
        };
        let limit = |s: f64| {
            let (uu, vv) = if collapsed == 0 { (s, v) } else { (u, s) };
            let d = rational_surface_derivatives(
                &self.basis,
                &self.control_points,
                &self.weights,
                uu,
                vv,
            );
            let n = if collapsed == 0 {
                d[1][1].cross(d[0][1])
            } else {
                d[1][0].cross(d[1][1])
            };
            (n * side).try_normalize()
        };
        let along = &domain[collapsed];
        let here = limit(if collapsed == 0 { u } else { v })?;
        for fraction in [1.0 / 3.0, 2.0 / 3.0] {
            let other = limit(along.min + fraction * along.span())?;
            if (other - here).length() > POLE_NORMAL_AGREEMENT {
                return None;
            }
        }
        Some(here)
    }
}

impl Surface for NurbsSurface {
    fn eval(&self, u: f64, v: f64) -> SurfacePoint {
        let [range_u, range_v] = self.domain();
        let d = rational_surface_derivatives(
            &self.basis,
            &self.control_points,
            &self.weights,
            range_u.normalize(u),
            range_v.normalize(v),
        );
        SurfacePoint {
            point: d[0][0],
            du: d[1][0],
            dv: d[0][1],
            duu: d[2][0],
            duv: d[1][1],
            dvv: d[0][2],
        }
    }

    fn domain(&self) -> [ParamRange; 2] {
        [0, 1].map(|direction| {
            let (min, max) = self.basis[direction].domain();
            ParamRange {
                min,
                max,
                periodic: self.periodic[direction],
            }
        })
    }

    /// S_u × S_v normalised; at a collapsed row or column its limit from inside the domain
    /// (see the type's docs); `None` where S_u and S_v are parallel or both vanish.
    fn normal(&self, u: f64, v: f64) -> Option<DVec3> {
        let [range_u, range_v] = self.domain();
        let (u, v) = (range_u.normalize(u), range_v.normalize(v));
        let d = self.eval(u, v);
        let (length_u, length_v) = (d.du.length(), d.dv.length());
        let small_u = length_u <= DEGENERATE_RELATIVE_EPS * self.size / range_u.span();
        let small_v = length_v <= DEGENERATE_RELATIVE_EPS * self.size / range_v.span();
        match (small_u, small_v) {
            (false, false) => {
                let n = d.du.cross(d.dv);
                (n.length() > PARALLEL_RELATIVE_EPS * length_u * length_v).then(|| n.normalize())
            }
            (true, false) => self.pole_normal(0, u, v),
            (false, true) => self.pole_normal(1, u, v),
            (true, true) => None,
        }
    }
}
