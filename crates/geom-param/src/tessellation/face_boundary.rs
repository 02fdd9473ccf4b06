//! The boundary of a face's region in its (u, v) plane, as loops of shared mesh vertices.
//!
//! - A face over its whole parameter rectangle: one counter-clockwise loop along the four sides
//!   (u_min..u_max at v_min, then up u_max, back along v_max, down u_min). A side on an edge
//!   takes the edge's samples. A side collapsed into a vertex (a pole or apex) around a periodic
//!   parameter is cut off by a ring (the parameter line a short way in, sampled like an edge)
//!   and closed by a fan of triangles from the pole to the ring, as a revolved pole is; any
//!   other collapsed side is sampled in the parameter plane with every sample that one vertex
//!   (the triangles along it have no area and are dropped). The two sides of a periodic
//!   parameter are the two copies of one seam (the parameter line at the domain's start),
//!   sampled once, so both copies are the same vertices.
//! - A trimmed face: one loop per trim loop, each edge's samples mapped through its entry's
//!   p-curve, in the loop's direction, with periodic parameters unwrapped to run continuously.

use crate::curves::curve::ParamRange;
use crate::tessellation::edge_sampling::{EdgeSamples, Seam, SeamAxis, sample_seam};
use crate::tessellation::face_metric::FaceMetric;
use crate::tessellation::face_triangulation::sampled_deviation;
use crate::tessellation::plane_map::PlaneMap;
use crate::tessellation::vertex_table::VertexTable;
use crate::topology::feature::{EdgeId, FaceId, FeatureLocation, VertexId};
use crate::topology::solid::{Boundary, EdgeOn, ParamSide, Solid};
use glam::{DVec2, DVec3};

/// One point of a boundary loop: its (u, v) on the face and its mesh vertex.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct BoundaryPoint {
    /// Face parameters (periodic ones unwrapped along the loop).
    pub uv: DVec2,
    /// The mesh vertex.
    pub id: u32,
}

/// A closed loop of boundary points; the last joins the first. The face lies on its left.
pub(crate) type BoundaryLoop = Vec<BoundaryPoint>;

/// A triangle built with the boundary: mesh vertices and their (u, v), counter-clockwise.
pub(crate) type FanTriangle = ([u32; 3], [[f64; 2]; 3]);

/// A face's boundary: the loops its region's triangulation is bounded by, the plane it is
/// triangulated in, and the pole fans already triangulated outside them.
#[derive(Debug)]
pub(crate) struct FaceBoundary {
    /// The triangulation plane over the loops' parameter box.
    pub map: PlaneMap,
    /// Loop 0 bounds the region from outside (counter-clockwise); others are holes.
    pub loops: Vec<BoundaryLoop>,
    /// Fan triangles from poles to their rings.
    pub fans: Vec<FanTriangle>,
    /// Largest sampled deviation of the fan triangles (mm).
    pub fan_error: f64,
}

/// Relative mismatch allowed between parameter values that must agree (an edge's domain and
/// the side it runs along, a sample and the start of a periodic parameter).
const PARAM_MATCH: f64 = 1e-9;
/// Points along a collapsed side at which the face's normal is averaged into the pole's.
const POLE_NORMAL_SAMPLES: usize = 16;

/// Everything the boundary of one face needs.
pub(crate) struct BoundaryInput<'a> {
    /// The solid.
    pub solid: &'a Solid,
    /// The face.
    pub face: FaceId,
    /// Its metric (for the sample count of collapsed sides and seams' target length).
    pub metric: &'a FaceMetric,
    /// The samples of every edge of the solid.
    pub edges: &'a [EdgeSamples],
    /// Chord budget for seams and rings (mm).
    pub edge_budget: f64,
    /// Deviation budget of pole fan triangles (mm).
    pub budget: f64,
}

/// The loops bounding `input.face`, creating seam and pole vertices in `table`.
///
/// # Errors
/// A reason when the face's sides or loops do not fit together.
pub(crate) fn face_boundary(
    input: &BoundaryInput<'_>,
    table: &mut VertexTable,
) -> Result<FaceBoundary, String> {
    if input.solid.face(input.face).trim.is_some() {
        let loops = trimmed_boundary(input)?;
        let mut lo = DVec2::splat(f64::INFINITY);
        let mut hi = DVec2::splat(f64::NEG_INFINITY);
        for p in loops.iter().flatten() {
            lo = lo.min(p.uv);
            hi = hi.max(p.uv);
        }
        if !(lo.x < hi.x && lo.y < hi.y) {
            return Err("its boundary loops enclose no area".into());
        }
        Ok(FaceBoundary {
            map: PlaneMap::new(input.solid, input.face, lo, hi)?,
            loops,
            fans: Vec::new(),
            fan_error: 0.0,
        })
    } else {
        rectangle_boundary(input, table)
    }
}

