//! [`HybridBvh`], the default [`BroadPhase`]: component-based hybrid trees (OBB internal
//! nodes, bevelled leaves) traversed tree against tree.

use geom_param::{ComponentId, DPose3, ObjectModel};

use crate::broad_phase::BroadPhase;
use crate::hybrid_tree::{HybridTree, TreeOptions};
use crate::traverse::{TraversalScratch, overlapping_pairs};

/// The default Stage 1: one [`HybridTree`] per object, built with its `options`, queried by
/// simultaneous descent ([`overlapping_pairs`]), from the last query's front when the scratch
/// holds one for the same trees. Two trees built with different options can
/// be queried against each other.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct HybridBvh {
    /// How trees are built (leaf volume kind).
    pub options: TreeOptions,
}

impl BroadPhase for HybridBvh {
    type Tree = HybridTree;
    type Scratch = TraversalScratch;

    fn build(&self, object: &ObjectModel, margin: f64) -> HybridTree {
        HybridTree::build(object, margin, &self.options)
    }

    fn overlapping_components(
        &self,
        a: &HybridTree,
        b: &HybridTree,
        pose_ab: &DPose3,
        scratch: &mut TraversalScratch,
        out: &mut Vec<(ComponentId, ComponentId)>,
    ) {
        overlapping_pairs(a, b, pose_ab, scratch, out);
    }
}
