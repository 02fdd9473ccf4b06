//! Judging a finished solve: its diagnostics (conditioning, second-order check,
//! continuous-contact detection, error estimates), and the nearest-boundary test that a
//! penetration witness is not measured through the material.

pub(crate) mod diagnostics;
pub(crate) mod witness_check;
