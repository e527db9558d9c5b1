//! Flat shading: a light direction for a view, and each face's brightness under it (Lambert,
//! the face's normal turned toward the viewer), for fills and hatching.

use crate::geom::V3;
use crate::scene::FaceId;
use crate::view::{Camera, View};

/// The view's frame: screen right, screen up, and toward the viewer, in world coordinates.
fn view_axes(camera: &Camera) -> (V3, V3, V3) {
    let m = &camera.matrix;
    let row = |r: usize| V3::new(m[(r, 0)], m[(r, 1)], m[(r, 2)]).normalize();
    let (u, v) = (row(0), row(1));
    (u, v, u.cross(&v))
}

/// The unit direction toward the light: `world` when given (and not zero), else from the
/// upper left, in front of the picture (fixed to the camera).
pub(crate) fn light_direction(camera: &Camera, world: Option<V3>) -> V3 {
    if let Some(l) = world.and_then(|l| l.try_normalize(0.0)) {
        return l;
    }
    let (u, v, w) = view_axes(camera);
    (u * -0.4 + v * 0.6 + w).normalize()
}

/// The light's direction across the picture (screen x, y), when it has one.
pub(crate) fn light_on_screen(camera: &Camera, light: &V3) -> Option<[f64; 2]> {
    let (u, v, _) = view_axes(camera);
    let (x, y) = (light.dot(&u), light.dot(&v));
    let n = x.hypot(y);
    (n > 1e-9).then(|| [x / n, y / n])
}

/// Brightness of face `f` in [0, 1]: the cosine between its normal (turned toward the
/// viewer) and the light, 0 when it faces away from the light.
pub(crate) fn face_shade(view: &View, f: FaceId, light: &V3) -> f64 {
    let (_, _, w) = view_axes(&view.camera);
    let n: V3 = view
        .screen
        .pieces_of(f)
        .map(|p| view.screen.world_pts(p).newell())
        .sum();
    let n = if n.dot(&w) < 0.0 { -n } else { n };
    n.try_normalize(0.0).map_or(0.0, |n| n.dot(light).max(0.0))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_light_comes_from_the_upper_left_front() {
        let cam = Camera::orthographic(V3::new(0., 0., -1.), V3::y()).unwrap();
        let l = light_direction(&cam, None);
        assert!(l.x < 0.0 && l.y > 0.0 && l.z > 0.0, "{l:?}");
        let s = light_on_screen(&cam, &l).unwrap();
        assert!(s[0] < 0.0 && s[1] > 0.0);
        assert!(light_on_screen(&cam, &V3::z()).is_none());
        assert_eq!(light_direction(&cam, Some(V3::new(0., 2., 0.))), V3::y());
    }
}
