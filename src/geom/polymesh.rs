//! A plain polygon mesh: what loaders and primitives produce before cleanup.

use super::P3;

/// Vertices and polygonal faces (each a list of vertex indices, counter-clockwise seen from
/// outside for solids). No invariants are promised: cleanup checks and repairs them.
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct PolyMesh {
    /// Vertex positions.
    pub vertices: Vec<P3>,
    /// Faces as vertex index lists.
    pub faces: Vec<Vec<u32>>,
}

impl PolyMesh {
    /// A mesh from its parts.
    pub(crate) fn new(vertices: Vec<P3>, faces: Vec<Vec<u32>>) -> Self {
        PolyMesh { vertices, faces }
    }

    /// Appends `other` beside this mesh: its vertices after ours, its faces renumbered.
    pub(crate) fn append(&mut self, other: &PolyMesh) {
        let base = self.vertices.len() as u32;
        self.vertices.extend(&other.vertices);
        self.faces.extend(
            other
                .faces
                .iter()
                .map(|f| f.iter().map(|&v| v + base).collect()),
        );
    }

    /// Positions of the corners of face `f`.
    pub(crate) fn face_points(&self, f: usize) -> impl Iterator<Item = &P3> + '_ {
        self.faces[f]
            .iter()
            .map(move |&i| &self.vertices[i as usize])
    }

    #[cfg(test)]
    /// The face's vector area (half the sum of cross products; Newell's normal).
    pub(crate) fn face_vector_area(&self, f: usize) -> super::V3 {
        let pts: Vec<&P3> = self.face_points(f).collect();
        let mut n = super::V3::zeros();
        let o = pts[0];
        for i in 1..pts.len().saturating_sub(1) {
            n += (pts[i] - o).cross(&(pts[i + 1] - o));
        }
        n * 0.5
    }
}
