//! Exact features as parry's packed feature ids.

use geom_param::{FeatureId, FeatureLocation};
use parry3d_f64::shape::PackedFeatureId;

/// Largest index parry's packed ids hold (30 bits).
const MAX_CODE: u32 = 0x3fff_ffff;

/// The exact feature of `location` as parry's id: `face(i)`, `edge(i)` or `vertex(i)` with the
/// solid's own face, edge or vertex index, so that a contact keeps its ids while it stays on
/// the same features (they are the solid's, not a mesh's); `UNKNOWN` for an index beyond 30
/// bits.
#[must_use]
pub fn packed_feature(location: &FeatureLocation) -> PackedFeatureId {
    let (index, pack): (u32, fn(u32) -> PackedFeatureId) = match location.feature() {
        FeatureId::Face(id) => (id.0, PackedFeatureId::face),
        FeatureId::Edge(id) => (id.0, PackedFeatureId::edge),
        FeatureId::Vertex(id) => (id.0, PackedFeatureId::vertex),
    };
    if index <= MAX_CODE {
        pack(index)
    } else {
        PackedFeatureId::UNKNOWN
    }
}
