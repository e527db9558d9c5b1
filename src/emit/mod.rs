//! The emit stage: what people look at and what test suites diff.

pub mod chain;
pub mod clip_segment;
pub mod edges;
pub mod intersect;
pub mod json;
pub mod lines;
pub mod marks;
pub mod picture;
pub mod png;
pub mod region;
pub mod svg;
pub mod world;

pub use edges::{EdgeKind, EdgeOptions, EdgeSet};
pub use json::{to_json, Lines};
pub use lines::{draw, Drawing, LineOptions, Stroke};
