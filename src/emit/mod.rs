//! The emit stage: what people look at and what test suites diff.

pub mod chain;
pub mod clip_rect;
pub mod clip_segment;
pub mod color;
pub mod dash;
pub mod dedup;
pub mod edges;
pub mod hatch;
pub mod intersect;
pub mod join;
pub mod json;
pub mod lines;
pub mod marks;
pub mod once;
pub mod page;
pub mod picture;
pub mod plot;
pub mod png;
pub mod region;
pub mod shade;
pub mod svg;
pub mod tour;
pub mod world;

pub use color::Rgb;
pub use edges::{EdgeKind, EdgeOptions, EdgeSet};
pub use hatch::HatchOptions;
pub use json::{to_json, Lines};
pub use lines::{draw, Drawing, LineOptions, Stroke};
pub use page::PageSize;
pub use picture::{LayerMode, Pen, Picture, PictureOptions, PlotStats};
