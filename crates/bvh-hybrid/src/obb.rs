//! Oriented bounding boxes (OBBs), the internal-node volumes of the Stage 1 tree: fitting
//! (covariance eigenvectors plus a few candidate orientations), containment, rigid motion
//! and the exact 15-axis separating-axis overlap test. All lengths are in mm.

use glam::{DMat3, DQuat, DVec3};

/// Relative rounding guard (dimensionless). Fitted extents are widened by this fraction of
/// the coordinate magnitudes involved, and overlap tests only report "separated" when the
/// gap exceeds a slack of this relative size, so that floating-point rounding can never
/// make a covered point fall outside or a true overlap be reported separated.
pub(crate) const ROUND_PAD: f64 = 1e-12;

/// Added to every |cos| between box axes in [`Obb::overlaps`], the usual guard that keeps
/// the cross-product axes of nearly parallel edges from producing a false separation.
const PARALLEL_EPS: f64 = 1e-12;

/// Rotation angles (radians) tried about each covariance axis in [`Obb::fit`]. A box is
/// symmetric under quarter turns, so angles in (0, pi/2) cover every distinct candidate.
const CANDIDATE_ANGLES: [f64; 5] = [
    std::f64::consts::PI / 12.0,
    std::f64::consts::PI / 6.0,
    std::f64::consts::PI / 4.0,
    std::f64::consts::PI / 3.0,
    5.0 * std::f64::consts::PI / 12.0,
];

/// An oriented bounding box. Every field is expressed in one caller frame (the "body" frame
/// of the solid whose surface it bounds, or any frame both operands of a test share).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Obb {
    /// Centre of the box, in the body frame (mm).
    pub center: DVec3,
    /// Box axes as the columns of a rotation: orthonormal and right-handed, expressed in the
    /// body frame. A point `p` has box-local coordinates `axes^T (p - center)`.
    pub axes: DMat3,
    /// Half side lengths along the three axes (mm), each `>= 0`.
    pub half_extents: DVec3,
}

impl Obb {
    /// Fits a box around `points` (body frame, mm), widened by `inflate` (mm) on every side.
    ///
    /// The orientation is the best (smallest volume, then smallest surface area, of the
    /// inflated box) among: the eigenvectors of the points' covariance; the body axes; and
    /// the covariance frame turned about each of its three axes by 15, 30, 45, 60 and 75
    /// degrees. The extents are the exact min/max of the projected points plus `inflate`,
    /// plus a rounding guard of about 1e-12 of the coordinate magnitudes. Every input point,
    /// and every point within distance `inflate` of one, satisfies [`Obb::contains_point`].
    ///
    /// Returns `None` for no points, a non-finite point, or an `inflate` that is negative
    /// or not finite. Degenerate inputs (one point, collinear, coplanar) give a valid box
    /// with some half extents equal to `inflate` (plus the guard).
    pub fn fit(points: &[DVec3], inflate: f64) -> Option<Obb> {
        if points.is_empty()
            || !inflate.is_finite()
            || inflate < 0.0
            || !points.iter().all(|p| p.is_finite())
        {
            return None;
        }
        let mean = points.iter().copied().sum::<DVec3>() / points.len() as f64;
        let pca = covariance_frame(points, mean);

        let mut candidates = vec![pca, DMat3::IDENTITY];
        for k in 0..3 {
            for angle in CANDIDATE_ANGLES {
                let turned = DMat3::from_axis_angle(pca.col(k), angle) * pca;
                if let Some(frame) = orthonormalize(turned) {
                    candidates.push(frame);
                }
            }
        }

        let mut best: Option<(DMat3, DVec3, DVec3, f64, f64)> = None;
        for axes in candidates {
            let (lo, hi) = projected_range(points, mean, axes);
            let size = hi - lo + DVec3::splat(2.0 * inflate);
            let volume = size.x * size.y * size.z;
            let area = size.x * size.y + size.y * size.z + size.z * size.x;
            let better = match &best {
                None => true,
                Some((_, _, _, best_volume, best_area)) => {
                    volume < *best_volume * (1.0 - 1e-12)
                        || (volume <= *best_volume * (1.0 + 1e-12) && area < *best_area)
                }
            };
            if better {
                best = Some((axes, lo, hi, volume, area));
            }
        }
        let (axes, lo, hi, _, _) = best?;

        // Re-measure about the final centre with the exact expression `contains_point`
        // uses, so that the input points are contained bit-for-bit.
        let center = mean + axes * ((lo + hi) * 0.5);
        let half = points.iter().fold(DVec3::ZERO, |acc, &p| {
            acc.max(to_local(center, axes, p).abs())
        });
        let pad = ROUND_PAD * (center.abs().max_element() + half.max_element() + inflate);
        Some(Obb {
            center,
            axes,
            half_extents: half + DVec3::splat(inflate + pad),
        })
    }

