//! Dense sampling of a posed solid's faces: a (u, v) grid per face whose world spacing is about
//! `spacing` (sized from |S_u| and |S_v|), restricted to the parts near a region of interest.
//!
//! Two passes. The coarse pass cuts every face into patches about `COARSE` spacings across
//! and bounds the solid (a surface point lies within one patch diameter of a patch corner).
//! The fine pass samples only the patches within reach of the other solid's box. Rows include
//! the face's boundary (edges and poles are sampled); a pole row holds one sample per patch.
//!
//! A trimmed face is gridded over its trim's (u, v) box and keeps only the samples inside the
//! trim; its boundary is sampled on the edges themselves: every edge that runs along no side
//! of a rectangle (both its uses on trims) gets samples at about `spacing` along its curve,
//! its end vertices included, each a [`Sample`] of its first use's face at the use's (u, v).

use crate::samples::kdtree::KdTree;
use crate::solids::posed::PosedSolid;
use crate::solids::trim_grid::{Region, classify};
use geom_param::{EdgeId, FaceId, ParamRange, Solid};
use glam::{DVec2, DVec3};

/// Coarse patches are about this many fine spacings across.
const COARSE: f64 = 8.0;
/// Probe grid per face for the largest parametric speeds (|S_u|, |S_v|).
const PROBE: usize = 16;
/// Most coarse patches per face direction.
const MAX_PATCHES: usize = 256;
/// Safety factor on the probed speeds (a Bezier's speed peaks between probes).
const SPEED_SAFETY: f64 = 1.25;

/// One surface sample in the world frame.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Sample {
    pub face: FaceId,
    pub uv: [f64; 2],
    pub point: DVec3,
    /// Unit outward normal, zero where the face has no tangent plane (an apex).
    pub normal: DVec3,
}

/// An axis-aligned box in the world frame.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Aabb {
    pub lo: DVec3,
    pub hi: DVec3,
}

impl Aabb {
    pub fn empty() -> Self {
        Self {
            lo: DVec3::splat(f64::INFINITY),
            hi: DVec3::splat(f64::NEG_INFINITY),
        }
    }

    pub fn add(&mut self, p: DVec3) {
        self.lo = self.lo.min(p);
        self.hi = self.hi.max(p);
    }

    pub fn expanded(&self, by: f64) -> Self {
        Self {
            lo: self.lo - DVec3::splat(by),
            hi: self.hi + DVec3::splat(by),
        }
    }

    pub fn distance(&self, p: DVec3) -> f64 {
        (self.lo - p).max(p - self.hi).max(DVec3::ZERO).length()
    }

    pub fn extent(&self) -> f64 {
        (self.hi - self.lo).max_element()
    }
}

/// A face cut into coarse patches.
#[derive(Debug)]
pub(crate) struct CoarseFace {
    face: FaceId,
    us: Vec<f64>,
    vs: Vec<f64>,
    /// World points at (us[i], vs[j]), row-major by v.
    corners: Vec<DVec3>,
    /// Largest patch diameter on this face (mm).
    diameter: f64,
}

/// The coarse pass over a whole solid.
#[derive(Debug)]
pub(crate) struct CoarseSolid {
    pub faces: Vec<CoarseFace>,
    /// Bounds every surface point.
    pub bounds: Aabb,
    /// Every patch corner, and a tree over them.
    corners: KdTree,
    /// Every surface point lies within this distance of a corner (mm).
    slack: f64,
}

impl CoarseSolid {
    /// A lower bound on the distance from `p` to the solid's surface, within `slack` of it.
    fn distance_bound(&self, p: DVec3, limit: f64) -> Option<f64> {
        self.corners
            .nearest_within(p, limit + self.slack)
            .map(|(_, d)| (d - self.slack).max(0.0))
    }
}

/// The (u, v) box a face is sampled over: its trim's bounds (not periodic: the trim's
/// polylines may run past a period, evaluation wraps), or its domain.
fn param_box(solid: &Solid, face: FaceId) -> [ParamRange; 2] {
    match &solid.face(face).trim {
        Some(trim) => {
            let (lo, hi) = trim.bounds();
            let range = |i: usize| ParamRange {
                min: lo[i],
                max: hi[i],
                periodic: false,
            };
            [range(0), range(1)]
        }
        None => solid.face(face).surface.domain(),
    }
}

