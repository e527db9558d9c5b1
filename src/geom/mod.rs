//! Geometry shared by every stage, and the one home of its predicates: exact orientation
//! tests, Newell normals, rectangles, polygons and the adapter to the 2D boolean engine.

pub(crate) mod accurate;
pub(crate) mod boolean;
pub(crate) mod box3;
pub(crate) mod box_pairs;
pub(crate) mod box_tree;
pub(crate) mod coarse;
pub(crate) mod construct;
pub(crate) mod convexity;
pub(crate) mod corners;
pub(crate) mod grid;
pub(crate) mod hull2;
pub(crate) mod hull3;
pub(crate) mod key_hash;
pub(crate) mod normal;
pub(crate) mod plane_cut;
pub(crate) mod poly2;
pub(crate) mod polymesh;
pub(crate) mod predicates;
pub(crate) mod rect;
pub(crate) mod ring_check;
pub(crate) mod rng;
pub(crate) mod solid_angle;
pub(crate) mod tri_box;
pub(crate) mod tri_intersect;
pub(crate) mod triangle;

pub(crate) use box3::Box3;
pub(crate) use corners::Corners;
pub(crate) use normal::{newell, newell_indexed};
pub(crate) use polymesh::PolyMesh;
pub(crate) use predicates::{orient2d, orient3d, orient3d_refs, winding, winding_step};
pub(crate) use rect::Rect;

/// A point in 3-space (f64).
pub type P3 = nalgebra::Point3<f64>;
/// A vector in 3-space (f64).
pub type V3 = nalgebra::Vector3<f64>;
/// A 4x4 homogeneous matrix (f64).
pub type M4 = nalgebra::Matrix4<f64>;

/// Largest coordinate magnitude accepted anywhere (input vertices, transformed points,
/// numbers in scene files): far from f64's limits, so that products in the predicates and
/// areas stay finite.
pub(crate) const MAX_COORD: f64 = 1e12;
