//! Triboxes (Crosnier and Rossignac, paper 000): 18-sided bounds over nine fixed directions,
//! their boundary, and hierarchies of them (the view stage's level-of-detail substitution,
//! [`crate::view::lod`], is built from them).
//!
//! - [`bounds`]: the tribox of a point set: 18 projection bounds, interference, transforms.
//! - [`boundary`]: section 3's boundary evaluation (corner classification, the four cases).
//! - [`combos`]: tight bounds and outward simplification from the bounds alone.
//! - [`hierarchy`]: section 4's hierarchical triboxes and levels of detail.
//! - [`hull`]: convex hulls, to compare tribox volumes with (the one 3D hull, in geom).
//! - [`interfere`]: exact face-face intersection of objects whose triboxes meet.
//! - [`collide`]: the same question by walking two object trees at once (paper 002).

pub mod boundary;
pub mod bounds;
pub mod collide;
pub mod combos;
pub mod hierarchy;
pub mod interfere;
mod table;

pub use crate::geom::hull3 as hull;

pub use boundary::{Boundary, Case};
pub use bounds::{Tribox, DIRECTIONS};
pub use hierarchy::{Hierarchy, HierarchyOptions};
pub use table::{table, Table, TableOptions, TableRow};