    /// Fits a box (body frame, mm) around the corners of `children`, for an internal node
    /// covering them. Returns `None` when there are no children or a child is not finite.
    pub fn enclosing<'a>(children: impl IntoIterator<Item = &'a Obb>) -> Option<Obb> {
        let corners: Vec<DVec3> = children.into_iter().flat_map(Obb::corners).collect();
        Obb::fit(&corners, 0.0)
    }

    /// Whether `p` (body frame, mm) lies in the closed box. Exact: no tolerance is added.
    pub fn contains_point(&self, p: DVec3) -> bool {
        to_local(self.center, self.axes, p)
            .abs()
            .cmple(self.half_extents)
            .all()
    }

    /// The eight corners (body frame, mm). Corner `i` takes `+half_extents` along axis `k`
    /// when bit `k` of `i` is set, `-half_extents` otherwise.
    pub fn corners(&self) -> [DVec3; 8] {
        std::array::from_fn(|i| self.center + self.axes * (self.half_extents * corner_signs(i)))
    }

    /// The box moved by the rigid motion `p -> rot * p + trans` (`rot` a unit quaternion,
    /// `trans` in mm): the result is expressed in the frame the motion maps into.
    pub fn transformed(&self, rot: DQuat, trans: DVec3) -> Obb {
        Obb {
            center: rot * self.center + trans,
            axes: DMat3::from_quat(rot) * self.axes,
            half_extents: self.half_extents,
        }
    }

    /// Whether the two closed boxes intersect; both must be expressed in the same frame.
    ///
    /// The exact separating-axis test over the 15 axes (3 + 3 face normals, 9 edge cross
    /// products). Conservative: |cos| between axes is raised by 1e-12 (guarding the cross
    /// products of nearly parallel axes) and a separation must exceed a rounding slack of
    /// about 1e-12 of the magnitudes involved, so touching or overlapping boxes are never
    /// reported separated. Cost: about 200 flops, with early exits.
    pub fn overlaps(&self, other: &Obb) -> bool {
        self.separation(other).is_none()
    }

    /// [`Obb::overlaps`] with the separation it found: `None` where the boxes intersect,
    /// otherwise the gap (mm) by which the first separating axis's projections are apart
    /// beyond the rounding slack. A lower bound on the boxes' distance: on a cross-product
    /// axis the projections are scaled by its length (at most 1).
    pub fn separation(&self, other: &Obb) -> Option<f64> {
        let a = self.half_extents.to_array();
        let b = other.half_extents.to_array();
        let d = other.center - self.center;
        let mut r = [[0.0; 3]; 3];
        let mut abs_r = [[0.0; 3]; 3];
        for i in 0..3 {
            for j in 0..3 {
                r[i][j] = self.axes.col(i).dot(other.axes.col(j));
                abs_r[i][j] = r[i][j].abs() + PARALLEL_EPS;
            }
        }
        let t = [
            d.dot(self.axes.col(0)),
            d.dot(self.axes.col(1)),
            d.dot(self.axes.col(2)),
        ];
        let slack = ROUND_PAD
            * (d.length()
                + self.center.length()
                + other.center.length()
                + a.iter().sum::<f64>()
                + b.iter().sum::<f64>());

        let apart = |projected: f64, reach: f64| {
            let gap = projected.abs() - (reach + slack);
            (gap > 0.0).then_some(gap)
        };
        // Face normals of self.
        for i in 0..3 {
            let rb: f64 = (0..3).map(|j| b[j] * abs_r[i][j]).sum();
            if let Some(gap) = apart(t[i], a[i] + rb) {
                return Some(gap);
            }
        }
        // Face normals of other.
        for j in 0..3 {
            let ra: f64 = (0..3).map(|i| a[i] * abs_r[i][j]).sum();
            let tj: f64 = (0..3).map(|i| t[i] * r[i][j]).sum();
            if let Some(gap) = apart(tj, ra + b[j]) {
                return Some(gap);
            }
        }
        // Cross products self.axis(i) x other.axis(j).
        for i in 0..3 {
            let (i1, i2) = ((i + 1) % 3, (i + 2) % 3);
            for j in 0..3 {
                let (j1, j2) = ((j + 1) % 3, (j + 2) % 3);
                let ra = a[i1] * abs_r[i2][j] + a[i2] * abs_r[i1][j];
                let rb = b[j1] * abs_r[i][j2] + b[j2] * abs_r[i][j1];
                let tl = t[i2] * r[i1][j] - t[i1] * r[i2][j];
                if let Some(gap) = apart(tl, ra + rb) {
                    return Some(gap);
                }
            }
        }
        None
    }
}

