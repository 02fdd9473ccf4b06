//! STEP curves and surfaces as specifications in millimetres, and their construction as the
//! general model's [`Curve`]s and [`Surface`]s over a chosen domain.
//!
//! Parametrisations: every analytic surface of the model follows STEP (ISO 10303-42) in u, the
//! angle about the placement's axis from its ref_direction, and in v for the cylinder (height
//! along the axis), sphere (latitude in [−π/2, π/2]) and torus (angle around the tube); the
//! cone's v runs along a ruling as in OpenCASCADE, where STEP's runs along the axis
//! ([`SurfaceSpec::pcurve_scale`] maps a file's (u, v) onto the model's). A file's PCURVE is
//! used only where it agrees with the projection of the 3D edge onto our surface (module
//! `pcurve`), so a difference in convention cannot misplace a trim.

use crate::GeometryError;
use crate::curves::circle_curve::CircleCurve;
use crate::curves::curve::{Curve, CurvePoint, ParamRange};
use crate::curves::ellipse_curve::EllipseCurve;
use crate::curves::line_curve::LineCurve;
use crate::curves::nurbs_curve::NurbsCurve;
use crate::io::step::error::StepError;
use crate::io::step::graph::{Entity, Graph};
use crate::surfaces::cone_surface::ConeSurface;
use crate::surfaces::cylinder_surface::CylinderSurface;
use crate::surfaces::linear_extrusion_surface::LinearExtrusionSurface;
use crate::surfaces::nurbs_surface::NurbsSurface;
use crate::surfaces::placement::Placement;
use crate::surfaces::plane::Plane;
use crate::surfaces::revolution_surface::RevolutionSurface;
use crate::surfaces::sphere_surface::SphereSurface;
use crate::surfaces::surface::Surface;
use crate::surfaces::torus_surface::TorusSurface;
use glam::{DVec2, DVec3};
use std::f64::consts::{FRAC_PI_2, TAU};

/// Nesting of curve wrappers (SURFACE_CURVE, TRIMMED_CURVE, ...) followed.
const MAX_CURVE_NESTING: usize = 8;

/// The full turn of an angle parameter, periodic.
pub(crate) const TURN: ParamRange = ParamRange {
    min: 0.0,
    max: TAU,
    periodic: true,
};

/// A closed, non-periodic range.
pub(crate) fn range(min: f64, max: f64) -> ParamRange {
    ParamRange {
        min,
        max,
        periodic: false,
    }
}

/// A B-spline's data in millimetres.
#[derive(Clone, Debug)]
pub(crate) struct BSplineData<P> {
    /// Degree.
    pub degree: usize,
    /// Knots with multiplicities expanded.
    pub knots: Vec<f64>,
    /// Control points.
    pub points: P,
    /// Weights (1 for a non-rational spline), same shape as the points.
    pub weights: Vec<f64>,
}

/// A 3D curve of the file, in millimetres.
#[derive(Clone, Debug)]
pub(crate) enum CurveSpec {
    /// C(t) = origin + t · direction (direction with the VECTOR's magnitude).
    Line { origin: DVec3, direction: DVec3 },
    /// C(t) = O + R (cos t x + sin t y).
    Circle { placement: Placement, radius: f64 },
    /// C(t) = O + a cos t x + b sin t y.
    Ellipse {
        placement: Placement,
        a: f64,
        b: f64,
    },
    /// A (rational) B-spline curve.
    Nurbs(BSplineData<Vec<DVec3>>),
}

/// A surface of the file, in millimetres.
#[derive(Clone, Debug)]
pub(crate) enum SurfaceSpec {
    /// PLANE.
    Plane(Placement),
    /// CYLINDRICAL_SURFACE.
    Cylinder(Placement, f64),
    /// CONICAL_SURFACE: radius in the placement's plane, semi-angle (rad).
    Cone(Placement, f64, f64),
    /// SPHERICAL_SURFACE.
    Sphere(Placement, f64),
    /// TOROIDAL_SURFACE: major and minor radius.
    Torus(Placement, f64, f64),
    /// SURFACE_OF_LINEAR_EXTRUSION: swept curve, extrusion vector (mm).
    Extrusion(CurveSpec, DVec3),
    /// SURFACE_OF_REVOLUTION: swept curve, axis point, axis direction.
    Revolution(CurveSpec, DVec3, DVec3),
    /// B_SPLINE_SURFACE_WITH_KNOTS (rational or not): degrees, knots, net rows along u.
    Nurbs {
        /// Degrees (u, v).
        degree: [usize; 2],
        /// Expanded knots (u, v).
        knots: [Vec<f64>; 2],
        /// Control net, rows along u.
        points: Vec<Vec<DVec3>>,
        /// Weights, same shape.
        weights: Vec<Vec<f64>>,
    },
}

/// Reads geometry entities with the file's units.
pub(crate) struct GeometryReader<'g, 'a> {
    /// The entity graph.
    pub graph: &'g Graph<'a>,
    /// Millimetres per file length unit.
    pub scale: f64,
    /// Radians per file angle unit.
    pub angle: f64,
}

