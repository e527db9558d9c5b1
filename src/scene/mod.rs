//! The scene database: Franklin's object tree with CBOX/INBOX, instancing, cleanup and FLATTEN.

pub(crate) mod cleanup;
pub(crate) mod contain;
pub(crate) mod face_id;
pub(crate) mod flatten;
pub(crate) mod names;
pub(crate) mod object;
pub(crate) mod object_tree;
pub(crate) mod proof;
pub(crate) mod section_info;
pub(crate) mod style;
pub(crate) mod texture;
pub(crate) mod topology;
pub(crate) mod triangulate;
pub(crate) mod union_find;

use std::path::PathBuf;

use crate::geom::{Box3, M4, P3, V3};

pub(crate) use face_id::FaceId;
pub(crate) use object::{Content, Face, FaceIndices, Mesh, Object};
pub(crate) use proof::{CapFailure, ProvenPieces, Solidity};
pub(crate) use texture::{Texture, TextureFrame};

/// Vertical field of view of a perspective camera that names none (an eye point on the
/// command line, or a scene file's camera block), degrees.
pub(crate) const DEFAULT_FOV_DEG: f64 = 45.0;

/// A camera as a scene file states it (the view stage turns it into a matrix).
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum CameraSpec {
    /// Orthographic, looking along `dir`.
    Orthographic {
        /// Viewing direction.
        dir: V3,
        /// Up vector.
        up: V3,
    },
    /// Perspective from `eye` toward `target` with a vertical field of view in degrees.
    Perspective {
        /// Eye position.
        eye: P3,
        /// Point looked at.
        target: P3,
        /// Up vector.
        up: V3,
        /// Vertical field of view, degrees.
        fov_deg: f64,
    },
}

/// A loaded scene: the object tree (its root has no name in paths) and an optional camera.
#[derive(Debug, Clone)]
pub struct Scene {
    /// The root object; its subobjects are the scene's top-level objects.
    pub root: Object,
    /// The scene file's camera block, if any.
    pub(crate) camera: Option<CameraSpec>,
    /// Where the scene file's camera block is (for messages about it).
    pub(crate) camera_at: Option<crate::error::Location>,
    /// The file the scene came from.
    pub source: PathBuf,
    /// What a section cut did, when this scene is one (`RenderOptions::sections`).
    pub(crate) section: Option<std::sync::Arc<section_info::SectionInfo>>,
    /// The scene file's `section` planes (point, normal), cut when a render gives none.
    pub(crate) sections: Vec<(P3, V3)>,
    /// Style rules by object path or pattern (`--styles`), applied after the objects' own.
    pub(crate) styles: Vec<(String, style::Style)>,
}

/// One leaf object placed in the world: its path, its mesh and its world transform.
#[derive(Debug, Clone)]
pub(crate) struct Leaf<'a> {
    /// Object path from the top level, names joined by '/'.
    pub path: String,
    /// The leaf's vertices and faces (in its own coordinates).
    pub mesh: &'a Mesh,
    /// Transform to world coordinates.
    pub transform: M4,
    /// Index of this leaf's first face in the global face order.
    pub first_face: usize,
}

impl Leaf<'_> {
    /// True when the transform mirrors (negative determinant): face windings must be reversed.
    pub(crate) fn mirrors(&self) -> bool {
        self.transform.fixed_view::<3, 3>(0, 0).determinant() < 0.0
    }

    /// World position of vertex `k`.
    pub(crate) fn world_vertex(&self, k: u32) -> P3 {
        self.transform
            .transform_point(&self.mesh.vertices[k as usize])
    }

    /// World positions of all vertices, in order ([`Leaf::world_vertex`] of each: the same
    /// bits wherever they are made, which lets the screen and the drawing share them).
    pub(crate) fn world_vertices(&self) -> impl ExactSizeIterator<Item = P3> + '_ {
        self.mesh
            .vertices
            .iter()
            .map(|v| self.transform.transform_point(v))
    }
}

impl Scene {
    /// A scene of one root object.
    pub fn new(root: Object, source: PathBuf) -> Self {
        Scene {
            root,
            camera: None,
            camera_at: None,
            source,
            section: None,
            sections: Vec::new(),
            styles: Vec::new(),
        }
    }

    /// The leaves in global face order (depth-first, instances expanded).
    pub(crate) fn leaves(&self) -> Vec<Leaf<'_>> {
        let mut out = Vec::new();
        let mut first_face = 0;
        self.root
            .for_each_mesh(&M4::identity(), &mut |path, mesh, xf| {
                out.push(Leaf {
                    path: path.join("/"),
                    mesh,
                    transform: *xf,
                    first_face,
                });
                first_face += mesh.faces.len();
            });
        out
    }

    /// Total number of faces (instances expanded).
    pub fn face_count(&self) -> usize {
        self.root.face_count()
    }

    /// The world CBOX of the whole scene.
    pub fn cbox(&self) -> Box3 {
        self.root.cbox
    }

    /// The up vector of the scene file's camera, if it has one.
    pub fn camera_up(&self) -> Option<V3> {
        match self.camera.as_ref()? {
            CameraSpec::Orthographic { up, .. } | CameraSpec::Perspective { up, .. } => Some(*up),
        }
    }

    /// A scene with this one's source and camera and another object tree (substitutes of
    /// its objects, say).
    pub fn with_root(&self, root: Object) -> Scene {
        Scene {
            root,
            camera: self.camera.clone(),
            camera_at: self.camera_at.clone(),
            source: self.source.clone(),
            section: self.section.clone(),
            sections: self.sections.clone(),
            styles: self.styles.clone(),
        }
    }
}

