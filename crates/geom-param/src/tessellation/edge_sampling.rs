//! Adaptive sampling of a solid's edges, and of the seams where a face's periodic parameter is
//! cut open, into the shared mesh vertices both faces along them use.
//!
//! A piece [t_a, t_b] of an edge is accepted when its chord P_a P_b is no longer than the target
//! length of the faces on either side and deviates by at most the edge budget, at the quarter
//! points s = 1/4, 1/2, 3/4, both from the curve (|C(t_a + s Δt) - lerp(P_a, P_b, s)|) and from
//! each face's surface along the straight p-curve chord (|S(lerp(uv_a, uv_b, s)) - lerp(P_a,
//! P_b, s)|): the second is what a triangle with that side interpolates. Rejected pieces are
//! halved. Every sample becomes one vertex, so the faces on both sides meet exactly.

use crate::curves::curve::ParamRange;
use crate::tessellation::face_metric::FaceMetric;
use crate::tessellation::plane_map::PlaneMap;
use crate::tessellation::vertex_table::VertexTable;
use crate::topology::feature::{EdgeId, FaceId, FeatureLocation, VertexId};
use crate::topology::solid::{EdgeOn, ParamSide, Solid};
use glam::{DVec2, DVec3};

/// Upper bound on the samples of one edge or seam, which keeps sampling finite for absurd
/// tolerances; the faces' measured error then reports what was reached.
const MAX_SAMPLES: usize = 1 << 16;
/// Where a piece's deviation from its chord is sampled.
const FRACTIONS: [f64; 3] = [0.25, 0.5, 0.75];
/// Pieces an edge starts from before refinement: enough that a closed curve is not taken for a
/// point and an S-shaped piece is not taken for its chord.
const INITIAL_PIECES_CLOSED: usize = 8;
const INITIAL_PIECES_OPEN: usize = 2;

/// The samples of one edge or seam, in increasing parameter.
#[derive(Clone, Debug, Default)]
pub(crate) struct EdgeSamples {
    /// Parameters, increasing, from the domain's min to its max.
    pub ts: Vec<f64>,
    /// The vertex of each sample. For a closed (periodic) edge the last equals the first.
    pub ids: Vec<u32>,
}

/// Splits every piece between consecutive `initial` parameters in halves until `accept` holds
/// for it, depth first, and returns the resulting parameters in order. Stops splitting once
/// [`MAX_SAMPLES`] are reached.
fn subdivide(
    initial: &[f64],
    mut accept: impl FnMut(f64, f64) -> Result<bool, String>,
) -> Result<Vec<f64>, String> {
    let mut out = vec![initial[0]];
    for w in initial.windows(2) {
        let mut a = w[0];
        let mut stack = vec![w[1]];
        while let Some(&b) = stack.last() {
            if out.len() + stack.len() < MAX_SAMPLES && !accept(a, b)? {
                stack.push(0.5 * (a + b));
            } else {
                out.push(b);
                a = b;
                stack.pop();
            }
        }
    }
    Ok(out)
}

/// Evenly spaced parameters over `range` in `pieces` pieces, merged with `required` ones.
fn initial_params(range: ParamRange, pieces: usize, required: &[f64]) -> Vec<f64> {
    let mut ts: Vec<f64> = (0..=pieces)
        .map(|k| range.min + range.span() * k as f64 / pieces as f64)
        .collect();
    ts.extend(required.iter().copied().filter(|t| t.is_finite()));
    ts.sort_by(f64::total_cmp);
    let gap = 1e-9 * range.span();
    ts.dedup_by(|b, a| *b - *a <= gap);
    // Keep the domain's ends exact.
    if let Some(last) = ts.last_mut() {
        *last = range.max;
    }
    ts[0] = range.min;
    ts
}

/// Whether the chord from `pa` to `pb` is within `max_length` and every `deviation(s)` at the
/// quarter points is within `budget`.
fn chord_accepts(
    pa: DVec3,
    pb: DVec3,
    budget: f64,
    max_length: f64,
    mut exact_at: impl FnMut(f64) -> Result<Vec<DVec3>, String>,
) -> Result<bool, String> {
    if pa.distance(pb) > max_length {
        return Ok(false);
    }
    for s in FRACTIONS {
        let linear = pa.lerp(pb, s);
        for p in exact_at(s)? {
            if p.distance(linear) > budget {
                return Ok(false);
            }
        }
    }
    Ok(true)
}

