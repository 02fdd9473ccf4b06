//! Stage 1 of exact multiple-contact detection between curved solids: component-based hybrid
//! bounding-volume trees (paper section II, Stage 1, and section III-A).
//!
//! Each object gets one binary tree whose leaves are whole **surface components** (not
//! triangles), so a tree has `2n - 1` nodes for `n` components and its size and query cost do
//! not depend on the mesh resolution. Internal nodes are oriented bounding boxes ([`Obb`]);
//! leaves are bevelled boxes ([`BevelledVolume`], the paper's octagonal volumes: an OBB with
//! its edges cut by planes tight to the component, in the component's own frame), which fit
//! curved components much better than boxes. Every volume covers its component's exact
//! surface (the mesh plus its measured chordal error) inflated by half the margin `delta`, so
//! two leaves overlap whenever their components come within `delta`; `delta` must exceed the
//! motion of one time step (section III-A). Overlap tests are exact for the volumes used
//! (separating-axis tests for boxes, GJK with a separating-axis fallback for bevelled leaves),
//! so no pair within the margin is missed and false positives only cost time.
//!
//! - [`BroadPhase`]: the Stage 1 boundary trait (frames, margin, guarantees).
//! - [`HybridBvh`]: its default implementation; [`HybridTree`] (build, [`HybridTree::validate`])
//!   and [`overlapping_pairs`] (tree-vs-tree traversal with caller-owned [`TraversalScratch`],
//!   which keeps the last traversal's front for the next query on the same trees).
//! - [`obb`], [`bevelled_volume`]: the two volume types and their overlap tests.
//!
//! What this crate deliberately does not know: meshes beyond their vertex positions and
//! chordal error, convexity of components, hulls, triangles, exact features, seeds or Newton
//! refinement (Stages 2 and 3), and world frames (a query only sees B's pose in A's frame).
//!
//! Units: millimetres; frames: each object's own frame. No cargo features.

pub mod bevelled_volume;
mod broad_phase;
mod gjk;
mod hybrid_bvh;
mod hybrid_tree;
pub mod obb;
mod split;
mod traversal_front;
mod traverse;
mod validate;

pub use bevelled_volume::BevelledVolume;
pub use broad_phase::BroadPhase;
pub use hybrid_bvh::HybridBvh;
pub use hybrid_tree::{HybridTree, LeafShape, Node, NodeKind, TreeOptions};
pub use obb::Obb;
pub use traverse::{TraversalScratch, overlapping_pairs};
pub use validate::TreeError;
