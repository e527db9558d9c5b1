//! The view stage: a camera turns the scene into screen-space faces and a view tree.
//!
//! - [`camera`]: the world-to-screen matrix, chosen from flags, the scene or a default.
//! - [`lod`]: small objects replaced by their triboxes for this camera (optional).
//! - [`cull`]: subtrees HIDDEN by inboxes, found from boxes before any face is projected.
//! - [`screen`]: the remaining faces projected as planar pieces; [`backfaces`]: which back
//!   faces are culled (a solid's, a capped open mesh's away from its holes).
//! - [`tree`]: the object tree in screen space, with bounds for VISFAC2's pruning.
//! - [`frame`]: the part of the screen plane a picture shows.
//! - [`mod@turntable`]: cameras carried round the scene, and one frame for all of them.
//! - [`up`]: the up axis of a scene without a camera (`--up auto`).

pub(crate) mod backfaces;
pub(crate) mod camera;
pub(crate) mod cull;
pub(crate) mod finite;
pub(crate) mod frame;
pub(crate) mod lod;
pub(crate) mod piece_id;
pub(crate) mod ring_index;
pub(crate) mod screen;
pub(crate) mod section;
pub(crate) mod tree;
pub(crate) mod turntable;
pub(crate) mod up;

pub(crate) use camera::{Camera, Projection};
pub(crate) use cull::Cull;
pub(crate) use frame::Frame;
pub(crate) use lod::{substitute, LodOptions, LodStats};
pub(crate) use piece_id::PieceId;
pub(crate) use screen::{Facing, ScreenFaces};
pub(crate) use tree::ViewTree;

use std::sync::Arc;

use crate::progress::{Phase, Progress, Stage};
use crate::scene::{FaceId, Scene};

/// Everything visibility needs about one view of one scene.
#[derive(Debug, Clone)]
pub struct View {
    /// The camera.
    pub camera: Camera,
    /// Faces in screen space, as planar pieces.
    pub(crate) screen: Arc<ScreenFaces>,
    /// The object tree with screen bounds.
    pub(crate) tree: ViewTree,
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

    /// Number of faces of the scene (face ids run from 0 below it), culled ones included.
    pub fn face_count(&self) -> usize {
        self.screen.face_count()
    }

    /// The projected faces that can hide something, as a z-buffer or a ray caster needs
    /// them, in face order: for each planar piece of a face (one for a planar face), the
    /// face, its screen corners (x, y, depth; depth grows toward the viewer) and three of
    /// those corners, by index, that span its plane well.
    ///
    /// ```
    /// use kepler_hsr::{Camera, Mesh, Object, Scene, View, P3, V3};
    ///
    /// let cube = Mesh::cuboid(P3::new(0., 0., 0.), P3::new(1., 1., 1.));
    /// let scene = Scene::new(Object::from_mesh("cube", cube), "cube".into());
    /// let camera = Camera::orthographic(V3::new(0., 0., -1.), V3::y()).unwrap();
    /// let view = View::new(&scene, camera);
    /// // The front and the back: the sides are edge-on, and the back is not culled because
    /// // the scene was not prepared.
    /// assert_eq!(view.screen_polygons().count(), 2);
    /// ```
    pub fn screen_polygons(
        &self,
    ) -> impl Iterator<Item = (FaceId, Vec<[f64; 3]>, [usize; 3])> + '_ {
        let sf = &self.screen;
        sf.piece_ids()
            .filter(|&p| sf.piece(p).is_occluder())
            .map(|p| {
                let piece = sf.piece(p);
                let corners = sf.pts(p).iter().copied().collect();
                (piece.face, corners, piece.refs.map(|k| k as usize))
            })
    }

    /// The path of the leaf object face `f` belongs to (`f` must have been projected: not
    /// culled by an inbox).
    pub fn face_path(&self, f: FaceId) -> &str {
        &self.screen.leaf_of_face(f).path
    }

    /// The paths of the leaf objects this view projected, in order.
    pub fn object_paths(&self) -> impl Iterator<Item = &str> + '_ {
        self.screen.leaves.iter().map(|l| l.path.as_str())
    }

    /// Projects the faces a cull of `scene` kept: hidden subtrees are left out of the screen
    /// faces and the tree, and their faces' VTPs are empty.
    ///
    /// As the view stage's phases in `progress`: [`Phase::Project`] counting the kept leaves'
    /// faces projected, then [`Phase::Tree`] every face placed in the view tree.
    pub(crate) fn from_cull(
        scene: &Scene,
        camera: Camera,
        cull: &Cull,
        progress: &Progress,
    ) -> View {
        let kept = cull.leaves.iter().map(|l| l.mesh.faces.len()).sum();
        progress.enter_phase(Stage::View, Phase::Project, kept);
        let mut screen = ScreenFaces::from_cull(cull, &camera, progress.count());
        screen.section_first = scene.section.as_ref().map(|s| s.first_face);
        mark_occlude_only(scene, &mut screen);
        progress.enter_phase(Stage::View, Phase::Tree, screen.face_count());
        let tree = ViewTree::build(scene, &camera, &screen, &cull.hidden, progress.count());
        View {
            camera,
            screen: Arc::new(screen),
            tree,
            culled: CullSummary {
                subtrees: cull.hidden.len() as u64 + cull.components_hidden,
                faces: cull.hidden_faces(),
                tested: cull.objects_tested,
            },
        }
    }
}

/// Marks the projected leaves whose style is occlude-only.
fn mark_occlude_only(scene: &Scene, screen: &mut ScreenFaces) {
    let styles = scene.leaf_styles();
    if styles.is_empty() {
        return;
    }
    let hidden: std::collections::HashMap<usize, bool> = scene
        .leaves()
        .iter()
        .zip(&styles)
        .filter(|(l, _)| !l.mesh.faces.is_empty())
        .map(|(l, s)| (l.first_face, s.hidden()))
        .collect();
    for l in &mut screen.leaves {
        l.occlude_only = hidden
            .get(&(l.first_face.index()))
            .copied()
            .unwrap_or(false);
    }
}

impl View {
    /// A face's normal in view space (Newell's normal of its world corners turned by the
    /// camera, not normalised): +z faces the viewer of an orthographic view.
    pub fn face_normal(&self, f: crate::scene::FaceId) -> crate::geom::V3 {
        let n = crate::geom::newell(&self.screen.face_world_pts(f));
        self.camera.matrix.fixed_view::<3, 3>(0, 0) * n
    }

    /// The path of the object (leaf) a face belongs to, as `kepler info` names it; "" for a
    /// face this view does not hold (in a culled subtree).
    pub fn object_path(&self, f: crate::scene::FaceId) -> &str {
        self.screen
            .leaves
            .iter()
            .find(|l| l.faces().contains(&f))
            .map_or("", |l| l.path.as_str())
    }
}
