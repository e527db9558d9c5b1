//! The prepare stage: view-independent facts computed once after loading — which meshes are
//! proven solids (back faces may be culled), and INBOXes.

pub mod convex;
pub mod grow;
pub mod halfspace;
pub mod inbox;
pub mod place;
pub mod solid;
pub mod solidity;

pub use inbox::{compute_inboxes, mesh_inbox};
pub use solidity::{mark_solids, solidity};

use crate::scene::Scene;

/// The prepare stage for a whole scene: every mesh's solidity (once per prototype), and
/// INBOXes for every object lacking one. A scene of one leaf object gets no INBOX: an inbox
/// prunes only other objects, so there is nothing for it to do ("model no more than a scene
/// needs").
pub fn prepare(scene: &mut Scene) {
    mark_solids(&mut scene.root);
    if scene.leaves().len() >= 2 {
        compute_inboxes(&mut scene.root);
    }
}
