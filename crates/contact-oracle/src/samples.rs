//! Dense samples of both solids, near the other solid only (faces on (u, v) grids, edges and
//! corners on their own geometry), and the kd-tree that finds each sample's nearest sample of
//! the other solid.

pub(crate) mod kdtree;
pub(crate) mod sampling;
