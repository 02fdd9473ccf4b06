//! Stage 1: component-based hybrid bounding-volume trees.

pub mod bevelled_volume;
pub mod obb;
