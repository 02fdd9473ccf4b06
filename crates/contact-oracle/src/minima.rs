//! What the oracle reports, found and sorted: local minima of distance, penetration witnesses
//! (local minima of the signed distance), a polished pair turned into a contact (and dropped
//! when measured through the material), and one answer per region of near-minimal distance.

pub(crate) mod found;
pub(crate) mod local_minima;
pub(crate) mod penetration;
pub(crate) mod regions;
