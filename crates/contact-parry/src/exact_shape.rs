//! [`ExactShape`]: a prepared exact solid as a parry [`Shape`] (`ShapeType::Custom`).

use crate::closed_mesh::ClosedMesh;
use crate::error::ShapeError;
use contact_pipeline::{ContactPipeline, PreparedObject};
use geom_param::ObjectModel;
use glam::DVec3;
use parry3d_f64::bounding_volume::{Aabb, BoundingSphere};
use parry3d_f64::mass_properties::MassProperties;
use parry3d_f64::math::{Pose, Real, Vector};
use parry3d_f64::query::{
    PointProjection, PointQuery, Ray, RayCast, RayCullingMode, RayIntersection,
};
use parry3d_f64::shape::{Ball, Cuboid, FeatureId, Shape, ShapeType, TypedShape};
use std::sync::Arc;

/// An exact solid (a [`PreparedObject`] of the default pipeline) as a parry shape, with the
/// pipeline that prepared it. Clones share the preparation (`Arc`s): many colliders of one
/// model cost one preparation.
///
/// Units: the object's millimetres are parry's length unit (1 parry unit = 1 mm); use the same
/// unit for every other shape and pose, and give rapier `length_unit = 1000` for a world
/// in millimetres (gravity 9810 mm/s²).
///
/// What is exact and what is not:
/// - Contacts, distances, closest points and intersection tests go through
///   [`crate::ExactDispatcher`], which answers them with the contact pipeline on the exact
///   faces, edges and vertices.
/// - The bounding volumes hold the exact surface: the local AABB is the mesh's box grown by
///   the chordal error e; the bounding sphere is the prepared object's
///   ([`PreparedObject::bounding_centre`], [`PreparedObject::bounding_radius`]).
/// - Mass properties come from the closed mesh ([`ClosedMesh`]: the component meshes welded),
///   by the divergence theorem (parry's tetrahedron sums): every mesh point is within e of
///   the exact surface, so the volume is within about area × e of the exact solid's (a 10 mm ball
///   meshed at the default e = 0.05 mm: bound 50 mm³ of 4189 mm³, 1.2 %; measured 19 mm³,
///   0.45 %, in `tests/shape.rs`), and the centre of mass and inertia likewise to first
///   order in e.
///   [`ExactShape::volume_error_bound`] gives that bound.
/// - Point projections and ray casts (parry's `PointQuery` and `RayCast`, which every
///   `Shape` must offer; rapier's scene queries use them) are answered on the closed mesh:
///   within e of the exact answer. Parry's own free functions (`parry3d_f64::query::*`,
///   [`parry3d_f64::query::DefaultQueryDispatcher`]) know nothing of this type: they answer
///   `Unsupported` for it, except a `Ball` intersection test, which parry answers by point
///   projection (so on the mesh). Use [`crate::ExactDispatcher`].
#[derive(Clone)]
pub struct ExactShape {
    pipeline: Arc<ContactPipeline>,
    object: Arc<PreparedObject>,
    placement: Pose,
    /// The parry primitive this shape is exactly (its mass properties are then the closed
    /// form's), if any.
    primitive: Option<Primitive>,
    mesh: Arc<ClosedMesh>,
    local_aabb: Aabb,
    ccd_thickness: f64,
}

/// A parry primitive an exact shape is exactly (centred in the shape's frame, mm).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Primitive {
    /// A ball of this radius.
    Ball(f64),
    /// A cuboid of these half extents.
    Cuboid(DVec3),
}

impl std::fmt::Debug for ExactShape {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ExactShape")
            .field("name", &self.object.model.name)
            .field("mesh", &self.mesh)
            .field("ccd_thickness", &self.ccd_thickness)
            .finish()
    }
}

impl ExactShape {
    /// The shape of `object`, which `pipeline` prepared ([`ContactPipeline::prepare`]; an
    /// object prepared by a pipeline with other options would make every query wrong, which
    /// this cannot check: use [`Self::from_model`] when in doubt). Welds the object's meshes
    /// into one closed mesh and measures the CCD thickness (a ray per mesh vertex).
    ///
    /// # Errors
    /// [`ShapeError`] when the component meshes do not weld into a closed, outward mesh.
    pub fn new(
        pipeline: Arc<ContactPipeline>,
        object: Arc<PreparedObject>,
    ) -> Result<Self, ShapeError> {
        Self::placed(pipeline, object, Pose::IDENTITY)
    }

