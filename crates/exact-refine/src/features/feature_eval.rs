//! Uniform evaluation of a feature (face, edge, vertex, or a fixed point) in A's frame: the
//! point, its first and second derivatives for 0, 1 or 2 parameters, and an outward direction.

use geom_param::{
    DPose3, DVec3, FaceId, FeatureLocation, POLE_MERIDIANS, ParamRange, ParamSide, Solid,
    SurfacePoint,
};
use glam::DMat3;

/// What one side of the problem is: a feature of a posed solid, or a fixed point (the target
/// of a projection). Positions are in A's frame: a solid's points are `frame.point(local)`.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Body<'a> {
    /// A solid posed in A's frame.
    Solid {
        /// The solid.
        solid: &'a Solid,
        /// Its pose in A's frame.
        frame: Frame,
        /// Where re-entry from an edge or vertex may go: any face (`None`), or only this face,
        /// its edges and vertices (a solve kept on its seed's face, see
        /// `newton_refiner::on_seed_faces`).
        within: Option<FaceId>,
    },
    /// A fixed point in A's frame (no parameters).
    Point(DVec3),
}

/// A pose with its rotation as a matrix: applied to the point and five derivatives of every
/// evaluation, where a matrix product costs half a quaternion rotation.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Frame {
    rotation: DMat3,
    translation: DVec3,
}

impl Frame {
    /// The identity: A's frame is the solid's own.
    pub(crate) fn identity() -> Self {
        Self {
            rotation: DMat3::IDENTITY,
            translation: DVec3::ZERO,
        }
    }

    pub(crate) fn new(pose: &DPose3) -> Self {
        Self {
            rotation: DMat3::from_quat(pose.rotation),
            translation: pose.translation,
        }
    }

    /// A direction in A's frame.
    pub(crate) fn vector(&self, v: DVec3) -> DVec3 {
        self.rotation * v
    }

    /// A point in A's frame.
    pub(crate) fn point(&self, p: DVec3) -> DVec3 {
        self.rotation * p + self.translation
    }
}

/// `range.normalize(t)`, keeping a value already inside the range as it is (the usual case:
/// [`crate::features::feature_switch::settle`] keeps parameters there) without a remainder
/// computation.
pub(crate) fn wrap(range: &ParamRange, t: f64) -> f64 {
    if range.periodic && t >= range.min && t < range.max {
        t
    } else {
        range.normalize(t)
    }
}

/// Where the variable point of a body is: a feature location, or `None` for a fixed point.
pub(crate) type Loc = Option<FeatureLocation>;

/// Point and derivatives of a feature in A's frame for its `n` (0, 1 or 2) parameters.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct FeatureEval {
    /// The point (mm).
    pub point: DVec3,
    /// Number of parameters.
    pub n: usize,
    /// First derivatives ∂P/∂x_i.
    pub d: [DVec3; 2],
    /// Second derivatives ∂²P/∂x_i∂x_j.
    pub dd: [[DVec3; 2]; 2],
}

/// The parameters of a location as an array and their count.
pub(crate) fn params(loc: &Loc) -> ([f64; 2], usize) {
    match loc {
        Some(FeatureLocation::Face { u, v, .. }) => ([*u, *v], 2),
        Some(FeatureLocation::Edge { t, .. }) => ([*t, 0.0], 1),
        _ => ([0.0; 2], 0),
    }
}

/// The same feature with new parameters.
pub(crate) fn with_params(loc: &Loc, x: [f64; 2]) -> Loc {
    match *loc {
        Some(FeatureLocation::Face { id, .. }) => Some(FeatureLocation::Face {
            id,
            u: x[0],
            v: x[1],
        }),
        Some(FeatureLocation::Edge { id, .. }) => Some(FeatureLocation::Edge { id, t: x[0] }),
        other => other,
    }
}

/// Parameter side of a face rectangle at index `param` (0 = u, 1 = v), at its min or max end.
pub(crate) fn side_of(param: usize, at_max: bool) -> ParamSide {
    match (param, at_max) {
        (0, false) => ParamSide::UMin,
        (0, true) => ParamSide::UMax,
        (_, false) => ParamSide::VMin,
        (_, true) => ParamSide::VMax,
    }
}

