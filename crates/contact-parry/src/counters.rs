//! Counts of a dispatcher's answers by the path that gave them, for measurements.

use std::sync::atomic::{AtomicU64, Ordering};

/// Which path answered one dispatcher call.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DispatchPath {
    /// A full pipeline query (all three stages where needed).
    Exact,
    /// A coherent frame that refined only the tracked minima (Stage 3 alone).
    Warm,
    /// The fallback dispatcher on the closed meshes ([`crate::BeyondReach::MeshApproximation`]).
    Mesh,
    /// `Unsupported`.
    Unsupported,
}

/// Atomic counts of a dispatcher's answers for pairs with an exact shape, by path (pairs
/// without one, answered by the fallback, are not counted). Shared between threads.
#[derive(Debug, Default)]
pub struct DispatchCounters {
    exact: AtomicU64,
    warm: AtomicU64,
    mesh: AtomicU64,
    unsupported: AtomicU64,
}

/// A snapshot of [`DispatchCounters`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct DispatchCounts {
    /// Full pipeline queries.
    pub exact: u64,
    /// Warm coherent frames.
    pub warm: u64,
    /// Mesh approximations.
    pub mesh: u64,
    /// `Unsupported` answers.
    pub unsupported: u64,
}

impl DispatchCounters {
    /// Counts one answer by `path`.
    pub fn note(&self, path: DispatchPath) {
        let counter = match path {
            DispatchPath::Exact => &self.exact,
            DispatchPath::Warm => &self.warm,
            DispatchPath::Mesh => &self.mesh,
            DispatchPath::Unsupported => &self.unsupported,
        };
        counter.fetch_add(1, Ordering::Relaxed);
    }

    /// The counts so far.
    #[must_use]
    pub fn snapshot(&self) -> DispatchCounts {
        DispatchCounts {
            exact: self.exact.load(Ordering::Relaxed),
            warm: self.warm.load(Ordering::Relaxed),
            mesh: self.mesh.load(Ordering::Relaxed),
            unsupported: self.unsupported.load(Ordering::Relaxed),
        }
    }
}
