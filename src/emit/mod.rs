//! The emit stage: what people look at and what test suites diff, in three rooms.
//!
//! - [`lines`]: hidden-line geometry, the visible and hidden part of every edge.
//! - [`plot`]: plotter post-processing, the drawing laid out on a page as a [`Picture`].
//! - [`write`]: the writers, SVG, PNG and canonical JSON.

pub mod lines;
pub mod plot;
pub mod write;

pub use lines::edges::{EdgeKind, EdgeOptions, EdgeSet};
pub use lines::{draw, Drawing, LineOptions, Stroke};
pub use plot::color::Rgb;
pub use plot::hatch::HatchOptions;
pub use plot::page::PageSize;
pub use plot::picture::{LayerMode, Pen, Picture, PictureOptions, PlotStats};
pub use write::json::{to_json, Lines};
