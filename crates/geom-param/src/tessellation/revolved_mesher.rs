//! Curvature-adaptive, error-checked tessellation of a solid of revolution into component
//! meshes.
//!
//! The surface is cut into **rings** (circles of constant segment parameter s) and **strips**
//! between consecutive rings of a segment. Ring k of radius r carries n_k vertices at
//! u = 2π j / n_k; a strip is triangulated by zipping its two rings in order of u, and a pole
//! (a ring of radius 0) is one vertex joined by a fan. Rings at segment joints are the exact edge
//! circles, shared by the faces on both sides, so the mesh is watertight across edges.
//!
//! Strips are also kept stout: no taller than four vertex spacings of their wider ring (see
//! `is_too_tall`), so that triangle trees over the mesh can cull.
//!
//! Refinement is driven by the measured error, not by a formula: every strip's triangles are
//! sampled at 12 interior and edge points in parameter space and the distance between the exact
//! point S(u, v) and its linear interpolant is taken. A strip over budget gets more vertices on
//! a ring whose own chord error is over half the budget, or else a new ring half-way in s. The
//! initial rings follow the curvature (arc pieces from the sagitta formula, ring counts from
//! r (1 - cos(π / n)) <= budget / 2), so most strips pass at once.

use crate::revolution::profile::{Closure, Profile};
use crate::revolution::profile_segment::ProfileSegment;
use crate::surfaces::revolved_surface::RevolvedSurface;
use crate::surfaces::surface::Surface;
use crate::tessellation::component_mesh::ComponentMesh;
use crate::topology::components::SurfaceComponent;
use crate::topology::feature::{EdgeId, FaceId, FeatureLocation, VertexId};
use glam::{DVec2, DVec3};
use std::collections::HashMap;
use std::f64::consts::{PI, TAU};

/// The refinement aims at this fraction of the requested tolerance, leaving room for the error
/// between the sampled points.
const BUDGET_FRACTION: f64 = 0.8;
/// Upper bounds that keep refinement finite for absurd tolerances.
const MAX_RING_COUNT: usize = 1 << 15;
const MAX_RINGS_PER_SEGMENT: usize = 1 << 12;
const MAX_PASSES: usize = 64;
/// Largest ratio of a strip's height to the vertex spacing on its wider ring.
const MAX_ASPECT: f64 = 4.0;

#[derive(Clone, Copy, Debug)]
enum RingKind {
    Interior,
    Joint(EdgeId),
    Pole(VertexId),
}

#[derive(Clone, Copy, Debug)]
struct Ring {
    point: DVec2,
    count: usize,
    kind: RingKind,
}

/// A triangle corner: which ring, which vertex of it (unwrapped index, may equal the count),
/// and its face parameters (u unwrapped, s).
#[derive(Clone, Copy, Debug)]
struct Corner {
    ring: usize,
    index: usize,
    u: f64,
    s: f64,
}

/// Rings along the whole profile and, per segment, its rings in order of s.
struct RingSet {
    rings: Vec<Ring>,
    per_segment: Vec<Vec<(f64, usize)>>,
}

/// The tessellation of a whole profile, ready to be split into component meshes.
pub(crate) struct ProfileTessellation {
    rings: RingSet,
    /// Per segment: its triangles and the measured chordal error of its strips.
    faces: Vec<(Vec<[Corner; 3]>, f64)>,
    segments: Vec<ProfileSegment>,
}

/// Vertex count for a ring of radius `r` whose chord sagitta must stay under `budget`.
fn count_for_radius(r: f64, budget: f64) -> usize {
    if r <= 0.0 {
        return 1;
    }
    if budget >= r {
        return 3;
    }
    let n = (PI / (1.0 - budget / r).acos()).ceil();
    (n as usize).clamp(3, MAX_RING_COUNT)
}

fn chord_error(ring: &Ring) -> f64 {
    if ring.count <= 1 {
        0.0
    } else {
        ring.point.x * (1.0 - (PI / ring.count as f64).cos())
    }
}