/// A side's points in increasing running parameter: (running parameter, vertex).
type SidePoints = Vec<(f64, u32)>;

const SIDES: [ParamSide; 4] = [
    ParamSide::UMin,
    ParamSide::UMax,
    ParamSide::VMin,
    ParamSide::VMax,
];

/// The parameter that runs along `side` (v on a u side) and the value the other one is fixed at.
fn running(domain: &[ParamRange; 2], side: ParamSide) -> (ParamRange, f64) {
    let [du, dv] = *domain;
    match side {
        ParamSide::UMin => (dv, du.min),
        ParamSide::UMax => (dv, du.max),
        ParamSide::VMin => (du, dv.min),
        ParamSide::VMax => (du, dv.max),
    }
}

fn side_uv(side: ParamSide, run: f64, fixed: f64) -> DVec2 {
    match side {
        ParamSide::UMin | ParamSide::UMax => DVec2::new(fixed, run),
        ParamSide::VMin | ParamSide::VMax => DVec2::new(run, fixed),
    }
}

fn rectangle_boundary(
    input: &BoundaryInput<'_>,
    table: &mut VertexTable,
) -> Result<FaceBoundary, String> {
    let solid = input.solid;
    let face = solid.face(input.face);
    let full_domain = face.surface.domain();
    for (k, r) in full_domain.iter().enumerate() {
        if !(r.min.is_finite() && r.max.is_finite() && r.max > r.min) {
            return Err(format!(
                "parameter {k} has the empty or unbounded domain [{}, {}]",
                r.min, r.max
            ));
        }
    }
    // The rectangle the loop bounds: the domain less the pole caps.
    let mut domain = full_domain;
    let mut fans: Vec<FanTriangle> = Vec::new();
    let mut fan_error = 0.0_f64;
    let mut sides: [Option<SidePoints>; 4] = [None, None, None, None];
    for side in SIDES {
        let Boundary::Vertex(p) = face.boundary(side) else {
            continue;
        };
        if let Some(cap) = pole_cap(input, side, p, table)? {
            let k = across_index(side);
            if matches!(side, ParamSide::UMin | ParamSide::VMin) {
                domain[k].min = cap.cut;
            } else {
                domain[k].max = cap.cut;
            }
            fans.extend(cap.fans);
            fan_error = fan_error.max(cap.error);
            sides[side as usize] = Some(cap.ring);
        }
    }
    let map = PlaneMap::new(
        solid,
        input.face,
        DVec2::new(domain[0].min, domain[1].min),
        DVec2::new(domain[0].max, domain[1].max),
    )?;
    // Seams cross the plane's stretch (a revolved face's seam runs from its smallest radius to
    // its largest): pieces as long in the plane as a target length where the stretch is
    // largest, so that they are graded like the triangles beside them.
    let seam_plane = Some((&map, input.metric.target_length / map.max_stretch()));
    for side in SIDES {
        if sides[side as usize].is_some() {
            continue;
        }
        let across = full_domain[across_index(side)];
        sides[side as usize] = match face.boundary(side) {
            Boundary::Edge(e) => Some(edge_side(input, side, e)?),
            Boundary::Vertex(p) => Some(pole_side(input, side, p, table)),
            Boundary::Periodic if across.periodic => None,
            Boundary::Periodic => {
                return Err(format!(
                    "side {side:?} is periodic but its parameter is not"
                ));
            }
            Boundary::Trimmed => {
                return Err(format!("side {side:?} is trimmed but the face has no trim"));
            }
        };
    }

    // Corners from the sides that carry vertices; a corner between two periodic sides (a torus)
    // is one face vertex at the domain's start.
    let mut origin: Option<u32> = None;
    let mut corner = |us: ParamSide, vs: ParamSide, table: &mut VertexTable| -> u32 {
        if let Some(points) = &sides[vs as usize] {
            return if us == ParamSide::UMin {
                points[0].1
            } else {
                points[points.len() - 1].1
            };
        }
        if let Some(points) = &sides[us as usize] {
            return if vs == ParamSide::VMin {
                points[0].1
            } else {
                points[points.len() - 1].1
            };
        }
        *origin.get_or_insert_with(|| {
            let location = FeatureLocation::Face {
                id: input.face,
                u: domain[0].min,
                v: domain[1].min,
            };
            let id = table.add(solid, location);
            if let Some(n) = solid.face_normal_at(&location) {
                table.add_normal(id, input.face, n);
            }
            id
        })
    };
    use ParamSide::{UMax, UMin, VMax, VMin};
    let c00 = corner(UMin, VMin, table);
    let c10 = corner(UMax, VMin, table);
    let c01 = corner(UMin, VMax, table);
    let c11 = corner(UMax, VMax, table);

    // Seams: one per periodic parameter, shared by both of its sides.
    for (axis, lo_side, hi_side, ends) in [
        (SeamAxis::AlongV, UMin, UMax, [c00, c01]),
        (SeamAxis::AlongU, VMin, VMax, [c00, c10]),
    ] {
        if sides[lo_side as usize].is_some() && sides[hi_side as usize].is_some() {
            continue;
        }
        if sides[lo_side as usize].is_some() || sides[hi_side as usize].is_some() {
            return Err(format!(
                "only one of sides {lo_side:?} and {hi_side:?} is periodic"
            ));
        }
        let (run, fixed) = running(&domain, lo_side);
        let seam = Seam {
            face: input.face,
            axis,
            fixed,
            range: run,
            ends,
            plane: seam_plane,
        };
        let samples = sample_seam(
            solid,
            &seam,
            input.edge_budget,
            input.metric.target_length,
            table,
        )?;
        let points: SidePoints = samples.ts.into_iter().zip(samples.ids).collect();
        sides[lo_side as usize] = Some(points.clone());
        sides[hi_side as usize] = Some(points);
    }

    let mut out: BoundaryLoop = Vec::new();
    for (side, reverse, from, to) in [
        (VMin, false, c00, c10),
        (UMax, false, c10, c11),
        (VMax, true, c11, c01),
        (UMin, true, c01, c00),
    ] {
        let points = sides[side as usize]
            .as_ref()
            .ok_or_else(|| format!("side {side:?} has no points"))?;
        let (_, fixed) = running(&domain, side);
        let ordered: Vec<(f64, u32)> = if reverse {
            points.iter().rev().copied().collect()
        } else {
            points.clone()
        };
        let (first, last) = (ordered[0].1, ordered[ordered.len() - 1].1);
        if first != from || last != to {
            return Err(format!(
                "side {side:?} runs from vertex {first} to {last} but its corners are {from} and {to}: the sides do not meet at common vertices"
            ));
        }
        out.extend(
            ordered[..ordered.len() - 1]
                .iter()
                .map(|&(run, id)| BoundaryPoint {
                    uv: side_uv(side, run, fixed),
                    id,
                }),
        );
    }
    Ok(FaceBoundary {
        loops: vec![out],
        map,
        fans,
        fan_error,
    })
}

