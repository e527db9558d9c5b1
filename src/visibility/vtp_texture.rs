//! A face's VTP read in the face's own texture coordinates (the paper's second use of texture).

use crate::geom::newell;
use crate::geom::poly2::MultiPolygon;
use crate::geom::P3;
use crate::scene::{FaceId, TextureFrame};
use crate::view::View;

use super::Visibility;

/// The world point of face `id`'s plane that projects to screen point (x, y): the line of
/// points with that image meets the plane once (None when the face is edge-on).
pub(crate) fn screen_to_face(view: &View, id: FaceId, xy: [f64; 2]) -> Option<P3> {
    let pts = view.screen.face_world_pts(id);
    if pts.len() < 3 {
        return None;
    }
    let n = newell(&pts);
    let d = n.dot(&pts[0].coords);
    let a = view.camera.unproject([xy[0], xy[1], 0.0]);
    let b = view.camera.unproject([xy[0], xy[1], 1.0]);
    let dir = b - a;
    let denom = n.dot(&dir);
    if denom == 0.0 || !denom.is_finite() {
        return None;
    }
    let t = (d - n.dot(&a.coords)) / denom;
    Some(a + dir * t)
}

/// The texture frame of face `id` (origin nearest the world origin, horizontal x axis).
pub(crate) fn face_frame(view: &View, id: FaceId) -> Option<TextureFrame> {
    let pts = view.screen.face_world_pts(id);
    TextureFrame::of_plane(pts.first()?, &newell(&pts))
}

/// VTP(F) of face `id` in F's texture coordinates: every screen point of the visible region
/// taken back to F's plane, then into the paper's local 2-D system of the face.
pub(crate) fn vtp_in_texture(view: &View, vis: &Visibility, id: FaceId) -> Option<MultiPolygon> {
    let frame = face_frame(view, id)?;
    let map_ring = |r: &Vec<[f64; 2]>| -> Option<Vec<[f64; 2]>> {
        r.iter()
            .map(|q| screen_to_face(view, id, *q).map(|p| frame.to_texture(&p)))
            .collect()
    };
    vis.face(id)
        .visible()
        .iter()
        .map(|poly| poly.iter().map(map_ring).collect::<Option<Vec<_>>>())
        .collect()
}