impl Body<'_> {
    /// How far apart (mm) one point may evaluate on two adjacent features of this body: the
    /// solid's model tolerance (an edge lies within it of its faces, a vertex of its edges'
    /// ends); 0 for a fixed point.
    pub fn feature_gap(&self) -> f64 {
        match self {
            Self::Solid { solid, .. } => solid.model_tolerance(),
            Self::Point(_) => 0.0,
        }
    }

    /// Parameter domains of the feature at `loc` (unused entries are a dummy range).
    pub fn domains(&self, loc: &Loc) -> [ParamRange; 2] {
        let dummy = ParamRange {
            min: 0.0,
            max: 0.0,
            periodic: false,
        };
        match (self, loc) {
            (Self::Solid { solid, .. }, Some(FeatureLocation::Face { id, .. })) => {
                solid.face(*id).surface.domain()
            }
            (Self::Solid { solid, .. }, Some(FeatureLocation::Edge { id, .. })) => {
                [solid.edge(*id).curve.domain(), dummy]
            }
            _ => [dummy; 2],
        }
    }

    /// [`Self::eval`], taking a face's surface evaluation from `known` when it is of the same
    /// face at the same (wrapped) parameters, bit for bit: the same answer without evaluating
    /// the surface again.
    ///
    /// Comparing the location's own parameters suffices: [`wrap`] keeps a wrapped parameter
    /// as it is, so equal bits give the surface evaluation [`Self::eval`] would take.
    pub fn eval_reusing(&self, loc: &Loc, known: Option<&LocalFacePoint>) -> FeatureEval {
        if let (Self::Solid { frame, .. }, Some(FeatureLocation::Face { id, u, v }), Some(k)) =
            (self, loc, known)
        {
            if k.face == *id && [u.to_bits(), v.to_bits()] == k.uv.map(f64::to_bits) {
                return face_eval(frame, &k.at);
            }
        }
        self.eval(loc)
    }

    /// Point and derivatives at `loc`, in A's frame.
    pub fn eval(&self, loc: &Loc) -> FeatureEval {
        match (self, loc) {
            (Self::Point(p), _) => FeatureEval {
                point: *p,
                ..FeatureEval::default()
            },
            (Self::Solid { solid, frame, .. }, Some(location)) => {
                let r = |v: DVec3| frame.vector(v);
                match *location {
                    FeatureLocation::Face { id, u, v } => {
                        let surface = &solid.face(id).surface;
                        let [du, dv] = surface.domain();
                        face_eval(frame, &surface.eval(wrap(&du, u), wrap(&dv, v)))
                    }
                    FeatureLocation::Edge { id, t } => {
                        let curve = &solid.edge(id).curve;
                        let c = curve.eval(wrap(&curve.domain(), t));
                        FeatureEval {
                            point: frame.point(c.point),
                            n: 1,
                            d: [r(c.d1), DVec3::ZERO],
                            dd: [[r(c.d2), DVec3::ZERO], [DVec3::ZERO; 2]],
                        }
                    }
                    FeatureLocation::Vertex { id } => FeatureEval {
                        point: frame.point(solid.vertex(id).point),
                        ..FeatureEval::default()
                    },
                }
            }
            (Self::Solid { frame, .. }, None) => FeatureEval {
                point: frame.translation,
                ..FeatureEval::default()
            },
        }
    }

    /// [`Self::outward`] at `loc` where `eval` is the evaluation there: on a face the normal is
    /// ∂P/∂u × ∂P/∂v of `eval` (the orientation of every face), which costs no evaluation;
    /// where that cross product is degenerate (a pole) the surface's own normal.
    pub fn outward_at(&self, loc: &Loc, eval: &FeatureEval) -> Option<DVec3> {
        if let (Some(FeatureLocation::Face { .. }), 2) = (loc, eval.n) {
            // Unit derivatives first, so that a tiny speed near an axis loses no precision.
            let cross = eval.d[0]
                .normalize_or_zero()
                .cross(eval.d[1].normalize_or_zero());
            if cross.length_squared() > 1e-12 {
                return Some(cross.normalize());
            }
        }
        self.outward(loc)
    }

    /// Unit outward direction of the solid at `loc`, in A's frame: the face normal; for an edge
    /// the normalised sum of its faces' normals there; for a vertex the normal of a pole, or at
    /// an apex minus the mean of the faces' inward tangents. `None` for a fixed point or where
    /// none of these exists.
    pub fn outward(&self, loc: &Loc) -> Option<DVec3> {
        let (Self::Solid { solid, frame, .. }, Some(location)) = (self, loc) else {
            return None;
        };
        let local = match *location {
            FeatureLocation::Face { id, u, v } => {
                let surface = &solid.face(id).surface;
                let [du, dv] = surface.domain();
                surface.normal(wrap(&du, u), wrap(&dv, v))
            }
            FeatureLocation::Edge { id, t } => {
                let edge = solid.edge(id);
                let t = wrap(&edge.curve.domain(), t);
                let sum: DVec3 = edge
                    .uses
                    .iter()
                    .filter_map(|use_| {
                        let [a, b] = solid.use_params(use_, t);
                        let surface = &solid.face(use_.face).surface;
                        let [ra, rb] = surface.domain();
                        surface.normal(wrap(&ra, a), wrap(&rb, b))
                    })
                    .sum();
                sum.try_normalize()
            }
            FeatureLocation::Vertex { id } => {
                // Where edges end (a corner): the mean of their faces' normals there.
                if let Some(corner) = corner_normal(solid, id) {
                    return Some(frame.vector(corner));
                }
                // A pole has a normal; only an apex needs the inward tangents. Four meridians of
                // each face side collapsed here: every fourth of its `PoleMeridians`.
                solid
                    .pole_meridians(id)
                    .find_map(|meridians| {
                        let surface = &solid.face(meridians.face).surface;
                        let domain = surface.domain();
                        meridians
                            .at
                            .iter()
                            .step_by(POLE_MERIDIANS / 4)
                            .find_map(|&t| {
                                let [a, b] = meridians.side.params_at(&domain, t);
                                surface.normal(a, b)
                            })
                    })
                    .or_else(|| {
                        let inward: DVec3 = solid
                            .pole_meridians(id)
                            .flat_map(|meridians| {
                                meridians.tangents.iter().step_by(POLE_MERIDIANS / 4)
                            })
                            .map(|t| t.normalize_or_zero())
                            .sum();
                        (-inward).try_normalize()
                    })
            }
        };
        local.map(|n| frame.vector(n))
    }
}