impl GeometryReader<'_, '_> {
    /// A CARTESIAN_POINT in mm.
    pub(crate) fn point(&self, from: &Entity<'_>, id: u64) -> Result<DVec3, StepError> {
        let e = self.graph.get_as(from, id, "CARTESIAN_POINT", "a point")?;
        let c = e.real_list(1)?;
        if c.len() != 3 {
            return Err(e.malformed(format!("{} coordinates, needs 3", c.len())));
        }
        Ok(DVec3::new(c[0], c[1], c[2]) * self.scale)
    }

    /// A DIRECTION (not normalised).
    pub(crate) fn direction(&self, from: &Entity<'_>, id: u64) -> Result<DVec3, StepError> {
        let e = self.graph.get_as(from, id, "DIRECTION", "a direction")?;
        let c = e.real_list(1)?;
        if c.len() != 3 {
            return Err(e.malformed(format!("{} components, needs 3", c.len())));
        }
        let d = DVec3::new(c[0], c[1], c[2]);
        if d.length() == 0.0 {
            return Err(e.malformed("the direction is zero"));
        }
        Ok(d)
    }

    /// An AXIS2_PLACEMENT_3D (missing axis: z; missing ref_direction: x, or y when the axis
    /// is along x).
    pub(crate) fn placement(&self, from: &Entity<'_>, id: u64) -> Result<Placement, StepError> {
        let e = self
            .graph
            .get_as(from, id, "AXIS2_PLACEMENT_3D", "a placement")?;
        let origin = self.point(&e, e.reference(1)?)?;
        let axis = match e.optional_reference(2)? {
            Some(a) => self.direction(&e, a)?,
            None => DVec3::Z,
        };
        let reference = match e.optional_reference(3)? {
            Some(r) => self.direction(&e, r)?,
            None if axis.normalize().x.abs() > 0.9 => DVec3::Y,
            None => DVec3::X,
        };
        Placement::new(origin, axis, reference).map_err(|g| e.geometry(g))
    }

    fn length(&self, e: &Entity<'_>, i: usize) -> Result<f64, StepError> {
        let v = e.real(i)? * self.scale;
        if v.is_finite() && v > 0.0 {
            Ok(v)
        } else {
            Err(e.geometry(GeometryError::NonPositiveRadius {
                what: "length",
                value: v,
            }))
        }
    }

    /// The 3D curve of entity `id` (through SURFACE_CURVE, SEAM_CURVE and TRIMMED_CURVE to
    /// their basis curve: an edge's vertices bound it).
    pub(crate) fn curve(&self, from: &Entity<'_>, id: u64) -> Result<CurveSpec, StepError> {
        self.curve_at(from, id, 0)
    }

    fn curve_at(&self, from: &Entity<'_>, id: u64, depth: usize) -> Result<CurveSpec, StepError> {
        let e = self.graph.get(from, id)?;
        if depth > MAX_CURVE_NESTING {
            return Err(e.malformed("curve wrappers nest too deeply"));
        }
        let r = e.record;
        if r.parts.len() == 1 {
            let name = r.parts[0].0.as_str();
            match name {
                "LINE" => {
                    let origin = self.point(&e, e.reference(1)?)?;
                    let v = self
                        .graph
                        .get_as(&e, e.reference(2)?, "VECTOR", "a line's vector")?;
                    let dir = self.direction(&v, v.reference(1)?)?.normalize();
                    let magnitude = v.real(2)? * self.scale;
                    if !(magnitude.is_finite() && magnitude > 0.0) {
                        return Err(v.malformed("the magnitude is not positive"));
                    }
                    return Ok(CurveSpec::Line {
                        origin,
                        direction: dir * magnitude,
                    });
                }
                "CIRCLE" => {
                    return Ok(CurveSpec::Circle {
                        placement: self.placement(&e, e.reference(1)?)?,
                        radius: self.length(&e, 2)?,
                    });
                }
                "ELLIPSE" => {
                    let (a, b) = (self.length(&e, 2)?, self.length(&e, 3)?);
                    if b > a {
                        return Err(e.malformed("semi_axis_2 exceeds semi_axis_1"));
                    }
                    return Ok(CurveSpec::Ellipse {
                        placement: self.placement(&e, e.reference(1)?)?,
                        a,
                        b,
                    });
                }
                "SURFACE_CURVE" | "SEAM_CURVE" | "TRIMMED_CURVE" => {
                    return self.curve_at(&e, e.reference(1)?, depth + 1);
                }
                "B_SPLINE_CURVE_WITH_KNOTS" => {
                    let degree = degree_of(&e, 1)?;
                    let points = self.points(&e, 2)?;
                    let knots = expand_knots(&e, 6, 7)?;
                    let weights = vec![1.0; points.len()];
                    return checked_curve(
                        &e,
                        BSplineData {
                            degree,
                            knots,
                            points,
                            weights,
                        },
                    );
                }
                "QUASI_UNIFORM_CURVE" | "UNIFORM_CURVE" | "BEZIER_CURVE" => {
                    let degree = degree_of(&e, 1)?;
                    let points = self.points(&e, 2)?;
                    let form = KnotForm::of(name).ok_or_else(|| e.unsupported("an edge curve"))?;
                    let knots = form.knots(&e, degree, points.len())?;
                    let weights = vec![1.0; points.len()];
                    return checked_curve(
                        &e,
                        BSplineData {
                            degree,
                            knots,
                            points,
                            weights,
                        },
                    );
                }
                _ => return Err(e.unsupported("an edge curve")),
            }
        }
        // The complex forms of a B-spline curve: its knots given (B_SPLINE_CURVE_WITH_KNOTS)
        // or implied by a uniform, quasi-uniform or Bezier form.
        if let Some(b) = r.part("B_SPLINE_CURVE") {
            let be = Entity { params: b, ..e };
            let degree = degree_of(&be, 0)?;
            let points = self.points(&be, 1)?;
            let knots = match r.part("B_SPLINE_CURVE_WITH_KNOTS") {
                Some(k) => expand_knots(&Entity { params: k, ..e }, 0, 1)?,
                None => {
                    let form = ["QUASI_UNIFORM_CURVE", "UNIFORM_CURVE", "BEZIER_CURVE"]
                        .into_iter()
                        .find(|f| r.has(f))
                        .and_then(KnotForm::of)
                        .ok_or_else(|| e.unsupported("an edge curve"))?;
                    form.knots(&e, degree, points.len())?
                }
            };
            let weights = match r.part("RATIONAL_B_SPLINE_CURVE") {
                Some(w) => Entity { params: w, ..e }.real_list(0)?,
                None => vec![1.0; points.len()],
            };
            return checked_curve(
                &e,
                BSplineData {
                    degree,
                    knots,
                    points,
                    weights,
                },
            );
        }
        Err(e.unsupported("an edge curve"))
    }

