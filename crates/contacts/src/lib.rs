//! The `contacts` command's library part: scene files, built-in objects, JSON output and the
//! runs behind `contacts query`, `contacts bench` and `contacts demo`.

pub mod builtin_objects;
pub mod demo;
pub mod output;
pub mod run;
pub mod scene;
