//! The prepare stage: view-independent bounds computed once after loading — INBOXes.

pub mod convex;
pub mod grow;
pub mod halfspace;
pub mod inbox;
pub mod place;
pub mod solid;

pub use inbox::{compute_inboxes, mesh_inbox};
