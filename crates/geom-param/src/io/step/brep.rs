//! The mapping of a STEP B-rep (MANIFOLD_SOLID_BREP or BREP_WITH_VOIDS with closed shells of
//! ADVANCED_FACEs) into a [`Solid`]: edges oriented from their first to their second vertex,
//! p-curves projected per face use, healing of the file's gaps within a bounded tolerance.

use crate::curves::curve::{Curve, ParamRange};
use crate::curves::curve2::Curve2;
use crate::io::step::error::StepError;
use crate::io::step::geometry::{CurveSpec, GeometryReader, SurfaceSpec, range};
use crate::io::step::graph::{Entity, Graph};
use crate::io::step::pcurve::{FitInput, MappedPCurve, fit};
use crate::io::step::units::{context_of, units_of};
use crate::object_model::{MeshOptions, ModelError, ObjectModel};
use crate::surfaces::reversed_surface::ReversedSurface;
use crate::surfaces::surface::Surface;
use crate::topology::convexity::classify_convexity;
use crate::topology::feature::{EdgeId, FaceId, VertexId};
use crate::topology::solid::{
    Boundary, Edge, EdgeConvexity, EdgeOn, EdgeUse, Face, FaceConvexity, Solid, Vertex,
};
use crate::topology::trim::{Trim, TrimEntry, TrimLoop};
use crate::topology::validate::validate;
use glam::{DVec2, DVec3};
use std::collections::HashMap;
use std::f64::consts::TAU;
use std::sync::Arc;

/// Uncertainty assumed when the file states none (mm).
pub const DEFAULT_UNCERTAINTY_MM: f64 = 1e-6;
/// The healed model tolerance may reach this multiple of the file's uncertainty (edges that
/// miss their faces, loops that close, vertices off their edges); farther is refused.
pub const MAX_HEAL_FACTOR: f64 = 1000.0;
/// The p-curve fit's share of the file's uncertainty.
const FIT_SHARE: f64 = 0.25;
/// The least uncertainty used, relative to the model's extent (largest coordinate, mm): a
/// file may state an uncertainty (1e-13 mm in some CAx-IF test files) below what a surface
/// evaluated in f64 at that distance from the origin can resolve (about 1e-16 of it per
/// rounding, times the conditioning of a projection); fits and gaps are measured against
/// the larger of the two, so exact geometry written with rounding is not refused.
pub const UNCERTAINTY_FLOOR: f64 = 4e-12;
/// The healed tolerance's margin over the largest measured gap.
const HEAL_MARGIN: f64 = 2.0;
/// Margin of a free parameter's domain around the face's loops, relative to their extent.
const DOMAIN_MARGIN: f64 = 0.25;
/// Most faces of one solid.
pub const MAX_FACES: usize = 100_000;

/// One solid read from a STEP file.
#[derive(Debug)]
pub struct StepSolid {
    /// The B-rep's name (its `name` attribute), or `#id` when empty.
    pub name: String,
    /// The `#id` of its MANIFOLD_SOLID_BREP or BREP_WITH_VOIDS, or of the CLOSED_SHELL a
    /// SHELL_BASED_SURFACE_MODEL lists.
    pub id: u64,
    /// The solid, in millimetres, validated, its convexity classified.
    pub solid: Solid,
    /// Where its p-curves came from (the file's PCURVEs or projections).
    pub pcurves: PCurveCount,
}

impl StepSolid {
    /// Prepares the solid for queries ([`ObjectModel::from_solid`]: convexity, meshes,
    /// components, hulls) under its name.
    ///
    /// # Errors
    /// As [`ObjectModel::from_solid`].
    pub fn into_model(self, options: &MeshOptions) -> Result<ObjectModel, ModelError> {
        ObjectModel::from_solid(self.name, self.solid, options)
    }
}

struct EdgeRecord {
    /// The EDGE_CURVE's id.
    step_id: u64,
    /// Its edge_geometry's id (a SURFACE_CURVE or SEAM_CURVE lists the file's p-curves);
    /// 0 for a seam the reader added.
    geometry_id: u64,
    /// dt_file / dt of the edge's parameter: ±1 for its sense, over radians per angle unit
    /// for a conic (whose file parameter is an angle).
    rate: f64,
    curve: Box<dyn Curve>,
    ends: [u64; 2],
    uses: Vec<EdgeUse>,
}

struct Builder<'g, 'a> {
    reader: GeometryReader<'g, 'a>,
    solid_id: u64,
    uncertainty: f64,
    fit_tolerance: f64,
    vertices: HashMap<u64, DVec3>,
    edges: Vec<EdgeRecord>,
    edge_index: HashMap<u64, usize>,
    /// Largest gap found (mm): edge to face, edge end to vertex, loop closure.
    worst_gap: f64,
    /// P-curves taken from the file's PCURVEs, and projected.
    pcurves: PCurveCount,
    /// Whether the file's PCURVEs are tried before fitting a projection.
    use_file_pcurves: bool,
}

