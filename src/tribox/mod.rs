//! Triboxes (Crosnier and Rossignac, paper 000): 18-sided bounds over nine fixed directions,
//! their boundary, hierarchies of them, and level-of-detail substitutes built from them.
//!
//! - [`bounds`]: the tribox of a point set: 18 projection bounds, interference, transforms.
//! - [`boundary`]: section 3's boundary evaluation (corner classification, the four cases).
//! - [`combos`]: tight bounds and outward simplification from the bounds alone.
//! - [`hierarchy`]: section 4's hierarchical triboxes and levels of detail.
//! - [`screen`]: the 2D analogue in screen space, an octagon over x, y, x+y, x−y.
//! - [`lod`]: substitution of small objects by their triboxes before the view stage.
//! - [`hull`]: convex hulls, to compare tribox volumes with.
//! - [`interfere`]: exact face-face intersection of objects whose triboxes meet.

pub mod boundary;
pub mod bounds;
pub mod combos;
pub mod hierarchy;
pub mod hull;
pub mod interfere;
pub mod lod;
pub mod screen;

pub use boundary::{Boundary, Case};
pub use bounds::{Tribox, DIRECTIONS};
pub use hierarchy::{Hierarchy, HierarchyOptions};
pub use lod::{substitute, LodOptions, LodStats};
pub use screen::Octagon;