/// Box-local coordinates `axes^T (p - center)`; the one expression used both when fitting
/// and when testing containment, so that fitted points are contained bit-for-bit.
pub(crate) fn to_local(center: DVec3, axes: DMat3, p: DVec3) -> DVec3 {
    axes.mul_transpose_vec3(p - center)
}

/// Signs (+1 or -1 per axis) of corner `i`: bit `k` set means `+` along axis `k`.
pub(crate) fn corner_signs(i: usize) -> DVec3 {
    let sign = |bit: usize| if i & (1 << bit) != 0 { 1.0 } else { -1.0 };
    DVec3::new(sign(0), sign(1), sign(2))
}

/// Component-wise min and max of `axes^T (p - origin)` over the points.
fn projected_range(points: &[DVec3], origin: DVec3, axes: DMat3) -> (DVec3, DVec3) {
    points.iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), &p| {
            let q = to_local(origin, axes, p);
            (lo.min(q), hi.max(q))
        },
    )
}

/// Eigenvectors of the points' covariance about `mean`, as the columns of a right-handed
/// rotation, sorted by decreasing eigenvalue. Falls back to the identity if the
/// eigenvectors cannot be orthonormalized (they always can: Jacobi rotations keep them
/// orthonormal even for repeated eigenvalues such as points on a circle or a line).
fn covariance_frame(points: &[DVec3], mean: DVec3) -> DMat3 {
    let mut c = [[0.0; 3]; 3];
    for &p in points {
        let d = (p - mean).to_array();
        for i in 0..3 {
            for j in 0..3 {
                c[i][j] += d[i] * d[j];
            }
        }
    }
    let (values, vectors) = symmetric_eigen(c);
    let mut order = [0, 1, 2];
    order.sort_by(|&i, &j| values[j].total_cmp(&values[i]));
    let sorted = DMat3::from_cols(
        vectors.col(order[0]),
        vectors.col(order[1]),
        vectors.col(order[2]),
    );
    orthonormalize(sorted).unwrap_or(DMat3::IDENTITY)
}

/// Eigen-decomposition of a symmetric 3x3 matrix by cyclic Jacobi rotations: the
/// eigenvalues and the matrix whose columns are the matching eigenvectors.
fn symmetric_eigen(mut a: [[f64; 3]; 3]) -> ([f64; 3], DMat3) {
    let mut v = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    for _sweep in 0..64 {
        let off = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
        let diag = a[0][0] * a[0][0] + a[1][1] * a[1][1] + a[2][2] * a[2][2];
        if off <= 1e-30 * diag || off == 0.0 {
            break;
        }
        for (p, q) in [(0, 1), (0, 2), (1, 2)] {
            let apq = a[p][q];
            if apq == 0.0 {
                continue;
            }
            let theta = (a[q][q] - a[p][p]) / (2.0 * apq);
            let t = if theta.abs() > 1e150 {
                0.5 / theta
            } else {
                theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt())
            };
            let c = 1.0 / (t * t + 1.0).sqrt();
            let s = t * c;
            a[p][p] -= t * apq;
            a[q][q] += t * apq;
            a[p][q] = 0.0;
            a[q][p] = 0.0;
            let r = 3 - p - q;
            let (arp, arq) = (a[r][p], a[r][q]);
            a[r][p] = c * arp - s * arq;
            a[p][r] = a[r][p];
            a[r][q] = s * arp + c * arq;
            a[q][r] = a[r][q];
            for row in &mut v {
                let (vp, vq) = (row[p], row[q]);
                row[p] = c * vp - s * vq;
                row[q] = s * vp + c * vq;
            }
        }
    }
    let vectors = DMat3::from_cols(
        DVec3::new(v[0][0], v[1][0], v[2][0]),
        DVec3::new(v[0][1], v[1][1], v[2][1]),
        DVec3::new(v[0][2], v[1][2], v[2][2]),
    );
    ([a[0][0], a[1][1], a[2][2]], vectors)
}

/// Gram-Schmidt on the first two columns, third column = their cross product: an exactly
/// right-handed, orthonormal-to-rounding frame. `None` if the first two are (nearly)
/// parallel or zero.
fn orthonormalize(m: DMat3) -> Option<DMat3> {
    let x = m.col(0).try_normalize()?;
    let y = (m.col(1) - x * x.dot(m.col(1))).try_normalize()?;
    Some(DMat3::from_cols(x, y, x.cross(y)))
}