/// The index of the parameter that is constant along `side` (u on a u side).
fn across_index(side: ParamSide) -> usize {
    match side {
        ParamSide::UMin | ParamSide::UMax => 0,
        ParamSide::VMin | ParamSide::VMax => 1,
    }
}

/// A pole cut off by a ring: the ring's samples (running parameter, vertex), the value of the
/// cut parameter along it, and the fan from the pole to the ring.
struct PoleCap {
    ring: SidePoints,
    cut: f64,
    fans: Vec<FanTriangle>,
    error: f64,
}

/// Cuts off the pole that `side` collapses into when the parameter running along the side is
/// periodic with both its sides periodic (a sphere's or a revolved face's pole): a ring at the
/// parameter value where the surface is about half a target length from the pole, sampled like
/// an edge (closed, from the running parameter's start), and a fan of triangles from the pole
/// to consecutive ring samples. The ring moves towards the pole until the fan's sampled
/// deviation is within the budget. `None` when the side's running parameter is not periodic.
///
/// # Errors
/// A reason when the surface is not finite near the pole or no ring meets the budget.
fn pole_cap(
    input: &BoundaryInput<'_>,
    side: ParamSide,
    pole: VertexId,
    table: &mut VertexTable,
) -> Result<Option<PoleCap>, String> {
    let solid = input.solid;
    let face = solid.face(input.face);
    let domain = face.surface.domain();
    let (run, fixed) = running(&domain, side);
    let ends_periodic = match side {
        ParamSide::UMin | ParamSide::UMax => {
            face.boundary(ParamSide::VMin) == Boundary::Periodic
                && face.boundary(ParamSide::VMax) == Boundary::Periodic
        }
        ParamSide::VMin | ParamSide::VMax => {
            face.boundary(ParamSide::UMin) == Boundary::Periodic
                && face.boundary(ParamSide::UMax) == Boundary::Periodic
        }
    };
    if !(run.periodic && ends_periodic) {
        return Ok(None);
    }
    add_pole_normal(input, side, pole, table);
    let across = domain[across_index(side)];
    let inward = if matches!(side, ParamSide::UMin | ParamSide::VMin) {
        1.0
    } else {
        -1.0
    };
    let apex = solid.vertex(pole).point;
    let target = 0.5 * input.metric.target_length;
    let radius_at = |cut: f64| -> f64 {
        (0..POLE_NORMAL_SAMPLES)
            .map(|k| {
                let r = run.min + run.span() * k as f64 / POLE_NORMAL_SAMPLES as f64;
                let uv = side_uv(side, r, cut);
                solid.eval_face(input.face, uv.x, uv.y).point.distance(apex)
            })
            .fold(0.0, f64::max)
    };
    let mut delta = 0.5 * across.span();
    for _ in 0..60 {
        // NaN radii do not stop the shrinking; the fan's sampling reports them.
        if radius_at(fixed + inward * delta) <= target {
            break;
        }
        delta *= 0.5;
    }
    let axis = match side {
        ParamSide::UMin | ParamSide::UMax => SeamAxis::AlongV,
        ParamSide::VMin | ParamSide::VMax => SeamAxis::AlongU,
    };
    let mut worst = f64::NAN;
    for _ in 0..40 {
        let cut = fixed + inward * delta;
        let start_uv = side_uv(side, run.min, cut);
        let location = FeatureLocation::Face {
            id: input.face,
            u: start_uv.x,
            v: start_uv.y,
        };
        let start = table.add(solid, location);
        if let Some(n) = solid.face_normal_at(&location) {
            table.add_normal(start, input.face, n);
        }
        let seam = Seam {
            face: input.face,
            axis,
            fixed: cut,
            range: run,
            ends: [start, start],
            plane: None,
        };
        let ring = sample_seam(
            solid,
            &seam,
            input.edge_budget,
            input.metric.target_length,
            table,
        )?;
        let mut fans = Vec::with_capacity(ring.ts.len());
        let mut error = 0.0_f64;
        for k in 0..ring.ts.len() - 1 {
            let (ta, tb) = (ring.ts[k], ring.ts[k + 1]);
            let pole_uv = side_uv(side, 0.5 * (ta + tb), fixed);
            let mut corners = [
                (pole_uv, pole.0),
                (side_uv(side, ta, cut), ring.ids[k]),
                (side_uv(side, tb, cut), ring.ids[k + 1]),
            ];
            if (corners[1].0 - pole_uv).perp_dot(corners[2].0 - pole_uv) < 0.0 {
                corners.swap(1, 2);
            }
            let uv = corners.map(|c| c.0);
            let p = corners.map(|c| table.get(c.1).position);
            error = error.max(sampled_deviation(solid, input.face, uv, p)?);
            fans.push((corners.map(|c| c.1), uv.map(|q| q.to_array())));
        }
        if error <= input.budget {
            return Ok(Some(PoleCap {
                ring: ring.ts.into_iter().zip(ring.ids).collect(),
                cut,
                fans,
                error,
            }));
        }
        worst = error;
        delta *= 0.5;
    }
    Err(format!(
        "the fan around vertex {} deviates by {worst} mm however close its ring",
        pole.0
    ))
}

