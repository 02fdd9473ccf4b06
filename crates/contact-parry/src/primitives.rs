//! Parry primitives the pipeline can represent exactly: a [`Ball`] as a sphere of revolution
//! and a [`Cuboid`] as an extruded rectangle (sharp edges and corners, as parry's), prepared
//! once per pipeline and size and cached.

use crate::error::ShapeError;
use crate::exact_shape::{ExactShape, Primitive};
use contact_pipeline::ContactPipeline;
use geom_param::{
    DVec2, MIN_RELATIVE_TOLERANCE, MeshOptions, ObjectModel, PlanarProfile, PlanarSegment, Profile,
    SegmentSpec, extrude,
};
use glam::{DQuat, DVec3};
use parry3d_f64::math::Pose;
use parry3d_f64::shape::{Ball, Cuboid, Shape};
use std::collections::HashMap;
use std::sync::{Arc, Mutex};

/// The chordal tolerance for a primitive of size `scale` (mm): the pipeline's, raised to the
/// smallest the model allows for that size ([`MIN_RELATIVE_TOLERANCE`], with 1 % to spare).
fn tolerance(pipeline: &ContactPipeline, scale: f64) -> MeshOptions {
    MeshOptions {
        chordal_tolerance: pipeline
            .options()
            .chordal_tolerance
            .max(1.01 * MIN_RELATIVE_TOLERANCE * scale),
    }
}

/// The exact sphere of `radius` (mm) about the origin, as parry's [`Ball`]: the revolution of
/// a half circle, placed ([`ExactShape::placed`]) with its axis along [`BALL_AXIS`].
///
/// Why not about z: the revolution's parametrization is singular at its two poles, and Stage 3
/// does not converge on a *touch* (gap within about 1e-6 mm) between about 1e-6 and 0.05 rad
/// from a pole (Newton reaches its iteration limit; a gap of 0.01 mm converges; see
/// `tests/queries.rs`, `touches_near_a_sphere_pole`). Resting contacts of a z-up world lie
/// along ±z, and of boxes along the axes, so the poles go along a direction far from those; a
/// ball that rolls can still bring a pole to a touch. FIXME (exact-refine): Newton at a touch
/// next to a pole of a revolved face.
///
/// # Errors
/// [`ShapeError::Primitive`] for a radius that is not finite and positive; else as
/// [`ExactShape::new`].
pub fn exact_ball(pipeline: Arc<ContactPipeline>, radius: f64) -> Result<ExactShape, ShapeError> {
    let bad = |reason: String| ShapeError::Primitive {
        kind: "ball",
        reason,
    };
    if !(radius.is_finite() && radius > 0.0) {
        return Err(bad(format!("radius {radius} is not finite and > 0")));
    }
    let profile = Profile::new(&[SegmentSpec::Arc {
        center: [0.0, 0.0],
        from: [0.0, -radius],
        to: [0.0, radius],
        ccw: true,
    }])
    .map_err(|e| bad(e.to_string()))?;
    let options = tolerance(&pipeline, radius);
    let model = ObjectModel::from_profile("ball", profile, &options)?;
    let object = Arc::new(pipeline.prepare(model));
    let placement = Pose::from_parts(
        DVec3::ZERO,
        DQuat::from_rotation_arc(DVec3::Z, BALL_AXIS.normalize()),
    );
    Ok(ExactShape::placed(pipeline, object, placement)?.with_primitive(Primitive::Ball(radius)))
}

/// The direction of an exact ball's poles in its shape's frame (normalized where used): 34° or
/// more from each of ±x, ±y, ±z, 22° or more from the octants' diagonals.
pub const BALL_AXIS: DVec3 = DVec3::new(0.31, 0.47, 0.83);

/// The exact box [−h.x, h.x] × [−h.y, h.y] × [−h.z, h.z] (mm), as parry's [`Cuboid`]: a
/// rectangle extruded along z, with sharp edges and corners.
///
/// # Errors
/// [`ShapeError::Primitive`] for half extents that are not finite and positive, else as
/// [`ExactShape::new`].
pub fn exact_cuboid(
    pipeline: Arc<ContactPipeline>,
    half_extents: DVec3,
) -> Result<ExactShape, ShapeError> {
    let bad = |reason: String| ShapeError::Primitive {
        kind: "cuboid",
        reason,
    };
    if !(half_extents.is_finite() && half_extents.min_element() > 0.0) {
        return Err(bad(format!(
            "half extents {half_extents} are not finite and > 0"
        )));
    }
    let (x, y) = (half_extents.x, half_extents.y);
    let corners = [
        DVec2::new(-x, -y),
        DVec2::new(x, -y),
        DVec2::new(x, y),
        DVec2::new(-x, y),
    ];
    let outer = (0..4)
        .map(|k| PlanarSegment::Line {
            from: corners[k],
            to: corners[(k + 1) % 4],
        })
        .collect();
    let profile = PlanarProfile {
        outer,
        holes: Vec::new(),
    };
    let solid =
        extrude(&profile, -half_extents.z, half_extents.z).map_err(|e| bad(e.to_string()))?;
    let options = tolerance(&pipeline, half_extents.max_element());
    let model = ObjectModel::from_solid("cuboid", solid, &options)?;
    Ok(ExactShape::from_model(pipeline, model)?.with_primitive(Primitive::Cuboid(half_extents)))
}

/// Which primitive, by kind and the bits of its dimensions, for one pipeline (by address).
type PrimitiveKey = (usize, u8, [u64; 3]);

/// Exact shapes of the parry primitives met so far, one per pipeline, kind and size; a
/// primitive that could not be built is remembered as `None` (not retried).
#[derive(Default)]
pub(crate) struct PrimitiveCache {
    shapes: Mutex<HashMap<PrimitiveKey, Option<ExactShape>>>,
}

impl PrimitiveCache {
    /// The exact shape of `shape` if it is a [`Ball`] or a [`Cuboid`] (built with `pipeline`
    /// on first use), else `None`.
    pub(crate) fn exact_of(
        &self,
        pipeline: &Arc<ContactPipeline>,
        shape: &dyn Shape,
    ) -> Option<ExactShape> {
        let (kind, dims) = if let Some(ball) = shape.as_shape::<Ball>() {
            (0u8, DVec3::new(ball.radius, 0.0, 0.0))
        } else if let Some(cuboid) = shape.as_shape::<Cuboid>() {
            (1u8, cuboid.half_extents)
        } else {
            return None;
        };
        let key = (
            Arc::as_ptr(pipeline) as usize,
            kind,
            dims.to_array().map(f64::to_bits),
        );
        // A poisoned lock only means another thread panicked while building; the map is
        // still consistent (entries are inserted whole).
        let mut shapes = self
            .shapes
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner);
        shapes
            .entry(key)
            .or_insert_with(|| {
                let built = if kind == 0 {
                    exact_ball(Arc::clone(pipeline), dims.x)
                } else {
                    exact_cuboid(Arc::clone(pipeline), dims)
                };
                built.ok()
            })
            .clone()
    }
}