/// Whether the strip between two rings is more than [`MAX_ASPECT`] times taller (along the
/// profile chord) than the vertex spacing that the chord budget gives its wider ring. The chordal
/// tolerance alone lets a cylinder be two rings of needles as long as the cylinder; such slivers
/// make every triangle tree useless (each needle's box spans the object), so the mesher keeps
/// them stout. The spacing comes from the budget, not from the ring's actual count, which
/// refinement may have raised: near an apex that would shrink the spacing without bound.
fn is_too_tall(a: &Ring, b: &Ring, budget: f64) -> bool {
    let spacing = |ring: &Ring| {
        let natural = count_for_radius(ring.point.x, 0.5 * budget);
        if natural <= 1 {
            0.0
        } else {
            TAU * ring.point.x / natural as f64
        }
    };
    let widest = spacing(a).max(spacing(b));
    widest > 0.0 && a.point.distance(b.point) > MAX_ASPECT * widest
}

fn initial_pieces(segment: &ProfileSegment, budget: f64) -> usize {
    match segment {
        ProfileSegment::Line(_) => 1,
        ProfileSegment::Arc(a) => {
            let max_angle = if budget >= a.radius {
                PI
            } else {
                2.0 * (1.0 - budget / a.radius).acos()
            };
            ((a.sweep.abs() / max_angle).ceil() as usize).clamp(1, MAX_RINGS_PER_SEGMENT / 2)
        }
        ProfileSegment::Bezier(_) => 8,
    }
}

/// Tessellates `profile` so that every face is within `tolerance` (mm) of its mesh.
pub(crate) fn tessellate(profile: &Profile, tolerance: f64) -> ProfileTessellation {
    let budget = BUDGET_FRACTION * tolerance;
    let segments = profile.segments().to_vec();
    let n = segments.len();
    let mut rings: Vec<Ring> = Vec::new();
    let ring = |point: DVec2, kind: RingKind, rings: &mut Vec<Ring>| {
        let count = match kind {
            RingKind::Pole(_) => 1,
            _ => count_for_radius(point.x, 0.5 * budget),
        };
        rings.push(Ring { point, count, kind });
        rings.len() - 1
    };
    // Shared rings: joints and poles.
    let joints = profile.joints();
    let joint_ring: Vec<usize> = joints
        .iter()
        .enumerate()
        .map(|(k, &(i, _))| {
            ring(
                segments[i].end(),
                RingKind::Joint(EdgeId(k as u32)),
                &mut rings,
            )
        })
        .collect();
    let axis = profile.closure() == Closure::Axis;
    let (first_pole, last_pole) = if axis {
        let a = ring(
            DVec2::new(0.0, segments[0].start().y),
            RingKind::Pole(VertexId(0)),
            &mut rings,
        );
        let b = ring(
            DVec2::new(0.0, segments[n - 1].end().y),
            RingKind::Pole(VertexId(1)),
            &mut rings,
        );
        (a, b)
    } else {
        (usize::MAX, usize::MAX)
    };

    let mut per_segment = Vec::with_capacity(n);
    for (i, segment) in segments.iter().enumerate() {
        let start_ring = match (i, axis) {
            (0, true) => first_pole,
            (0, false) => joint_ring[n - 1],
            _ => joint_ring[i - 1],
        };
        let end_ring = if axis && i == n - 1 {
            last_pole
        } else {
            joint_ring[i]
        };
        let pieces = initial_pieces(segment, 0.5 * budget);
        let mut list = vec![(0.0, start_ring)];
        for k in 1..pieces {
            let s = k as f64 / pieces as f64;
            list.push((
                s,
                ring(segment.eval(s).point, RingKind::Interior, &mut rings),
            ));
        }
        list.push((1.0, end_ring));
        per_segment.push(list);
    }
    let mut set = RingSet { rings, per_segment };
    refine(&mut set, &segments, budget);

    let faces = (0..n)
        .map(|i| {
            let mut triangles = Vec::new();
            let mut error = 0.0_f64;
            for w in set.per_segment[i].windows(2) {
                let strip = zip_strip(&set.rings, w[0], w[1]);
                error = error.max(strip_error(&segments[i], &set.rings, &strip));
                triangles.extend(strip);
            }
            (triangles, error)
        })
        .collect();
    ProfileTessellation {
        rings: set,
        faces,
        segments,
    }
}

