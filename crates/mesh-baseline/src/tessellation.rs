//! Uniform tessellation of a whole [`Solid`] into one welded, outward triangle mesh of about a
//! requested triangle count: what a user without the exact pipeline would feed a mesh collider.
//!
//! Every face S(u, v) must have u periodic and each v side on an edge or a vertex (all solids of
//! revolution do). A face is cut into **rows** of constant v, evenly spaced in arc length along
//! v; row v carries n(v) = max(3, ⌈L_u(v) / h⌉) vertices at u = u_min + span · j / n, where
//! L_u(v) is the length of the u-curve at v and h the target spacing (mm). A row on an edge
//! takes its count from the edge's length and its points from the edge curve, so both faces of
//! the edge share the same vertices (welded by (edge, j), with no position tolerance); a row on
//! a vertex is that one vertex (a pole or apex, joined by a fan). Consecutive rows are zipped
//! in order of u into triangles counter-clockwise seen from outside (u then v is the positive
//! orientation, as S_u × S_v points outwards). The spacing h is found by iterating
//! h ← h √(count / target) from h₀ = √(2 A / target), A the total area.
//!
//! The chordal error is measured, not assumed: at 25 barycentric points of every triangle
//! (a grid of step 1/6, corners excluded) the distance to the face is bounded by Gauss-Newton
//! projection started at the interpolated (u, v); every iterate is a point of the face, so the
//! reported error never underestimates the distance at a sample.

use crate::error::BaselineError;
use geom_param::{Boundary, EdgeId, Face, ParamRange, ParamSide, Solid, Surface, VertexId};
use glam::DVec3;
use std::collections::HashMap;

/// Samples per polyline when measuring lengths along u, along v and along edges.
const LENGTH_SAMPLES: usize = 128;
/// Stop the spacing iteration when the count is within this fraction of the target.
const COUNT_TOLERANCE: f64 = 0.02;
const MAX_ITERATIONS: usize = 60;
/// Gauss-Newton steps of the closest-point projection used to measure the chordal error.
const PROJECTION_STEPS: usize = 8;
/// Barycentric grid resolution of the error samples.
const SAMPLE_GRID: usize = 6;

/// The output of [`tessellate`]: welded vertices (object frame, mm) and outward triangles.
pub(crate) struct Tessellation {
    pub positions: Vec<DVec3>,
    pub triangles: Vec<[u32; 3]>,
    /// Largest measured distance (mm) from a triangle sample to the exact surface.
    pub chordal_error: f64,
}

#[derive(Clone, Copy, Debug)]
enum End {
    Edge(EdgeId),
    Vertex(VertexId),
}

/// One face, measured once: its domains, what closes its v ends, and length tables.
struct FacePlan {
    index: u32,
    u: ParamRange,
    v: ParamRange,
    ends: [End; 2],
    /// (v, arc length from v_min along the v-curve at the middle u), increasing.
    v_length: Vec<(f64, f64)>,
    /// Length of the u-curve at each `v_length` sample.
    u_length: Vec<f64>,
}

#[derive(Clone, Copy, Debug)]
enum RowKind {
    Interior,
    Edge(EdgeId),
    Vertex(VertexId),
}

