//! Face markings (texture lines and polygon outlines) clipped exactly to each face's VTP.
//!
//! Texture coordinates are in the frame of the face's plane in its mesh's coordinates (Newell
//! normal through the first corner, as the loader attaches them); they go to world through the
//! leaf's transform and to screen through the camera.

use std::collections::BTreeMap;

use crate::geom::poly2::Pt2;
use crate::geom::{newell, P3};
use crate::scene::{FaceId, Scene, TextureFrame};
use crate::view::View;
use crate::visibility::Visibility;

use super::clip_segment::{at, intervals_in};
use super::edges::EdgeKind;
use super::{project_segment, strokes, Stroke};

/// The visible parts of every face's markings, as strokes (kind [`EdgeKind::Plain`]).
pub(crate) fn face_marks(scene: &Scene, view: &View, vis: &Visibility) -> Vec<Stroke> {
    let mut groups: BTreeMap<(u32, EdgeKind), Vec<[Pt2; 2]>> = BTreeMap::new();
    for (li, leaf) in scene.leaves().iter().enumerate() {
        for (k, face) in leaf.mesh.faces.iter().enumerate() {
            let Some(tex) = &face.texture else { continue };
            let fv = vis.face(FaceId((leaf.first_face + k) as u32));
            if fv.is_empty() {
                continue;
            }
            let region = fv.visible();
            let local: Vec<P3> = face
                .vertices
                .iter()
                .map(|&v| leaf.mesh.vertices[v as usize])
                .collect();
            let Some(frame) = TextureFrame::of_plane(&local[0], &newell(&local)) else {
                continue;
            };
            let world = |i: u32| {
                tex.points
                    .get(i as usize)
                    .map(|st| leaf.transform.transform_point(&frame.to_world(*st)))
            };
            let mut pairs: Vec<[u32; 2]> = tex.lines.clone();
            for poly in &tex.polygons {
                for i in 0..poly.len() {
                    pairs.push([poly[i], poly[(i + 1) % poly.len()]]);
                }
            }
            let out = groups.entry((li as u32, EdgeKind::Plain)).or_default();
            for [i, j] in pairs {
                let (Some(p), Some(q)) = (world(i), world(j)) else {
                    continue;
                };
                let Some([a, b]) = project_segment(&view.camera, &p, &q) else {
                    continue;
                };
                if a == b {
                    continue;
                }
                for iv in intervals_in(a, b, &region) {
                    if iv[1] > iv[0] {
                        out.push([at(a, b, iv[0]), at(a, b, iv[1])]);
                    }
                }
            }
        }
    }
    strokes(groups)
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use super::*;
    use crate::emit::lines::total_length;
    use crate::geom::V3;
    use crate::scene::{Face, Mesh, Object, Texture};
    use crate::view::Camera;
    use crate::visibility::{solve, PassOptions};

    #[test]
    fn marking_is_clipped_to_the_face() {
        // A horizontal unit square (frame x = (1,0,0), y = (0,1,0), origin 0) with a line
        // from (-1, 0.5) to (2, 0.5): only its middle unit lies on the face.
        let tex = Texture {
            points: vec![[-1.0, 0.5], [2.0, 0.5]],
            lines: vec![[0, 1]],
            polygons: vec![],
        };
        let mut f = Face::new(vec![0, 1, 2, 3]);
        f.texture = Some(Arc::new(tex));
        let mesh = Mesh {
            vertices: vec![
                P3::new(0., 0., 0.),
                P3::new(1., 0., 0.),
                P3::new(1., 1., 0.),
                P3::new(0., 1., 0.),
            ],
            faces: vec![f],
            closed: false,
            solidity: None,
            caps: Vec::new(),
            proven: None,
            pieces: None,
        };
        let scene = Scene::new(
            Object::group("", vec![Object::from_mesh("sq", mesh)]),
            "t".into(),
        );
        let cam = Camera::orthographic(V3::new(0., 0., -1.), V3::y()).unwrap();
        let view = View::new(&scene, cam);
        let vis = solve(&view, PassOptions::default(), crate::count::Count::NONE);
        let m = face_marks(&scene, &view, &vis);
        assert_eq!(m.len(), 1);
        assert_eq!(total_length(&m), 1.0);
    }
}