fn refine(set: &mut RingSet, segments: &[ProfileSegment], budget: f64) {
    for _ in 0..MAX_PASSES {
        let mut bump: Vec<(usize, usize)> = Vec::new(); // (ring, new count)
        let mut inserts: Vec<(usize, usize, f64)> = Vec::new(); // (segment, position, s)
        for (i, list) in set.per_segment.iter().enumerate() {
            for (p, w) in list.windows(2).enumerate() {
                if is_too_tall(&set.rings[w[0].1], &set.rings[w[1].1], budget)
                    && list.len() < MAX_RINGS_PER_SEGMENT
                {
                    inserts.push((i, p + 1, 0.5 * (w[0].0 + w[1].0)));
                    continue;
                }
                let strip = zip_strip(&set.rings, w[0], w[1]);
                if strip_error(&segments[i], &set.rings, &strip) <= budget {
                    continue;
                }
                let (a, b) = (&set.rings[w[0].1], &set.rings[w[1].1]);
                let grow = |n: usize| (n + 1).max(n * 3 / 2).min(MAX_RING_COUNT);
                let over: Vec<usize> = [w[0].1, w[1].1]
                    .into_iter()
                    .filter(|&k| chord_error(&set.rings[k]) > 0.5 * budget)
                    .collect();
                if !over.is_empty() {
                    bump.extend(over.into_iter().map(|k| (k, grow(set.rings[k].count))));
                } else if a.count > 1
                    && b.count > 1
                    && a.count.max(b.count) > 2 * a.count.min(b.count)
                {
                    let (small, large) = if a.count < b.count {
                        (w[0].1, b.count)
                    } else {
                        (w[1].1, a.count)
                    };
                    bump.push((small, large.div_ceil(2)));
                } else if list.len() < MAX_RINGS_PER_SEGMENT {
                    inserts.push((i, p + 1, 0.5 * (w[0].0 + w[1].0)));
                }
            }
        }
        if bump.is_empty() && inserts.is_empty() {
            return;
        }
        for (k, count) in bump {
            set.rings[k].count = set.rings[k].count.max(count);
        }
        for &(i, position, s) in inserts.iter().rev() {
            let point = segments[i].eval(s).point;
            let list = &set.per_segment[i];
            let neighbours = set.rings[list[position - 1].1]
                .count
                .max(set.rings[list[position].1].count);
            let count = count_for_radius(point.x, 0.5 * budget).max(neighbours);
            set.rings.push(Ring {
                point,
                count,
                kind: RingKind::Interior,
            });
            let index = set.rings.len() - 1;
            set.per_segment[i].insert(position, (s, index));
        }
    }
}

/// Triangulates the strip between two rings of one segment, counter-clockwise seen from outside
/// (u increasing, then s increasing, is the positive orientation of a revolved face).
fn zip_strip(rings: &[Ring], (s_a, a): (f64, usize), (s_b, b): (f64, usize)) -> Vec<[Corner; 3]> {
    let (na, nb) = (rings[a].count, rings[b].count);
    let ua = |i: usize| TAU * i as f64 / na as f64;
    let ub = |j: usize| TAU * j as f64 / nb as f64;
    let ca = |i: usize, u: f64| Corner {
        ring: a,
        index: i,
        u,
        s: s_a,
    };
    let cb = |j: usize, u: f64| Corner {
        ring: b,
        index: j,
        u,
        s: s_b,
    };
    let mut out = Vec::with_capacity(na + nb);
    if na == 1 {
        for j in 0..nb {
            let mid = 0.5 * (ub(j) + ub(j + 1));
            out.push([ca(0, mid), cb(j + 1, ub(j + 1)), cb(j, ub(j))]);
        }
    } else if nb == 1 {
        for i in 0..na {
            let mid = 0.5 * (ua(i) + ua(i + 1));
            out.push([ca(i, ua(i)), ca(i + 1, ua(i + 1)), cb(0, mid)]);
        }
    } else {
        let (mut i, mut j) = (0, 0);
        while i < na || j < nb {
            let advance_a = j == nb || (i < na && ua(i + 1) <= ub(j + 1));
            if advance_a {
                out.push([ca(i, ua(i)), ca(i + 1, ua(i + 1)), cb(j, ub(j))]);
                i += 1;
            } else {
                out.push([ca(i, ua(i)), cb(j + 1, ub(j + 1)), cb(j, ub(j))]);
                j += 1;
            }
        }
    }
    out
}

fn ring_vertex(ring: &Ring, index: usize) -> (usize, f64, DVec3) {
    let k = index % ring.count;
    let u = TAU * k as f64 / ring.count as f64;
    let (sin, cos) = u.sin_cos();
    (
        k,
        u,
        DVec3::new(ring.point.x * cos, ring.point.x * sin, ring.point.y),
    )
}

fn surface_point(segment: &ProfileSegment, u: f64, s: f64) -> DVec3 {
    let p = segment.eval(s).point;
    let (sin, cos) = u.sin_cos();
    DVec3::new(p.x * cos, p.x * sin, p.y)
}

