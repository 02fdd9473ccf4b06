//! A lofted solid: one free-form NURBS side face through a stack of horizontal ellipses, closed
//! by two trimmed planar caps.
//!
//! The side face is a single [`NurbsSurface`], rational quadratic and periodic in u, of degree
//! min(3, n − 1) in v for n sections. Its control net is built so that every iso-v row is an
//! exact ellipse lying in the horizontal plane z = v:
//!
//! - each section is the affine image A_k(c) = centre_k + R(θ_k) diag(a_k, b_k) c of the unit
//!   circle, whose exact rational quadratic form (The NURBS Book A7.1, four quarter arcs) has
//!   control points c_i and weights w_i; so section k has control points A_k(c_i), weights w_i;
//! - column i of the net interpolates the points A_k(c_i) at the parameters v̄_k = z_k (A9.1,
//!   knots by averaging), with weight w_i all along the column, and the control heights are the
//!   Greville abscissae of the v knots.
//!
//! With weights constant along v the row at v is the rational curve with control points
//! Σ_j N_j(v) P_ij and weights w_i. Interpolation is linear in the data and reproduces
//! constants, so Σ_j N_j(v) P_ij = A(v)(c_i) for the affine map A(v) = Σ_k λ_k(v) A_k (λ_k the
//! cardinal splines): every row is an ellipse, the image of the unit circle by A(v). The
//! Greville abscissae are the coefficients of the identity function (Marsden), so z = v exactly:
//! the horizontal section of the solid at height z is the row at v = z, and the solid's volume
//! is ∫ area(row(z)) dz.

use crate::builders::CAP_DOMAIN_FACTOR;
use crate::builders::build_error::BuildError;
use crate::curves::curve::ParamRange;
use crate::curves::nurbs_curve::NurbsCurve;
use crate::curves::nurbs_curve2::NurbsCurve2;
use crate::nurbs::basis::BSplineBasis;
use crate::nurbs::circle_arc::arc_net;
use crate::nurbs::interpolation::{averaged_knots, interpolate_columns};
use crate::surfaces::nurbs_surface::NurbsSurface;
use crate::surfaces::placement::Placement;
use crate::surfaces::plane::Plane;
use crate::surfaces::surface::Surface;
use crate::topology::feature::{EdgeId, FaceId};
use crate::topology::solid::{
    Boundary, Edge, EdgeConvexity, EdgeOn, EdgeUse, Face, FaceConvexity, ParamSide, Solid,
};
use crate::topology::trim::{Trim, TrimEntry, TrimLoop};
use crate::topology::validate::validate;
use glam::{DMat2, DVec2, DVec3};
use std::f64::consts::{FRAC_PI_2, PI, TAU};

/// Highest degree in v (cubic, as is usual for skinning).
const MAX_V_DEGREE: usize = 3;
/// Samples per knot span of v at which the interpolated cross-section is checked.
const AREA_SAMPLES_PER_SPAN: usize = 64;
/// Smallest allowed area of an interpolated cross-section, relative to the largest section's.
const MIN_RELATIVE_AREA: f64 = 1e-6;

/// One horizontal elliptical cross-section of a [`loft`]: the ellipse with centre `center`,
/// semi-axes `semi_axes` (a along its own x axis, b along its y axis) rotated by `rotation`
/// about +z, in the plane z = `z` (mm, rad). As a map of the unit circle:
/// c ↦ centre + R(rotation) diag(a, b) c, run counter-clockwise seen from +z.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(
    feature = "json",
    derive(serde::Serialize, serde::Deserialize),
    serde(deny_unknown_fields)
)]
pub struct EllipseSection {
    /// Centre in the xy plane (mm).
    pub center: DVec2,
    /// Semi-axes (a, b) (mm, > 0), before the rotation: a along x, b along y.
    pub semi_axes: DVec2,
    /// Rotation about +z (rad, counter-clockwise seen from +z).
    pub rotation: f64,
    /// Height of the section's plane (mm).
    pub z: f64,
}

impl EllipseSection {
    /// The image of the unit-circle point `c` on this section, in xy (mm).
    #[must_use]
    pub fn map(&self, c: DVec2) -> DVec2 {
        self.center + DMat2::from_angle(self.rotation) * (self.semi_axes * c)
    }

    /// The enclosed area π a b (mm²).
    #[must_use]
    pub fn area(&self) -> f64 {
        PI * self.semi_axes.x * self.semi_axes.y
    }
}

fn range(min: f64, max: f64) -> ParamRange {
    ParamRange {
        min,
        max,
        periodic: false,
    }
}