/// How a solid's p-curves were made.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct PCurveCount {
    /// The file's own PCURVEs, which agreed with the projection within the uncertainty.
    pub from_file: usize,
    /// Fitted to the projection of the 3D edge (no PCURVE in the file, one on another
    /// surface, of a type or surface the reader does not map, or one that disagreed).
    pub projected: usize,
}

/// Reads solid `root` (a MANIFOLD_SOLID_BREP, a BREP_WITH_VOIDS, or a CLOSED_SHELL of a
/// surface model), whose representation lists `item` (the solid itself, or the
/// SHELL_BASED_SURFACE_MODEL holding the shell).
pub(crate) fn read_solid(graph: &Graph<'_>, root: u64, item: u64) -> Result<StepSolid, StepError> {
    match read_solid_with(graph, root, item, true) {
        // The file's p-curves agree with the edges within the fit tolerance, but where a
        // loop is tight (a tangent arc along a line) that much can make it cross itself where
        // the projections would not: the solid is read again from projections alone.
        Err(StepError::Topology { .. }) => read_solid_with(graph, root, item, false),
        other => other,
    }
}

/// [`read_solid`], with the file's PCURVEs used where they agree or never.
fn read_solid_with(
    graph: &Graph<'_>,
    root: u64,
    item: u64,
    use_file_pcurves: bool,
) -> Result<StepSolid, StepError> {
    let top = graph.root(root).ok_or(StepError::NoSolid)?;
    let context = context_of(graph, item).ok_or(StepError::Units {
        id: root,
        reason: "no representation context with units holds the solid".into(),
    })?;
    let units = units_of(graph, context)?;
    let uncertainty = units.uncertainty_mm.unwrap_or(DEFAULT_UNCERTAINTY_MM);
    let mut name_attr = top.string(0);
    if (name_attr.trim().is_empty() || name_attr == "NONE") && item != root {
        name_attr = graph.root(item).map(|m| m.string(0)).unwrap_or_default();
    }
    let name = if name_attr.trim().is_empty() || name_attr == "NONE" {
        format!("#{root}")
    } else {
        name_attr
    };
    let mut builder = Builder {
        reader: GeometryReader {
            graph,
            scale: units.length_mm,
            angle: units.angle_rad,
        },
        solid_id: root,
        uncertainty,
        fit_tolerance: FIT_SHARE * uncertainty,
        vertices: HashMap::new(),
        edges: Vec::new(),
        edge_index: HashMap::new(),
        worst_gap: 0.0,
        pcurves: PCurveCount::default(),
        use_file_pcurves,
    };
    // Shells: (closed shell, faces flipped).
    let outer = if top.record.has("CLOSED_SHELL") {
        root
    } else {
        top.reference(1)?
    };
    let mut shells = vec![(outer, false)];
    if top.record.has("BREP_WITH_VOIDS") {
        for void in top.ref_list(2)? {
            let v = graph.get_as(&top, void, "ORIENTED_CLOSED_SHELL", "a void shell")?;
            let shell = v.reference(2)?;
            shells.push((shell, !v.boolean(3)?));
        }
    }
    let mut faces_in: Vec<(Entity<'_>, bool)> = Vec::new();
    for (shell, flip) in shells {
        let s = graph.get(&top, shell)?;
        if s.record.parts.len() != 1 || s.record.parts[0].0 != "CLOSED_SHELL" {
            return Err(s.unsupported("a solid's shell (a CLOSED_SHELL is needed)"));
        }
        for f in s.ref_list(1)? {
            let face = graph.get(&s, f)?;
            if !(face.record.has("ADVANCED_FACE") || face.record.has("FACE_SURFACE")) {
                return Err(face.unsupported("a shell's face"));
            }
            faces_in.push((face, flip));
            if faces_in.len() > MAX_FACES {
                return Err(StepError::TooLarge {
                    what: "faces of one solid",
                    limit: MAX_FACES,
                });
            }
        }
    }
    // The model's extent, for the provisional domains of free parameters.
    let mut faces = Vec::with_capacity(faces_in.len());
    let mut pending = Vec::with_capacity(faces_in.len());
    for (face, flip) in &faces_in {
        pending.push(builder.read_face(face, *flip)?);
    }
    let extent = builder
        .vertices
        .values()
        .fold(1.0_f64, |m, p| m.max(p.abs().max_element()));
    let big = 8.0 * extent;
    builder.uncertainty = builder.uncertainty.max(UNCERTAINTY_FLOOR * extent);
    builder.fit_tolerance = FIT_SHARE * builder.uncertainty;
    for (fi, p) in pending.into_iter().enumerate() {
        let face_id = FaceId(u32::try_from(fi).map_err(|_| StepError::TooLarge {
            what: "faces of one solid",
            limit: MAX_FACES,
        })?);
        faces.push(builder.build_face(p, face_id, big)?);
    }
    builder.finish(name, faces)
}

/// One entry of a loop as read: (edge index, reversed, ORIENTED_EDGE id).
type LoopEntry = (usize, bool, u64);
/// A loop as read: (EDGE_LOOP id, entries).
type ReadLoop = (u64, Vec<LoopEntry>);
/// A loop that wraps once around a periodic u: (EDGE_LOOP id, entries, +1 or −1).
type WrappingLoop = (u64, Vec<LoopEntry>, f64);
/// One entry with its p-curve: (edge index, reversed, p-curve).
type FittedEntry = (usize, bool, Box<dyn crate::Curve2>);

/// What every loop fit of one face shares.
struct LoopContext<'s> {
    face: u64,
    surface: &'s dyn Surface,
    guess: &'s dyn Fn(DVec3) -> Option<[f64; 2]>,
    periods: [f64; 2],
    /// Parameters in which the surface closes without being periodic.
    closed: [bool; 2],
    /// The ids a PCURVE of this face names as its basis surface.
    surface_ids: &'s [u64],
    /// File (u, v) to model (u, v) factors, a reversed face's v negated; `None` where the
    /// file's p-curves are not mapped.
    pcurve_scale: Option<DVec2>,
}

