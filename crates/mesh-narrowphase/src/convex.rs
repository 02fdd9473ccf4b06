//! The convex-convex path: GJK between two components' convex hulls.

pub mod convex_pair;
pub mod hill_climb_support;