    /// As [`Self::new`], with the object placed in the shape's frame by `placement` (shape
    /// point = placement × object point): the shape's frame, in which parry gives poses and
    /// takes points, need not be the object's.
    ///
    /// # Errors
    /// As [`Self::new`].
    pub fn placed(
        pipeline: Arc<ContactPipeline>,
        object: Arc<PreparedObject>,
        placement: Pose,
    ) -> Result<Self, ShapeError> {
        let mesh = ClosedMesh::weld(&object.model, &placement)?;
        let e = mesh.chordal_error;
        let aabb = mesh.trimesh.local_aabb();
        let local_aabb = Aabb::new(aabb.mins - Vector::splat(e), aabb.maxs + Vector::splat(e));
        let ccd_thickness = half_thinnest_wall(&mesh);
        Ok(Self {
            pipeline,
            object,
            placement,
            primitive: None,
            mesh: Arc::new(mesh),
            local_aabb,
            ccd_thickness,
        })
    }

    /// Prepares `model` with `pipeline` and wraps it as [`Self::new`] does.
    ///
    /// # Errors
    /// As [`Self::new`].
    pub fn from_model(
        pipeline: Arc<ContactPipeline>,
        model: ObjectModel,
    ) -> Result<Self, ShapeError> {
        let object = Arc::new(pipeline.prepare(model));
        Self::new(pipeline, object)
    }

    /// This shape with the mass properties of `primitive` (a parry ball or cuboid it is
    /// exactly, in the shape's frame), in place of the mesh's.
    pub(crate) fn with_primitive(mut self, primitive: Primitive) -> Self {
        self.primitive = Some(primitive);
        self
    }

    /// The pipeline that prepared the object (queries between two exact shapes need the same
    /// one, compared by pointer).
    #[must_use]
    pub fn pipeline(&self) -> &Arc<ContactPipeline> {
        &self.pipeline
    }

    /// The prepared exact object.
    #[must_use]
    pub fn object(&self) -> &Arc<PreparedObject> {
        &self.object
    }

    /// The object's frame in the shape's frame (identity unless built with [`Self::placed`]).
    #[must_use]
    pub fn placement(&self) -> &Pose {
        &self.placement
    }

    /// The closed mesh (shape frame, mm) that mass properties, point projections and ray
    /// casts are computed on, and that [`crate::BeyondReach::MeshApproximation`] hands to
    /// parry.
    #[must_use]
    pub fn closed_mesh(&self) -> &ClosedMesh {
        &self.mesh
    }

    /// Bound (mm³) on the difference between the closed mesh's volume and the exact solid's:
    /// the mesh area times its chordal error.
    #[must_use]
    pub fn volume_error_bound(&self) -> f64 {
        self.mesh.area * self.mesh.chordal_error
    }
}

/// Half the thinnest wall of the mesh (mm): from every vertex along its inward vertex normal
/// (the sum of its triangles' area-weighted normals) and from every triangle's centroid along
/// its inward normal, the distance to where the ray leaves the solid (triangles facing the
/// ray's way only, so the start's own triangles are not hit); the least, halved, as parry's
/// `ccd_thickness` is a half-thickness (a ball's radius, a cuboid's smallest half extent).
/// 0 when no ray finds an exit.
fn half_thinnest_wall(mesh: &ClosedMesh) -> f64 {
    let vertices = mesh.trimesh.vertices();
    let mut normals = vec![DVec3::ZERO; vertices.len()];
    let mut starts = Vec::with_capacity(vertices.len() + mesh.trimesh.indices().len());
    for t in mesh.trimesh.indices() {
        let [a, b, c] = t.map(|i| vertices[i as usize]);
        let n = (b - a).cross(c - a);
        for &i in t {
            normals[i as usize] += n;
        }
        starts.push(((a + b + c) / 3.0, n));
    }
    starts.extend(vertices.iter().copied().zip(normals));
    let mut thinnest = f64::INFINITY;
    for (p, n) in starts {
        let Some(n) = n.try_normalize() else { continue };
        let ray = Ray::new(p, -n);
        // A ray of a closed mesh always leaves it; one that finds no exit grazed an edge or
        // a vertex of the far side exactly (from a box's corner to the opposite one), and is
        // skipped: the triangles around it start rays of their own.
        if let Some(hit) = mesh.trimesh.cast_local_ray_with_culling(
            &ray,
            Real::MAX,
            RayCullingMode::IgnoreFrontfaces,
        ) {
            thinnest = thinnest.min(hit.time_of_impact);
        }
    }
    if thinnest.is_finite() {
        0.5 * thinnest
    } else {
        0.0
    }
}

