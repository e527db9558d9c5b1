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
pub(crate) fn flatten(scene: &Scene) -> FlatMesh {
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
            // A name with a newline would start lines of its own: written escaped.
            let name = if path.is_empty() { "scene" } else { path };
            let _ = writeln!(s, "o {}", super::names::printable(name));
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
pub(crate) fn num(x: f64) -> String {
    let mut s = String::new();
    write_num(&mut s, x);
    s
}

/// [`num`] appended to `s` (no allocation of its own: the JSON writer's hot path).
pub(crate) fn write_num(s: &mut String, x: f64) {
    use std::fmt::Write as _;
    // Writing to a String cannot fail.
    let _ = if x == 0.0 {
        s.write_str("0")
    } else if x == x.trunc() && x.abs() < 1e15 {
        write!(s, "{x}")
    } else if (ZMIJ_FROM..ZMIJ_BELOW).contains(&x.abs()) {
        let mut buffer = zmij::Buffer::new();
        let digits = buffer.format_finite(x);
        if may_tie(x, digits) {
            write!(s, "{x:?}")
        } else {
            s.write_str(digits)
        }
    } else {
        write!(s, "{x:?}")
    };
}

/// True when zmij's shortest `digits` of `x` may differ from Rust's `{:?}`. In the range
/// both write plain decimals (Rust's `{:?}` from 1e-4 up, zmij up to 1e15, where zmij is
/// three times as fast), both write the shortest digits that read back to `x`, the nearest
/// to `x` among them, unless two are equally near: the one case they may break differently
/// (found: 999999999999782.25). That tie needs `x` halfway between two numbers of k
/// decimals, an odd multiple of 2^-(k+1).
fn may_tie(x: f64, digits: &str) -> bool {
    let decimals = digits.find('.').map_or(0, |i| digits.len() - i - 1) as i32;
    // Scaling by a power of two is exact here (|x| from 1e-4 to 1e15, a few dozen decimals),
    // and so is halving. Not `scaled % 2.0`: the compiler evaluates it before the first test
    // fails, and the remainder is a slow library call (43% of nefertiti's JSON time).
    let scaled = x * 2f64.powi(decimals + 1);
    scaled.fract() == 0.0 && (scaled * 0.5).fract() != 0.0
}

/// The least magnitude [`write_num`] writes through zmij (below, Rust's `{:?}` has an exponent).
const ZMIJ_FROM: f64 = 1e-4;

/// The magnitude from which [`write_num`] leaves zmij (from there, it has an exponent).
const ZMIJ_BELOW: f64 = 1e15;

impl Scene {
    /// The paper's FLATTEN: the whole tree as one mesh in world coordinates, one group per
    /// leaf object, faces in global face order ([`FlatMesh::to_obj`] writes it as OBJ).
    pub fn flatten(&self) -> FlatMesh {
        flatten(self)
    }
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
            pieces: None,
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

    #[test]
    fn numbers_are_rusts_debug_digits() {
        // Random bits across the magnitudes zmij writes and around its bounds, and the bounds.
        let mut rng = crate::geom::rng::XorShift::new(11);
        let mut seen = 0;
        for k in 0..200_000 {
            let x = match k % 4 {
                0 => f64::from_bits(rng.next_u64()),
                1 => (rng.unit() - 0.5) * 10f64.powi((k % 40) - 20),
                2 => ZMIJ_FROM * (1.0 + (rng.unit() - 0.5) * 1e-12),
                _ => ZMIJ_BELOW * (1.0 + (rng.unit() - 0.5) * 1e-12),
            };
            if !x.is_finite() {
                continue;
            }
            let want = if x == 0.0 {
                "0".to_string()
            } else if x == x.trunc() && x.abs() < 1e15 {
                format!("{x}")
            } else {
                format!("{x:?}")
            };
            seen += usize::from((ZMIJ_FROM..ZMIJ_BELOW).contains(&x.abs()));
            assert_eq!(num(x), want, "{:#x}", x.to_bits());
        }
        assert!(seen > 50_000, "{seen}");
        // Odd multiples of powers of two: where shortest digits can tie.
        for j in 1..70 {
            for _ in 0..300 {
                let odd = (rng.next_u64() >> (11 + rng.below(50))) | 1;
                let x = odd as f64 * 2f64.powi(-j);
                if x.is_finite() && x != x.trunc() {
                    assert_eq!(num(x), format!("{x:?}"), "{:#x}", x.to_bits());
                }
            }
        }
        for x in [
            ZMIJ_FROM,
            -ZMIJ_FROM,
            0.1,
            0.3,
            2.0 / 3.0,
            123.456,
            1e15 - 0.5,
        ] {
            assert_eq!(num(x), format!("{x:?}"));
        }
    }
}