/// Largest |S_u| and |S_v| over a probe grid of the face (object frame; the pose does not
/// change lengths).
fn speeds(solid: &Solid, face: FaceId) -> (f64, f64) {
    let [du, dv] = param_box(solid, face);
    let mut out = (0.0_f64, 0.0_f64);
    for i in 0..=PROBE {
        for j in 0..=PROBE {
            let u = du.min + du.span() * i as f64 / PROBE as f64;
            let v = dv.min + dv.span() * j as f64 / PROBE as f64;
            let s = solid.eval_face(face, u, v);
            out = (out.0.max(s.du.length()), out.1.max(s.dv.length()));
        }
    }
    out
}

/// Largest side of the object-frame bounding box of a solid's probe points (mm).
pub(crate) fn object_extent(solid: &Solid) -> f64 {
    let mut bounds = Aabb::empty();
    for f in 0..solid.faces.len() {
        let face = FaceId(f as u32);
        let [du, dv] = param_box(solid, face);
        for i in 0..=PROBE {
            for j in 0..=PROBE {
                let u = du.min + du.span() * i as f64 / PROBE as f64;
                let v = dv.min + dv.span() * j as f64 / PROBE as f64;
                bounds.add(solid.eval_face(face, u, v).point);
            }
        }
    }
    bounds.extent()
}

fn grid(min: f64, span: f64, n: usize) -> Vec<f64> {
    (0..=n).map(|k| min + span * k as f64 / n as f64).collect()
}

/// Pieces needed to cover `span` at `speed` mm per unit with pieces of length `step`.
fn pieces(span: f64, speed: f64, step: f64, cap: usize) -> usize {
    let n = (span * speed * SPEED_SAFETY / step).ceil();
    if n.is_finite() {
        (n as usize).clamp(1, cap)
    } else {
        cap
    }
}

/// The coarse pass. `None` when some face evaluates to non-finite points.
pub(crate) fn coarse(posed: &PosedSolid, spacing: f64) -> Option<CoarseSolid> {
    let solid = posed.solid;
    let mut faces = Vec::with_capacity(solid.faces.len());
    let mut bounds = Aabb::empty();
    for f in 0..solid.faces.len() {
        let face = FaceId(f as u32);
        let [du, dv] = param_box(solid, face);
        let (su, sv) = speeds(solid, face);
        let step = COARSE * spacing;
        let us = grid(du.min, du.span(), pieces(du.span(), su, step, MAX_PATCHES));
        let vs = grid(dv.min, dv.span(), pieces(dv.span(), sv, step, MAX_PATCHES));
        let mut corners = Vec::with_capacity(us.len() * vs.len());
        for &v in &vs {
            for &u in &us {
                corners.push(posed.eval(face, u, v).point);
            }
        }
        if corners.iter().any(|p| !p.is_finite()) {
            return None;
        }
        let nu = us.len();
        let mut diameter = 0.0_f64;
        for j in 0..vs.len() - 1 {
            for i in 0..nu - 1 {
                let c = [
                    corners[j * nu + i],
                    corners[j * nu + i + 1],
                    corners[(j + 1) * nu + i],
                    corners[(j + 1) * nu + i + 1],
                ];
                diameter = diameter
                    .max(c[0].distance(c[3]))
                    .max(c[1].distance(c[2]))
                    .max(c[0].distance(c[1]))
                    .max(c[0].distance(c[2]));
            }
        }
        for &p in &corners {
            bounds.add(p);
        }
        faces.push(CoarseFace {
            face,
            us,
            vs,
            corners,
            diameter,
        });
    }
    let slack = faces.iter().map(|f| f.diameter).fold(0.0, f64::max);
    let all: Vec<DVec3> = faces
        .iter()
        .flat_map(|f| f.corners.iter().copied())
        .collect();
    Some(CoarseSolid {
        faces,
        bounds: bounds.expanded(slack),
        corners: KdTree::new(&all),
        slack,
    })
}

