//! The visibility stage: VISFAC, VISFAC2, VISOBJ, VISP and INCLUDE (paper 001, ALGORITHMS),
//! and the whole-scene pass that gives every face its visibility texture polygon (VTP).

pub(crate) mod cover;
pub(crate) mod empty;
pub(crate) mod include;
pub(crate) mod occlusion;
pub(crate) mod pass;
pub(crate) mod result;
pub(crate) mod stats;
pub(crate) mod visfac;
pub(crate) mod visobj;
pub(crate) mod visp;
#[cfg(test)]
pub(crate) mod vtp_texture;

pub(crate) use include::include;
pub(crate) use pass::{solve, PassOptions};
pub(crate) use result::{FaceVisibility, Visibility};
pub(crate) use stats::Counters;
pub(crate) use visobj::visobj;
pub(crate) use visp::visp;
