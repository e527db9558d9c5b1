//! The emit stage: what people look at and what test suites diff, in three rooms.
//!
//! - [`lines`]: hidden-line geometry, the visible and hidden part of every edge.
//! - [`plot`]: plotter post-processing, the drawing laid out on a page as a [`Picture`].
//! - [`write`]: the writers, SVG, PNG and canonical JSON.

pub(crate) mod lines;
pub(crate) mod plot;
pub(crate) mod write;