/// A face's surface evaluated in its solid's own frame at wrapped parameters `uv`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct LocalFacePoint {
    /// The face.
    pub face: geom_param::FaceId,
    /// The (wrapped) parameters the surface was evaluated at.
    pub uv: [f64; 2],
    /// The evaluation, in the solid's frame.
    pub at: SurfacePoint,
}

/// A face's evaluation `s` (its solid's frame) moved into A's frame by `frame`.
fn face_eval(frame: &Frame, s: &SurfacePoint) -> FeatureEval {
    let r = |v: DVec3| frame.vector(v);
    FeatureEval {
        point: frame.point(s.point),
        n: 2,
        d: [r(s.du), r(s.dv)],
        dd: [[r(s.duu), r(s.duv)], [r(s.duv), r(s.dvv)]],
    }
}

/// The mean of the normals of the faces around a vertex where edges end, taken at the edges'
/// ends; `None` where no edge ends at the vertex or the normals cancel.
fn corner_normal(solid: &Solid, id: geom_param::VertexId) -> Option<DVec3> {
    let mut sum = DVec3::ZERO;
    for &e in &solid.vertex(id).edges {
        let edge = solid.edge(e);
        let Some(ends) = edge.ends else { continue };
        let range = edge.curve.domain();
        for (end, t) in [(ends[0], range.min), (ends[1], range.max)] {
            if end != id {
                continue;
            }
            for use_ in &edge.uses {
                let [a, b] = solid.use_params(use_, t);
                let surface = &solid.face(use_.face).surface;
                let [ra, rb] = surface.domain();
                if let Some(n) = surface.normal(wrap(&ra, a), wrap(&rb, b)) {
                    sum += n;
                }
            }
        }
    }
    sum.try_normalize()
}
