//! Contacts between two baseline meshes through parry's contact manifolds.

use crate::contact::BaselineContact;
use crate::error::BaselineError;
use crate::mesh::BaselineMesh;
use geom_param::DPose3;
use parry3d_f64::query::{
    ContactManifold, ContactManifoldsWorkspace, DefaultQueryDispatcher, PersistentQueryDispatcher,
};

/// parry's persistent contact-manifold query between two [`BaselineMesh`]es.
///
/// Warm use ([`Self::contacts`]) keeps the manifolds and the triangle-pair workspace between
/// calls, as a physics engine does from one step to the next: for the same pair at the same
/// or a slowly changing pose, parry then only updates the cached contacts. Cold use
/// ([`Self::contacts_cold`]) starts each call from an empty workspace. Keep one baseline per
/// pair of objects: the cache belongs to the last pair queried.
pub struct MeshOnlyBaseline {
    dispatcher: DefaultQueryDispatcher,
    manifolds: Vec<ContactManifold<(), ()>>,
    workspace: Option<ContactManifoldsWorkspace>,
}

impl std::fmt::Debug for MeshOnlyBaseline {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("MeshOnlyBaseline")
            .field("manifolds", &self.manifolds.len())
            .field("warm", &self.workspace.is_some())
            .finish()
    }
}

impl Default for MeshOnlyBaseline {
    fn default() -> Self {
        Self {
            dispatcher: DefaultQueryDispatcher,
            manifolds: Vec::new(),
            workspace: None,
        }
    }
}

impl MeshOnlyBaseline {
    /// An empty (cold) baseline.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    /// Forgets the cached manifolds and workspace: the next query is cold.
    pub fn reset(&mut self) {
        self.manifolds.clear();
        self.workspace = None;
    }

    /// Every contact point parry reports between mesh `a` at `pose_a` and mesh `b` at `pose_b`
    /// (object to world) with signed distance at most `prediction` (mm), in the world frame.
    /// Reuses the cache of the previous call (warm).
    ///
    /// parry returns one manifold per pair of triangles within `prediction` of each other, with
    /// up to a few points each, so one physical contact shows as a cluster of nearby points.
    ///
    /// # Errors
    /// [`BaselineError::BadPose`] for a non-finite pose or a rotation whose quaternion norm is
    /// off 1 by more than 1e-6 (nearer ones are normalised), [`BaselineError::BadPrediction`]
    /// for a negative or non-finite prediction, [`BaselineError::Unsupported`] if parry's
    /// dispatcher refuses the pair.
    pub fn contacts(
        &mut self,
        a: &BaselineMesh,
        pose_a: &DPose3,
        b: &BaselineMesh,
        pose_b: &DPose3,
        prediction: f64,
    ) -> Result<Vec<BaselineContact>, BaselineError> {
        let pose_a = checked(pose_a, "a")?;
        let pose_b = checked(pose_b, "b")?;
        if !(prediction.is_finite() && prediction >= 0.0) {
            return Err(BaselineError::BadPrediction(prediction));
        }
        let pos12 = pose_a.inverse() * pose_b;
        self.dispatcher
            .contact_manifolds(
                &pos12,
                a.trimesh(),
                b.trimesh(),
                prediction,
                &mut self.manifolds,
                &mut self.workspace,
            )
            .map_err(|_| BaselineError::Unsupported)?;
        let mut out = Vec::new();
        for m in &self.manifolds {
            // Points are in each part's frame; a triangle mesh's parts have none (identity).
            let part_a = m.subshape_pos1().copied().unwrap_or(DPose3::IDENTITY);
            let part_b = m.subshape_pos2().copied().unwrap_or(DPose3::IDENTITY);
            let (frame_a, frame_b) = (pose_a * part_a, pose_b * part_b);
            let normal = frame_a.rotation * m.local_n1;
            out.extend(
                m.points
                    .iter()
                    .filter(|p| p.dist <= prediction)
                    .map(|p| BaselineContact {
                        point_a: frame_a * p.local_p1,
                        point_b: frame_b * p.local_p2,
                        distance: p.dist,
                        normal,
                    }),
            );
        }
        Ok(out)
    }

    /// As [`Self::contacts`] from an empty cache (cold).
    ///
    /// # Errors
    /// As [`Self::contacts`].
    pub fn contacts_cold(
        &mut self,
        a: &BaselineMesh,
        pose_a: &DPose3,
        b: &BaselineMesh,
        pose_b: &DPose3,
        prediction: f64,
    ) -> Result<Vec<BaselineContact>, BaselineError> {
        self.reset();
        self.contacts(a, pose_a, b, pose_b, prediction)
    }
}

/// The pose with its rotation normalised, if it is a rigid motion to within 1e-6.
fn checked(pose: &DPose3, object: &'static str) -> Result<DPose3, BaselineError> {
    let q = pose.rotation;
    let norm = q.length();
    if !(q.is_finite() && pose.translation.is_finite() && (norm - 1.0).abs() <= 1e-6) {
        return Err(BaselineError::BadPose { object });
    }
    Ok(DPose3 {
        rotation: q / norm,
        translation: pose.translation,
    })
}
