//! Validation of a boundary representation: the checks that make a [`Solid`] safe for every
//! stage, each failure a typed [`TopologyError`].
//!
//! Checked, in this order: every id in range; finite geometry (faces on a grid, edges along
//! their parameter, vertices); every edge referenced by exactly the two face positions its uses
//! name (no free edge: a closed shell), traversed in opposite directions by them (consistent
//! orientation); every p-curve (or side) on its edge's curve and every edge end on its vertex
//! within the model tolerance; every loop closed within tolerance, simple, not crossing
//! another loop, outer counter-clockwise and holes clockwise inside it; no zero-area face.
//!
//! Distances are in mm against [`Solid::model_tolerance`]; loops are checked on their
//! polylines ([`crate::TrimLoop`]), which follow the p-curves within
//! [`crate::topology::trim::FLATNESS`] of the loop's extent.

use crate::topology::feature::{EdgeId, FaceId, VertexId};
use crate::topology::solid::{Boundary, EdgeOn, ParamSide, Solid};
use crate::topology::trim::TrimLoop;
use glam::{DVec2, DVec3};

/// Samples along an edge for the p-curve and finiteness checks.
const EDGE_SAMPLES: usize = 16;
/// Grid size per parameter of a face's finiteness check.
const FACE_SAMPLES: usize = 5;

/// Why a solid cannot be used.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum TopologyError {
    /// The solid has no face.
    #[error("the solid has no face")]
    Empty,
    /// An id names a face, edge or vertex that does not exist.
    #[error("{what} names {target}, which does not exist")]
    BadReference {
        /// Where the reference is.
        what: String,
        /// What it names.
        target: String,
    },
    /// A position, derivative or normal is not a finite number.
    #[error("{what} is not finite")]
    NonFinite {
        /// Which feature and where.
        what: String,
    },
    /// An edge is referenced by other than the two face positions its uses name: a free edge
    /// (open shell) or an edge shared by more than two faces.
    #[error(
        "edge {edge:?} is on {count} face boundaries where its uses name 2 (open shell, free or non-manifold edge)"
    )]
    EdgeUseCount {
        /// The edge.
        edge: EdgeId,
        /// How many face positions reference it.
        count: usize,
    },
    /// An edge's use names a face position that does not name the edge back.
    #[error("edge {edge:?} says it lies on face {face:?}, whose boundary does not hold it")]
    UseNotOnFace {
        /// The edge.
        edge: EdgeId,
        /// The face.
        face: FaceId,
    },
    /// Both faces of an edge traverse it in the same direction: their orientations disagree.
    #[error(
        "faces {faces:?} traverse edge {edge:?} in the same direction: inconsistent orientation"
    )]
    InconsistentOrientation {
        /// The edge.
        edge: EdgeId,
        /// Its two faces.
        faces: [FaceId; 2],
    },
    /// A p-curve (or a rectangle side) does not follow its edge's curve within tolerance.
    #[error(
        "edge {edge:?} on face {face:?} is {deviation:.3e} mm from the face's p-curve point (tolerance {tolerance:.1e} mm)"
    )]
    PCurveOffEdge {
        /// The edge.
        edge: EdgeId,
        /// The face.
        face: FaceId,
        /// Largest sampled distance (mm).
        deviation: f64,
        /// The model tolerance (mm).
        tolerance: f64,
    },
    /// An edge's end is not at its vertex.
    #[error("edge {edge:?} ends {gap:.3e} mm from its vertex {vertex:?}")]
    EdgeEndOffVertex {
        /// The edge.
        edge: EdgeId,
        /// The vertex.
        vertex: VertexId,
        /// Distance (mm).
        gap: f64,
    },
    /// Consecutive entries of a loop do not meet.
    #[error(
        "loop {loop_index} of face {face:?} is open: a gap of {gap:.3e} mm after entry {index}"
    )]
    LoopNotClosed {
        /// The face.
        face: FaceId,
        /// The loop.
        loop_index: usize,
        /// The entry after which the gap is.
        index: usize,
        /// Distance (mm) between the entry's end and the next one's start on the surface.
        gap: f64,
    },
    /// A loop crosses itself.
    #[error("loop {loop_index} of face {face:?} intersects itself")]
    SelfIntersectingLoop {
        /// The face.
        face: FaceId,
        /// The loop.
        loop_index: usize,
    },
    /// Two loops of a face cross.
    #[error("loops {loops:?} of face {face:?} cross")]
    LoopsCross {
        /// The face.
        face: FaceId,
        /// The two loops.
        loops: [usize; 2],
    },
    /// The outer loop runs clockwise, a hole counter-clockwise, or a hole lies outside the
    /// outer loop.
    #[error(
        "loop {loop_index} of face {face:?} is wrongly oriented or placed (outer loops run counter-clockwise, holes clockwise inside them)"
    )]
    WrongLoopOrientation {
        /// The face.
        face: FaceId,
        /// The loop.
        loop_index: usize,
    },
    /// A face encloses no area.
    #[error("face {face:?} has zero area")]
    ZeroAreaFace {
        /// The face.
        face: FaceId,
    },
}