    /// A 2D point of a p-curve, in the surface's parameter units as the file writes them.
    fn point2(&self, from: &Entity<'_>, id: u64) -> Result<DVec2, StepError> {
        let e = self
            .graph
            .get_as(from, id, "CARTESIAN_POINT", "a p-curve's point")?;
        let c = e.real_list(1)?;
        if c.len() != 2 {
            return Err(e.malformed(format!("{} coordinates, needs 2", c.len())));
        }
        Ok(DVec2::new(c[0], c[1]))
    }

    fn points2(&self, e: &Entity<'_>, i: usize) -> Result<Vec<DVec2>, StepError> {
        e.ref_list(i)?
            .into_iter()
            .map(|p| self.point2(e, p))
            .collect()
    }

    /// The 2D curve of a PCURVE (`pcurve`): the first item of its DEFINITIONAL_REPRESENTATION,
    /// a LINE, CIRCLE or B-spline (simple or complex, with knots or an implied knot form), in
    /// the file's parameter units and with the 3D curve's parameter.
    ///
    /// # Errors
    /// [`StepError::Unsupported`] for other 2D curve types, and the errors of reading the
    /// entities; the caller then projects the edge instead (a p-curve is a redundant image of
    /// the edge's 3D curve, which defines it).
    pub(crate) fn pcurve_2d(
        &self,
        pcurve: &Entity<'_>,
    ) -> Result<Box<dyn crate::Curve2>, StepError> {
        let rep = self.graph.get_as(
            pcurve,
            pcurve.reference(2)?,
            "DEFINITIONAL_REPRESENTATION",
            "a p-curve's representation",
        )?;
        let items = rep.ref_list(1)?;
        let first = items.first().ok_or_else(|| rep.malformed("no item"))?;
        let e = self.graph.get(&rep, *first)?;
        let r = e.record;
        let whole = ParamRange {
            min: f64::NEG_INFINITY,
            max: f64::INFINITY,
            periodic: false,
        };
        if r.parts.len() == 1 {
            match r.parts[0].0.as_str() {
                "LINE" => {
                    let origin = self.point2(&e, e.reference(1)?)?;
                    let v = self
                        .graph
                        .get_as(&e, e.reference(2)?, "VECTOR", "a line's vector")?;
                    let d = self
                        .graph
                        .get_as(&v, v.reference(1)?, "DIRECTION", "a direction")?;
                    let c = d.real_list(1)?;
                    let dir = match c.as_slice() {
                        [x, y] => DVec2::new(*x, *y),
                        _ => return Err(d.malformed("a 2D direction needs 2 components")),
                    };
                    let dir = dir
                        .try_normalize()
                        .ok_or_else(|| d.malformed("the direction is zero"))?;
                    let magnitude = v.real(2)?;
                    if !(magnitude.is_finite() && magnitude > 0.0) {
                        return Err(v.malformed("the magnitude is not positive"));
                    }
                    return Ok(Box::new(crate::Line2 {
                        origin,
                        direction: dir * magnitude,
                        range: whole,
                    }));
                }
                "CIRCLE" => {
                    let a = self.graph.get_as(
                        &e,
                        e.reference(1)?,
                        "AXIS2_PLACEMENT_2D",
                        "a circle's placement",
                    )?;
                    let center = self.point2(&a, a.reference(1)?)?;
                    let x = match a.optional_reference(2)? {
                        Some(d) => {
                            let d = self.graph.get_as(&a, d, "DIRECTION", "a direction")?;
                            match d.real_list(1)?.as_slice() {
                                [x, y] => DVec2::new(*x, *y),
                                _ => {
                                    return Err(d.malformed("a 2D direction needs 2 components"));
                                }
                            }
                        }
                        None => DVec2::X,
                    };
                    let radius = e.real(2)?;
                    if !(radius.is_finite() && radius > 0.0 && x.length() > 0.0) {
                        return Err(e.malformed("a circle needs a positive radius and an axis"));
                    }
                    return Ok(Box::new(crate::Circle2 {
                        center,
                        radius,
                        phase: x.y.atan2(x.x),
                        sense: 1.0,
                        range: whole,
                    }));
                }
                "B_SPLINE_CURVE_WITH_KNOTS" => {
                    let degree = degree_of(&e, 1)?;
                    let points = self.points2(&e, 2)?;
                    let knots = expand_knots(&e, 6, 7)?;
                    let weights = vec![1.0; points.len()];
                    return nurbs2(&e, degree, knots, points, weights);
                }
                "QUASI_UNIFORM_CURVE" | "UNIFORM_CURVE" | "BEZIER_CURVE" => {
                    let degree = degree_of(&e, 1)?;
                    let points = self.points2(&e, 2)?;
                    let form = KnotForm::of(r.parts[0].0.as_str())
                        .ok_or_else(|| e.unsupported("a p-curve"))?;
                    let knots = form.knots(&e, degree, points.len())?;
                    let weights = vec![1.0; points.len()];
                    return nurbs2(&e, degree, knots, points, weights);
                }
                _ => return Err(e.unsupported("a p-curve")),
            }
        }
        if let Some(b) = r.part("B_SPLINE_CURVE") {
            let be = Entity { params: b, ..e };
            let degree = degree_of(&be, 0)?;
            let points = self.points2(&be, 1)?;
            let knots = match r.part("B_SPLINE_CURVE_WITH_KNOTS") {
                Some(k) => expand_knots(&Entity { params: k, ..e }, 0, 1)?,
                None => {
                    let form = ["QUASI_UNIFORM_CURVE", "UNIFORM_CURVE", "BEZIER_CURVE"]
                        .into_iter()
                        .find(|f| r.has(f))
                        .and_then(KnotForm::of)
                        .ok_or_else(|| e.unsupported("a p-curve"))?;
                    form.knots(&e, degree, points.len())?
                }
            };
            let weights = match r.part("RATIONAL_B_SPLINE_CURVE") {
                Some(w) => Entity { params: w, ..e }.real_list(0)?,
                None => vec![1.0; points.len()],
            };
            return nurbs2(&e, degree, knots, points, weights);
        }
        Err(e.unsupported("a p-curve"))
    }

