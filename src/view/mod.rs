//! The view stage: a camera turns the scene into screen-space faces and a view tree.
//!
//! - [`camera`]: the world-to-screen matrix, chosen from flags, the scene or a default.
//! - [`lod`]: small objects replaced by their triboxes for this camera (optional).
//! - [`cull`]: subtrees HIDDEN by inboxes, found from boxes before any face is projected.
//! - [`screen`]: the remaining faces projected as planar pieces; [`mod@caps`]: which back
//!   faces are culled (a solid's, a capped open mesh's away from its holes).
//! - [`tree`]: the object tree in screen space, with bounds for VISFAC2's pruning.
//! - [`frame`]: the part of the screen plane a picture shows.
//! - [`mod@turntable`]: cameras carried round the scene, and one frame for all of them.

pub mod camera;
pub mod caps;
pub mod cull;
pub mod finite;
pub mod frame;
pub mod lod;
pub mod piece_id;
pub mod ring_index;
pub mod screen;
pub mod tree;
pub mod turntable;

pub use camera::{Camera, CameraRequest, Projection};
pub use cull::Cull;
pub use frame::Frame;
pub use lod::{substitute, LodOptions, LodStats};
pub use piece_id::PieceId;
pub use screen::{Facing, Piece, ScreenFaces};
pub use tree::{ObjectNode, ViewTree};
pub use turntable::{turntable, turntable_frame};

use crate::progress::{Phase, Progress, Stage};
use crate::scene::Scene;

/// Everything visibility needs about one view of one scene.
#[derive(Debug, Clone)]
pub struct View {
    /// The camera.
    pub camera: Camera,
    /// Faces in screen space, as planar pieces.
    pub screen: ScreenFaces,
    /// The object tree with screen bounds.
    pub tree: ViewTree,
    /// What culling hid before projection: subtrees, their faces, and objects tested.
    pub culled: CullSummary,
}

/// What the cull did, for the counters.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct CullSummary {
    /// Subtrees (objects, and components of object trees) found HIDDEN as a whole.
    pub subtrees: u64,
    /// Faces in them.
    pub faces: u64,
    /// Objects whose CBOX was tested.
    pub tested: u64,
}

impl View {
    /// Projects every face of `scene` with `camera` (no cull).
    pub fn new(scene: &Scene, camera: Camera) -> View {
        Self::from_cull(scene, camera, &Cull::none(scene), &Progress::default())
    }

    /// Culls `scene` with its inboxes, then projects what is left.
    pub fn culled(scene: &Scene, camera: Camera) -> View {
        Self::from_cull(
            scene,
            camera,
            &Cull::new(scene, &camera),
            &Progress::default(),
        )
    }

    /// Projects the faces a cull of `scene` kept: hidden subtrees are left out of the screen
    /// faces and the tree, and their faces' VTPs are empty.
    ///
    /// As the view stage's phases in `progress`: [`Phase::Project`] counting the kept leaves'
    /// faces projected, then [`Phase::Tree`] every face placed in the view tree.
    pub fn from_cull(scene: &Scene, camera: Camera, cull: &Cull, progress: &Progress) -> View {
        let kept = cull.leaves.iter().map(|l| l.mesh.faces.len()).sum();
        progress.enter_phase(Stage::View, Phase::Project, kept);
        let screen = ScreenFaces::from_cull(cull, &camera, progress.count());
        progress.enter_phase(Stage::View, Phase::Tree, screen.face_count());
        let tree = ViewTree::build(scene, &camera, &screen, &cull.hidden, progress.count());
        View {
            camera,
            screen,
            tree,
            culled: CullSummary {
                subtrees: cull.hidden.len() as u64 + cull.components_hidden,
                faces: cull.hidden_faces(),
                tested: cull.objects_tested,
            },
        }
    }
}