impl PointQuery for ExactShape {
    /// On the closed mesh (within its chordal error of the exact surface).
    fn project_local_point(&self, pt: Vector, solid: bool) -> PointProjection {
        self.mesh.trimesh.project_local_point(pt, solid)
    }

    /// On the closed mesh; the feature is the mesh triangle's.
    fn project_local_point_and_get_feature(&self, pt: Vector) -> (PointProjection, FeatureId) {
        self.mesh.trimesh.project_local_point_and_get_feature(pt)
    }

    /// On the closed mesh (its pseudo-normals decide inside from outside).
    fn contains_local_point(&self, pt: Vector) -> bool {
        self.mesh.trimesh.contains_local_point(pt)
    }
}

impl RayCast for ExactShape {
    /// On the closed mesh. A `solid` ray starting inside hits at time 0 (with a zero normal).
    fn cast_local_ray_and_get_normal(
        &self,
        ray: &Ray,
        max_time_of_impact: Real,
        solid: bool,
    ) -> Option<RayIntersection> {
        if solid && self.mesh.trimesh.contains_local_point(ray.origin) {
            return Some(RayIntersection::new(0.0, Vector::ZERO, FeatureId::Unknown));
        }
        self.mesh
            .trimesh
            .cast_local_ray_and_get_normal(ray, max_time_of_impact, false)
    }
}

impl Shape for ExactShape {
    /// The mesh's box grown by its chordal error: holds the exact surface.
    fn compute_local_aabb(&self) -> Aabb {
        self.local_aabb
    }

    /// The prepared object's ball: holds the exact surface.
    fn compute_local_bounding_sphere(&self) -> BoundingSphere {
        BoundingSphere::new(
            self.placement * self.object.bounding_centre,
            self.object.bounding_radius,
        )
    }

    fn clone_dyn(&self) -> Box<dyn Shape> {
        Box::new(self.clone())
    }

    /// `None`: a scaled exact solid would need its own preparation (and a non-uniform scale
    /// changes the surface kinds); scale the model and prepare it instead.
    fn scale_dyn(&self, _scale: Vector, _num_subdivisions: u32) -> Option<Box<dyn Shape>> {
        None
    }

    /// Of the closed mesh, by the divergence theorem, at `density` (mass per mm³): within
    /// [`ExactShape::volume_error_bound`] × density of the exact solid's mass. Exact (parry's
    /// closed forms) for the shapes of [`crate::exact_ball`] and [`crate::exact_cuboid`]: a
    /// ball's mesh puts its centre of mass about 5e-4 mm off its centre, enough for a ball at
    /// rest on a plane to start rolling.
    fn mass_properties(&self, density: Real) -> MassProperties {
        match self.primitive {
            Some(Primitive::Ball(radius)) => Ball::new(radius).mass_properties(density),
            Some(Primitive::Cuboid(half_extents)) => {
                Cuboid::new(half_extents).mass_properties(density)
            }
            None => MassProperties::from_trimesh(
                density,
                self.mesh.trimesh.vertices(),
                self.mesh.trimesh.indices(),
            ),
        }
    }

    fn shape_type(&self) -> ShapeType {
        ShapeType::Custom
    }

    fn as_typed_shape(&self) -> TypedShape<'_> {
        TypedShape::Custom(self)
    }

    /// Half the thinnest wall, measured on the mesh along its vertex normals (see the
    /// construction): a body moving less than this per step cannot tunnel through this one.
    fn ccd_thickness(&self) -> Real {
        self.ccd_thickness
    }

    /// π/4, as parry's triangle meshes (a curved surface's contact moves under any rotation).
    fn ccd_angular_thickness(&self) -> Real {
        std::f64::consts::FRAC_PI_4
    }

    /// Parry's fallback for world-space boxes: the local box moved (holds the moved surface).
    fn compute_aabb(&self, position: &Pose) -> Aabb {
        self.local_aabb.transform_by(position)
    }
}