/// The edge parameters that must be samples of edge `id`: where an untrimmed face with a
/// periodic parameter running along the edge is cut open (its domain's start).
pub(crate) fn required_params(solid: &Solid, id: EdgeId) -> Vec<f64> {
    let edge = solid.edge(id);
    let range = edge.curve.domain();
    let mut out = Vec::new();
    for use_ in &edge.uses {
        let face = solid.face(use_.face);
        if face.trim.is_some() {
            continue;
        }
        if let EdgeOn::Side(side) = use_.on {
            let running = match side {
                ParamSide::UMin | ParamSide::UMax => face.surface.domain()[1],
                ParamSide::VMin | ParamSide::VMax => face.surface.domain()[0],
            };
            if running.periodic {
                out.push(range.normalize(running.min));
            }
        }
    }
    out
}

/// Samples edge `id` (see the module docs) into vertices of `table`: its end vertices at the
/// domain's ends of an open edge, `Edge { id, t }` vertices elsewhere.
///
/// # Errors
/// A reason when the curve or a face along it does not evaluate to finite points.
pub(crate) fn sample_edge(
    solid: &Solid,
    id: EdgeId,
    budget: f64,
    metrics: &[FaceMetric],
    table: &mut VertexTable,
) -> Result<EdgeSamples, String> {
    let edge = solid.edge(id);
    let range = edge.curve.domain();
    if !(range.min.is_finite() && range.max.is_finite() && range.max > range.min) {
        return Err(format!(
            "edge {} has the empty or unbounded domain [{}, {}]",
            id.0, range.min, range.max
        ));
    }
    let max_length = edge
        .uses
        .iter()
        .map(|u| metrics[u.face.0 as usize].target_length)
        .fold(f64::INFINITY, f64::min);
    let ends = if range.periodic { None } else { edge.ends };
    let point = |t: f64| -> Result<DVec3, String> {
        let p = match ends {
            Some([a, _]) if t == range.min => solid.vertex(a).point,
            Some([_, b]) if t == range.max => solid.vertex(b).point,
            _ => edge.curve.eval(t).point,
        };
        if p.is_finite() {
            Ok(p)
        } else {
            Err(format!("edge {} is not finite at t = {t}", id.0))
        }
    };
    let face_point = |face: FaceId, uv: DVec2| -> Result<DVec3, String> {
        let p = solid.eval_face(face, uv.x, uv.y).point;
        if p.is_finite() {
            Ok(p)
        } else {
            Err(format!(
                "face {} is not finite at (u, v) = ({}, {}) along edge {}",
                face.0, uv.x, uv.y, id.0
            ))
        }
    };
    let pieces = if range.periodic {
        INITIAL_PIECES_CLOSED
    } else {
        INITIAL_PIECES_OPEN
    };
    let initial = initial_params(range, pieces, &required_params(solid, id));
    let ts = subdivide(&initial, |ta, tb| {
        let (pa, pb) = (point(ta)?, point(tb)?);
        let uvs: Vec<(FaceId, DVec2, DVec2)> = edge
            .uses
            .iter()
            .map(|u| {
                let [ua, va] = solid.use_params(u, ta);
                let [ub, vb] = solid.use_params(u, tb);
                (u.face, DVec2::new(ua, va), DVec2::new(ub, vb))
            })
            .collect();
        chord_accepts(pa, pb, budget, max_length, |s| {
            let mut out = vec![point(ta + s * (tb - ta))?];
            for &(face, a, b) in &uvs {
                out.push(face_point(face, a.lerp(b, s))?);
            }
            Ok(out)
        })
    })?;

    let last = ts.len() - 1;
    let mut ids = Vec::with_capacity(ts.len());
    for (k, &t) in ts.iter().enumerate() {
        let vertex = match ends {
            Some([a, _]) if k == 0 => Some(a),
            Some([_, b]) if k == last => Some(b),
            _ => None,
        };
        let vid = match vertex {
            Some(VertexId(v)) => v,
            None if range.periodic && k == last => ids[0],
            None => table.add(solid, FeatureLocation::Edge { id, t }),
        };
        if range.periodic && k == last {
            ids.push(vid);
            continue;
        }
        for u in &edge.uses {
            let [fu, fv] = solid.use_params(u, t);
            let location = FeatureLocation::Face {
                id: u.face,
                u: fu,
                v: fv,
            };
            if let Some(n) = solid.face_normal_at(&location) {
                table.add_normal(vid, u.face, n);
            }
        }
        ids.push(vid);
    }
    Ok(EdgeSamples { ts, ids })
}