#[derive(Clone, Copy, Debug)]
struct Row {
    v: f64,
    count: usize,
    kind: RowKind,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
enum Key {
    Vertex(u32),
    Edge(u32, usize),
    Face(u32, usize, usize),
}

/// A triangle corner: welded vertex id and its face parameters (u unwrapped).
#[derive(Clone, Copy, Debug)]
struct Corner {
    id: u32,
    u: f64,
    v: f64,
}

fn polyline_length(points: impl Iterator<Item = DVec3>) -> f64 {
    let mut length = 0.0;
    let mut last: Option<DVec3> = None;
    for p in points {
        if let Some(q) = last {
            length += p.distance(q);
        }
        last = Some(p);
    }
    length
}

fn at(range: &ParamRange, k: usize, n: usize) -> f64 {
    range.min + range.span() * k as f64 / n as f64
}

fn end_of(solid: &Solid, index: u32, face: &Face, side: ParamSide) -> Result<End, BaselineError> {
    match face.boundary(side) {
        Boundary::Vertex(id) if (id.0 as usize) < solid.vertices.len() => Ok(End::Vertex(id)),
        Boundary::Edge(id) if (id.0 as usize) < solid.edges.len() => {
            let [u, _] = face.surface.domain();
            let t = solid.edge(id).curve.domain();
            if t.periodic == u.periodic && t.min == u.min && t.max == u.max {
                Ok(End::Edge(id))
            } else {
                Err(BaselineError::UnsupportedFace {
                    face: index,
                    reason: "an edge's parameter range differs from the face's u range",
                })
            }
        }
        Boundary::Periodic => Err(BaselineError::UnsupportedFace {
            face: index,
            reason: "v is periodic",
        }),
        _ => Err(BaselineError::UnsupportedFace {
            face: index,
            reason: "a v side refers to a feature the solid does not have",
        }),
    }
}

fn plan_face(solid: &Solid, index: u32, face: &Face) -> Result<FacePlan, BaselineError> {
    let unsupported = |reason| BaselineError::UnsupportedFace {
        face: index,
        reason,
    };
    let [u, v] = face.surface.domain();
    let periodic_u = u.periodic
        && face.boundary(ParamSide::UMin) == Boundary::Periodic
        && face.boundary(ParamSide::UMax) == Boundary::Periodic;
    if !periodic_u {
        return Err(unsupported("u is not periodic"));
    }
    if !(u.span() > 0.0 && v.span() > 0.0 && u.span().is_finite() && v.span().is_finite()) {
        return Err(unsupported("empty or infinite parameter range"));
    }
    let ends = [
        end_of(solid, index, face, ParamSide::VMin)?,
        end_of(solid, index, face, ParamSide::VMax)?,
    ];
    let surface: &dyn Surface = face.surface.as_ref();
    let u_mid = 0.5 * (u.min + u.max);
    let mut v_length = Vec::with_capacity(LENGTH_SAMPLES + 1);
    let mut u_length = Vec::with_capacity(LENGTH_SAMPLES + 1);
    let mut total = 0.0;
    let mut last = surface.eval(u_mid, v.min).point;
    for k in 0..=LENGTH_SAMPLES {
        let vk = at(&v, k, LENGTH_SAMPLES);
        let p = surface.eval(u_mid, vk).point;
        total += p.distance(last);
        last = p;
        v_length.push((vk, total));
        u_length.push(polyline_length((0..=LENGTH_SAMPLES).map(|j| {
            surface
                .eval(u.normalize(at(&u, j, LENGTH_SAMPLES)), vk)
                .point
        })));
    }
    if !(total > 0.0 && total.is_finite()) {
        return Err(BaselineError::EmptySolid);
    }
    Ok(FacePlan {
        index,
        u,
        v,
        ends,
        v_length,
        u_length,
    })
}

impl FacePlan {
    fn length(&self) -> f64 {
        self.v_length.last().map_or(0.0, |&(_, s)| s)
    }

    /// The v at arc length `s` along v, and the u-length there (linear in the tables).
    fn at_length(&self, s: f64) -> (f64, f64) {
        let k = self
            .v_length
            .partition_point(|&(_, sk)| sk < s)
            .clamp(1, self.v_length.len() - 1);
        let ((v0, s0), (v1, s1)) = (self.v_length[k - 1], self.v_length[k]);
        let t = if s1 > s0 {
            ((s - s0) / (s1 - s0)).clamp(0.0, 1.0)
        } else {
            0.0
        };
        (
            v0 + t * (v1 - v0),
            self.u_length[k - 1] + t * (self.u_length[k] - self.u_length[k - 1]),
        )
    }

    /// Area (mm²) by the trapezoid rule over the tables.
    fn area(&self) -> f64 {
        self.v_length
            .windows(2)
            .zip(self.u_length.windows(2))
            .map(|(s, l)| (s[1].1 - s[0].1) * 0.5 * (l[0] + l[1]))
            .sum()
    }

    fn rows(&self, spacing: f64, edge_counts: &[usize]) -> Vec<Row> {
        let both_poles = matches!(self.ends, [End::Vertex(_), End::Vertex(_)]);
        let strips = ((self.length() / spacing).round() as usize)
            .clamp(if both_poles { 2 } else { 1 }, MAX_ROWS);
        (0..=strips)
            .map(|k| {
                let end = match k {
                    0 => Some(self.ends[0]),
                    k if k == strips => Some(self.ends[1]),
                    _ => None,
                };
                match end {
                    Some(End::Vertex(id)) => Row {
                        v: if k == 0 { self.v.min } else { self.v.max },
                        count: 1,
                        kind: RowKind::Vertex(id),
                    },
                    Some(End::Edge(id)) => Row {
                        v: if k == 0 { self.v.min } else { self.v.max },
                        count: edge_counts[id.0 as usize],
                        kind: RowKind::Edge(id),
                    },
                    None => {
                        let (v, u_length) =
                            self.at_length(self.length() * k as f64 / strips as f64);
                        Row {
                            v,
                            count: ring_count(u_length, spacing),
                            kind: RowKind::Interior,
                        }
                    }
                }
            })
            .collect()
    }
}

/// Largest number of rows per face and vertices per row: keeps absurd spacings finite.
const MAX_ROWS: usize = 1 << 14;

fn ring_count(length: f64, spacing: f64) -> usize {
    ((length / spacing).ceil() as usize).clamp(3, MAX_ROWS)
}

fn strip_triangles(a: usize, b: usize) -> usize {
    match (a, b) {
        (1, n) | (n, 1) => n,
        (a, b) => a + b,
    }
}

struct Plan {
    faces: Vec<FacePlan>,
    edge_lengths: Vec<f64>,
}

impl Plan {
    fn edge_counts(&self, spacing: f64) -> Vec<usize> {
        self.edge_lengths
            .iter()
            .map(|&l| ring_count(l, spacing))
            .collect()
    }