    fn points(&self, e: &Entity<'_>, i: usize) -> Result<Vec<DVec3>, StepError> {
        e.ref_list(i)?
            .into_iter()
            .map(|p| self.point(e, p))
            .collect()
    }

    /// The surface of entity `id` (a RECTANGULAR_TRIMMED_SURFACE by its basis surface: the
    /// face's loops bound it).
    pub(crate) fn surface(&self, from: &Entity<'_>, id: u64) -> Result<SurfaceSpec, StepError> {
        let mut e = self.graph.get(from, id)?;
        // A RECTANGULAR_TRIMMED_SURFACE by its basis surface (the face's loops bound it).
        let mut depth = 0;
        while e.record.parts.len() == 1 && e.record.parts[0].0 == "RECTANGULAR_TRIMMED_SURFACE" {
            depth += 1;
            if depth > MAX_CURVE_NESTING {
                return Err(e.malformed("trimmed surfaces nest too deeply"));
            }
            e = self.graph.get(&e, e.reference(1)?)?;
        }
        let spec = self.surface_spec(&e)?;
        // The constructors' checks (radii, knots, weights) at the surface's own entity, so an
        // error names it rather than the face (the domain here is a placeholder).
        spec.build([range(0.0, 1.0), range(0.0, 1.0)])
            .map_err(|g| e.geometry(g))?;
        Ok(spec)
    }

