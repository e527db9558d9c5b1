//! The paper's object: a name, a CBOX, an INBOX, and either subobjects or vertices and faces.

use std::path::Path;
use std::sync::Arc;

use super::object_tree::ObjectTree;
use crate::error::{Result, Warning};
use crate::geom::{Box3, PolyMesh, M4, P3};

use super::cleanup::{cleanup, Origin};
use super::proof::{ProvenPieces, Solidity};
use super::texture::Texture;
use super::topology::Pieces;

/// A face's vertex indices: up to four held inline, more on the heap. It dereferences to
/// `[u32]`; make one with `FaceIndices::from_slice` or `collect()`.
pub type FaceIndices = smallvec::SmallVec<[u32; 4]>;

/// A planar polygon of an object, indexing the object's vertex list (the paper's FACE).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Face {
    /// Indices into the object's vertices, counter-clockwise seen from outside for solids
    /// (inline up to four: a triangle or a quad takes no heap block of its own).
    pub vertices: FaceIndices,
    /// Surface markings in the face's texture coordinates (the paper's first use of texture).
    pub(crate) texture: Option<Arc<Texture>>,
}

impl Face {
    /// A face with no texture, of the indices `vertices` (a `Vec`, an array, a slice).
    pub fn new(vertices: impl AsRef<[u32]>) -> Self {
        Face {
            vertices: FaceIndices::from_slice(vertices.as_ref()),
            texture: None,
        }
    }
}

/// Vertices and faces of a leaf object, after cleanup.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Mesh {
    /// The paper's (VERTi): no two share coordinates.
    pub vertices: Vec<P3>,
    /// The paper's \[FACEi\].
    pub faces: Vec<Face>,
    /// True when every edge is shared by exactly two faces traversing it in opposite
    /// directions: a closed, consistently oriented surface.
    pub closed: bool,
    /// Whether back faces may be culled, decided exactly by the prepare stage (None until
    /// then: an unprepared mesh is never culled).
    pub(crate) solidity: Option<Solidity>,
    /// Where the whole mesh is not a solid ([`Mesh::solidity`] says why), the pieces of it
    /// that are: their back faces may be culled, away from their caps (None when no piece
    /// is proven, or the whole is).
    pub(crate) proven: Option<ProvenPieces>,
    /// The edge-connected pieces of a mesh the prepare stage proved a solid
    /// ([`Mesh::cullable`]), as its test found them (None otherwise): the line drawing reads
    /// them instead of matching the edges again.
    pub(crate) pieces: Option<Arc<Pieces>>,
    /// The virtual triangles capping the holes of a [`Solidity::Capped`] mesh (or of the
    /// proven pieces of [`Mesh::proven`]), counter-clockwise
    /// seen from outside the capped solid (empty otherwise). Never drawn, never in the output,
    /// never occluders or targets: the view only asks whether a cap facing the viewer lies over
    /// a back face ([`mod@crate::prepare::solidity::caps`]).
    pub(crate) caps: Vec<[P3; 3]>,
}

impl Mesh {
    /// True when the prepare stage proved the mesh a solid whose back faces may be culled.
    pub fn cullable(&self) -> bool {
        self.solidity.is_some_and(Solidity::is_solid)
    }

    /// True when the prepare stage capped the mesh's holes into a solid: back faces may be
    /// culled where no cap facing the viewer lies over them.
    pub fn capped(&self) -> bool {
        self.solidity.is_some_and(Solidity::is_capped)
    }
}

impl Mesh {
    /// A clean mesh of polygons given by vertex indices (each counter-clockwise seen from
    /// outside for a solid): the cleanup a loaded mesh gets (merged vertices, split
    /// non-planar faces, dropped degenerate ones), its warnings appended to `warnings`.
    ///
    /// ```
    /// use kepler_hsr::{Mesh, P3};
    ///
    /// let square = vec![
    ///     P3::new(0., 0., 0.),
    ///     P3::new(1., 0., 0.),
    ///     P3::new(1., 1., 0.),
    ///     P3::new(0., 1., 0.),
    /// ];
    /// let mesh = Mesh::from_polygons(square, vec![vec![0, 1, 2, 3]], &mut Vec::new())?;
    /// assert_eq!(mesh.faces.len(), 1);
    /// # Ok::<(), kepler_hsr::Error>(())
    /// ```
    pub fn from_polygons(
        vertices: Vec<P3>,
        faces: Vec<Vec<u32>>,
        warnings: &mut Vec<Warning>,
    ) -> Result<Mesh> {
        let origin = Origin {
            file: Path::new("polygons"),
            face_pos: &[],
        };
        cleanup(
            &PolyMesh::new(vertices, faces),
            &origin,
            warnings,
            Default::default(),
        )
    }

