//! Geometry shared by every stage, and the one home of its predicates: exact orientation
//! tests, Newell normals, rectangles, polygons and the adapter to the 2D boolean engine.

pub mod boolean;
pub mod box3;
pub mod box_pairs;
pub mod box_tree;
pub mod convexity;
pub mod corners;
pub mod grid;
pub mod hull2;
pub mod hull3;
pub(crate) mod key_hash;
pub mod normal;
pub mod poly2;
pub mod polymesh;
pub mod predicates;
pub mod rect;
pub mod ring_check;
pub(crate) mod rng;
pub mod solid_angle;
pub mod tri_box;
pub mod tri_intersect;
pub mod triangle;

pub use box3::Box3;
pub use corners::Corners;
pub use normal::{newell, newell_indexed};
pub use poly2::{MultiPolygon, Polygon, Pt2, Ring};
pub use polymesh::PolyMesh;
pub use predicates::{orient2d, orient3d, orient3d_refs, winding, winding_step};
pub use rect::Rect;

/// A point in 3-space (f64).
pub type P3 = nalgebra::Point3<f64>;
/// A vector in 3-space (f64).
pub type V3 = nalgebra::Vector3<f64>;
/// A 4x4 homogeneous matrix (f64).
pub type M4 = nalgebra::Matrix4<f64>;

/// Largest coordinate magnitude accepted anywhere (input vertices, transformed points,
/// numbers in scene files): far from f64's limits, so that products in the predicates and
/// areas stay finite.
pub const MAX_COORD: f64 = 1e12;