/// Checks `solid` (see the module doc).
///
/// # Errors
/// The first [`TopologyError`] found.
pub fn validate(solid: &Solid) -> Result<(), TopologyError> {
    if solid.faces.is_empty() {
        return Err(TopologyError::Empty);
    }
    check_references(solid)?;
    check_finite(solid)?;
    check_edge_uses(solid)?;
    check_on_curves(solid)?;
    for (f, face) in solid.faces.iter().enumerate() {
        let id = FaceId(index32(f));
        match &face.trim {
            Some(trim) => check_loops(solid, id, &trim.loops)?,
            None => {
                let [u, v] = face.surface.domain();
                if !(u.span() > 0.0 && v.span() > 0.0) {
                    return Err(TopologyError::ZeroAreaFace { face: id });
                }
            }
        }
    }
    Ok(())
}

fn index32(i: usize) -> u32 {
    u32::try_from(i).expect("fewer than 2^32 features")
}

fn check_references(solid: &Solid) -> Result<(), TopologyError> {
    let (nf, ne, nv) = (solid.faces.len(), solid.edges.len(), solid.vertices.len());
    let bad = |what: String, target: String| Err(TopologyError::BadReference { what, target });
    for (f, face) in solid.faces.iter().enumerate() {
        for b in face.boundary {
            match b {
                Boundary::Edge(e) if e.0 as usize >= ne => {
                    return bad(format!("face {f}"), format!("edge {}", e.0));
                }
                Boundary::Vertex(v) if v.0 as usize >= nv => {
                    return bad(format!("face {f}"), format!("vertex {}", v.0));
                }
                _ => {}
            }
        }
        for l in face.trim.iter().flat_map(|t| &t.loops) {
            if l.entries.is_empty() {
                return bad(format!("face {f}"), "an empty loop".into());
            }
            for entry in &l.entries {
                if entry.edge.0 as usize >= ne {
                    return bad(format!("face {f}"), format!("edge {}", entry.edge.0));
                }
            }
        }
    }
    for (e, edge) in solid.edges.iter().enumerate() {
        for use_ in &edge.uses {
            let Some(face) = solid.faces.get(use_.face.0 as usize) else {
                return bad(format!("edge {e}"), format!("face {}", use_.face.0));
            };
            if let EdgeOn::Trim { loop_index, index } = use_.on {
                let exists = face
                    .trim
                    .as_ref()
                    .and_then(|t| t.loops.get(loop_index as usize))
                    .is_some_and(|l| (index as usize) < l.entries.len());
                if !exists {
                    return bad(
                        format!("edge {e}"),
                        format!("entry {index} of loop {loop_index} of face {}", use_.face.0),
                    );
                }
            }
        }
        for v in edge.ends.iter().flatten() {
            if v.0 as usize >= nv {
                return bad(format!("edge {e}"), format!("vertex {}", v.0));
            }
        }
    }
    for (v, vertex) in solid.vertices.iter().enumerate() {
        if vertex.faces.iter().any(|f| f.0 as usize >= nf) {
            return bad(format!("vertex {v}"), "a face".into());
        }
        if vertex.edges.iter().any(|e| e.0 as usize >= ne) {
            return bad(format!("vertex {v}"), "an edge".into());
        }
    }
    Ok(())
}