/// Fine samples of the patches that may come within `keep_distance` of `other`'s surface, at about
/// `spacing`; the grid is shifted by `offset` (fractions of a fine step, in [0, 1)) so two runs
/// can sample different points. Err(estimated count) when the count would exceed `budget`.
pub(crate) fn fine(
    posed: &PosedSolid,
    coarse: &CoarseSolid,
    other: &CoarseSolid,
    keep_distance: f64,
    spacing: f64,
    offset: f64,
    budget: usize,
) -> Result<Vec<Sample>, usize> {
    // Plan first (patch list with sub-grid sizes), so the budget is checked before allocating.
    let mut plan = Vec::new();
    let mut needed = 0_usize;
    for cf in &coarse.faces {
        let nu = cf.us.len();
        let [du, dv] = param_box(posed.solid, cf.face);
        for j in 0..cf.vs.len() - 1 {
            for i in 0..nu - 1 {
                let c = [
                    cf.corners[j * nu + i],
                    cf.corners[j * nu + i + 1],
                    cf.corners[(j + 1) * nu + i],
                    cf.corners[(j + 1) * nu + i + 1],
                ];
                // A patch point is within one diameter of a corner.
                let limit = keep_distance + cf.diameter;
                let near = c.iter().any(|&p| {
                    other.bounds.distance(p) <= limit
                        && other.distance_bound(p, limit).is_some_and(|d| d <= limit)
                });
                if !near {
                    continue;
                }
                let (u0, u1, v0, v1) = (cf.us[i], cf.us[i + 1], cf.vs[j], cf.vs[j + 1]);
                let region = patch_in_trim(posed, cf.face, [u0, v0], [u1, v1]);
                if region == Region::Outside {
                    continue;
                }
                let mut sv = 0.0_f64;
                let mut su = 0.0_f64;
                for (u, v) in [
                    (u0, v0),
                    (u1, v0),
                    (u0, v1),
                    (u1, v1),
                    (0.5 * (u0 + u1), 0.5 * (v0 + v1)),
                ] {
                    let s = posed.eval(cf.face, u, v);
                    sv = sv.max(s.dv.length());
                    su = su.max(s.du.length());
                }
                let mv = pieces(v1 - v0, sv, spacing, 1 << 16);
                let mu = pieces(u1 - u0, su, spacing, 1 << 16);
                needed = needed.saturating_add((mv + 1).saturating_mul(mu + 1));
                let last_u = !du.periodic && i + 2 == nu;
                let last_v = !dv.periodic && j + 2 == cf.vs.len();
                plan.push((cf.face, u0, u1, v0, v1, mv, last_u, last_v, region));
            }
        }
    }
    let edges = edge_plan(posed, other, keep_distance, spacing);
    needed = edges
        .iter()
        .fold(needed, |n, &(_, _, pieces)| n.saturating_add(pieces + 1));
    if needed > budget {
        return Err(needed);
    }
    let mut out = Vec::with_capacity(needed);
    for (face, u0, u1, v0, v1, mv, last_u, last_v, region) in plan {
        let rows = if last_v { mv + 1 } else { mv };
        for t in 0..rows {
            // The offset shifts interior rows only: the boundary rows stay on the edges.
            let frac = if t == 0 || t == mv {
                t as f64
            } else {
                t as f64 + offset - 0.5 * offset
            };
            let v = v0 + (v1 - v0) * frac / mv as f64;
            let row = posed.eval(face, 0.5 * (u0 + u1), v);
            let su = row
                .du
                .length()
                .max(posed.eval(face, u0, v).du.length())
                .max(posed.eval(face, u1, v).du.length());
            let mu = pieces(u1 - u0, su, spacing, 1 << 16);
            let cols = if last_u { mu + 1 } else { mu };
            for s in 0..cols {
                let frac = if last_u && s == mu {
                    s as f64
                } else {
                    s as f64 + offset
                };
                let u = u0 + (u1 - u0) * (frac / mu as f64).min(1.0);
                let [u, v] = posed.normalize(face, [u, v]);
                if region == Region::Boundary && !posed.inside(face, [u, v]) {
                    continue;
                }
                let p = posed.eval(face, u, v);
                out.push(Sample {
                    face,
                    uv: [u, v],
                    point: p.point,
                    normal: posed.normal(face, u, v).unwrap_or(DVec3::ZERO),
                });
            }
        }
    }
    for (edge, range, pieces) in edges {
        edge_samples(
            posed,
            other,
            keep_distance,
            edge,
            range,
            pieces,
            offset,
            &mut out,
        );
    }
    Ok(out)
}

/// Where the patch [lo, hi] of `face` (in the trim's unwrapped (u, v)) lies with respect to
/// the face's trim ([`crate::solids::trim_grid::classify`]); every point of a face without trim is
/// inside.
fn patch_in_trim(posed: &PosedSolid, face: FaceId, lo: [f64; 2], hi: [f64; 2]) -> Region {
    match posed.trim(face) {
        Some(trim) => classify(
            trim,
            posed.trim_extent(face),
            DVec2::from(lo),
            DVec2::from(hi),
        ),
        None => Region::Inside,
    }
}