/// Which parameter a seam runs along.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum SeamAxis {
    /// The seam is u = const and runs along v (the cut of a periodic u).
    AlongV,
    /// The seam is v = const and runs along u (the cut of a periodic v).
    AlongU,
}

/// The seam of a face whose periodic parameter is cut open: the parameter line at `fixed` (the
/// periodic parameter's domain start) running over `range` of the other parameter, from vertex
/// `ends[0]` to `ends[1]`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Seam<'a> {
    /// The face.
    pub face: FaceId,
    /// Which parameter the seam runs along.
    pub axis: SeamAxis,
    /// The value of the cut (periodic) parameter.
    pub fixed: f64,
    /// The range of the running parameter.
    pub range: ParamRange,
    /// The vertices at the running parameter's min and max.
    pub ends: [u32; 2],
    /// The face's triangulation plane and the longest a seam piece may be in it (mm), or
    /// `None` for a seam along which the plane is not stretched (a pole's ring).
    pub plane: Option<(&'a PlaneMap, f64)>,
}

/// Samples `seam` like an edge; its interior samples become face vertices.
///
/// # Errors
/// A reason when the surface does not evaluate to finite points along the seam.
pub(crate) fn sample_seam(
    solid: &Solid,
    seam: &Seam<'_>,
    budget: f64,
    max_length: f64,
    table: &mut VertexTable,
) -> Result<EdgeSamples, String> {
    let Seam {
        face,
        axis,
        fixed,
        range,
        ends,
        plane,
    } = *seam;
    let uv = |s: f64| match axis {
        SeamAxis::AlongV => DVec2::new(fixed, s),
        SeamAxis::AlongU => DVec2::new(s, fixed),
    };
    let point = |s: f64| -> Result<DVec3, String> {
        let q = uv(s);
        let p = solid.eval_face(face, q.x, q.y).point;
        if p.is_finite() {
            Ok(p)
        } else {
            Err(format!(
                "its surface is not finite at (u, v) = ({}, {}) on its seam",
                q.x, q.y
            ))
        }
    };
    let ends_at = |s: f64| {
        if s == range.min {
            Some(table.get(ends[0]).position)
        } else if s == range.max {
            Some(table.get(ends[1]).position)
        } else {
            None
        }
    };
    let position = |s: f64| -> Result<DVec3, String> {
        match ends_at(s) {
            Some(p) => Ok(p),
            None => point(s),
        }
    };
    let pieces = if ends[0] == ends[1] {
        INITIAL_PIECES_CLOSED
    } else {
        INITIAL_PIECES_OPEN
    };
    let initial = initial_params(range, pieces, &[]);
    let ts = subdivide(&initial, |a, b| {
        let plane_length =
            |(map, _): (&PlaneMap, f64)| map.plane_point(uv(a)).distance(map.plane_point(uv(b)));
        if plane.is_some_and(|p| plane_length(p) > p.1) {
            return Ok(false);
        }
        let (pa, pb) = (position(a)?, position(b)?);
        chord_accepts(pa, pb, budget, max_length, |s| {
            Ok(vec![point(a + s * (b - a))?])
        })
    })?;
    let last = ts.len() - 1;
    let mut ids = Vec::with_capacity(ts.len());
    for (k, &s) in ts.iter().enumerate() {
        let id = if k == 0 {
            ends[0]
        } else if k == last {
            ends[1]
        } else {
            let q = uv(s);
            let location = FeatureLocation::Face {
                id: face,
                u: q.x,
                v: q.y,
            };
            let id = table.add(solid, location);
            if let Some(n) = solid.face_normal_at(&location) {
                table.add_normal(id, face, n);
            }
            id
        };
        ids.push(id);
    }
    Ok(EdgeSamples { ts, ids })
}
