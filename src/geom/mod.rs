//! Geometric types and exact predicates shared by every stage.

pub mod box3;
pub mod box_pairs;
pub mod hull2;
pub mod poly2;
pub mod polymesh;

pub use box3::Box3;
pub use polymesh::PolyMesh;

/// A point in 3-space (f64).
pub type P3 = nalgebra::Point3<f64>;
/// A vector in 3-space (f64).
pub type V3 = nalgebra::Vector3<f64>;
/// A 4x4 homogeneous matrix (f64).
pub type M4 = nalgebra::Matrix4<f64>;