/// The edges sampled on their curves (no use along a rectangle side, whose boundary rows
/// sample it already) that come near `other` (a coarse probe of the curve within
/// `keep_distance` + the probe step of its surface): (edge, parameter range, pieces of about
/// `spacing`).
fn edge_plan(
    posed: &PosedSolid,
    other: &CoarseSolid,
    keep_distance: f64,
    spacing: f64,
) -> Vec<(EdgeId, ParamRange, usize)> {
    let solid = posed.solid;
    let mut out = Vec::new();
    for (e, edge) in solid.edges.iter().enumerate() {
        if edge.uses.iter().any(|u| u.on.side().is_some()) {
            continue;
        }
        let id = EdgeId(e as u32);
        let range = edge.curve.domain();
        let probes: Vec<_> = (0..=PROBE)
            .map(|k| posed.eval_edge(id, range.min + range.span() * k as f64 / PROBE as f64))
            .collect();
        let speed = probes.iter().map(|c| c.d1.length()).fold(0.0, f64::max);
        let step = probes
            .windows(2)
            .map(|w| w[0].point.distance(w[1].point))
            .fold(0.0, f64::max);
        let limit = keep_distance + step;
        let near = probes.iter().any(|c| {
            other.bounds.distance(c.point) <= limit
                && other
                    .distance_bound(c.point, limit)
                    .is_some_and(|d| d <= limit)
        });
        if near {
            out.push((id, range, pieces(range.span(), speed, spacing, 1 << 20)));
        }
    }
    out
}

