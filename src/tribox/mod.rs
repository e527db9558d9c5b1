//! Triboxes (Crosnier and Rossignac, paper 000): 18-sided bounds over nine fixed directions,
//! their boundary, hierarchies of them, and level-of-detail substitutes built from them.
//!
//! - [`bounds`]: the tribox of a point set: 18 projection bounds, interference, transforms.
//! - [`boundary`]: section 3's boundary evaluation (corner classification, the four cases).
//! - [`combos`]: tight bounds and outward simplification from the bounds alone.

pub mod boundary;
pub mod bounds;
pub mod combos;

pub use boundary::{Boundary, Case};
pub use bounds::{Tribox, DIRECTIONS};
