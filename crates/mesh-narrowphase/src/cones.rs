//! The default concave path ([`crate::ConcavePath::NormalCones`]): hierarchies of exact surface
//! patches with normal cones, traversed pairwise with the band as a distance cutoff, their
//! fronts carried from one query to the next, and one seed per minimum.

pub mod cone_front;
pub(crate) mod cone_path;
pub mod cone_traversal;
pub mod normal_cone;
pub mod patch_tree;
