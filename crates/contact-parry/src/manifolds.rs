//! [`PersistentQueryDispatcher`] for [`ExactDispatcher`]: contact manifolds from coherent
//! pipeline queries, one manifold per local minimum, the pair's
//! [`PairCache`] kept in parry's [`ContactManifoldsWorkspace`].

use crate::counters::DispatchPath;
use crate::dispatcher::{BeyondReach, ExactDispatcher, Resolved, depthless_penetration, meshed};
use crate::exact_shape::ExactShape;
use crate::feature_ids::packed_feature;
use contact_pipeline::{ContactId, FrameKind, PairCache, PairReport, QueryScratch};
use parry3d_f64::math::{Pose, Real};
use parry3d_f64::query::details::{
    ContactManifoldsWorkspace, NormalConstraints, TypedWorkspaceData, WorkspaceData,
};
use parry3d_f64::query::{ContactManifold, PersistentQueryDispatcher, TrackedContact, Unsupported};
use parry3d_f64::shape::Shape;

/// What one pair keeps across frames in parry's manifold workspace: the coherence cache, the
/// query's working memory and report, the contact id of each manifold handed out last frame
/// (in order), and parry's own workspace for frames answered on meshes.
struct ExactWorkspace {
    cache: PairCache,
    scratch: QueryScratch,
    report: PairReport,
    ids: Vec<ContactId>,
    mesh_workspace: Option<ContactManifoldsWorkspace>,
}

impl ExactWorkspace {
    fn new() -> Self {
        Self {
            cache: PairCache::new(),
            scratch: QueryScratch::default(),
            report: PairReport::default(),
            ids: Vec::new(),
            mesh_workspace: None,
        }
    }
}

impl WorkspaceData for ExactWorkspace {
    fn as_typed_workspace_data(&self) -> TypedWorkspaceData<'_> {
        TypedWorkspaceData::Custom
    }

    /// The cache, ids and report are copied; the working memory starts empty.
    fn clone_dyn(&self) -> Box<dyn WorkspaceData> {
        Box::new(Self {
            cache: self.cache.clone(),
            scratch: QueryScratch::default(),
            report: self.report.clone(),
            ids: self.ids.clone(),
            mesh_workspace: self.mesh_workspace.clone(),
        })
    }
}

/// The pair's [`ExactWorkspace`], made (replacing whatever else was there) when missing.
fn exact_workspace(workspace: &mut Option<ContactManifoldsWorkspace>) -> &mut ExactWorkspace {
    let ours = workspace
        .as_ref()
        .is_some_and(|w| w.0.as_any().is::<ExactWorkspace>());
    if !ours {
        *workspace = Some(ContactManifoldsWorkspace(Box::new(ExactWorkspace::new())));
    }
    workspace
        .as_mut()
        .and_then(|w| w.0.downcast_mut::<ExactWorkspace>())
        .unwrap_or_else(|| unreachable!("the workspace was just made an ExactWorkspace"))
}

impl<D, ManifoldData, ContactData> PersistentQueryDispatcher<ManifoldData, ContactData>
    for ExactDispatcher<D>