/// Small scenes shared by the unit tests of several stages.
#[cfg(test)]
pub(crate) mod testing {
    use super::{Object, Scene};
    use crate::geom::{PolyMesh, P3};
    use crate::scene::cleanup::{cleanup, Origin};

    /// A leaf object from a raw mesh, through the loader's cleanup.
    pub(crate) fn leaf(name: &str, raw: &PolyMesh) -> Object {
        let origin = Origin {
            file: std::path::Path::new("t"),
            face_pos: &[],
        };
        Object::from_mesh(
            name,
            cleanup(raw, &origin, &mut Vec::new(), crate::count::Count::NONE).unwrap(),
        )
    }

    /// A scene of one open leaf "sq": the unit square [0, 1]^2 at z = 0, cut into `faces`
    /// (indices of its corners (0,0), (1,0), (1,1), (0,1)).
    pub(crate) fn unit_square_scene(faces: Vec<Vec<u32>>) -> Scene {
        let corners = [[0., 0.], [1., 0.], [1., 1.], [0., 1.]].map(|c| P3::new(c[0], c[1], 0.));
        let sq = leaf("sq", &PolyMesh::new(corners.to_vec(), faces));
        Scene::new(Object::group("", vec![sq]), "t".into())
    }

    /// A closed box as a leaf.
    pub(crate) fn cuboid(name: &str, lo: [f64; 3], hi: [f64; 3]) -> Object {
        let raw = crate::primitives::cuboid(P3::from(lo), P3::from(hi));
        leaf(name, &raw)
    }

    /// The unit cube [0, 1]^3 as a closed leaf named "cube".
    pub(crate) fn unit_cube() -> Object {
        cuboid("cube", [0., 0., 0.], [1., 1., 1.])
    }

    /// A scene whose face and piece numbers differ: `warped` (face 0, a quad bent out of its
    /// plane, two planar pieces) at z = 0, then the closed box `wall` (faces 1-6) in front of
    /// it at z in [1, 2], then the closed box `hidden` (faces 7-12) behind the wall at
    /// z in [-3, -2], then `beside` (faces 13-18) off to the side. Seen along -z.
    pub(crate) fn warped_scene() -> Scene {
        let bent = PolyMesh::new(
            vec![
                P3::new(-4., -4., 0.),
                P3::new(-3., -4., 0.),
                P3::new(-3., -3., 0.1),
                P3::new(-4., -3., 0.),
            ],
            vec![vec![0, 1, 2, 3]],
        );
        let objects = vec![
            leaf("warped", &bent),
            cuboid("wall", [-2., -2., 1.], [2., 2., 2.]),
            cuboid("hidden", [-1., -1., -3.], [1., 1., -2.]),
            cuboid("beside", [5., 5., -1.], [6., 6., 0.]),
        ];
        Scene::new(Object::group("", objects), "t".into())
    }

    /// A scene of the unit cube alone.
    pub(crate) fn unit_cube_scene() -> Scene {
        Scene::new(Object::group("", vec![unit_cube()]), "t".into())
    }
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use super::*;

    fn tri(z: f64) -> Mesh {
        Mesh {
            vertices: vec![P3::new(0., 0., z), P3::new(1., 0., z), P3::new(0., 1., z)],
            faces: vec![Face::new(vec![0, 1, 2])],
            closed: false,
            solidity: None,
            caps: Vec::new(),
            proven: None,
            pieces: None,
        }
    }

    #[test]
    fn instancing_stores_once_places_many() {
        let proto = Arc::new(Object::from_mesh("t", tri(0.0)));
        let a = Object::instance(
            "a",
            proto.clone(),
            nalgebra::Translation3::new(10., 0., 0.).to_homogeneous(),
        );
        let b = Object::instance("b", proto.clone(), M4::new_scaling(2.0));
        let root = Object::group(
            "",
            vec![
                Object::group("g", vec![a, b]),
                Object::from_mesh("c", tri(5.0)),
            ],
        );
        let scene = Scene::new(root, "x".into());
        let leaves = scene.leaves();
        assert_eq!(
            leaves.iter().map(|l| l.path.as_str()).collect::<Vec<_>>(),
            vec!["g/a", "g/b", "c"]
        );
        assert_eq!(
            leaves.iter().map(|l| l.first_face).collect::<Vec<_>>(),
            vec![0, 1, 2]
        );
        assert_eq!(leaves[0].world_vertex(1), P3::new(11., 0., 0.));
        assert_eq!(leaves[1].world_vertex(2), P3::new(0., 2., 0.));
        assert!(std::ptr::eq(leaves[0].mesh, leaves[1].mesh));
        assert_eq!(Arc::strong_count(&proto), 3);
        assert_eq!(
            scene.cbox(),
            Box3::new(P3::new(0., 0., 0.), P3::new(11., 2., 5.))
        );
    }

    #[test]
    fn mirrored_instance_is_detected() {
        let proto = Arc::new(Object::from_mesh("t", tri(0.0)));
        let root = Object::group(
            "",
            vec![Object::instance(
                "m",
                proto,
                M4::new_nonuniform_scaling(&V3::new(-1., 1., 1.)),
            )],
        );
        let scene = Scene::new(root, "x".into());
        assert!(scene.leaves()[0].mirrors());
    }
}