    fn surface_spec(&self, e: &Entity<'_>) -> Result<SurfaceSpec, StepError> {
        let e = *e;
        let r = e.record;
        if r.parts.len() == 1 {
            let name = r.parts[0].0.as_str();
            let placement = || self.placement(&e, e.reference(1)?);
            return Ok(match name {
                "PLANE" => SurfaceSpec::Plane(placement()?),
                "CYLINDRICAL_SURFACE" => SurfaceSpec::Cylinder(placement()?, self.length(&e, 2)?),
                "CONICAL_SURFACE" => {
                    let radius = e.real(2)? * self.scale;
                    let angle = e.real(3)? * self.angle;
                    SurfaceSpec::Cone(placement()?, radius, angle)
                }
                "SPHERICAL_SURFACE" => SurfaceSpec::Sphere(placement()?, self.length(&e, 2)?),
                "TOROIDAL_SURFACE" => {
                    SurfaceSpec::Torus(placement()?, self.length(&e, 2)?, self.length(&e, 3)?)
                }
                "SURFACE_OF_LINEAR_EXTRUSION" => {
                    let curve = self.curve(&e, e.reference(1)?)?;
                    let v =
                        self.graph
                            .get_as(&e, e.reference(2)?, "VECTOR", "an extrusion axis")?;
                    let dir = self.direction(&v, v.reference(1)?)?.normalize();
                    let magnitude = v.real(2)? * self.scale;
                    if !(magnitude.is_finite() && magnitude > 0.0) {
                        return Err(v.malformed("the magnitude is not positive"));
                    }
                    SurfaceSpec::Extrusion(curve, dir * magnitude)
                }
                "SURFACE_OF_REVOLUTION" => {
                    let curve = self.curve(&e, e.reference(1)?)?;
                    let a = self
                        .graph
                        .get_as(&e, e.reference(2)?, "AXIS1_PLACEMENT", "an axis")?;
                    let point = self.point(&a, a.reference(1)?)?;
                    let axis = match a.optional_reference(2)? {
                        Some(d) => self.direction(&a, d)?.normalize(),
                        None => DVec3::Z,
                    };
                    SurfaceSpec::Revolution(curve, point, axis)
                }
                "QUASI_UNIFORM_SURFACE" | "UNIFORM_SURFACE" | "BEZIER_SURFACE" => {
                    let degree = [degree_of(&e, 1)?, degree_of(&e, 2)?];
                    let points = self.net(&e, 3)?;
                    let form = KnotForm::of(name).ok_or_else(|| e.unsupported("a face surface"))?;
                    let knots = net_knots(&e, form, degree, &points)?;
                    let weights = points.iter().map(|row| vec![1.0; row.len()]).collect();
                    SurfaceSpec::Nurbs {
                        degree,
                        knots,
                        points,
                        weights,
                    }
                }
                "B_SPLINE_SURFACE_WITH_KNOTS" => {
                    let degree = [degree_of(&e, 1)?, degree_of(&e, 2)?];
                    let points = self.net(&e, 3)?;
                    let knots = [expand_knots(&e, 8, 10)?, expand_knots(&e, 9, 11)?];
                    let weights = points.iter().map(|row| vec![1.0; row.len()]).collect();
                    SurfaceSpec::Nurbs {
                        degree,
                        knots,
                        points,
                        weights,
                    }
                }
                _ => return Err(e.unsupported("a face surface")),
            });
        }
        if let Some(b) = r.part("B_SPLINE_SURFACE") {
            let be = Entity { params: b, ..e };
            let degree = [degree_of(&be, 0)?, degree_of(&be, 1)?];
            let points = self.net(&be, 2)?;
            let knots = match r.part("B_SPLINE_SURFACE_WITH_KNOTS") {
                Some(k) => {
                    let ke = Entity { params: k, ..e };
                    [expand_knots(&ke, 0, 2)?, expand_knots(&ke, 1, 3)?]
                }
                None => {
                    let form = ["QUASI_UNIFORM_SURFACE", "UNIFORM_SURFACE", "BEZIER_SURFACE"]
                        .into_iter()
                        .find(|f| r.has(f))
                        .and_then(KnotForm::of)
                        .ok_or_else(|| e.unsupported("a face surface"))?;
                    net_knots(&e, form, degree, &points)?
                }
            };
            let weights = match r.part("RATIONAL_B_SPLINE_SURFACE") {
                Some(w) => {
                    let we = Entity { params: w, ..e };
                    let rows = we.list(0)?;
                    rows.iter()
                        .map(|row| match row {
                            crate::io::step::part21::Param::List(items) => items
                                .iter()
                                .map(|p| {
                                    crate::io::step::graph::real_of(p)
                                        .ok_or_else(|| we.malformed("a weight is not a number"))
                                })
                                .collect(),
                            _ => Err(we.malformed("the weights are not a list of rows")),
                        })
                        .collect::<Result<Vec<Vec<f64>>, StepError>>()?
                }
                None => points.iter().map(|row| vec![1.0; row.len()]).collect(),
            };
            return Ok(SurfaceSpec::Nurbs {
                degree,
                knots,
                points,
                weights,
            });
        }
        Err(e.unsupported("a face surface"))
    }