/// Checks the sections' values: at least two, finite, positive semi-axes, heights increasing by
/// more than `tolerance`.
fn check_sections(sections: &[EllipseSection], tolerance: f64) -> Result<(), BuildError> {
    if sections.len() < 2 {
        return Err(BuildError::BadDimension {
            what: "loft sections",
            value: sections.len() as f64,
            requirement: "at least 2",
        });
    }
    for s in sections {
        for value in [s.center.x, s.center.y, s.rotation, s.z] {
            if !value.is_finite() {
                return Err(BuildError::BadDimension {
                    what: "section centre, rotation or height",
                    value,
                    requirement: "finite",
                });
            }
        }
        for value in [s.semi_axes.x, s.semi_axes.y] {
            if !(value.is_finite() && value > tolerance) {
                return Err(BuildError::BadDimension {
                    what: "ellipse semi-axis",
                    value,
                    requirement: "finite and above the model tolerance",
                });
            }
        }
    }
    for pair in sections.windows(2) {
        let gap = pair[1].z - pair[0].z;
        if gap.is_nan() || gap <= tolerance {
            return Err(BuildError::BadDimension {
                what: "height step between sections",
                value: gap,
                requirement: "above the model tolerance (sections strictly increasing in z)",
            });
        }
    }
    Ok(())
}

/// The lofted solid through `sections` (at least two, listed bottom to top with strictly
/// increasing z): the side face is one NURBS surface whose iso-v rows are horizontal ellipses,
/// the row at v being the section of the solid at height z = v (see the module docs), passing
/// through every given section; the caps are the planes z = z_first and z = z_last, trimmed by
/// the first and last ellipse. The model tolerance is 1e-9 of the size (the largest absolute
/// coordinate of a section's centre plus its larger semi-axis, or of a height).
///
/// Parametrisation of the side face (face 0): u in [0, 2π], periodic, the parameter of the
/// rational quadratic unit circle (A7.1: the angle at multiples of π/2, not between), running
/// counter-clockwise seen from +z, so ∂S/∂u × ∂S/∂v points out; v in [z_first, z_last] (mm),
/// degree min(3, n − 1), knots by averaging the section heights. Face 1 is the bottom cap
/// (normal −z, (u, v) = (x, −y)), face 2 the top cap (normal +z, (u, v) = (x, y)), planes over
/// [−2m, 2m]² (m the largest |x| or |y| of the net) trimmed by the end ellipses. Edge 0 is
/// the bottom ellipse, edge 1 the top one: [`NurbsCurve`]s with the side face's u knots and
/// weights, so an edge's t is the side face's u; on the caps their p-curves are the same rows
/// as [`NurbsCurve2`]s (mirrored in y on the bottom cap). No vertices.
///
/// # Errors
/// [`BuildError::BadDimension`] for fewer than two sections, a non-finite value, a semi-axis
/// not above the tolerance, heights not increasing by more than the tolerance, or sections
/// whose interpolated cross-section between them flattens or turns over (its area falls below
/// 1e-6 of the largest section's at one of 64 samples per knot span of v: too much twist or
/// shrinking between neighbouring sections; add sections in between);
/// [`BuildError::Geometry`] or [`BuildError::Topology`] if the net or the solid fails its
/// checks.
pub fn loft(sections: &[EllipseSection]) -> Result<Solid, BuildError> {
    let size = sections
        .iter()
        .map(|s| (s.center.abs().max_element() + s.semi_axes.max_element()).max(s.z.abs()))
        .fold(0.0, f64::max);
    let tolerance = 1e-9 * if size.is_finite() { size } else { 1.0 };
    check_sections(sections, tolerance)?;
    let n = sections.len();
    let heights: Vec<f64> = sections.iter().map(|s| s.z).collect();
    let degree_v = MAX_V_DEGREE.min(n - 1);
    let knots_v = averaged_knots(&heights, degree_v);
    let basis_v = BSplineBasis::new(degree_v, knots_v.clone(), n)?;

    // The unit circle as four rational quadratic quarter arcs: 9 control points, the last
    // equal to the first.
    let unit = arc_net(DVec3::ZERO, DVec3::X, DVec3::Y, 1.0, 0.0, TAU);
    let columns: Vec<Vec<DVec2>> = unit
        .points
        .iter()
        .map(|c| sections.iter().map(|s| s.map(c.truncate())).collect())
        .collect();
    let Some(solved) = interpolate_columns(&basis_v, &heights, &columns) else {
        return Err(BuildError::BadDimension {
            what: "height step between sections",
            value: heights[1] - heights[0],
            requirement: "heights that give a non-singular interpolation",
        });
    };
    // Greville abscissae: the v-spline with these coefficients is v itself.
    let greville: Vec<f64> = (0..n)
        .map(|j| knots_v[j + 1..=j + degree_v].iter().sum::<f64>() / degree_v as f64)
        .collect();
    let points: Vec<Vec<DVec3>> = solved
        .iter()
        .map(|column| {
            column
                .iter()
                .zip(&greville)
                .map(|(p, &z)| DVec3::new(p.x, p.y, z))
                .collect()
        })
        .collect();
    let weights: Vec<Vec<f64>> = unit.weights.iter().map(|&w| vec![w; n]).collect();
    let side = NurbsSurface::new(
        [2, degree_v],
        [unit.knots.clone(), knots_v],
        points.clone(),
        weights,
        [true, false],
    )?;
    check_cross_sections(&side, &basis_v, sections)?;

    let row = |j: usize| -> Vec<DVec3> { points.iter().map(|column| column[j]).collect() };
    let edge_curve =
        |j: usize| NurbsCurve::new(2, unit.knots.clone(), row(j), unit.weights.clone(), true);
    let pcurve = |j: usize, mirror: bool| {
        let flip = if mirror { -1.0 } else { 1.0 };
        NurbsCurve2::new(
            2,
            unit.knots.clone(),
            row(j).iter().map(|p| DVec2::new(p.x, flip * p.y)).collect(),
            unit.weights.clone(),
            true,
        )
    };
    let (bottom_z, top_z) = (heights[0], heights[n - 1]);
    let use_ = |face: u32, on: EdgeOn| EdgeUse {
        face: FaceId(face),
        on,
    };
    let cap_use = |face: u32| {
        use_(
            face,
            EdgeOn::Trim {
                loop_index: 0,
                index: 0,
            },
        )
    };
    let edges = vec![
        Edge {
            curve: Box::new(edge_curve(0)?),
            uses: [use_(0, EdgeOn::Side(ParamSide::VMin)), cap_use(1)],
            ends: None,
            convexity: EdgeConvexity::Convex,
        },
        Edge {
            curve: Box::new(edge_curve(n - 1)?),
            uses: [use_(0, EdgeOn::Side(ParamSide::VMax)), cap_use(2)],
            ends: None,
            convexity: EdgeConvexity::Convex,
        },
    ];
    let half = points
        .iter()
        .flatten()
        .map(|p| p.truncate().abs().max_element())
        .fold(0.0, f64::max)
        * CAP_DOMAIN_FACTOR;
    let cap_domain = [range(-half, half), range(-half, half)];
    // Bottom cap: normal −z, x along +x, so y = −y: (u, v) = (x, −y), and the ellipse, which
    // runs counter-clockwise in xy, runs clockwise there; the loop takes it backwards.
    let bottom = Plane::new(
        Placement::new(DVec3::new(0.0, 0.0, bottom_z), DVec3::NEG_Z, DVec3::X)?,
        cap_domain,
    )?;
    let top = Plane::new(
        Placement::new(DVec3::new(0.0, 0.0, top_z), DVec3::Z, DVec3::X)?,
        cap_domain,
    )?;
    let bottom_trim = Trim::new(
        vec![TrimLoop::new(vec![TrimEntry::new(
            EdgeId(0),
            Box::new(pcurve(0, true)?),
            true,
        )])],
        &cap_domain,
    );
    let top_trim = Trim::new(
        vec![TrimLoop::new(vec![TrimEntry::new(
            EdgeId(1),
            Box::new(pcurve(n - 1, false)?),
            false,
        )])],
        &cap_domain,
    );
    let cap = |surface: Plane, trim: Trim| Face {
        surface: Box::new(surface),
        boundary: [Boundary::Trimmed; 4],
        trim: Some(trim),
        convexity: FaceConvexity::Flat,
    };
    let solid = Solid::new(
        vec![
            Face {
                surface: Box::new(side),
                boundary: [
                    Boundary::Periodic,
                    Boundary::Periodic,
                    Boundary::Edge(EdgeId(0)),
                    Boundary::Edge(EdgeId(1)),
                ],
                trim: None,
                convexity: FaceConvexity::Flat,
            },
            cap(bottom, bottom_trim),
            cap(top, top_trim),
        ],
        edges,
        Vec::new(),
        tolerance,
    );
    validate(&solid)?;
    Ok(solid)
}