/// Samples along each side of the domain compared with the opposite side to find a surface
/// closed in that parameter.
const CLOSED_SAMPLES: usize = 9;

/// Whether the surface closes in each non-periodic parameter: S(min, t) and S(max, t) (or
/// S(t, min) and S(t, max)) within `tolerance` at [`CLOSED_SAMPLES`] values of the other
/// parameter.
fn closed_parameters(surface: &dyn Surface, tolerance: f64) -> [bool; 2] {
    let d = surface.domain();
    [0, 1].map(|i| {
        if d[i].periodic {
            return false;
        }
        let o = d[1 - i];
        (0..CLOSED_SAMPLES).all(|k| {
            let t = o.min + o.span() * k as f64 / (CLOSED_SAMPLES - 1) as f64;
            let (a, b) = if i == 0 {
                (surface.eval(d[0].min, t), surface.eval(d[0].max, t))
            } else {
                (surface.eval(t, d[1].min), surface.eval(t, d[1].max))
            };
            a.point.distance(b.point) <= tolerance
        })
    })
}

/// One loop's p-curves.
struct FittedLoop {
    entries: Vec<FittedEntry>,
    /// Whole periods between the loop's end and its start in (u, v) (0 for a loop that
    /// closes in the parameter plane).
    wrap: [i32; 2],
    /// Twice the signed area of the loop in (u, v), sampled.
    area: f64,
}

/// A face read but not yet built: its surface, sense and loops of (edge index, reversed).
struct PendingFace<'a> {
    entity: Entity<'a>,
    /// The face's surface and, through RECTANGULAR_TRIMMED_SURFACEs, its basis: the ids a
    /// PCURVE of this face may name.
    surface_ids: Vec<u64>,
    surface: SurfaceSpec,
    sense: bool,
    loops: Vec<ReadLoop>,
}

impl<'g, 'a> Builder<'g, 'a> {
    fn vertex(&mut self, from: &Entity<'_>, id: u64) -> Result<DVec3, StepError> {
        if let Some(p) = self.vertices.get(&id) {
            return Ok(*p);
        }
        let v = self
            .reader
            .graph
            .get_as(from, id, "VERTEX_POINT", "an edge's vertex")?;
        let p = self.reader.point(&v, v.reference(1)?)?;
        self.vertices.insert(id, p);
        Ok(p)
    }

