//! The prepare stage: view-independent bounds computed once after loading — INBOXes.

pub mod convex;
pub mod grow;
pub mod halfspace;
pub mod inbox;
pub mod place;
pub mod solid;

pub use inbox::{compute_inboxes, mesh_inbox};

use crate::scene::Scene;

/// The prepare stage for a whole scene: INBOXes for every object lacking one. A scene of one
/// leaf object is left alone: an inbox prunes only other objects, so there is nothing for it
/// to do ("model no more than a scene needs").
pub fn prepare(scene: &mut Scene) {
    if scene.leaves().len() >= 2 {
        compute_inboxes(&mut scene.root);
    }
}
