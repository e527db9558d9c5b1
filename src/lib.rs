//! kepler: exact hidden-surface removal for polyhedral scenes, after W.R. Franklin's KEPLER (1981).
//!
//! Data flows one way: load → prepare → view → visibility → emit.

pub mod emit;
pub mod error;
pub mod geom;
pub mod load;
pub mod prepare;
pub mod primitives;
pub mod scene;
pub mod tribox;
pub mod view;
pub mod visibility;

pub use error::{Error, Location, Pos, Result, Warning, Warnings};