    /// The generalized winding number of the faces around `p`
    /// (the sum of its faces' signed solid angles over 4π): about 1 inside a
    /// closed outward solid, 0 outside.
    pub fn winding_number(&self, p: &P3) -> f64 {
        crate::geom::solid_angle::winding_number(
            &self.vertices,
            self.faces.iter().map(|f| f.vertices.as_slice()),
            p,
        )
    }
}

/// A prototype placed with a transform: stored once, placed many times.
#[derive(Debug, Clone)]
pub struct Instance {
    /// The prototype object, shared by every placement.
    pub prototype: Arc<Object>,
    /// Affine transform from the prototype's coordinates into the parent's.
    pub transform: M4,
}

/// What an object is made of.
#[derive(Debug, Clone)]
pub enum Content {
    /// A leaf: vertices and faces.
    Mesh(Mesh),
    /// Subobjects (the paper's (SUBi)).
    Subobjects(Vec<Object>),
    /// A placed prototype: behaves as one subobject, transformed.
    Instance(Instance),
}

/// An object of the scene tree (the paper's OBJECT).
#[derive(Debug, Clone)]
pub struct Object {
    /// Name, unique among its siblings.
    pub name: String,
    /// Circumscribing box, in the object's own coordinates (the parent's frame).
    pub cbox: Box3,
    /// Inscribed box, in the same frame, where known.
    pub inbox: Option<Box3>,
    /// Subobjects, or vertices and faces, or an instance. Edits may replace a prototype by
    /// a prepared copy but must not change the number of faces below.
    pub content: Content,
    /// Faces in the subtree, instances expanded (kept so that culling can skip a subtree in
    /// constant time, and so that a scene's size is known before anything is expanded);
    /// saturating at `usize::MAX`.
    faces: usize,
    /// The object tree of a leaf mesh (paper 002), built by the prepare stage.
    pub(crate) tree: Option<Arc<ObjectTree>>,
    /// Vertices in the subtree, instances expanded; saturating.
    vertices: usize,
    /// How the object is drawn (scene files' `style` node), inherited by its parts.
    pub(crate) style: Option<super::style::Style>,
}

/// A placed prototype whose expansion has more vertices than this gets the CBOX of its
/// prototype's CBOX corners (a valid CBOX, looser under rotations) instead of the box of
/// every placed vertex: placing it costs the same whatever it expands to.
const EXACT_PLACED_CBOX: usize = 1 << 20;

impl Object {
    /// A leaf object; its CBOX is computed.
    pub fn from_mesh(name: impl Into<String>, mesh: Mesh) -> Self {
        let cbox = Box3::from_points(mesh.vertices.iter());
        Object {
            name: name.into(),
            cbox,
            inbox: None,
            faces: mesh.faces.len(),
            vertices: mesh.vertices.len(),
            content: Content::Mesh(mesh),
            tree: None,
            style: None,
        }
    }

    /// An object with subobjects; its CBOX is the union of theirs.
    pub fn group(name: impl Into<String>, subs: Vec<Object>) -> Self {
        let cbox = subs.iter().fold(Box3::empty(), |b, s| b.union(&s.cbox));
        Object {
            name: name.into(),
            cbox,
            inbox: None,
            faces: subs.iter().fold(0, |n, s| n.saturating_add(s.faces)),
            vertices: subs.iter().fold(0, |n, s| n.saturating_add(s.vertices)),
            content: Content::Subobjects(subs),
            tree: None,
            style: None,
        }
    }

    /// A placement of `prototype` with `transform`; its CBOX is that of the placed vertices
    /// (for a prototype that expands to more than `EXACT_PLACED_CBOX` vertices, that of its
    /// CBOX's placed corners). Nothing is expanded beyond that bound.
    pub fn instance(name: impl Into<String>, prototype: Arc<Object>, transform: M4) -> Self {
        let mut cbox = Box3::empty();
        if prototype.vertices <= EXACT_PLACED_CBOX {
            prototype.for_each_mesh(&transform, &mut |_, mesh, m| {
                for v in &mesh.vertices {
                    cbox.add_point(&m.transform_point(v));
                }
            });
        } else if !prototype.cbox.is_empty() {
            for c in prototype.cbox.corners() {
                cbox.add_point(&transform.transform_point(&c));
            }
        }
        Object {
            name: name.into(),
            cbox,
            inbox: None,
            faces: prototype.faces,
            vertices: prototype.vertices,
            content: Content::Instance(Instance {
                prototype,
                transform,
            }),
            tree: None,
            style: None,
        }
    }