    fn net(&self, e: &Entity<'_>, i: usize) -> Result<Vec<Vec<DVec3>>, StepError> {
        e.list(i)?
            .iter()
            .map(|row| match row {
                crate::io::step::part21::Param::List(items) => items
                    .iter()
                    .map(|p| match p {
                        crate::io::step::part21::Param::Ref(id) => self.point(e, *id),
                        _ => Err(e.malformed("a control point is not a reference")),
                    })
                    .collect(),
                _ => Err(e.malformed("the control net is not a list of rows")),
            })
            .collect()
    }
}

/// A B-spline whose knots its type implies (ISO 10303-42, 4.3.4 and 4.3.5: the subtypes of
/// B_SPLINE_CURVE and B_SPLINE_SURFACE that carry no knot list).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum KnotForm {
    /// Knots −p, −p + 1, ..., n + 1, each once (n + 1 control points, degree p).
    Uniform,
    /// Knots 0, 1, ..., n − p, the end ones p + 1 times, the interior ones once.
    QuasiUniform,
    /// Piecewise Bezier: knots 0, 1, ..., n / p, the end ones p + 1 times, the interior
    /// ones p times (n must be a multiple of p).
    Bezier,
}

impl KnotForm {
    fn of(name: &str) -> Option<Self> {
        Some(match name {
            "UNIFORM_CURVE" | "UNIFORM_SURFACE" => Self::Uniform,
            "QUASI_UNIFORM_CURVE" | "QUASI_UNIFORM_SURFACE" => Self::QuasiUniform,
            "BEZIER_CURVE" | "BEZIER_SURFACE" => Self::Bezier,
            _ => return None,
        })
    }

    /// The expanded knots of `count` control points of degree `degree` (n + p + 2 of them,
    /// n + 1 = count).
    fn knots(self, e: &Entity<'_>, degree: usize, count: usize) -> Result<Vec<f64>, StepError> {
        if count <= degree {
            return Err(e.malformed(format!(
                "{count} control points for degree {degree} (at least {} needed)",
                degree + 1
            )));
        }
        let n = count - 1;
        let p = degree;
        Ok(match self {
            Self::Uniform => (0..=n + p + 1).map(|k| k as f64 - p as f64).collect(),
            Self::QuasiUniform => {
                let mut out = vec![0.0; p + 1];
                out.extend((1..n - p + 1).map(|k| k as f64));
                out.extend(std::iter::repeat_n((n - p + 1) as f64, p + 1));
                out
            }
            Self::Bezier => {
                if n % p != 0 {
                    return Err(e.malformed(format!(
                        "{count} control points do not make Bezier segments of degree {degree}"
                    )));
                }
                let segments = n / p;
                let mut out = vec![0.0; p + 1];
                for k in 1..segments {
                    out.extend(std::iter::repeat_n(k as f64, p));
                }
                out.extend(std::iter::repeat_n(segments as f64, p + 1));
                out
            }
        })
    }
}

/// The implied knots (u, v) of a control net with rows along u.
fn net_knots(
    e: &Entity<'_>,
    form: KnotForm,
    degree: [usize; 2],
    points: &[Vec<DVec3>],
) -> Result<[Vec<f64>; 2], StepError> {
    let columns = points.first().map_or(0, Vec::len);
    if points.iter().any(|row| row.len() != columns) {
        return Err(e.malformed("the control net's rows differ in length"));
    }
    Ok([
        form.knots(e, degree[0], points.len())?,
        form.knots(e, degree[1], columns)?,
    ])
}

/// A B-spline p-curve, its data checked by the constructor at its entity.
fn nurbs2(
    e: &Entity<'_>,
    degree: usize,
    knots: Vec<f64>,
    points: Vec<DVec2>,
    weights: Vec<f64>,
) -> Result<Box<dyn crate::Curve2>, StepError> {
    let c = crate::curves::nurbs_curve2::NurbsCurve2::new(degree, knots, points, weights, false)
        .map_err(|g| e.geometry(g))?;
    Ok(Box::new(c))
}

/// A B-spline curve whose data the constructor accepts (knots, weights), with the
/// constructor's error naming the entity.
fn checked_curve(e: &Entity<'_>, data: BSplineData<Vec<DVec3>>) -> Result<CurveSpec, StepError> {
    NurbsCurve::new(
        data.degree,
        data.knots.clone(),
        data.points.clone(),
        data.weights.clone(),
        false,
    )
    .map_err(|g| e.geometry(g))?;
    Ok(CurveSpec::Nurbs(data))
}

fn degree_of(e: &Entity<'_>, i: usize) -> Result<usize, StepError> {
    let d = e.int(i)?;
    usize::try_from(d)
        .ok()
        .filter(|&d| (1..=crate::MAX_DEGREE).contains(&d))
        .ok_or_else(|| e.malformed(format!("degree {d} is outside 1..={}", crate::MAX_DEGREE)))
}