    fn count(&self, spacing: f64) -> usize {
        let edges = self.edge_counts(spacing);
        self.faces
            .iter()
            .map(|f| {
                f.rows(spacing, &edges)
                    .windows(2)
                    .map(|w| strip_triangles(w[0].count, w[1].count))
                    .sum::<usize>()
            })
            .sum()
    }
}

/// Measures every face and edge of `solid` once.
fn plan(solid: &Solid) -> Result<Plan, BaselineError> {
    if solid.faces.is_empty() {
        return Err(BaselineError::EmptySolid);
    }
    let faces = solid
        .faces
        .iter()
        .enumerate()
        .map(|(i, f)| plan_face(solid, i as u32, f))
        .collect::<Result<Vec<_>, _>>()?;
    let edge_lengths = solid
        .edges
        .iter()
        .map(|e| {
            let t = e.curve.domain();
            polyline_length(
                (0..=LENGTH_SAMPLES).map(|j| e.curve.eval(at(&t, j, LENGTH_SAMPLES)).point),
            )
        })
        .collect();
    Ok(Plan {
        faces,
        edge_lengths,
    })
}

/// Meshes `solid` with about `target` triangles (within 2 % where the topology allows).
pub(crate) fn tessellate(
    solid: &Solid,
    target: usize,
    maximum: usize,
) -> Result<Tessellation, BaselineError> {
    let plan = plan(solid)?;
    let minimum = plan.count(f64::INFINITY);
    if target < minimum || target > maximum {
        return Err(BaselineError::BadTarget {
            target,
            minimum,
            maximum,
        });
    }
    let area: f64 = plan.faces.iter().map(FacePlan::area).sum();
    let mut spacing = (2.0 * area / target as f64).sqrt();
    let mut best = (usize::MAX, spacing);
    for _ in 0..MAX_ITERATIONS {
        let count = plan.count(spacing);
        let miss = count.abs_diff(target);
        if miss < best.0 {
            best = (miss, spacing);
        }
        if (miss as f64) <= COUNT_TOLERANCE * target as f64 {
            break;
        }
        spacing *= (count as f64 / target as f64).sqrt();
    }
    Ok(build(solid, &plan, best.1))
}

/// Welded vertices: one per (vertex), (edge, j) or (face, row, j).
#[derive(Default)]
struct Welder {
    index: HashMap<Key, u32>,
    positions: Vec<DVec3>,
}

impl Welder {
    /// The corner at vertex `j` (unwrapped) of row `row_index` of a face, at face parameter u.
    fn corner(
        &mut self,
        solid: &Solid,
        face: &FacePlan,
        (row_index, row): (usize, &Row),
        j: usize,
        u: f64,
    ) -> Corner {
        let wrapped = j % row.count;
        let key = match row.kind {
            RowKind::Interior => Key::Face(face.index, row_index, wrapped),
            RowKind::Edge(id) => Key::Edge(id.0, wrapped),
            RowKind::Vertex(id) => Key::Vertex(id.0),
        };
        let positions = &mut self.positions;
        let id = *self.index.entry(key).or_insert_with(|| {
            let point = match row.kind {
                RowKind::Interior => {
                    let surface = &solid.faces[face.index as usize].surface;
                    surface.eval(face.u.normalize(u), row.v).point
                }
                RowKind::Edge(id) => {
                    let curve = &solid.edge(id).curve;
                    curve.eval(at(&curve.domain(), wrapped, row.count)).point
                }
                RowKind::Vertex(id) => solid.vertex(id).point,
            };
            positions.push(point);
            (positions.len() - 1) as u32
        });
        Corner { id, u, v: row.v }
    }
}

/// Zips rows `a` (index k) and `b` (index k + 1) of a face into triangles, counter-clockwise
/// in (u, v): u increasing along a row, then v increasing to the next row.
fn zip(
    welder: &mut Welder,
    solid: &Solid,
    face: &FacePlan,
    k: usize,
    (a, b): (&Row, &Row),
) -> Vec<[Corner; 3]> {
    let ua = |i: usize| at(&face.u, i, a.count);
    let ub = |j: usize| at(&face.u, j, b.count);
    let mut c = |on_b: bool, j: usize, u: f64| {
        if on_b {
            welder.corner(solid, face, (k + 1, b), j, u)
        } else {
            welder.corner(solid, face, (k, a), j, u)
        }
    };
    let mut strip = Vec::with_capacity(a.count + b.count);
    if a.count == 1 {
        for j in 0..b.count {
            let mid = 0.5 * (ub(j) + ub(j + 1));
            strip.push([
                c(false, 0, mid),
                c(true, j + 1, ub(j + 1)),
                c(true, j, ub(j)),
            ]);
        }
    } else if b.count == 1 {
        for i in 0..a.count {
            let mid = 0.5 * (ua(i) + ua(i + 1));
            strip.push([
                c(false, i, ua(i)),
                c(false, i + 1, ua(i + 1)),
                c(true, 0, mid),
            ]);
        }
    } else {
        let (mut i, mut j) = (0, 0);
        while i < a.count || j < b.count {
            let advance_a = j == b.count || (i < a.count && ua(i + 1) <= ub(j + 1));
            if advance_a {
                strip.push([
                    c(false, i, ua(i)),
                    c(false, i + 1, ua(i + 1)),
                    c(true, j, ub(j)),
                ]);
                i += 1;
            } else {
                strip.push([
                    c(false, i, ua(i)),
                    c(true, j + 1, ub(j + 1)),
                    c(true, j, ub(j)),
                ]);
                j += 1;
            }
        }
    }
    strip
}

fn build(solid: &Solid, plan: &Plan, spacing: f64) -> Tessellation {
    let edge_counts = plan.edge_counts(spacing);
    let mut welder = Welder::default();
    let mut triangles: Vec<[u32; 3]> = Vec::new();
    let mut chordal_error = 0.0_f64;
    for face in &plan.faces {
        let surface: &dyn Surface = solid.faces[face.index as usize].surface.as_ref();
        let rows = face.rows(spacing, &edge_counts);
        for (k, w) in rows.windows(2).enumerate() {
            for tri in zip(&mut welder, solid, face, k, (&w[0], &w[1])) {
                let p = tri.map(|c| welder.positions[c.id as usize]);
                chordal_error = chordal_error.max(triangle_error(surface, face, &tri, p));
                triangles.push(tri.map(|c| c.id));
            }
        }
    }
    Tessellation {
        positions: welder.positions,
        triangles,
        chordal_error,
    }
}

/// Largest distance (mm) from the triangle's error samples to the face.
fn triangle_error(surface: &dyn Surface, plan: &FacePlan, tri: &[Corner; 3], p: [DVec3; 3]) -> f64 {
    let mut worst = 0.0_f64;
    let n = SAMPLE_GRID;
    for i in 0..=n {
        for j in 0..=n - i {
            let k = n - i - j;
            if i == n || j == n || k == n {
                continue;
            }
            let b = [
                i as f64 / n as f64,
                j as f64 / n as f64,
                k as f64 / n as f64,
            ];
            let point = p[0] * b[0] + p[1] * b[1] + p[2] * b[2];
            let u = b[0] * tri[0].u + b[1] * tri[1].u + b[2] * tri[2].u;
            let v = b[0] * tri[0].v + b[1] * tri[1].v + b[2] * tri[2].v;
            worst = worst.max(distance_to_face(surface, plan, point, u, v));
        }
    }
    worst
}

/// An upper bound (mm) on the distance from `point` to the face: the closest of the
/// Gauss-Newton iterates of the projection started at (u, v).
fn distance_to_face(surface: &dyn Surface, plan: &FacePlan, point: DVec3, u: f64, v: f64) -> f64 {
    let (mut u, mut v) = (u, v);
    let mut best = f64::INFINITY;
    for _ in 0..PROJECTION_STEPS {
        let s = surface.eval(plan.u.normalize(u), plan.v.normalize(v));
        let r = point - s.point;
        best = best.min(r.length());
        let (e, f, g) = (s.du.dot(s.du), s.du.dot(s.dv), s.dv.dot(s.dv));
        let det = e * g - f * f;
        let regular = det > 1e-12 * e * g;
        if !regular {
            break;
        }
        let (a, b) = (r.dot(s.du), r.dot(s.dv));
        let (step_u, step_v) = ((g * a - f * b) / det, (e * b - f * a) / det);
        u += step_u;
        v = (v + step_v).clamp(plan.v.min, plan.v.max);
        // Converged to 1e-10 mm: the next iterate is no closer.
        if step_u * step_u * e + step_v * step_v * g <= 1e-20 {
            break;
        }
    }
    best
}
