//! The prepare stage: view-independent facts computed once after loading — which meshes are
//! proven solids (back faces may be culled), INBOXes, and object trees for flat meshes
//! (paper 002).
//!
//! - [`inbox`]: INBOXes, boxes proven inside the closed solids of an object.
//! - [`solidity`]: proven solids, open meshes capped, slits closed.
//! - [`trees`]: object trees B(T) for flat meshes.

pub(crate) mod inbox;
pub(crate) mod solidity;
pub(crate) mod trees;

pub(crate) use trees::bvtree::{HierarchyKind, ObjectTree};

use crate::progress::{Phase, Progress, Stage};
use crate::scene::Scene;

/// What the prepare stage builds.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct PrepareOptions {
    /// The object tree flat meshes get: with [`HierarchyKind::Median`] none is prepared and
    /// the view splits each mesh at the median per view, as before paper 002. None (the
    /// default) is the better one as measured: paper 002's tree for the meshes of prototypes
    /// placed more than once (one tree instead of one median split per placement and view),
    /// the median split per view for a mesh drawn once (building a tree costs more than one
    /// view saves: docs/history/issue12.md).
    pub hierarchy: Option<HierarchyKind>,
    /// INBOXes for every object, also where a render has no use for them (a scene of one
    /// object), as `kepler info` shows them.
    pub every_inbox: bool,
}

/// The prepare stage for a whole scene: every mesh's solidity (once per prototype), INBOXes
/// for every object lacking one, and an object tree for every large leaf mesh. A scene of one
/// leaf object gets no inboxes: an inbox prunes only other objects, so there is nothing for it
/// to do ("model no more than a scene needs").
///
/// Where it is goes to `progress` (stage `Prepare`): the phases `Solidity`, `Inboxes` and
/// `Trees` ([`crate::stats::Phase`]), each
/// counting the faces of the meshes it handles (a shared prototype's once). The prepared
/// scene is the same whatever watches it.
pub fn prepare(scene: &mut Scene, opts: &PrepareOptions, progress: &Progress) {
    let root = &mut scene.root;
    let faces = root.distinct_faces_where(&|_, m| m.solidity.is_none());
    progress.enter_phase(Stage::Prepare, Phase::Solidity, faces);
    solidity::mark_solids(root, progress.count());
    let several = has_two_leaves(root);
    if several || opts.every_inbox {
        let faces = root.distinct_faces_where(&|obj, _| obj.inbox.is_none());
        progress.enter_phase(Stage::Prepare, Phase::Inboxes, faces);
        inbox::compute_inboxes(root, progress.count());
    }
    // Trees for every large mesh, for shared prototypes' only, or none.
    let shared_only = match opts.hierarchy {
        Some(HierarchyKind::Simplify) => Some(false),
        Some(HierarchyKind::Median) => None,
        None => Some(true),
    };
    if let Some(shared_only) = shared_only {
        let kind = HierarchyKind::Simplify;
        let faces = trees::planned_faces(root, shared_only);
        progress.enter_phase(Stage::Prepare, Phase::Trees, faces);
        trees::attach_trees(root, kind, several, shared_only, progress.count());
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
