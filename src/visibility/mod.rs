//! The visibility stage: VISFAC, VISFAC2, VISOBJ, VISP and INCLUDE (paper 001, ALGORITHMS),
//! and the whole-scene pass that gives every face its visibility texture polygon (VTP).

pub mod cover;
pub mod empty;
pub mod include;
pub mod occlusion;
pub mod pass;
pub mod stats;
pub mod visfac;
pub mod visobj;
pub mod visp;
pub mod vtp_texture;

pub use include::{include, Inclusion};
pub use pass::{solve, FaceVisibility, PassOptions, Visibility};
pub use stats::Counters;
pub use visfac::{visfac, Verdict, Vtp};
pub use visobj::visobj;
pub use visp::{visp, PointVisibility};
