//! The key of per-pair state kept across queries (GJK warm starts, traversal fronts).

/// A component pair, by object address and component index: (A's object, A's component, B's
/// object, B's component). Ordered: (A, B) and (B, A) are two keys.
pub(crate) type PairKey = (usize, u32, usize, u32);
