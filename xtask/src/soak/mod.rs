//! `cargo xtask soak`: random near-contact poses of every ordered pair of the paper objects,
//! checked against an independent oracle and against properties that need no oracle.

pub mod normal_cone;
pub mod oracle_check;
pub mod pose_generator;
pub mod properties;
pub mod run;
pub mod table;