/// The samples of edge `edge` along `side`, in increasing running parameter. On a periodic
/// running parameter the closed edge is rotated to start at the domain's start and closed with
/// the first sample's vertex.
fn edge_side(
    input: &BoundaryInput<'_>,
    side: ParamSide,
    edge: EdgeId,
) -> Result<SidePoints, String> {
    let solid = input.solid;
    let e = solid.edge(edge);
    let Some(on) = e
        .uses
        .iter()
        .find(|u| u.face == input.face && u.on.side() == Some(side))
        .map(|u| u.on)
    else {
        return Err(format!(
            "side {side:?} is edge {} but the edge has no use on it",
            edge.0
        ));
    };
    // The samples by running parameter along the side (t, or −t for a reversed side),
    // increasing.
    let edge_samples = &input.edges[edge.0 as usize];
    let mut pairs: Vec<(f64, u32)> = edge_samples
        .ts
        .iter()
        .map(|&t| on.running(t))
        .zip(edge_samples.ids.iter().copied())
        .collect();
    if matches!(on, EdgeOn::SideReversed(_)) {
        pairs.reverse();
    }
    let samples = EdgeSamples {
        ts: pairs.iter().map(|p| p.0).collect(),
        ids: pairs.iter().map(|p| p.1).collect(),
    };
    let samples = &samples;
    let (run, _) = running(&solid.face(input.face).surface.domain(), side);
    let er = e.curve.domain();
    let er = ParamRange {
        min: on.running(er.min).min(on.running(er.max)),
        max: on.running(er.min).max(on.running(er.max)),
        periodic: er.periodic,
    };
    let tol = PARAM_MATCH * run.span();
    if run.periodic {
        if !er.periodic || (er.span() - run.span()).abs() > tol {
            return Err(format!(
                "edge {} on periodic side {side:?} is not closed with the same period",
                edge.0
            ));
        }
        let n = samples.ts.len() - 1;
        let period = run.span();
        let offset = |t: f64| (t - run.min).rem_euclid(period);
        let k = (0..n)
            .min_by(|&a, &b| {
                let d = |t: f64| offset(t).min(period - offset(t));
                d(samples.ts[a]).total_cmp(&d(samples.ts[b]))
            })
            .unwrap_or(0);
        let miss = offset(samples.ts[k]).min(period - offset(samples.ts[k]));
        if miss > tol {
            return Err(format!(
                "edge {} has no sample where side {side:?}'s periodic parameter starts",
                edge.0
            ));
        }
        let tk = samples.ts[k];
        let mut out: SidePoints = (0..n)
            .map(|j| {
                let idx = (k + j) % n;
                let d = if j == 0 {
                    0.0
                } else {
                    (samples.ts[idx] - tk).rem_euclid(period)
                };
                (run.min + d, samples.ids[idx])
            })
            .collect();
        out.push((run.max, samples.ids[k]));
        Ok(out)
    } else {
        let (t0, t1) = (samples.ts[0], samples.ts[samples.ts.len() - 1]);
        if (t0 - run.min).abs() > tol || (t1 - run.max).abs() > tol {
            return Err(format!(
                "edge {} spans [{t0}, {t1}] but side {side:?} spans [{}, {}]",
                edge.0, run.min, run.max
            ));
        }
        Ok(samples
            .ts
            .iter()
            .copied()
            .zip(samples.ids.iter().copied())
            .collect())
    }
}

