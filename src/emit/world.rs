//! World-space polygons of every face (unclipped, in mesh vertex order), with their leaf and vertex indices.

use crate::geom::{newell, Box3, P3, V3};
use crate::scene::Scene;

/// One face in world space.
#[derive(Debug, Clone)]
pub struct WorldFace {
    /// Index of the leaf object in [`Scene::leaves`] order.
    pub leaf: u32,
    /// The face's vertex indices in its leaf mesh.
    pub vertices: Vec<u32>,
    /// World points, in mesh order (not reversed for mirroring transforms).
    pub points: Vec<P3>,
    /// Newell normal of `points` (twice the vector area; zero for a degenerate face).
    pub normal: V3,
    /// World bounding box: min then max.
    pub bbox: [[f64; 3]; 2],
}

/// Every face of a scene in world space, by global face id.
#[derive(Debug, Clone, Default)]
pub struct WorldFaces {
    /// Faces by global id.
    pub faces: Vec<WorldFace>,
    /// Object path of every leaf, in [`Scene::leaves`] order.
    pub paths: Vec<String>,
}

impl WorldFaces {
    /// The world polygons of every face of `scene`, in global face order.
    pub fn build(scene: &Scene) -> WorldFaces {
        let mut faces = Vec::with_capacity(scene.face_count());
        let leaves = scene.leaves();
        for (li, leaf) in leaves.iter().enumerate() {
            let world: Vec<P3> = (0..leaf.mesh.vertices.len() as u32)
                .map(|k| leaf.world_vertex(k))
                .collect();
            for f in &leaf.mesh.faces {
                let points: Vec<P3> = f.vertices.iter().map(|&k| world[k as usize]).collect();
                faces.push(WorldFace {
                    leaf: li as u32,
                    vertices: f.vertices.clone(),
                    normal: newell(&points),
                    bbox: bbox(&points),
                    points,
                });
            }
        }
        let paths = leaves.into_iter().map(|l| l.path).collect();
        WorldFaces { faces, paths }
    }
}

/// Bounding box of points: min then max.
fn bbox(pts: &[P3]) -> [[f64; 3]; 2] {
    let b = Box3::from_points(pts.iter());
    [b.lo.into(), b.hi.into()]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn square_face_in_world() {
        let scene = crate::scene::testing::unit_square_scene(vec![vec![0, 1, 2, 3]]);
        let w = WorldFaces::build(&scene);
        assert_eq!(w.faces.len(), 1);
        assert_eq!(w.faces[0].normal, V3::new(0., 0., 2.));
        assert_eq!(w.faces[0].bbox, [[0., 0., 0.], [1., 1., 0.]]);
    }
}