    fn edge(&mut self, from: &Entity<'_>, id: u64) -> Result<usize, StepError> {
        if let Some(&i) = self.edge_index.get(&id) {
            return Ok(i);
        }
        let e = self
            .reader
            .graph
            .get_as(from, id, "EDGE_CURVE", "an oriented edge's edge")?;
        let (v1, v2) = (e.reference(1)?, e.reference(2)?);
        let (p1, p2) = (self.vertex(&e, v1)?, self.vertex(&e, v2)?);
        let geometry_id = e.reference(3)?;
        let spec = self.reader.curve(&e, geometry_id)?;
        let mut sense = if e.boolean(4)? { 1.0 } else { -1.0 };
        // A line runs from its first vertex to its second whatever same_sense says (some
        // exporters write it inconsistently for lines; the vertices decide).
        if let CurveSpec::Line { direction, .. } = &spec {
            sense = if (p2 - p1).dot(*direction) >= 0.0 {
                1.0
            } else {
                -1.0
            };
        }
        let closed = v1 == v2 || p1.distance(p2) <= self.uncertainty;
        let (t1, t2) = match &spec {
            CurveSpec::Line { .. } => (spec.param_of(p1, sense), spec.param_of(p2, sense)),
            CurveSpec::Circle { .. } | CurveSpec::Ellipse { .. } => {
                let t1 = spec.param_of(p1, sense);
                let mut t2 = spec.param_of(p2, sense);
                if closed {
                    t2 = t1 + TAU;
                } else {
                    while t2 <= t1 {
                        t2 += TAU;
                    }
                }
                (t1, t2)
            }
            CurveSpec::Nurbs(_) => {
                let natural = spec
                    .build(
                        spec.natural_domain()
                            .ok_or_else(|| e.malformed("empty knot vector"))?,
                        1.0,
                    )
                    .map_err(|g| e.geometry(g))?;
                let d = natural.domain();
                if closed {
                    if sense > 0.0 {
                        (d.min, d.max)
                    } else {
                        (-d.max, -d.min)
                    }
                } else {
                    let mut a = nearest_param(natural.as_ref(), p1);
                    let mut b = nearest_param(natural.as_ref(), p2);
                    // On a closed B-spline (C(min) = C(max)) a vertex at the closure point
                    // has two parameters: take the one that runs the edge in its sense.
                    let closure = natural.eval(d.min).point;
                    let ring = closure.distance(natural.eval(d.max).point) <= self.uncertainty;
                    if ring && sense * a >= sense * b {
                        let (first, last) = if sense > 0.0 {
                            (d.min, d.max)
                        } else {
                            (d.max, d.min)
                        };
                        if p1.distance(closure) <= self.uncertainty {
                            a = first;
                        }
                        if p2.distance(closure) <= self.uncertainty {
                            b = last;
                        }
                    }
                    (sense * a, sense * b)
                }
            }
        };
        if !(t1.is_finite() && t2.is_finite() && t2 > t1) {
            return Err(e.malformed(format!(
                "its vertices are not in the order of its curve (parameters {t1} and {t2})"
            )));
        }
        let curve = spec
            .build(range(t1, t2), sense)
            .map_err(|g| e.geometry(g))?;
        for (p, t) in [(p1, t1), (p2, t2)] {
            let gap = curve.eval(t).point.distance(p);
            self.worst_gap = self
                .worst_gap
                .max(if gap.is_nan() { f64::INFINITY } else { gap });
        }
        let rate = match spec {
            CurveSpec::Circle { .. } | CurveSpec::Ellipse { .. } => sense / self.reader.angle,
            _ => sense,
        };
        self.edges.push(EdgeRecord {
            step_id: id,
            geometry_id,
            rate,
            curve,
            ends: [v1, v2],
            uses: Vec::new(),
        });
        let i = self.edges.len() - 1;
        self.edge_index.insert(id, i);
        Ok(i)
    }