/// Knots with multiplicities expanded (lists at parameter indices `mults` and `knots`).
fn expand_knots(e: &Entity<'_>, mults: usize, knots: usize) -> Result<Vec<f64>, StepError> {
    let m = e.list(mults)?;
    let k = e.real_list(knots)?;
    if m.len() != k.len() {
        return Err(e.malformed(format!("{} multiplicities for {} knots", m.len(), k.len())));
    }
    let mut out = Vec::new();
    for (mult, &knot) in m.iter().zip(&k) {
        let count = match mult {
            crate::io::step::part21::Param::Int(c) if *c >= 1 && *c <= 64 => *c as usize,
            _ => return Err(e.malformed("a knot multiplicity is not an integer in 1..=64")),
        };
        out.extend(std::iter::repeat_n(knot, count));
    }
    if out.len() > 1_000_000 {
        return Err(e.malformed("too many knots"));
    }
    Ok(out)
}

impl CurveSpec {
    /// The parameter of the curve point nearest `p` (closed form for lines and conics, near
    /// `hint` or by sampling for B-splines), for a curve run in `sense` (+1 or −1, see
    /// [`CurveSpec::build`]).
    pub(crate) fn param_of(&self, p: DVec3, sense: f64) -> f64 {
        match self {
            Self::Line { origin, direction } => {
                (p - *origin).dot(*direction) / direction.length_squared() * sense
            }
            Self::Circle { placement, .. } | Self::Ellipse { placement, .. } => {
                let l = p - placement.origin;
                let (x, y) = (l.dot(placement.x), l.dot(placement.y) * sense);
                let (x, y) = match self {
                    Self::Ellipse { a, b, .. } => (x / a, y / b),
                    _ => (x, y),
                };
                y.atan2(x).rem_euclid(TAU)
            }
            Self::Nurbs(_) => f64::NAN,
        }
    }

    /// The curve over parameter `range` (in the sense-adjusted parameter), running in `sense`:
    /// +1 as the file defines it, −1 backwards (a conic about the flipped axis, a line or
    /// B-spline through t ↦ −t).
    pub(crate) fn build(
        &self,
        range_: ParamRange,
        sense: f64,
    ) -> Result<Box<dyn Curve>, GeometryError> {
        Ok(match self {
            Self::Line { origin, direction } => {
                Box::new(LineCurve::new(*origin, *direction * sense, range_)?)
            }
            Self::Circle { placement, radius } => Box::new(CircleCurve::new(
                flipped(placement, sense)?,
                *radius,
                range_,
            )?),
            Self::Ellipse { placement, a, b } => Box::new(EllipseCurve::new(
                flipped(placement, sense)?,
                *a,
                *b,
                range_,
            )?),
            Self::Nurbs(d) => {
                let curve = NurbsCurve::new(
                    d.degree,
                    d.knots.clone(),
                    d.points.clone(),
                    d.weights.clone(),
                    false,
                )?;
                Box::new(SubCurve {
                    inner: Box::new(curve),
                    sense,
                    range: range_,
                })
            }
        })
    }

    /// The domain of the curve as the file defines it (a B-spline's knot range; a full turn
    /// for conics; `None` for an unbounded line).
    pub(crate) fn natural_domain(&self) -> Option<ParamRange> {
        match self {
            Self::Line { .. } => None,
            Self::Circle { .. } | Self::Ellipse { .. } => Some(TURN),
            Self::Nurbs(d) => {
                let (lo, hi) = (
                    d.knots.get(d.degree)?,
                    d.knots.get(d.knots.len().checked_sub(d.degree + 1)?)?,
                );
                Some(range(*lo, *hi))
            }
        }
    }
}

fn flipped(p: &Placement, sense: f64) -> Result<Placement, GeometryError> {
    if sense > 0.0 {
        Ok(*p)
    } else {
        Placement::new(p.origin, -p.z, p.x)
    }
}

/// A curve run over part of its domain, forwards or backwards: C'(s) = C(sense · s) for s in
/// `range` (the B-spline of an edge between its vertices).
#[derive(Debug)]
pub(crate) struct SubCurve {
    /// The curve.
    pub inner: Box<dyn Curve>,
    /// +1 or −1.
    pub sense: f64,
    /// The domain of s.
    pub range: ParamRange,
}

impl Curve for SubCurve {
    fn eval(&self, s: f64) -> CurvePoint {
        let d = self.inner.domain();
        let t = (self.sense * s).clamp(d.min, d.max);
        let c = self.inner.eval(t);
        CurvePoint {
            point: c.point,
            d1: c.d1 * self.sense,
            d2: c.d2,
        }
    }

    fn domain(&self) -> ParamRange {
        self.range
    }
}

impl SurfaceSpec {
    /// True for the parameters that are periodic angles (u of every surface of revolution, v
    /// of a torus).
    pub(crate) fn periodic(&self) -> [bool; 2] {
        match self {
            Self::Cylinder(..) | Self::Cone(..) | Self::Sphere(..) | Self::Revolution(..) => {
                [true, false]
            }
            Self::Torus(..) => [true, true],
            Self::Extrusion(c, _) => [
                matches!(c, CurveSpec::Circle { .. } | CurveSpec::Ellipse { .. }),
                false,
            ],
            _ => [false, false],
        }
    }

