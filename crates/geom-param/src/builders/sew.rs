//! Sewing rectangle faces into a closed solid: the shared sides are found from the geometry,
//! so that a builder only lists surfaces with the right domains and orientations.

use crate::builders::build_error::BuildError;
use crate::curves::curve::ParamRange;
use crate::curves::iso_curve::IsoCurve;
use crate::surfaces::surface::Surface;
use crate::topology::feature::{EdgeId, FaceId, VertexId};
use crate::topology::solid::{
    Boundary, Edge, EdgeConvexity, EdgeOn, EdgeUse, Face, FaceConvexity, ParamSide, Solid, Vertex,
};
use crate::topology::validate::validate;
use glam::DVec3;
use std::sync::Arc;

/// Points compared along a side when matching it with another.
const SIDE_SAMPLES: usize = 7;

const SIDES: [ParamSide; 4] = [
    ParamSide::UMin,
    ParamSide::UMax,
    ParamSide::VMin,
    ParamSide::VMax,
];

/// The running parameter's range along `side` and the point at running parameter r.
fn side_range(domain: &[ParamRange; 2], side: ParamSide) -> ParamRange {
    match side {
        ParamSide::UMin | ParamSide::UMax => domain[1],
        ParamSide::VMin | ParamSide::VMax => domain[0],
    }
}

fn side_point(surface: &dyn Surface, side: ParamSide, r: f64) -> DVec3 {
    let [ru, rv] = surface.domain();
    match side {
        ParamSide::UMin => surface.eval(ru.min, r).point,
        ParamSide::UMax => surface.eval(ru.max, r).point,
        ParamSide::VMin => surface.eval(r, rv.min).point,
        ParamSide::VMax => surface.eval(r, rv.max).point,
    }
}

fn samples(range: ParamRange) -> impl Iterator<Item = f64> {
    (0..SIDE_SAMPLES).map(move |k| range.min + range.span() * k as f64 / (SIDE_SAMPLES - 1) as f64)
}

/// How side b runs along side a: the same running parameter, its negation, or not at all.
fn side_match(
    a: &dyn Surface,
    side_a: ParamSide,
    b: &dyn Surface,
    side_b: ParamSide,
    tolerance: f64,
) -> Option<bool> {
    let (ra, rb) = (
        side_range(&a.domain(), side_a),
        side_range(&b.domain(), side_b),
    );
    let slack = 1e-12 * (ra.span() + rb.span());
    for reversed in [false, true] {
        let image = |r: f64| if reversed { -r } else { r };
        let (lo, hi) = (
            image(ra.min).min(image(ra.max)),
            image(ra.min).max(image(ra.max)),
        );
        if (lo - rb.min).abs() > slack || (hi - rb.max).abs() > slack {
            continue;
        }
        let same = samples(ra).all(|r| {
            side_point(a, side_a, r).distance(side_point(b, side_b, image(r))) <= tolerance
        });
        if same {
            return Some(reversed);
        }
    }
    None
}