fn finite3(p: DVec3) -> bool {
    p.is_finite()
}

fn check_finite(solid: &Solid) -> Result<(), TopologyError> {
    for (v, vertex) in solid.vertices.iter().enumerate() {
        if !finite3(vertex.point) {
            return Err(TopologyError::NonFinite {
                what: format!("vertex {v}"),
            });
        }
    }
    for (e, edge) in solid.edges.iter().enumerate() {
        let r = edge.curve.domain();
        if !(r.min.is_finite() && r.max.is_finite() && r.max > r.min) {
            return Err(TopologyError::NonFinite {
                what: format!("the parameter range of edge {e}"),
            });
        }
        for k in 0..=EDGE_SAMPLES {
            let t = r.min + r.span() * k as f64 / EDGE_SAMPLES as f64;
            let c = edge.curve.eval(t);
            if !(finite3(c.point) && finite3(c.d1) && finite3(c.d2)) {
                return Err(TopologyError::NonFinite {
                    what: format!("edge {e} at t = {t}"),
                });
            }
        }
    }
    for (f, face) in solid.faces.iter().enumerate() {
        let [ru, rv] = face.surface.domain();
        if !(ru.min.is_finite() && ru.max.is_finite() && rv.min.is_finite() && rv.max.is_finite()) {
            return Err(TopologyError::NonFinite {
                what: format!("the parameter domain of face {f}"),
            });
        }
        for i in 0..=FACE_SAMPLES {
            for j in 0..=FACE_SAMPLES {
                let u = ru.min + ru.span() * i as f64 / FACE_SAMPLES as f64;
                let v = rv.min + rv.span() * j as f64 / FACE_SAMPLES as f64;
                let s = face.surface.eval(u, v);
                let all = [s.point, s.du, s.dv, s.duu, s.duv, s.dvv];
                if !all.into_iter().all(finite3) {
                    return Err(TopologyError::NonFinite {
                        what: format!("face {f} at (u, v) = ({u}, {v})"),
                    });
                }
            }
        }
    }
    Ok(())
}

/// Whether the position `on` of face `face` traverses its edge forwards (increasing t) when
/// the face's boundary is walked with the face on the left.
fn forward(solid: &Solid, face: FaceId, on: EdgeOn) -> bool {
    match on {
        // Counter-clockwise around the rectangle: +u along v_min, +v along u_max, -u along
        // v_max, -v along u_min.
        EdgeOn::Side(ParamSide::VMin | ParamSide::UMax)
        | EdgeOn::SideReversed(ParamSide::VMax | ParamSide::UMin) => true,
        EdgeOn::Side(ParamSide::VMax | ParamSide::UMin)
        | EdgeOn::SideReversed(ParamSide::VMin | ParamSide::UMax) => false,
        EdgeOn::Trim { loop_index, index } => {
            let trim = solid.face(face).trim.as_ref().expect("checked reference");
            !trim.loops[loop_index as usize].entries[index as usize].reversed
        }
    }
}

