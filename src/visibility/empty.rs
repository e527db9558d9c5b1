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
    let n = vis.ids().len();
    let shows = |k: usize| vis.at(k).area > 0.0;
    let perspective = view.camera.projection == Projection::Perspective;
    if !perspective && crate::chunked::position_first(n, shows).is_some() {
        return None;
    }
    // The bounds of what shows, folded on all threads (least and greatest are exact: the
    // same box, and the same answer, in any order).
    let bounds = |r: std::ops::Range<usize>| {
        r.filter(|&k| shows(k)).fold(Rect::EMPTY, |acc, k| {
            vis.at(k).fold_points(acc, |mut b, p| {
                b.add(p);
                b
            })
        })
    };
    let visible = if n <= crate::chunked::CHUNK || rayon::current_num_threads() == 1 {
        bounds(0..n)
    } else {
        use rayon::prelude::*;
        let chunk = crate::chunked::CHUNK;
        (0..n.div_ceil(chunk))
            .into_par_iter()
            .map(|c| bounds(c * chunk..((c + 1) * chunk).min(n)))
            .reduce(|| Rect::EMPTY, |a, b| a.union(&b))
    };
    if !visible.is_empty() {
        let window = Rect::new(-1.6, -1.0, 1.6, 1.0);
        let seen = !perspective || visible.overlaps_closed(&window);
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