/// Sews `surfaces`, each a face over its whole parameter rectangle oriented outwards
/// (∂S/∂u × ∂S/∂v out of the material), into a closed solid: every non-periodic side either
/// collapses to a point (a pole: a vertex) or coincides, point for point within `tolerance`
/// (mm), with one side of another face whose running parameter is the same or its negation.
/// Edges are the iso-curves of the first face's side; vertices are the poles and the edges'
/// ends, merged within `tolerance`. The result is validated; its convexity is assigned from the
/// geometry when it is prepared ([`crate::ObjectModel::from_solid`]).
///
/// # Errors
/// [`BuildError::UnmatchedSide`] for a side no other face shares (an open shell), or
/// [`BuildError::Topology`] if the sewn solid fails validation.
pub fn sew_rectangles(
    surfaces: Vec<Arc<dyn Surface>>,
    tolerance: f64,
) -> Result<Solid, BuildError> {
    let n = surfaces.len();
    let mut boundary = vec![[Boundary::Periodic; 4]; n];
    let mut open: Vec<(usize, ParamSide)> = Vec::new();
    let mut poles: Vec<(usize, ParamSide, DVec3)> = Vec::new();
    for (f, surface) in surfaces.iter().enumerate() {
        let domain = surface.domain();
        for side in SIDES {
            let across = match side {
                ParamSide::UMin | ParamSide::UMax => domain[0],
                ParamSide::VMin | ParamSide::VMax => domain[1],
            };
            if across.periodic {
                continue;
            }
            let range = side_range(&domain, side);
            let first = side_point(surface.as_ref(), side, range.min);
            if samples(range)
                .all(|r| side_point(surface.as_ref(), side, r).distance(first) <= tolerance)
            {
                poles.push((f, side, first));
            } else {
                open.push((f, side));
            }
        }
    }

    let mut edges: Vec<Edge> = Vec::new();
    let mut taken = vec![false; open.len()];
    for i in 0..open.len() {
        if taken[i] {
            continue;
        }
        let (fa, sa) = open[i];
        let found = (i + 1..open.len()).find_map(|j| {
            let (fb, sb) = open[j];
            (!taken[j])
                .then(|| {
                    side_match(
                        surfaces[fa].as_ref(),
                        sa,
                        surfaces[fb].as_ref(),
                        sb,
                        tolerance,
                    )
                })
                .flatten()
                .map(|reversed| (j, reversed))
        });
        let Some((j, reversed)) = found else {
            return Err(BuildError::UnmatchedSide {
                face: FaceId(index32(fa)),
                side: sa,
            });
        };
        taken[i] = true;
        taken[j] = true;
        let (fb, sb) = open[j];
        let id = EdgeId(index32(edges.len()));
        boundary[fa][sa as usize] = Boundary::Edge(id);
        boundary[fb][sb as usize] = Boundary::Edge(id);
        edges.push(Edge {
            curve: Box::new(IsoCurve {
                surface: Arc::clone(&surfaces[fa]),
                side: sa,
            }),
            uses: [
                EdgeUse {
                    face: FaceId(index32(fa)),
                    on: EdgeOn::Side(sa),
                },
                EdgeUse {
                    face: FaceId(index32(fb)),
                    on: if reversed {
                        EdgeOn::SideReversed(sb)
                    } else {
                        EdgeOn::Side(sb)
                    },
                },
            ],
            ends: None,
            convexity: EdgeConvexity::Smooth,
        });
    }

    // Vertices: poles and the ends of open edges, merged within tolerance.
    let mut vertices: Vec<Vertex> = Vec::new();
    let vertex_at = |p: DVec3, vertices: &mut Vec<Vertex>| -> VertexId {
        if let Some(k) = vertices
            .iter()
            .position(|v| v.point.distance(p) <= tolerance)
        {
            return VertexId(index32(k));
        }
        vertices.push(Vertex {
            point: p,
            faces: Vec::new(),
            edges: Vec::new(),
        });
        VertexId(index32(vertices.len() - 1))
    };
    for (f, side, p) in poles {
        let v = vertex_at(p, &mut vertices);
        boundary[f][side as usize] = Boundary::Vertex(v);
        vertices[v.0 as usize].faces.push(FaceId(index32(f)));
    }
    for (e, edge) in edges.iter_mut().enumerate() {
        let range = edge.curve.domain();
        if range.periodic {
            continue;
        }
        let start = vertex_at(edge.curve.eval(range.min).point, &mut vertices);
        let end = vertex_at(edge.curve.eval(range.max).point, &mut vertices);
        edge.ends = Some([start, end]);
        for v in [start, end] {
            let list = &mut vertices[v.0 as usize].edges;
            if !list.contains(&EdgeId(index32(e))) {
                list.push(EdgeId(index32(e)));
            }
        }
    }

    let faces = surfaces
        .into_iter()
        .zip(boundary)
        .map(|(surface, boundary)| Face {
            surface: Box::new(surface),
            boundary,
            trim: None,
            convexity: FaceConvexity::Flat,
        })
        .collect();
    let solid = Solid::new(faces, edges, vertices, tolerance);
    validate(&solid)?;
    Ok(solid)
}

fn index32(i: usize) -> u32 {
    u32::try_from(i).expect("fewer than 2^32 features")
}
