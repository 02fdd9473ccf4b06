//! The `contacts` command's library part: scene files, built-in objects, JSON output and the
//! runs behind `contacts query`, `contacts bench` and `contacts demo`.
//!
//! Cargo feature `render` (default): the `render` module, pictures of scenes with their contacts
//! marked, written as PNG with tiny-skia, and the `contacts render` subcommand. Embedders
//! who need no pictures can turn it off with `default-features = false`.

pub mod builtin_objects;
pub mod demo;
pub mod output;
#[cfg(feature = "render")]
pub mod render;
pub mod run;
pub mod scene;