fn check_edge_uses(solid: &Solid) -> Result<(), TopologyError> {
    // Every face position that names an edge.
    let mut refs: Vec<Vec<(FaceId, EdgeOn)>> = vec![Vec::new(); solid.edges.len()];
    for (f, face) in solid.faces.iter().enumerate() {
        let id = FaceId(index32(f));
        for (side, b) in [
            ParamSide::UMin,
            ParamSide::UMax,
            ParamSide::VMin,
            ParamSide::VMax,
        ]
        .into_iter()
        .zip(face.boundary)
        {
            if let Boundary::Edge(e) = b {
                refs[e.0 as usize].push((id, EdgeOn::Side(side)));
            }
        }
        for (li, l) in face.trim.iter().flat_map(|t| t.loops.iter().enumerate()) {
            for (ei, entry) in l.entries.iter().enumerate() {
                refs[entry.edge.0 as usize].push((
                    id,
                    EdgeOn::Trim {
                        loop_index: index32(li),
                        index: index32(ei),
                    },
                ));
            }
        }
    }
    for (e, edge) in solid.edges.iter().enumerate() {
        let id = EdgeId(index32(e));
        if refs[e].len() != 2 {
            return Err(TopologyError::EdgeUseCount {
                edge: id,
                count: refs[e].len(),
            });
        }
        for use_ in &edge.uses {
            // A side is named by the face's boundary whichever way the edge runs along it.
            let named = refs[e].iter().any(|&(face, on)| {
                face == use_.face
                    && (on == use_.on || on.side().is_some() && on.side() == use_.on.side())
            });
            if !named {
                return Err(TopologyError::UseNotOnFace {
                    edge: id,
                    face: use_.face,
                });
            }
        }
        let [a, b] = edge.uses;
        if a.face == b.face && (a.on == b.on || a.on.side().is_some() && a.on.side() == b.on.side())
        {
            return Err(TopologyError::EdgeUseCount { edge: id, count: 1 });
        }
        if forward(solid, a.face, a.on) == forward(solid, b.face, b.on) {
            return Err(TopologyError::InconsistentOrientation {
                edge: id,
                faces: [a.face, b.face],
            });
        }
    }
    Ok(())
}

fn check_on_curves(solid: &Solid) -> Result<(), TopologyError> {
    let tolerance = solid.model_tolerance();
    for (e, edge) in solid.edges.iter().enumerate() {
        let id = EdgeId(index32(e));
        let r = edge.curve.domain();
        for use_ in &edge.uses {
            let surface = &solid.face(use_.face).surface;
            let [ru, rv] = surface.domain();
            let mut deviation: f64 = 0.0;
            for k in 0..=EDGE_SAMPLES {
                let t = r.min + r.span() * k as f64 / EDGE_SAMPLES as f64;
                let [u, v] = solid.use_params(use_, t);
                let on_face = surface.eval(ru.normalize(u), rv.normalize(v)).point;
                let d = on_face.distance(edge.curve.eval(t).point);
                // NaN counts as off the edge.
                deviation = if d.is_nan() {
                    f64::INFINITY
                } else {
                    deviation.max(d)
                };
            }
            if deviation > tolerance {
                return Err(TopologyError::PCurveOffEdge {
                    edge: id,
                    face: use_.face,
                    deviation,
                    tolerance,
                });
            }
        }
        if let Some(ends) = edge.ends {
            for (vertex, t) in ends.into_iter().zip([r.min, r.max]) {
                let gap = solid
                    .vertex(vertex)
                    .point
                    .distance(edge.curve.eval(t).point);
                if gap.is_nan() || gap > tolerance {
                    return Err(TopologyError::EdgeEndOffVertex {
                        edge: id,
                        vertex,
                        gap,
                    });
                }
            }
        }
    }
    Ok(())
}