/// Barycentric sample points (in quarters) other than the corners.
const SAMPLES: [[f64; 3]; 12] = [
    [0.75, 0.25, 0.0],
    [0.5, 0.5, 0.0],
    [0.25, 0.75, 0.0],
    [0.0, 0.75, 0.25],
    [0.0, 0.5, 0.5],
    [0.0, 0.25, 0.75],
    [0.25, 0.0, 0.75],
    [0.5, 0.0, 0.5],
    [0.75, 0.0, 0.25],
    [0.5, 0.25, 0.25],
    [0.25, 0.5, 0.25],
    [0.25, 0.25, 0.5],
];

/// Largest sampled distance between the exact surface and the strip's triangles.
fn strip_error(segment: &ProfileSegment, rings: &[Ring], strip: &[[Corner; 3]]) -> f64 {
    let mut worst = 0.0_f64;
    for tri in strip {
        let p = tri.map(|c| ring_vertex(&rings[c.ring], c.index).2);
        for b in SAMPLES {
            let u = b[0] * tri[0].u + b[1] * tri[1].u + b[2] * tri[2].u;
            let s = b[0] * tri[0].s + b[1] * tri[1].s + b[2] * tri[2].s;
            let linear = p[0] * b[0] + p[1] * b[1] + p[2] * b[2];
            worst = worst.max(surface_point(segment, u, s).distance(linear));
        }
    }
    worst
}

impl ProfileTessellation {
    /// The mesh of one component: its faces' triangles with their own copy of the shared rings.
    pub(crate) fn component_mesh(&self, component: &SurfaceComponent) -> ComponentMesh {
        let mut mesh = ComponentMesh::default();
        let mut index_of: HashMap<(usize, usize), u32> = HashMap::new();
        for &face in &component.faces {
            let (triangles, error) = &self.faces[face.0 as usize];
            mesh.chordal_error = mesh.chordal_error.max(*error);
            for tri in triangles {
                let ids = tri.map(|c| {
                    let ring = &self.rings.rings[c.ring];
                    let (k, u, position) = ring_vertex(ring, c.index);
                    *index_of.entry((c.ring, k)).or_insert_with(|| {
                        mesh.positions.push(position);
                        mesh.normals.push(self.vertex_normal(ring, face, u, c.s));
                        mesh.vertex_locations.push(match ring.kind {
                            RingKind::Interior => FeatureLocation::Face {
                                id: face,
                                u,
                                v: c.s,
                            },
                            RingKind::Joint(id) => FeatureLocation::Edge { id, t: u },
                            RingKind::Pole(id) => FeatureLocation::Vertex { id },
                        });
                        (mesh.positions.len() - 1) as u32
                    })
                });
                mesh.triangles.push(ids);
                mesh.triangle_faces.push(face);
                mesh.triangle_params.push(tri.map(|c| [c.u, c.s]));
            }
        }
        mesh
    }

    /// Exact normal at a ring vertex; averaged over both faces on an edge circle, and the axis
    /// direction at an apex.
    fn vertex_normal(&self, ring: &Ring, face: FaceId, u: f64, s: f64) -> DVec3 {
        let normal_on = |segment: usize, s: f64| {
            RevolvedSurface {
                segment: self.segments[segment],
            }
            .normal(u, s)
        };
        match ring.kind {
            RingKind::Interior => normal_on(face.0 as usize, s).unwrap_or(DVec3::Z),
            RingKind::Joint(edge) => {
                let before = self.edge_faces(edge);
                let sum = normal_on(before.0, 1.0).unwrap_or(DVec3::ZERO)
                    + normal_on(before.1, 0.0).unwrap_or(DVec3::ZERO);
                sum.try_normalize().unwrap_or(DVec3::Z)
            }
            RingKind::Pole(_) => normal_on(face.0 as usize, s).unwrap_or_else(|| {
                // Apex: the mean of the cone of normals points along the axis.
                let n2 = self.segments[face.0 as usize].eval(s).outward_normal();
                DVec3::new(0.0, 0.0, n2.y.signum())
            }),
        }
    }

    /// The segments before and after the joint of `edge`.
    fn edge_faces(&self, edge: EdgeId) -> (usize, usize) {
        let k = edge.0 as usize;
        let n = self.segments.len();
        (k, (k + 1) % n)
    }
}
