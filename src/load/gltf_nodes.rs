//! glTF's node hierarchy checked (one parent at most, no cycles) and its transforms (a
//! `matrix`, or `translation`, `rotation`, `scale`) as matrices.

use super::gltf_json::J;
use crate::error::Result;
use crate::geom::{M4, V3};

/// The deepest node nesting read (the top nodes of a scene are depth 1), as deep as the
/// blocks of a scene file may nest.
pub(super) const MAX_NODE_DEPTH: usize = super::kdl::MAX_DEPTH;

/// The children of each node, checked: every child exists, no node is the child of two
/// nodes (or twice of one), and no node is its own ancestor.
pub(super) fn children(nodes: &[J]) -> Result<Vec<Vec<usize>>> {
    let mut parent: Vec<Option<usize>> = vec![None; nodes.len()];
    let mut out = Vec::with_capacity(nodes.len());
    for (i, n) in nodes.iter().enumerate() {
        let mut kids = Vec::new();
        for c in n.list("children")? {
            let k = c.index("nodes", nodes.len())?;
            if let Some(p) = parent[k] {
                return Err(c.err(format!(
                    "node {k} is already a child of node {p} (a node has one parent at most)"
                )));
            }
            if k == i {
                return Err(c.err(format!("node {k} is its own child (a cycle)")));
            }
            parent[k] = Some(i);
            kids.push(k);
        }
        out.push(kids);
    }
    check_acyclic(nodes, &parent)?;
    Ok(out)
}

/// An error at the `children` of a node on a cycle of parents.
fn check_acyclic(nodes: &[J], parent: &[Option<usize>]) -> Result<()> {
    // 0: not seen, 1: on the walk being made, 2: known to reach a root.
    let mut state = vec![0u8; nodes.len()];
    for start in 0..nodes.len() {
        let mut walk = Vec::new();
        let mut cur = Some(start);
        while let Some(c) = cur {
            match state[c] {
                2 => break,
                1 => {
                    let on = nodes[c].get("children").unwrap_or_else(|| nodes[c].clone());
                    return Err(on.err(format!(
                        "node {c} is its own ancestor (a cycle of children)"
                    )));
                }
                _ => {
                    state[c] = 1;
                    walk.push(c);
                    cur = parent[c];
                }
            }
        }
        for w in walk {
            state[w] = 2;
        }
    }
    Ok(())
}

/// The node's transform from its coordinates to its parent's.
pub(super) fn local_matrix(node: &J) -> Result<M4> {
    if let Some(m) = node.get("matrix") {
        let v = m.numbers(16)?;
        // Column-major, as glTF stores it.
        return Ok(M4::from_column_slice(&v));
    }
    let mut m = M4::identity();
    if let Some(t) = node.get("translation") {
        let v = t.numbers(3)?;
        m *= M4::new_translation(&V3::new(v[0], v[1], v[2]));
    }
    if let Some(r) = node.get("rotation") {
        let q = r.numbers(4)?;
        let quat = nalgebra::Quaternion::new(q[3], q[0], q[1], q[2]);
        let norm = quat.norm();
        if norm.is_nan() || norm <= 1e-6 {
            return Err(r.err("the rotation quaternion is zero"));
        }
        let unit = nalgebra::UnitQuaternion::from_quaternion(quat);
        m *= unit.to_homogeneous();
    }
    if let Some(s) = node.get("scale") {
        let v = s.numbers(3)?;
        m *= M4::new_nonuniform_scaling(&V3::new(v[0], v[1], v[2]));
    }
    Ok(m)
}

/// An error at `node` unless `world` is an invertible affine transform.
pub(super) fn check_affine(node: &J, world: &M4) -> Result<()> {
    let row = world.row(3);
    let affine = row[0] == 0.0 && row[1] == 0.0 && row[2] == 0.0 && row[3] == 1.0;
    if !affine {
        return Err(node.err("the transform is not affine (its last row is not 0 0 0 1)"));
    }
    let det = world.fixed_view::<3, 3>(0, 0).determinant();
    if !(det.is_finite() && det != 0.0) {
        return Err(node.err("the transform is singular (or not finite): it flattens the geometry"));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use super::*;
    use crate::geom::P3;

    fn doc(text: &str) -> serde_json::Value {
        serde_json::from_str(text).unwrap()
    }

    #[test]
    fn two_parents_and_cycles_are_refused() {
        let f = Path::new("t.gltf");
        let v = doc(r#"{"nodes":[{"children":[1,2]},{"children":[2]},{}]}"#);
        let nodes = J::top(&v, f).list("nodes").unwrap();
        let e = children(&nodes).unwrap_err().to_string();
        assert_eq!(
            e,
            "t.gltf: nodes[1].children[0]: node 2 is already a child of node 0 (a node has one parent at most)"
        );
        let v = doc(r#"{"nodes":[{"children":[1]},{"children":[2]},{"children":[0]}]}"#);
        let nodes = J::top(&v, f).list("nodes").unwrap();
        let e = children(&nodes).unwrap_err().to_string();
        assert!(e.contains("is its own ancestor"), "{e}");
        let v = doc(r#"{"nodes":[{"children":[1]},{"children":[2]},{}]}"#);
        let nodes = J::top(&v, f).list("nodes").unwrap();
        assert_eq!(children(&nodes).unwrap(), vec![vec![1], vec![2], vec![]]);
    }

    #[test]
    fn trs_is_translation_rotation_scale_in_that_order() {
        let f = Path::new("t.gltf");
        // A quarter turn about z (x -> y), scale 2, then translate by (10, 0, 0).
        let h = std::f64::consts::FRAC_1_SQRT_2;
        let text =
            format!(r#"{{"translation":[10,0,0],"rotation":[0,0,{h},{h}],"scale":[2,2,2]}}"#);
        let v = doc(&text);
        let m = local_matrix(&J::top(&v, f)).unwrap();
        let p = m.transform_point(&P3::new(1., 0., 0.));
        assert!((p - P3::new(10., 2., 0.)).norm() < 1e-12, "{p}");
        let v = doc(r#"{"matrix":[1,0,0,0, 0,1,0,0, 0,0,1,0, 5,6,7,1]}"#);
        let m = local_matrix(&J::top(&v, f)).unwrap();
        assert_eq!(m.transform_point(&P3::origin()), P3::new(5., 6., 7.));
        let v = doc(r#"{"scale":[1,0,1]}"#);
        let m = local_matrix(&J::top(&v, f)).unwrap();
        assert!(check_affine(&J::top(&v, f), &m).is_err());
    }
}