    /// The paper's NSUB / SUB: the subobjects (empty for a leaf; an instance has none of its own).
    pub fn subobjects(&self) -> &[Object] {
        match &self.content {
            Content::Subobjects(s) => s,
            _ => &[],
        }
    }

    /// The leaf mesh, if this object has vertices and faces.
    pub fn mesh(&self) -> Option<&Mesh> {
        match &self.content {
            Content::Mesh(m) => Some(m),
            _ => None,
        }
    }

    /// The paper's VERT: the vertices (empty unless a leaf).
    pub fn vertices(&self) -> &[P3] {
        self.mesh().map_or(&[], |m| &m.vertices)
    }

    /// The paper's FACE: the faces (empty unless a leaf).
    pub fn faces(&self) -> &[Face] {
        self.mesh().map_or(&[], |m| &m.faces)
    }

    /// Number of faces in the whole subtree, instances expanded.
    pub fn face_count(&self) -> usize {
        self.faces
    }

    /// Number of vertices in the whole subtree, instances expanded (saturating).
    pub fn vertex_count(&self) -> usize {
        self.vertices
    }

    /// Faces of the meshes below that pass `wanted` (given the mesh's object and the mesh),
    /// each shared prototype counted once however many instances place it: the work a pass
    /// over the distinct meshes does, for its progress count.
    pub(crate) fn distinct_faces_where(&self, wanted: &impl Fn(&Object, &Mesh) -> bool) -> usize {
        fn walk(
            obj: &Object,
            wanted: &impl Fn(&Object, &Mesh) -> bool,
            seen: &mut std::collections::HashSet<usize>,
        ) -> usize {
            match &obj.content {
                Content::Mesh(m) if wanted(obj, m) => m.faces.len(),
                Content::Mesh(_) => 0,
                Content::Subobjects(subs) => subs.iter().map(|s| walk(s, wanted, seen)).sum(),
                Content::Instance(i) if seen.insert(Arc::as_ptr(&i.prototype) as usize) => {
                    walk(&i.prototype, wanted, seen)
                }
                Content::Instance(_) => 0,
            }
        }
        walk(self, wanted, &mut std::collections::HashSet::new())
    }

    /// True when every leaf below is a closed, consistently oriented solid.
    pub fn is_closed(&self) -> bool {
        match &self.content {
            Content::Mesh(m) => m.closed,
            Content::Subobjects(s) => !s.is_empty() && s.iter().all(Object::is_closed),
            Content::Instance(i) => i.prototype.is_closed(),
        }
    }

    /// Visits every leaf mesh depth-first (the global face order), with the path of names
    /// below this object and the transform from the leaf's coordinates to `xf`'s target.
    pub fn for_each_mesh<'a>(&'a self, xf: &M4, f: &mut dyn FnMut(&[&'a str], &'a Mesh, &M4)) {
        let mut path = Vec::new();
        self.walk_meshes(xf, &mut path, f);
    }

    fn walk_meshes<'a>(
        &'a self,
        xf: &M4,
        path: &mut Vec<&'a str>,
        f: &mut dyn FnMut(&[&'a str], &'a Mesh, &M4),
    ) {
        match &self.content {
            Content::Mesh(m) => f(path, m, xf),
            Content::Subobjects(subs) => {
                for s in subs {
                    path.push(&s.name);
                    s.walk_meshes(xf, path, f);
                    path.pop();
                }
            }
            Content::Instance(i) => i.prototype.walk_meshes(&(xf * i.transform), path, f),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_triangle_or_a_quad_holds_its_indices_inline() {
        // 32 bytes a face, as with a Vec, but no heap block of its own up to four corners.
        assert_eq!(std::mem::size_of::<Face>(), 32);
        for n in 3..=4u32 {
            let f = Face::new((0..n).collect::<Vec<_>>());
            assert!(!f.vertices.spilled(), "{n} corners inline");
            assert_eq!(f.vertices[..], (0..n).collect::<Vec<_>>()[..]);
        }
        let five = Face::new([0, 1, 2, 3, 4]);
        assert!(five.vertices.spilled(), "five corners on the heap");
        assert_eq!(five.vertices.as_slice(), &[0, 1, 2, 3, 4]);
        assert_eq!(Face::new(&[7u32, 8, 9][..]), Face::new(vec![7, 8, 9]));
    }
}
