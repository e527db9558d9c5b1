//! Why a solved view shows nothing: the reason a render gives in a warning instead of an
//! empty picture without a word.

use crate::geom::Rect;
use crate::view::{Facing, Projection, View};

use super::result::Visibility;

/// The reason nothing (or nothing in the camera's field of view) is visible, if so; `faces`
/// is the scene's face count.
pub(crate) fn why_empty(faces: usize, view: &View, vis: &Visibility) -> Option<String> {
    if faces == 0 {
        return Some(
            "the scene has no faces: every face was dropped on loading (see the warnings above)"
                .into(),
        );
    }
    let mut visible = Rect::EMPTY;
    for (_, f) in vis.iter() {
        if f.area > 0.0 {
            visible = f.fold_points(visible, |mut r, p| {
                r.add(p);
                r
            });
        }
    }
    if !visible.is_empty() {
        let window = Rect::new(-1.6, -1.0, 1.6, 1.0);
        let seen =
            view.camera.projection != Projection::Perspective || visible.overlaps_closed(&window);
        return (!seen).then(|| {
            "nothing visible lies in the camera's field of view: the picture shows what lies outside it".into()
        });
    }
    let pieces = &view.screen.pieces;
    if pieces.is_empty() {
        return Some(format!("nothing is visible: all {faces} faces are hidden"));
    }
    let clipped = pieces
        .iter()
        .filter(|p| p.facing == Facing::Clipped)
        .count();
    Some(if clipped == pieces.len() {
        format!("nothing is visible: all {faces} faces are behind the camera")
    } else {
        format!(
            "nothing is visible: every face is behind the camera, seen exactly edge-on or too small to have area on the screen ({} of {} pieces behind the camera)",
            clipped,
            pieces.len()
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::{P3, V3};
    use crate::scene::testing::unit_cube_scene;
    use crate::view::Camera;
    use crate::{render, RenderOptions};

    fn reason(camera: Camera) -> Option<String> {
        let scene = unit_cube_scene();
        let r = render(
            &scene,
            &camera,
            &RenderOptions::default(),
            &crate::Progress::default(),
        )
        .unwrap();
        why_empty(scene.face_count(), &r.view, &r.visibility)
    }

    #[test]
    fn reasons_for_empty_views() {
        assert_eq!(reason(Camera::three_quarter()), None);
        let behind = Camera::perspective(
            P3::new(0.5, 0.5, -5.),
            P3::new(0.5, 0.5, -10.),
            V3::y(),
            40.0,
            0.01,
        )
        .unwrap();
        assert!(reason(behind).unwrap().contains("behind the camera"));
        let aside = Camera::perspective(
            P3::new(-3., 0.5, 5.),
            P3::new(50., 0.5, 5.),
            V3::y(),
            10.0,
            0.01,
        )
        .unwrap();
        assert!(reason(aside).unwrap().contains("field of view"));
    }
}