/// A side collapsed into vertex `pole`: evenly spaced parameter samples, all that vertex, about
/// one per target length of the side's extent in the scaled plane. Adds the face's normal at
/// the pole (its mean around the side, or just inside where the side itself has none).
fn pole_side(
    input: &BoundaryInput<'_>,
    side: ParamSide,
    pole: VertexId,
    table: &mut VertexTable,
) -> SidePoints {
    let solid = input.solid;
    let surface = &solid.face(input.face).surface;
    let domain = surface.domain();
    let (run, _) = running(&domain, side);
    let along = match side {
        ParamSide::UMin | ParamSide::UMax => input.metric.scale.y,
        ParamSide::VMin | ParamSide::VMax => input.metric.scale.x,
    };
    let length = run.span() * along;
    let n = ((length / input.metric.target_length).ceil() as usize).clamp(2, 1 << 12);

    add_pole_normal(input, side, pole, table);
    (0..=n)
        .map(|k| (run.min + run.span() * k as f64 / n as f64, pole.0))
        .collect()
}

/// Adds the face's normal at the pole `side` collapses into: its mean around the side, or just
/// inside where the side itself has none (the parametrisation is singular there).
fn add_pole_normal(
    input: &BoundaryInput<'_>,
    side: ParamSide,
    pole: VertexId,
    table: &mut VertexTable,
) {
    let surface = &input.solid.face(input.face).surface;
    let domain = surface.domain();
    let (run, fixed) = running(&domain, side);
    let (across, inward) = match side {
        ParamSide::UMin => (domain[0], 1.0),
        ParamSide::UMax => (domain[0], -1.0),
        ParamSide::VMin => (domain[1], 1.0),
        ParamSide::VMax => (domain[1], -1.0),
    };
    let mut sum = DVec3::ZERO;
    for shift in [0.0, 1e-6, 1e-4] {
        for k in 0..POLE_NORMAL_SAMPLES {
            let r = run.min + run.span() * (k as f64 + 0.5) / POLE_NORMAL_SAMPLES as f64;
            let uv = side_uv(side, r, fixed + inward * shift * across.span());
            if let Some(n) = surface.normal(uv.x, uv.y) {
                sum += n;
            }
        }
        if sum != DVec3::ZERO {
            break;
        }
    }
    if let Some(n) = sum.try_normalize() {
        table.add_normal(pole.0, input.face, n);
    }
}