    /// The surface over `domain` where a parameter is free (plane, heights, extrusion
    /// lengths, lines); angles keep their full turn and B-splines their knot range.
    pub(crate) fn build(&self, domain: [ParamRange; 2]) -> Result<Box<dyn Surface>, GeometryError> {
        Ok(match self {
            Self::Plane(p) => Box::new(Plane::new(*p, domain)?),
            Self::Cylinder(p, r) => Box::new(CylinderSurface::new(*p, *r, [TURN, domain[1]])?),
            Self::Cone(p, r, a) => {
                // Keep v on the side of the apex where the face is.
                let apex = -r / a.sin();
                let v = range(
                    domain[1].min.max(apex),
                    domain[1].max.max(apex + r.abs().max(1.0)),
                );
                Box::new(ConeSurface::new(*p, *r, *a, [TURN, v])?)
            }
            Self::Sphere(p, r) => Box::new(SphereSurface::new(
                *p,
                *r,
                [TURN, range(-FRAC_PI_2, FRAC_PI_2)],
            )?),
            Self::Torus(p, big, small) => {
                Box::new(TorusSurface::new(*p, *big, *small, [TURN, TURN])?)
            }
            Self::Extrusion(c, d) => {
                let u = c.natural_domain().unwrap_or(domain[0]);
                Box::new(LinearExtrusionSurface::new(
                    c.build(u, 1.0)?,
                    *d,
                    domain[1],
                )?)
            }
            Self::Revolution(c, point, axis) => {
                let v = c.natural_domain().unwrap_or(domain[1]);
                let v = ParamRange {
                    periodic: false,
                    ..v
                };
                Box::new(RevolutionSurface::new(
                    c.build(v, 1.0)?,
                    *point,
                    *axis,
                    TURN,
                )?)
            }
            Self::Nurbs {
                degree,
                knots,
                points,
                weights,
            } => Box::new(NurbsSurface::new(
                *degree,
                knots.clone(),
                points.clone(),
                weights.clone(),
                [false, false],
            )?),
        })
    }

    /// The factors from the file's (u, v) of a point of this surface to the model's (before
    /// a reversed face's v ↦ −v), given the file's millimetres per length unit and radians per
    /// angle unit: lengths scale, angles convert, a B-spline's knots stay; the cone's v runs
    /// along the ruling in the model and along the axis in STEP (v_model = v / cos a).
    /// `None` where the reader does not map a file's p-curves (extrusions and revolutions:
    /// their curve's own parameter), which are then projected.
    pub(crate) fn pcurve_scale(&self, scale: f64, angle: f64) -> Option<DVec2> {
        Some(match self {
            Self::Plane(_) => DVec2::new(scale, scale),
            Self::Cylinder(..) => DVec2::new(angle, scale),
            Self::Cone(_, _, a) => DVec2::new(angle, scale / a.cos()),
            Self::Sphere(..) | Self::Torus(..) => DVec2::new(angle, angle),
            Self::Nurbs { .. } => DVec2::ONE,
            Self::Extrusion(..) | Self::Revolution(..) => return None,
        })
    }

    /// Which parameters [`SurfaceSpec::build`] takes from its `domain` argument.
    pub(crate) fn free(&self) -> [bool; 2] {
        match self {
            Self::Plane(_) => [true, true],
            Self::Cylinder(..) | Self::Cone(..) => [false, true],
            Self::Extrusion(c, _) => [c.natural_domain().is_none(), true],
            Self::Revolution(c, ..) => [false, c.natural_domain().is_none()],
            _ => [false, false],
        }
    }

    /// A first guess of the (u, v) of the point `p` near the surface (closed form for the
    /// analytic surfaces), or `None` where a search is needed.
    pub(crate) fn guess(&self, p: DVec3) -> Option<[f64; 2]> {
        let local = |pl: &Placement| {
            let l = p - pl.origin;
            DVec3::new(l.dot(pl.x), l.dot(pl.y), l.dot(pl.z))
        };
        match self {
            Self::Plane(pl) => {
                let l = local(pl);
                Some([l.x, l.y])
            }
            Self::Cylinder(pl, _) => {
                let l = local(pl);
                Some([l.y.atan2(l.x), l.z])
            }
            Self::Cone(pl, r, a) => {
                let l = local(pl);
                // Nearest point on the ruling through the point's angle.
                let rho = l.x.hypot(l.y);
                let v = (rho - r) * a.sin() + l.z * a.cos();
                Some([l.y.atan2(l.x), v])
            }
            Self::Sphere(pl, _) => {
                let l = local(pl);
                Some([l.y.atan2(l.x), l.z.atan2(l.x.hypot(l.y))])
            }
            Self::Torus(pl, big, _) => {
                let l = local(pl);
                Some([l.y.atan2(l.x), l.z.atan2(l.x.hypot(l.y) - big)])
            }
            _ => None,
        }
    }
}
