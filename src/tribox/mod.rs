//! Triboxes (Crosnier and Rossignac, paper 000, docs/papers.md): 18-sided bounds over nine
//! fixed directions, their boundary, and hierarchies of them (the view stage's
//! level-of-detail substitution, `--lod`, is built from them); and paper 002's object trees
//! with the collision walk over two of them.
//!
//! Public: the paper's Table 1 ([`table`]), the convex hull volume it compares with
//! ([`hull_volume`]), object trees ([`ObjectTree`]) and their collision walk ([`collide`]).
//! Inside the crate:
//! - `bounds`: the tribox of a point set: 18 projection bounds, interference, transforms.
//! - `boundary`: section 3's boundary evaluation (corner classification, the four cases).
//! - `combos`: tight bounds and outward simplification from the bounds alone.
//! - `hierarchy`: section 4's hierarchical triboxes and levels of detail.
//! - `interfere`: exact face-face intersection of objects whose triboxes meet.
//! - `collide`: the same question by walking two object trees at once (paper 002).

pub(crate) mod boundary;
pub(crate) mod bounds;
pub(crate) mod collide;
pub(crate) mod combos;
pub(crate) mod hierarchy;
pub(crate) mod interfere;
mod table;

pub(crate) use boundary::Boundary;
pub(crate) use bounds::Tribox;
pub(crate) use hierarchy::Hierarchy;
pub use hierarchy::HierarchyOptions;
pub use table::{table, Table, TableOptions, TableRow};

pub use crate::geom::hull3::hull_volume;
pub use crate::prepare::trees::bvtree::TopDown;
pub use crate::scene::object_tree::{
    BuildTimes, Component, ComponentTree, ObjectTree, TreeNode, TreeShape,
};
pub use collide::{collide, collide_brute, CollideStats, FaceTriangles, Placed};
