//! The two solids as the oracle evaluates them: a solid posed in the world frame with its
//! faces' regions (rectangle, or trim with its containment grid), and where one point of a
//! pair lies on it (free on a face, held on an edge, or at a vertex).

pub(crate) mod held;
pub(crate) mod posed;
pub(crate) mod trim_grid;
