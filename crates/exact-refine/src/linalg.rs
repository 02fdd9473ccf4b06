//! The small (at most 4 x 4) symmetric Hessians of the refinement: direct solves (Cholesky,
//! Gaussian elimination) and eigen-decomposition.

pub(crate) mod dense_solve;
pub(crate) mod sym_eigen;