    fn read_face(&mut self, face: &Entity<'a>, flip: bool) -> Result<PendingFace<'a>, StepError> {
        let graph = self.reader.graph;
        let f = Entity {
            params: face
                .record
                .part("ADVANCED_FACE")
                .or_else(|| face.record.part("FACE_SURFACE"))
                .unwrap_or(face.params),
            ..*face
        };
        let surface = self.reader.surface(&f, f.reference(2)?)?;
        let mut surface_ids = vec![f.reference(2)?];
        while let Some(t) = graph
            .root(*surface_ids.last().unwrap_or(&0))
            .filter(|t| t.record.has("RECTANGULAR_TRIMMED_SURFACE") && surface_ids.len() < 8)
        {
            match t.reference(1) {
                Ok(basis) => surface_ids.push(basis),
                Err(_) => break,
            }
        }
        let sense = f.boolean(3)? != flip;
        let mut loops = Vec::new();
        for b in f.ref_list(1)? {
            let bound = graph.get(&f, b)?;
            let bp = bound
                .record
                .part("FACE_OUTER_BOUND")
                .or_else(|| bound.record.part("FACE_BOUND"))
                .ok_or_else(|| bound.unsupported("a face bound"))?;
            let bound = Entity {
                params: bp,
                ..bound
            };
            let orientation = bound.boolean(2)? != flip;
            let l = graph.get(&bound, bound.reference(1)?)?;
            if l.record.parts.len() != 1 || l.record.parts[0].0 != "EDGE_LOOP" {
                return Err(l.unsupported("a face bound's loop (an EDGE_LOOP is needed)"));
            }
            let mut entries = Vec::new();
            for oe in l.ref_list(1)? {
                let o = graph.get_as(&l, oe, "ORIENTED_EDGE", "a loop's edge")?;
                let edge = self.edge(&o, o.reference(3)?)?;
                entries.push((edge, !o.boolean(4)?, oe));
            }
            if !orientation {
                entries.reverse();
                for e in &mut entries {
                    e.1 = !e.1;
                }
            }
            if entries.is_empty() {
                return Err(l.malformed("the loop has no edge"));
            }
            loops.push((l.id, entries));
        }
        if loops.is_empty() {
            return Err(f.malformed("the face has no bound"));
        }
        Ok(PendingFace {
            entity: f,
            surface_ids,
            surface,
            sense,
            loops,
        })
    }

    fn make_surface(
        spec: &SurfaceSpec,
        sense: bool,
        domain: [ParamRange; 2],
    ) -> Result<Box<dyn Surface>, crate::GeometryError> {
        // A reversed surface runs v backwards: its free v range is the negated one.
        let inner_domain = if sense {
            domain
        } else {
            [domain[0], range(-domain[1].max, -domain[1].min)]
        };
        let s = spec.build(inner_domain)?;
        Ok(if sense {
            s
        } else {
            Box::new(ReversedSurface { inner: s })
        })
    }

    fn build_face(
        &mut self,
        p: PendingFace<'a>,
        face_id: FaceId,
        big: f64,
    ) -> Result<Face, StepError> {
        let f = p.entity;
        let free = p.surface.free();
        let periodic = p.surface.periodic();
        let provisional = [range(-big, big), range(-big, big)];
        let surface =
            Self::make_surface(&p.surface, p.sense, provisional).map_err(|g| f.geometry(g))?;
        let spec = p.surface.clone();
        let sense = p.sense;
        let guess = move |q: DVec3| {
            spec.guess(q)
                .map(|[u, v]| if sense { [u, v] } else { [u, -v] })
        };
        let domain = surface.domain();
        let periods = [0, 1].map(|i| {
            if domain[i].periodic {
                domain[i].span()
            } else {
                0.0
            }
        });
        let mut fitted_loops: Vec<Vec<FittedEntry>> = Vec::new();
        let mut areas = Vec::new();
        // Loops that wrap once around a periodic u: (loop id, entries, wrap sign).
        let mut wrapping: Vec<WrappingLoop> = Vec::new();
        let fit_ctx = LoopContext {
            face: f.id,
            surface: surface.as_ref(),
            guess: &guess,
            periods,
            closed: closed_parameters(surface.as_ref(), self.uncertainty),
            surface_ids: &p.surface_ids,
            pcurve_scale: p
                .surface
                .pcurve_scale(self.reader.scale, self.reader.angle)
                .map(|k| if p.sense { k } else { DVec2::new(k.x, -k.y) }),
        };
        for (loop_id, entries) in &p.loops {
            let fitted = self.fit_loop(&fit_ctx, *loop_id, entries)?;
            match fitted.wrap {
                [0, 0] => {
                    areas.push(fitted.area);
                    fitted_loops.push(fitted.entries);
                }
                [w, 0] if w.abs() == 1 => wrapping.push((*loop_id, entries.clone(), f64::from(w))),
                _ => {
                    return Err(StepError::Unsupported {
                        id: *loop_id,
                        entity: "EDGE_LOOP".into(),
                        role: "a loop that wraps around a closed surface's v or more than once",
                    });
                }
            }
        }
        if !wrapping.is_empty() {
            let merged = self.merge_wrapping(&f, &p.surface, wrapping)?;
            let fitted = self.fit_loop(&fit_ctx, merged.0, &merged.1)?;
            if fitted.wrap != [0, 0] {
                return Err(StepError::Unsupported {
                    id: merged.0,
                    entity: "EDGE_LOOP".into(),
                    role: "a pair of loops around a closed surface that a seam cannot join",
                });
            }
            areas.push(fitted.area);
            fitted_loops.push(fitted.entries);
        }
        // The outer loop: the counter-clockwise one of largest area, first.
        let outer = (0..areas.len())
            .max_by(|&a, &b| areas[a].total_cmp(&areas[b]))
            .unwrap_or(0);
        fitted_loops.swap(0, outer);
        // Domain: the loops' box with a margin, on free parameters.
        let mut lo = DVec2::splat(f64::INFINITY);
        let mut hi = DVec2::splat(f64::NEG_INFINITY);
        for l in &fitted_loops {
            for (_, _, c) in l {
                let d = c.domain();
                for k in 0..=16 {
                    let q = c.eval(d.min + d.span() * k as f64 / 16.0).point;
                    lo = lo.min(q);
                    hi = hi.max(q);
                }
            }
        }
        let span = (hi - lo).max(DVec2::splat(1e-9));
        let mut final_domain = provisional;
        for i in 0..2 {
            if free[i] {
                final_domain[i] = range(
                    lo[i] - DOMAIN_MARGIN * span[i],
                    hi[i] + DOMAIN_MARGIN * span[i],
                );
            }
        }
        let surface =
            Self::make_surface(&p.surface, p.sense, final_domain).map_err(|g| f.geometry(g))?;
        let mut loops = Vec::with_capacity(fitted_loops.len());
        for (li, l) in fitted_loops.into_iter().enumerate() {
            let mut entries = Vec::with_capacity(l.len());
            for (index, (edge, reversed, c)) in l.into_iter().enumerate() {
                self.edges[edge].uses.push(EdgeUse {
                    face: face_id,
                    on: EdgeOn::Trim {
                        loop_index: li as u32,
                        index: index as u32,
                    },
                });
                entries.push(TrimEntry::new(EdgeId(edge as u32), c, reversed));
            }
            loops.push(TrimLoop::new(entries));
        }
        let domain = surface.domain();
        let side = |i: usize| {
            if periodic[i] {
                Boundary::Periodic
            } else {
                Boundary::Trimmed
            }
        };
        Ok(Face {
            surface,
            boundary: [side(0), side(0), side(1), side(1)],
            trim: Some(Trim::new(loops, &domain)),
            convexity: FaceConvexity::Flat,
        })
    }

    /// The file's p-curves of `edge` on the face of `ctx` (the PCURVEs its SURFACE_CURVE or
    /// SEAM_CURVE lists whose basis is the face's surface), mapped to the model's (u, v) and
    /// edge parameter. A PCURVE the reader cannot read or map is left to the projection,
    /// which the 3D curve (the edge's definition) always allows: the 2D curve is a redundant
    /// image of it, and no geometry is lost.
    fn file_pcurves(&self, ctx: &LoopContext<'_>, edge: usize) -> Vec<Arc<dyn Curve2>> {
        let (Some(scale), record) = (ctx.pcurve_scale, &self.edges[edge]) else {
            return Vec::new();
        };
        if !self.use_file_pcurves {
            return Vec::new();
        }
        let graph = self.reader.graph;
        let Some(geometry) = graph.root(record.geometry_id) else {
            return Vec::new();
        };
        if !(geometry.record.has("SURFACE_CURVE") || geometry.record.has("SEAM_CURVE")) {
            return Vec::new();
        }
        let mut out: Vec<Arc<dyn Curve2>> = Vec::new();
        for id in geometry.ref_list(2).unwrap_or_default() {
            let Some(pcurve) = graph.root(id).filter(|e| e.record.has("PCURVE")) else {
                continue;
            };
            if !pcurve
                .reference(1)
                .is_ok_and(|basis| ctx.surface_ids.contains(&basis))
            {
                continue;
            }
            if let Ok(inner) = self.reader.pcurve_2d(&pcurve) {
                out.push(Arc::new(MappedPCurve {
                    inner,
                    scale,
                    rate: record.rate,
                }));
            }
        }
        out
    }

    /// Fits the p-curves of one loop, each entry starting where the previous one ended.
    fn fit_loop(
        &mut self,
        ctx: &LoopContext<'_>,
        loop_id: u64,
        entries: &[LoopEntry],
    ) -> Result<FittedLoop, StepError> {
        let surface = ctx.surface;
        let domain = surface.domain();
        let on = |uv: DVec2| {
            surface
                .eval(domain[0].normalize(uv.x), domain[1].normalize(uv.y))
                .point
        };
        let limit = MAX_HEAL_FACTOR * self.uncertainty;
        let mut fitted = Vec::with_capacity(entries.len());
        let mut previous_end: Option<DVec2> = None;
        let mut first_start: Option<DVec2> = None;
        for (k, &(edge, reversed, oe)) in entries.iter().enumerate() {
            // The last entry ends where the first began, unless the loop wraps: then the
            // snap would be a whole period off and is left to the wrap test below.
            let snap_end = if k + 1 == entries.len() && entries.len() > 1 {
                first_start
            } else {
                None
            };
            let file_pcurves = self.file_pcurves(ctx, edge);
            let input = FitInput {
                surface,
                guess: ctx.guess,
                curve: self.edges[edge].curve.as_ref(),
                reversed,
                previous_end,
                tolerance: self.fit_tolerance,
                snap_end,
                snap_limit: limit,
                closed: ctx.closed,
                file_pcurves: &file_pcurves,
                agreement: self.fit_tolerance,
            };
            let pc = fit(&input).map_err(|reason| StepError::PCurve {
                face: ctx.face,
                edge: self.edges[edge].step_id,
                tolerance: self.fit_tolerance,
                reason,
            })?;
            if pc.gap > limit || pc.gap.is_nan() {
                return Err(StepError::EdgeOffFace {
                    face: ctx.face,
                    edge: self.edges[edge].step_id,
                    gap: pc.gap,
                    limit,
                });
            }
            self.worst_gap = self.worst_gap.max(pc.gap + pc.fit_error);
            if pc.from_file {
                self.pcurves.from_file += 1;
            } else {
                self.pcurves.projected += 1;
            }
            let d = pc.curve.domain();
            let (start_t, end_t) = if reversed {
                (d.max, d.min)
            } else {
                (d.min, d.max)
            };
            let start = pc.curve.eval(start_t).point;
            let end = pc.curve.eval(end_t).point;
            if let Some(prev) = previous_end {
                let gap = on(prev).distance(on(start));
                if gap > limit || gap.is_nan() {
                    return Err(StepError::LoopNotClosed {
                        id: loop_id,
                        after: entries[k - 1].2,
                        gap,
                        tolerance: self.uncertainty,
                    });
                }
                self.worst_gap = self.worst_gap.max(gap);
            }
            let _ = oe;
            first_start.get_or_insert(start);
            previous_end = Some(end);
            fitted.push((edge, reversed, pc.curve));
        }
        let (Some(a), Some(b)) = (first_start, previous_end) else {
            return Err(StepError::Malformed {
                id: loop_id,
                entity: "EDGE_LOOP".into(),
                reason: "the loop has no edge".into(),
            });
        };
        let gap = on(a).distance(on(b));
        if gap > limit || gap.is_nan() {
            return Err(StepError::LoopNotClosed {
                id: loop_id,
                after: entries.last().map_or(0, |e| e.2),
                gap,
                tolerance: self.uncertainty,
            });
        }
        self.worst_gap = self.worst_gap.max(gap);
        let diff = b - a;
        let mut wrap = [0; 2];
        let mut residual = diff;
        for i in 0..2 {
            if ctx.periods[i] > 0.0 {
                let w = (diff[i] / ctx.periods[i]).round();
                wrap[i] = w as i32;
                residual[i] -= w * ctx.periods[i];
            }
        }
        if residual.length() > 1e-6 * (1.0 + a.length()) {
            // Closed in space but not in (u, v): the loop passes a pole.
            return Err(StepError::Unsupported {
                id: loop_id,
                entity: "EDGE_LOOP".into(),
                role: "a loop through a pole of its surface (a degenerate edge is not supported yet)",
            });
        }
        let mut area = 0.0;
        for (_, reversed, c) in &fitted {
            let d = c.domain();
            let n = 32;
            let mut prev = c.eval(if *reversed { d.max } else { d.min }).point;
            for k in 1..=n {
                let s = f64::from(k) / f64::from(n);
                let t = if *reversed {
                    d.max - s * d.span()
                } else {
                    d.min + s * d.span()
                };
                let q = c.eval(t).point;
                area += prev.perp_dot(q);
                prev = q;
            }
        }
        Ok(FittedLoop {
            entries: fitted,
            wrap,
            area,
        })
    }

    /// Joins two loops that each wrap once around a surface's periodic u (in opposite
    /// directions: the two ends of a cylinder face an exporter wrote without a seam) by a
    /// seam edge: a straight ruling from a vertex of the first to a vertex of the second at
    /// the same u. The merged loop is the first, the seam, the second, the seam backwards.
    fn merge_wrapping(
        &mut self,
        f: &Entity<'_>,
        spec: &SurfaceSpec,
        mut wrapping: Vec<WrappingLoop>,
    ) -> Result<ReadLoop, StepError> {
        let ruled = matches!(spec, SurfaceSpec::Cylinder(..) | SurfaceSpec::Cone(..));
        if wrapping.len() != 2 || wrapping[0].2 == wrapping[1].2 || !ruled {
            let id = wrapping[0].0;
            return Err(StepError::Unsupported {
                id,
                entity: "EDGE_LOOP".into(),
                role: "a loop around a closed surface without a seam edge (joined by a seam only for two opposite loops on a cylinder or cone)",
            });
        }
        // The loop that runs +u first.
        if wrapping[0].2 < 0.0 {
            wrapping.swap(0, 1);
        }
        let start_vertex = |e: &(usize, bool, u64), edges: &[EdgeRecord]| {
            let ends = edges[e.0].ends;
            if e.1 { ends[1] } else { ends[0] }
        };
        let (a_id, a_entries, _) = &wrapping[0];
        let (_, b_entries, _) = &wrapping[1];
        let va = start_vertex(&a_entries[0], &self.edges);
        let pa = self.vertices[&va];
        // The vertex of the second loop on the ruling through pa.
        let axis_dir = match spec {
            SurfaceSpec::Cylinder(pl, _) | SurfaceSpec::Cone(pl, ..) => pl,
            _ => unreachable!("checked ruled above"),
        };
        let angle = |p: DVec3| {
            let l = p - axis_dir.origin;
            l.dot(axis_dir.y).atan2(l.dot(axis_dir.x))
        };
        let ua = angle(pa);
        let mut best: Option<(f64, usize)> = None;
        for (k, e) in b_entries.iter().enumerate() {
            let p = self.vertices[&start_vertex(e, &self.edges)];
            let mut d = angle(p) - ua;
            d -= TAU * (d / TAU).round();
            let d = d.abs() * (p - axis_dir.origin).cross(axis_dir.z).length();
            if best.is_none_or(|(bd, _)| d < bd) {
                best = Some((d, k));
            }
        }
        let (d, k) = best.ok_or_else(|| f.malformed("an empty loop"))?;
        if d > MAX_HEAL_FACTOR * self.uncertainty {
            return Err(StepError::Unsupported {
                id: *a_id,
                entity: "EDGE_LOOP".into(),
                role: "a loop around a closed surface without a seam edge, whose partner loop has no vertex on the same ruling",
            });
        }
        let mut b_rot = b_entries[k..].to_vec();
        b_rot.extend_from_slice(&b_entries[..k]);
        let vb = start_vertex(&b_rot[0], &self.edges);
        let pb = self.vertices[&vb];
        let length = pa.distance(pb);
        let seam =
            crate::curves::line_curve::LineCurve::new(pa, (pb - pa) / length, range(0.0, length))
                .map_err(|g| f.geometry(g))?;
        self.edges.push(EdgeRecord {
            step_id: f.id,
            geometry_id: 0,
            rate: 1.0,
            curve: Box::new(seam),
            ends: [va, vb],
            uses: Vec::new(),
        });
        let seam = self.edges.len() - 1;
        let mut merged = a_entries.clone();
        merged.push((seam, false, f.id));
        merged.extend(b_rot);
        merged.push((seam, true, f.id));
        Ok((*a_id, merged))
    }

    fn finish(self, name: String, faces: Vec<Face>) -> Result<StepSolid, StepError> {
        let mut vertex_ids: HashMap<u64, VertexId> = HashMap::new();
        let mut vertices: Vec<Vertex> = Vec::new();
        let mut edges = Vec::with_capacity(self.edges.len());
        for (i, e) in self.edges.into_iter().enumerate() {
            if e.uses.len() != 2 {
                return Err(StepError::OpenShell {
                    solid: self.solid_id,
                    edge: e.step_id,
                    count: e.uses.len(),
                });
            }
            let mut ends = [VertexId(0); 2];
            for (k, v) in e.ends.into_iter().enumerate() {
                let id = *vertex_ids.entry(v).or_insert_with(|| {
                    vertices.push(Vertex {
                        point: self.vertices[&v],
                        faces: Vec::new(),
                        edges: Vec::new(),
                    });
                    VertexId((vertices.len() - 1) as u32)
                });
                if k == 0 || ends[0] != id {
                    vertices[id.0 as usize].edges.push(EdgeId(i as u32));
                }
                ends[k] = id;
            }
            edges.push(Edge {
                curve: e.curve,
                uses: [e.uses[0], e.uses[1]],
                ends: Some(ends),
                convexity: EdgeConvexity::Smooth,
            });
        }
        let tolerance = self.uncertainty.max(HEAL_MARGIN * self.worst_gap);
        let mut solid = Solid::new(faces, edges, vertices, tolerance);
        validate(&solid).map_err(|source| StepError::Topology {
            id: self.solid_id,
            name: name.clone(),
            source,
        })?;
        classify_convexity(&mut solid);
        Ok(StepSolid {
            name,
            id: self.solid_id,
            solid,
            pcurves: self.pcurves,
        })
    }
}

/// The parameter of the point of `curve` nearest `p`: the best of 64 samples polished by
/// Newton's method on (C − p) · C' = 0 within the domain.
fn nearest_param(curve: &dyn Curve, p: DVec3) -> f64 {
    let d = curve.domain();
    let n = 64;
    let mut best = (f64::INFINITY, d.min);
    for k in 0..=n {
        let t = d.min + d.span() * k as f64 / n as f64;
        let dist = curve.eval(t).point.distance_squared(p);
        if dist < best.0 {
            best = (dist, t);
        }
    }
    let mut t = best.1;
    for _ in 0..30 {
        let c = curve.eval(t);
        let r = c.point - p;
        let g = r.dot(c.d1);
        let h = c.d1.length_squared() + r.dot(c.d2);
        if h.is_nan() || h <= 0.0 {
            break;
        }
        let next = (t - g / h).clamp(d.min, d.max);
        if (next - t).abs() <= 1e-15 * (1.0 + t.abs()) {
            t = next;
            break;
        }
        t = next;
    }
    t
}