/// Refuses a side face whose row ellipse flattens or turns over between the sections: the
/// row at v is A(v)(unit circle), and the surface passes through A(v)(1, 0), A(v)(0, 1) and
/// A(v)(−1, 0) at u = 0, π/2, π (the arcs' joints), which give A(v)'s linear part and so the
/// row's area π det L(v).
fn check_cross_sections(
    side: &NurbsSurface,
    basis_v: &BSplineBasis,
    sections: &[EllipseSection],
) -> Result<(), BuildError> {
    let largest = sections
        .iter()
        .map(EllipseSection::area)
        .fold(0.0, f64::max);
    let knots = basis_v.knots();
    let mut smallest = f64::INFINITY;
    for span in knots.windows(2).filter(|w| w[1] > w[0]) {
        for k in 0..=AREA_SAMPLES_PER_SPAN {
            let v = span[0] + (span[1] - span[0]) * k as f64 / AREA_SAMPLES_PER_SPAN as f64;
            let at = |u: f64| side.eval(u, v).point.truncate();
            let (east, north, west) = (at(0.0), at(FRAC_PI_2), at(PI));
            let centre = 0.5 * (east + west);
            let area = PI * (east - centre).perp_dot(north - centre);
            smallest = smallest.min(area);
        }
    }
    if smallest.is_nan() || smallest <= MIN_RELATIVE_AREA * largest {
        return Err(BuildError::BadDimension {
            what: "area of the interpolated cross-section between sections",
            value: smallest,
            requirement: "above 1e-6 of the largest section's (the sections twist or shrink too much between neighbours)",
        });
    }
    Ok(())
}
