//! Pictures of results read back from a MED result file: the mesh in its
//! deformed shape coloured by a field (docs/post.md, `aster plot`), and
//! curves over time at one-node groups.
//!
//! Everything starts from the file, not from a study in memory, so a result
//! written by code_aster or SALOME draws the same way as one of ours. The
//! split: [`data`] finds fields, components and instants in what the file
//! holds; [`geometry`] turns cells into polygons in a drawing plane;
//! [`picture`] paints them; [`history`] draws the curves.

pub mod data;
pub mod geometry;
pub mod history;
pub mod picture;

pub use data::{Component, FieldChoice, ResultData};
pub use geometry::Plane;
pub use history::{draw_history, HistorySpec};
pub use picture::{colour_at, draw_result, PictureOptions, Rendered};
