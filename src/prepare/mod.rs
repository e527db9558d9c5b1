//! The prepare stage: view-independent bounds computed once after loading — INBOXes.

pub mod contain;
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
    if has_two_leaves(&scene.root) {
        compute_inboxes(&mut scene.root);
    }
}

/// True when the tree has at least two leaves (instances counted, none expanded: the walk
/// stops at the second leaf).
fn has_two_leaves(root: &crate::scene::Object) -> bool {
    fn count(o: &crate::scene::Object, n: &mut usize) {
        match &o.content {
            crate::scene::Content::Mesh(_) => *n += 1,
            crate::scene::Content::Subobjects(s) => {
                for c in s {
                    if *n >= 2 {
                        return;
                    }
                    count(c, n);
                }
            }
            crate::scene::Content::Instance(i) => count(&i.prototype, n),
        }
    }
    let mut n = 0;
    count(root, &mut n);
    n >= 2
}
