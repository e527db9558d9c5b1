//! The paper's FLATTEN: the whole tree as one object with world vertices and faces, and its OBJ form.

use std::fmt::Write as _;
use std::ops::Range;

use crate::geom::P3;

use super::cleanup::merge_duplicate_vertices;
use super::Scene;

/// A flattened scene: one vertex list (no duplicates) and all faces in global face order,
/// grouped by object path.
#[derive(Debug, Clone, PartialEq)]
pub struct FlatMesh {
    /// World vertices, unique, in order of first occurrence.
    pub vertices: Vec<P3>,
    /// Faces in global face order, indexing `vertices`.
    pub faces: Vec<Vec<u32>>,
    /// Object path and face range of each leaf, in order.
    pub groups: Vec<(String, Range<usize>)>,
}

/// Flattens `scene` in the paper's four steps: (1) recurse into subobjects, (2) number the
/// vertices uniquely throughout, (3) append the vertex lists and combine the face sets,
/// (4) sort the vertex list to find duplicates, combine and renumber them.
pub fn flatten(scene: &Scene) -> FlatMesh {
    let mut vertices = Vec::new();
    let mut faces = Vec::with_capacity(scene.face_count());
    let mut groups = Vec::new();
    for leaf in scene.leaves() {
        // Steps 1-3: every leaf's vertices get numbers offset past those before them.
        let offset = vertices.len() as u32;
        vertices.extend(
            leaf.mesh
                .vertices
                .iter()
                .map(|v| leaf.transform.transform_point(v)),
        );
        let start = faces.len();
        let mirrors = leaf.mirrors();
        for f in &leaf.mesh.faces {
            let mut idx: Vec<u32> = f.vertices.iter().map(|&k| k + offset).collect();
            if mirrors {
                idx.reverse();
            }
            faces.push(idx);
        }
        groups.push((leaf.path, start..faces.len()));
    }
    // Step 4: sort to find duplicates, combine, renumber, update the faces.
    let (vertices, remap) = merge_duplicate_vertices(&vertices);
    for f in &mut faces {
        for k in f.iter_mut() {
            *k = remap[*k as usize];
        }
    }
    FlatMesh {
        vertices,
        faces,
        groups,
    }
}

impl FlatMesh {
    /// The OBJ text: `v` lines with shortest round-trip f64 numbers, then one `o` group per
    /// object path with its faces (1-based indices).
    pub fn to_obj(&self) -> String {
        let mut s = String::with_capacity(self.vertices.len() * 40 + self.faces.len() * 24);
        s.push_str("# kepler flatten: world coordinates, faces in global face order\n");
        for v in &self.vertices {
            let _ = writeln!(s, "v {} {} {}", num(v.x), num(v.y), num(v.z));
        }
        for (path, range) in &self.groups {
            let _ = writeln!(s, "o {}", if path.is_empty() { "scene" } else { path });
            for f in &self.faces[range.clone()] {
                s.push('f');
                for k in f {
                    let _ = write!(s, " {}", k + 1);
                }
                s.push('\n');
            }
        }
        s
    }
}

/// Shortest round-trip decimal form of `x` (exponent form for very small or large
/// magnitudes, no trailing `.0` on integers), with -0 written as 0.
pub fn num(x: f64) -> String {
    let mut s = String::new();
    write_num(&mut s, x);
    s
}

/// [`num`] appended to `s` (no allocation of its own: the JSON writer's hot path).
pub fn write_num(s: &mut String, x: f64) {
    use std::fmt::Write as _;
    // Writing to a String cannot fail.
    let _ = if x == 0.0 {
        s.write_str("0")
    } else if x == x.trunc() && x.abs() < 1e15 {
        write!(s, "{x}")
    } else {
        write!(s, "{x:?}")
    };
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use super::*;
    use crate::geom::M4;
    use crate::scene::{Face, Mesh, Object, Scene};

    fn square() -> Mesh {
        Mesh {
            vertices: vec![
                P3::new(0., 0., 0.),
                P3::new(1., 0., 0.),
                P3::new(1., 1., 0.),
                P3::new(0., 1., 0.),
            ],
            faces: vec![Face::new(vec![0, 1, 2, 3])],
            closed: false,
            solidity: None,
            caps: Vec::new(),
            proven: None,
        }
    }

    #[test]
    fn shared_corners_are_merged_and_order_kept() {
        let proto = Arc::new(Object::from_mesh("sq", square()));
        let shift = nalgebra::Translation3::new(1., 0., 0.).to_homogeneous();
        let root = Object::group(
            "",
            vec![
                Object::instance("a", proto.clone(), M4::identity()),
                Object::instance("b", proto, shift),
            ],
        );
        let flat = flatten(&Scene::new(root, "t".into()));
        assert_eq!(
            flat.vertices.len(),
            6,
            "two squares sharing an edge have 6 distinct corners"
        );
        assert_eq!(flat.faces, vec![vec![0, 1, 2, 3], vec![1, 4, 5, 2]]);
        assert_eq!(
            flat.groups,
            vec![("a".to_string(), 0..1), ("b".to_string(), 1..2)]
        );
        let obj = flat.to_obj();
        assert!(obj.contains("o a\nf 1 2 3 4\no b\nf 2 5 6 3\n"), "{obj}");
    }

    #[test]
    fn mirrored_instances_keep_outward_winding() {
        let proto = Arc::new(Object::from_mesh("sq", square()));
        let mirror = M4::new_nonuniform_scaling(&crate::geom::V3::new(1., 1., -1.));
        let root = Object::group("", vec![Object::instance("m", proto, mirror)]);
        let flat = flatten(&Scene::new(root, "t".into()));
        assert_eq!(flat.faces[0], vec![3, 2, 1, 0]);
    }
}