fn check_loops(solid: &Solid, face: FaceId, loops: &[TrimLoop]) -> Result<(), TopologyError> {
    let tolerance = solid.model_tolerance();
    let surface = &solid.face(face).surface;
    let [ru, rv] = surface.domain();
    let at = |p: DVec2| surface.eval(ru.normalize(p.x), rv.normalize(p.y)).point;
    if loops.is_empty() {
        return Err(TopologyError::ZeroAreaFace { face });
    }
    for (li, l) in loops.iter().enumerate() {
        let n = l.entries.len();
        for (i, entry) in l.entries.iter().enumerate() {
            let next = &l.entries[(i + 1) % n];
            let gap = at(entry.end()).distance(at(next.start()));
            if gap.is_nan() || gap > tolerance {
                return Err(TopologyError::LoopNotClosed {
                    face,
                    loop_index: li,
                    index: i,
                    gap,
                });
            }
        }
        let segments: Vec<(DVec2, DVec2)> = l.segments().collect();
        if has_crossing(&segments, &segments, true) {
            return Err(TopologyError::SelfIntersectingLoop {
                face,
                loop_index: li,
            });
        }
        let area = l.signed_area();
        let wrong = if li == 0 { area <= 0.0 } else { area >= 0.0 };
        if wrong {
            return Err(TopologyError::WrongLoopOrientation {
                face,
                loop_index: li,
            });
        }
    }
    for a in 0..loops.len() {
        for b in a + 1..loops.len() {
            let sa: Vec<_> = loops[a].segments().collect();
            let sb: Vec<_> = loops[b].segments().collect();
            if has_crossing(&sa, &sb, false) {
                return Err(TopologyError::LoopsCross {
                    face,
                    loops: [a, b],
                });
            }
        }
    }
    // Holes inside the outer loop: a point of each hole has winding +1 about the outer loop.
    let outer: Vec<_> = loops[0].segments().collect();
    for (li, l) in loops.iter().enumerate().skip(1) {
        let p = l.entries[0].start();
        if winding(&outer, p) == 0 {
            return Err(TopologyError::WrongLoopOrientation {
                face,
                loop_index: li,
            });
        }
    }
    let total: f64 = loops.iter().map(TrimLoop::signed_area).sum();
    let (lo, hi) = {
        let mut lo = DVec2::splat(f64::INFINITY);
        let mut hi = DVec2::splat(f64::NEG_INFINITY);
        for (a, _) in &outer {
            lo = lo.min(*a);
            hi = hi.max(*a);
        }
        (lo, hi)
    };
    let box_area = (hi - lo).x * (hi - lo).y;
    if total.is_nan() || total <= 1e-12 * box_area {
        return Err(TopologyError::ZeroAreaFace { face });
    }
    Ok(())
}

/// Winding number of a closed polyline (as segments) around `p`.
fn winding(segments: &[(DVec2, DVec2)], p: DVec2) -> i32 {
    let mut w = 0;
    for &(a, b) in segments {
        if a.y <= p.y {
            if b.y > p.y && (b - a).perp_dot(p - a) > 0.0 {
                w += 1;
            }
        } else if b.y <= p.y && (b - a).perp_dot(p - a) < 0.0 {
            w -= 1;
        }
    }
    w
}

/// Whether a segment of `a` properly crosses a segment of `b` (touching at shared end points
/// does not count). With `same`, `a` and `b` are one closed polyline and neighbouring segments
/// are skipped.
fn has_crossing(a: &[(DVec2, DVec2)], b: &[(DVec2, DVec2)], same: bool) -> bool {
    let n = a.len();
    for (i, &(p, q)) in a.iter().enumerate() {
        let (lo, hi) = (p.min(q), p.max(q));
        for (j, &(r, s)) in b.iter().enumerate() {
            if same && (j <= i || j == i + 1 || (i == 0 && j == n - 1)) {
                continue;
            }
            if r.max(s).x < lo.x || r.min(s).x > hi.x || r.max(s).y < lo.y || r.min(s).y > hi.y {
                continue;
            }
            if proper_crossing(p, q, r, s) {
                return true;
            }
        }
    }
    false
}

/// Whether segments pq and rs cross at a point interior to both.
fn proper_crossing(p: DVec2, q: DVec2, r: DVec2, s: DVec2) -> bool {
    let d1 = (q - p).perp_dot(r - p);
    let d2 = (q - p).perp_dot(s - p);
    let d3 = (s - r).perp_dot(p - r);
    let d4 = (s - r).perp_dot(q - r);
    d1 * d2 < 0.0 && d3 * d4 < 0.0
}