where
    D: PersistentQueryDispatcher<ManifoldData, ContactData>,
    ManifoldData: Default + Clone + Send + Sync,
    ContactData: Default + Copy + Send + Sync,
{
    /// One manifold of one point per local minimum of distance the coherent pipeline query
    /// reports within `min(prediction, delta2)` (the pipeline's band ends at delta2: give it a
    /// delta2 at least the engine's prediction distance for every speculative contact), and per
    /// certified penetration region (negative `dist`, the exact depth). Each manifold's
    /// `local_n1` is the contact normal (first shape's frame, from the first shape to the
    /// second), `local_n2` its opposite in the second shape's frame; the point's `fid1` and
    /// `fid2` are the exact features ([`packed_feature`]). A contact that keeps its
    /// [`ContactId`] from the last frame gets last frame's manifold back (its `data` and its
    /// point's `data`, where rapier keeps the impulses that warm-start its solver). A
    /// penetration without a certified depth is beyond reach ([`BeyondReach`]: no manifold,
    /// `Unsupported`, or parry's manifolds between the closed meshes for that frame).
    fn contact_manifolds(
        &self,
        pos12: &Pose,
        g1: &dyn Shape,
        g2: &dyn Shape,
        prediction: Real,
        manifolds: &mut Vec<ContactManifold<ManifoldData, ContactData>>,
        workspace: &mut Option<ContactManifoldsWorkspace>,
    ) -> Result<(), Unsupported> {
        let pair = match self.resolve(g1, g2) {
            Resolved::Fallback => {
                return self
                    .fallback
                    .contact_manifolds(pos12, g1, g2, prediction, manifolds, workspace);
            }
            Resolved::Refused => {
                manifolds.clear();
                self.counters.note(DispatchPath::Unsupported);
                return Err(Unsupported);
            }
            Resolved::OutOfReach => {
                return self.mesh_manifolds(pos12, g1, g2, prediction, manifolds, workspace);
            }
            Resolved::Exact(pair) => pair,
        };
        let (a, b) = (&pair.0, &pair.1);
        let ws = exact_workspace(workspace);
        let frame = a.pipeline().query_coherent(
            a.object(),
            a.placement(),
            b.object(),
            &(*pos12 * *b.placement()),
            &self.options.coherence,
            &mut ws.cache,
            &mut ws.scratch,
            &mut ws.report,
        );
        let Ok(frame) = frame else {
            manifolds.clear();
            ws.ids.clear();
            self.counters.note(DispatchPath::Unsupported);
            return Err(Unsupported);
        };
        self.counters.note(match frame {
            FrameKind::Full => DispatchPath::Exact,
            FrameKind::Warm => DispatchPath::Warm,
        });
        if depthless_penetration(&ws.report) {
            ws.ids.clear();
            return self.mesh_manifolds(
                pos12,
                g1,
                g2,
                prediction,
                manifolds,
                &mut ws.mesh_workspace,
            );
        }
        let mut old = std::mem::take(manifolds);
        let old_ids = std::mem::take(&mut ws.ids);
        let inverse_rotation = pos12.rotation.inverse();
        for (c, &id) in ws.report.contacts.iter().zip(ws.cache.contact_ids()) {
            if c.distance > prediction {
                continue;
            }
            let reused = old_ids
                .iter()
                .position(|&o| o == id)
                .filter(|&k| k < old.len())
                .map(|k| std::mem::replace(&mut old[k], ContactManifold::new()));
            let mut manifold =
                reused.unwrap_or_else(|| ContactManifold::with_data(0, 0, ManifoldData::default()));
            let data = manifold
                .points
                .first()
                .map_or_else(ContactData::default, |p| p.data);
            let mut point = TrackedContact::new(
                c.point_a,
                pos12.inverse_transform_point(c.point_b),
                packed_feature(&c.location_a),
                packed_feature(&c.location_b),
                c.distance,
            );
            point.data = data;
            manifold.points.clear();
            manifold.points.push(point);
            manifold.local_n1 = c.normal;
            manifold.local_n2 = -(inverse_rotation * c.normal);
            manifolds.push(manifold);
            ws.ids.push(id);
        }
        Ok(())
    }

    /// `Unsupported` for a pair with an exact shape (an exact solid is not one of parry's
    /// convex shapes); the fallback's answer otherwise.
    fn contact_manifold_convex_convex(
        &self,
        pos12: &Pose,
        g1: &dyn Shape,
        g2: &dyn Shape,
        normal_constraints1: Option<&dyn NormalConstraints>,
        normal_constraints2: Option<&dyn NormalConstraints>,
        prediction: Real,
        manifold: &mut ContactManifold<ManifoldData, ContactData>,
    ) -> Result<(), Unsupported> {
        let exact = |g: &dyn Shape| g.as_shape::<ExactShape>().is_some();
        if exact(g1) || exact(g2) {
            self.counters.note(DispatchPath::Unsupported);
            return Err(Unsupported);
        }
        self.fallback.contact_manifold_convex_convex(
            pos12,
            g1,
            g2,
            normal_constraints1,
            normal_constraints2,
            prediction,
            manifold,
        )
    }
}

impl<D> ExactDispatcher<D> {
    /// Beyond reach, for manifolds: none and `Unsupported`, or the fallback's manifolds between
    /// the closed meshes.
    fn mesh_manifolds<ManifoldData, ContactData>(
        &self,
        pos12: &Pose,
        g1: &dyn Shape,
        g2: &dyn Shape,
        prediction: Real,
        manifolds: &mut Vec<ContactManifold<ManifoldData, ContactData>>,
        workspace: &mut Option<ContactManifoldsWorkspace>,
    ) -> Result<(), Unsupported>
    where
        D: PersistentQueryDispatcher<ManifoldData, ContactData>,
    {
        match self.options.beyond_reach {
            BeyondReach::Unsupported => {
                manifolds.clear();
                self.counters.note(DispatchPath::Unsupported);
                Err(Unsupported)
            }
            BeyondReach::MeshApproximation => {
                self.counters.note(DispatchPath::Mesh);
                self.fallback.contact_manifolds(
                    pos12,
                    meshed(g1),
                    meshed(g2),
                    prediction,
                    manifolds,
                    workspace,
                )
            }
        }
    }
}
