//! Solids of revolution: validated profiles in the (r, z) half-plane and the solid they sweep.

pub(crate) mod profile;
pub(crate) mod profile_error;
pub(crate) mod profile_segment;
pub(crate) mod revolve;
