//! The emit stage: what people look at and what test suites diff.

pub mod json;

pub use json::{to_json, Lines};