/// Samples of `edge` at `pieces` + 1 parameters over `range` (the ends unshifted, the others
/// shifted by `offset` / 2 of a piece, as the faces' interior rows are; a periodic curve's
/// last one is its first), those within `keep_distance` of `other`'s surface bound, appended
/// to `out` as samples of the edge's first use.
#[allow(clippy::too_many_arguments)]
fn edge_samples(
    posed: &PosedSolid,
    other: &CoarseSolid,
    keep_distance: f64,
    edge: EdgeId,
    range: ParamRange,
    pieces: usize,
    offset: f64,
    out: &mut Vec<Sample>,
) {
    let use_ = posed.solid.edge(edge).uses[0];
    let last = if range.periodic { pieces - 1 } else { pieces };
    for k in 0..=last {
        let frac = if !range.periodic && (k == 0 || k == pieces) {
            k as f64
        } else {
            k as f64 + 0.5 * offset
        };
        let t = range.min + range.span() * frac / pieces as f64;
        let uv = posed.use_params(&use_, t);
        let point = posed.eval(use_.face, uv[0], uv[1]).point;
        let near = other.bounds.distance(point) <= keep_distance
            && other
                .distance_bound(point, keep_distance)
                .is_some_and(|d| d <= keep_distance);
        if near {
            out.push(Sample {
                face: use_.face,
                uv,
                point,
                normal: posed.normal(use_.face, uv[0], uv[1]).unwrap_or(DVec3::ZERO),
            });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::closed_form::brep::{block, holed_plate, tetrahedron};
    use geom_param::DPose3;

    /// Fine samples of `solid` at `spacing`, against itself so that every patch is in reach.
    fn samples(solid: &Solid, spacing: f64) -> Vec<Sample> {
        let posed = PosedSolid::new(solid, &DPose3::IDENTITY);
        let c = coarse(&posed, spacing).expect("finite");
        fine(&posed, &c, &c, 100.0, spacing, 0.0, 1 << 22).expect("within budget")
    }

    /// A block's samples lie on its six face rectangles (closed form: one coordinate at ±half,
    /// the others within ±half), every corner is a sample and every edge is sampled at about
    /// the spacing.
    #[test]
    fn block_samples_stay_in_the_faces_and_cover_edges_and_corners() {
        let half = DVec3::new(10.0, 7.0, 5.0);
        let spacing = 0.5;
        let all = samples(&block(2.0 * half).expect("builds"), spacing);
        let eps = 1e-9;
        for s in &all {
            let q = s.point.abs();
            assert!(q.cmple(half + eps).all(), "outside the block: {s:?}");
            let on = (half - q).cmple(DVec3::splat(eps));
            assert!(on.any(), "not on a face: {s:?}");
        }
        for k in 0..8 {
            let corner = half
                * DVec3::new(
                    if k & 1 == 0 { -1.0 } else { 1.0 },
                    if k & 2 == 0 { -1.0 } else { 1.0 },
                    if k & 4 == 0 { -1.0 } else { 1.0 },
                );
            assert!(
                all.iter().any(|s| s.point.distance(corner) <= eps),
                "corner {corner} not sampled"
            );
        }
        // Points on an edge: two coordinates at ±half. Each edge of length L holds at least
        // L / spacing of them, and no gap along it is wider than the spacing (x 1.25 safety).
        for axis in 0..3 {
            let length = 2.0 * half[axis];
            for signs in 0..4 {
                let mut along: Vec<f64> = all
                    .iter()
                    .filter(|s| {
                        (0..3).filter(|&i| i != axis).enumerate().all(|(n, i)| {
                            let sign = if signs >> n & 1 == 0 { -1.0 } else { 1.0 };
                            (s.point[i] - sign * half[i]).abs() <= eps
                        })
                    })
                    .map(|s| s.point[axis])
                    .collect();
                along.sort_by(f64::total_cmp);
                along.dedup_by(|x, y| (*x - *y).abs() <= eps);
                assert!(
                    along.len() as f64 >= length / spacing,
                    "{axis} {signs}: {along:?}"
                );
                let widest = along.windows(2).map(|w| w[1] - w[0]).fold(0.0, f64::max);
                assert!(
                    widest <= 1.25 * spacing + eps,
                    "{axis} {signs}: gap {widest}"
                );
            }
        }
    }

    /// A tetrahedron's triangles are trimmed from their bounding rectangles: the samples lie
    /// in the triangles (closed form: barycentric coordinates >= 0 on one face's plane), the
    /// slanted sides, which no grid row follows, are sampled on the edges at about the
    /// spacing, and the corners are samples.
    #[test]
    fn tetrahedron_samples_stay_in_the_triangles_and_cover_the_edges() {
        let p = [
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(10.0, 1.0, 0.0),
            DVec3::new(2.0, 9.0, 1.0),
            DVec3::new(3.0, 3.0, 8.0),
        ];
        let spacing = 0.4;
        let all = samples(&tetrahedron(p).expect("builds"), spacing);
        let eps = 1e-9;
        let barycentric = |q: DVec3, [a, b, c]: [DVec3; 3]| {
            let n = (b - a).cross(c - a);
            let area = n.length_squared();
            let height = (q - a).dot(n) / n.length();
            let w = [
                (c - b).cross(q - b).dot(n) / area,
                (a - c).cross(q - c).dot(n) / area,
                (b - a).cross(q - a).dot(n) / area,
            ];
            (height, w)
        };
        let triangles = [
            [p[1], p[2], p[3]],
            [p[0], p[2], p[3]],
            [p[0], p[1], p[3]],
            [p[0], p[1], p[2]],
        ];
        for s in &all {
            let on_one = triangles.iter().any(|&t| {
                let (height, w) = barycentric(s.point, t);
                height.abs() <= eps && w.iter().all(|&x| x >= -eps)
            });
            assert!(on_one, "not in a triangle: {s:?}");
        }
        for &corner in &p {
            assert!(all.iter().any(|s| s.point.distance(corner) <= eps));
        }
        for i in 0..4 {
            for j in i + 1..4 {
                let (a, b) = (p[i], p[j]);
                let length = a.distance(b);
                let dir = (b - a) / length;
                let mut along: Vec<f64> = all
                    .iter()
                    .filter(|s| (s.point - a).reject_from_normalized(dir).length() <= eps)
                    .map(|s| (s.point - a).dot(dir))
                    .collect();
                along.sort_by(f64::total_cmp);
                let widest = along.windows(2).map(|w| w[1] - w[0]).fold(0.0, f64::max);
                assert!(along.len() >= 2, "edge {i}-{j} not sampled");
                assert!(along[0] <= eps && along[along.len() - 1] >= length - eps);
                assert!(widest <= 1.25 * spacing + eps, "edge {i}-{j}: gap {widest}");
            }
        }
    }

    /// No sample of the plate's top or bottom face falls in the hole (closed form: radius >=
    /// the hole's), and the hole's rim circles are sampled.
    #[test]
    fn plate_samples_skip_the_hole() {
        let (radius, thickness) = (6.0, 8.0);
        let all = samples(&holed_plate(40.0, thickness, radius).expect("builds"), 0.5);
        let eps = 1e-9;
        let mut rim = 0;
        for s in &all {
            let rho = s.point.truncate().length();
            assert!(rho >= radius - eps, "in the hole: {s:?}");
            if (s.point.z.abs() - 0.5 * thickness).abs() <= eps && rho <= radius + eps {
                rim += 1;
            }
        }
        // Two circles of circumference 37.7 mm at a 0.5 mm spacing.
        assert!(rim >= 2 * 75, "{rim} rim samples");
    }
}