fn trimmed_boundary(input: &BoundaryInput<'_>) -> Result<Vec<BoundaryLoop>, String> {
    let solid = input.solid;
    let face = solid.face(input.face);
    let trim = face
        .trim
        .as_ref()
        .ok_or_else(|| "the face has no trim".to_string())?;
    let periods = trim.periods;
    let unwrap_near = |mut uv: DVec2, near: DVec2| {
        for i in 0..2 {
            if periods[i] > 0.0 {
                uv[i] -= periods[i] * ((uv[i] - near[i]) / periods[i]).round();
            }
        }
        uv
    };
    let mut loops: Vec<BoundaryLoop> = Vec::with_capacity(trim.loops.len());
    for (li, l) in trim.loops.iter().enumerate() {
        let mut points: BoundaryLoop = Vec::new();
        let mut previous_end: Option<u32> = None;
        for (ei, entry) in l.entries.iter().enumerate() {
            let samples = &input.edges[entry.edge.0 as usize];
            let order: Vec<usize> = if entry.reversed {
                (0..samples.ts.len()).rev().collect()
            } else {
                (0..samples.ts.len()).collect()
            };
            let first = samples.ids[order[0]];
            if let Some(end) = previous_end.filter(|&end| end != first) {
                return Err(format!(
                    "loop {li} does not close: entry {ei} (edge {}) starts at vertex {first}, the entry before ends at vertex {end}",
                    entry.edge.0
                ));
            }
            for &k in &order[..order.len() - 1] {
                let mut uv = entry.pcurve.eval(samples.ts[k]).point;
                if !uv.is_finite() {
                    return Err(format!(
                        "the p-curve of entry {ei} of loop {li} is not finite at t = {}",
                        samples.ts[k]
                    ));
                }
                if let Some(prev) = points.last() {
                    uv = unwrap_near(uv, prev.uv);
                }
                points.push(BoundaryPoint {
                    uv,
                    id: samples.ids[k],
                });
            }
            previous_end = Some(samples.ids[order[order.len() - 1]]);
        }
        let (Some(first), Some(end)) = (points.first().copied(), previous_end) else {
            return Err(format!("loop {li} is empty"));
        };
        if end != first.id {
            return Err(format!(
                "loop {li} does not close: it ends at vertex {end} but starts at vertex {}",
                first.id
            ));
        }
        // The closing point, unwrapped after the last one, must come back to the first: a loop
        // that comes back one period further wraps around the surface.
        if let Some(last) = points.last() {
            let closing = unwrap_near(first.uv, last.uv);
            if closing != first.uv {
                return Err(format!(
                    "loop {li} wraps around a periodic parameter (a trim around a closed surface without a seam edge is not supported yet)"
                ));
            }
        }
        if points.len() < 3 {
            return Err(format!("loop {li} has fewer than three points"));
        }
        loops.push(points);
    }
    // Holes shifted by whole periods next to the outer loop.
    if let Some((outer, holes)) = loops.split_first_mut() {
        let mean = |l: &BoundaryLoop| l.iter().map(|p| p.uv).sum::<DVec2>() / l.len() as f64;
        let centre = mean(outer);
        for hole in holes {
            let shift = unwrap_near(mean(hole), centre) - mean(hole);
            for p in hole.iter_mut() {
                p.uv += shift;
            }
        }
    }
    Ok(loops)
}
