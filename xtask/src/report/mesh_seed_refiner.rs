//! A Stage 3 that does nothing: it hands the Stage 2 seed on unrefined, so that the pipeline
//! with it reports the mesh phase's own answer ("Stages 1-2 alone" in the report).

use exact_refine::{RefineDiagnostics, RefineStatus, RefinedContact, Refiner};
use geom_param::{DPose3, Seed, Solid};

/// Returns each seed as the contact: its two mesh points (A's frame), their distance signed by
/// A's exact outward normal at the seed's location, and the direction between them as the
/// normal. The diagnostics say "converged, a minimum" so that the pipeline keeps every seed;
/// the error estimates are zero because this stage does not estimate anything.
#[derive(Clone, Copy, Debug, Default)]
pub struct MeshSeedRefiner;

impl Refiner for MeshSeedRefiner {
    type Scratch = ();

    fn refine(
        &self,
        a: &Solid,
        _b: &Solid,
        pose_ab: &DPose3,
        seed: &Seed,
        _scratch: &mut (),
    ) -> RefinedContact {
        let point_a = seed.a.local_point;
        let point_b = *pose_ab * seed.b.local_point;
        let outward = a
            .face_normal_at(&seed.a.location)
            .unwrap_or(geom_param::DVec3::Z);
        let gap = point_b - point_a;
        let normal = match gap.try_normalize() {
            Some(direction) if direction.dot(outward) >= 0.0 => direction,
            Some(direction) => -direction,
            None => outward,
        };
        RefinedContact {
            point_a,
            point_b,
            location_a: seed.a.location,
            location_b: seed.b.location,
            distance: gap.dot(normal),
            normal,
            diagnostics: RefineDiagnostics {
                iterations: 0,
                gradient_norm: 0.0,
                condition: 1.0,
                converged: true,
                is_local_minimum: true,
                error_estimate: 0.0,
                point_error_estimate: 0.0,
                gap_curvature: f64::INFINITY,
                status: RefineStatus::Converged,
            },
        }
    }
}
