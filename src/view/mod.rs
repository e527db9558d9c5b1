//! The view stage: a camera turns the scene into screen-space faces and a view tree.

pub mod camera;
pub mod screen;
pub mod tree;

pub use camera::{Camera, Projection};
pub use screen::{Facing, ScreenFace, ScreenFaces};
pub use tree::{ObjectNode, ViewTree};

use crate::scene::Scene;

/// Everything visibility needs about one view of one scene.
#[derive(Debug, Clone)]
pub struct View {
    /// The camera.
    pub camera: Camera,
    /// Faces in screen space, by global id.
    pub screen: ScreenFaces,
    /// The object tree with screen bounds.
    pub tree: ViewTree,
}

impl View {
    /// Projects `scene` with `camera`.
    pub fn new(scene: &Scene, camera: Camera) -> View {
        let screen = ScreenFaces::build(scene, &camera);
        let tree = ViewTree::build(scene, &camera, &screen);
        View {
            camera,
            screen,
            tree,
        }
    }
}
