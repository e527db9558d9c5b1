//! The object tree of one flat mesh (paper 002, Tan, Chong and Low): a bounding-volume
//! hierarchy B(T) of a mesh's faces built from its simplified versions, once, in the mesh's
//! own frame, so that every view, every placement of a prototype and every interference
//! query walks the same tree.
//!
//! [`HierarchyKind::Median`] is the baseline: the median split alone over all the faces.
//! The tree's data types live in [`crate::scene::object_tree`]; its construction here.

use std::time::Instant;

use crate::scene::Mesh;

pub use super::binary::TopDown;
use super::binary::{Arena, Build};
pub(crate) use super::components::ComponentTree;
pub(crate) use crate::scene::object_tree::{BuildTimes, HierarchyKind, ObjectTree, TreeNode};

impl ObjectTree {
    /// The tree of `kind` over the faces of `mesh`: below the leaf components of the
    /// simplify tree the area split, the median split for the median tree.
    pub fn build(mesh: &Mesh, kind: HierarchyKind) -> ObjectTree {
        let below = match kind {
            HierarchyKind::Simplify => TopDown::Area,
            HierarchyKind::Median => TopDown::Median,
        };
        Self::build_with(mesh, kind, below)
    }

    /// The tree of `kind` with the top-down split `below` under its leaf components (all of
    /// the tree for the median kind): for measuring what each part brings.
    pub fn build_with(mesh: &Mesh, kind: HierarchyKind, below: TopDown) -> ObjectTree {
        let mut arena = Arena::new(mesh);
        let mut times = BuildTimes::default();
        let (components, root) = match kind {
            HierarchyKind::Simplify => {
                let t = Instant::now();
                let c = ComponentTree::build(mesh);
                times.components = t.elapsed();
                let t = Instant::now();
                let root = upper(&mut arena, &c, 0);
                times.bottom_up = t.elapsed();
                (c, root)
            }
            HierarchyKind::Median => {
                let all = (0..mesh.faces.len() as u32).collect();
                (ComponentTree::default(), arena.leaf(all, false))
            }
        };
        let t = Instant::now();
        arena.split_leaves(root, below);
        let mut tree = ObjectTree {
            kind,
            nodes: Vec::with_capacity(arena.nodes.len()),
            faces: Vec::with_capacity(mesh.faces.len()),
            components,
            times,
        };
        tree.flatten(&arena, root);
        tree.times.top_down = t.elapsed();
        tree
    }

    /// Copies the arena's subtree at `n` in depth-first order; returns its index.
    fn flatten(&mut self, arena: &Arena, n: usize) -> u32 {
        let id = self.nodes.len() as u32;
        let a = &arena.nodes[n];
        let start = self.faces.len() as u32;
        self.nodes.push(TreeNode {
            cbox: a.cbox,
            faces: start..start,
            children: None,
            component: a.component,
            inbox: None,
        });
        match &a.build {
            Build::Faces(f) => self.faces.extend(f),
            Build::Pair(l, r) => {
                let l = self.flatten(arena, *l);
                let r = self.flatten(arena, *r);
                self.nodes[id as usize].children = Some([l, r]);
            }
        }
        self.nodes[id as usize].faces.end = self.faces.len() as u32;
        id
    }
}

/// The upper BV-tree of C(T)'s node `c`: its children's subtrees merged bottom-up; a leaf
/// component becomes a pending leaf for the top-down split.
fn upper(arena: &mut Arena, c: &ComponentTree, k: u32) -> usize {
    let node = &c.nodes[k as usize];
    if node.children.is_empty() {
        return arena.leaf(node.faces.clone(), true);
    }
    let kids: Vec<usize> = node
        .children
        .iter()
        .map(|&ch| upper(arena, c, ch))
        .collect();
    arena.merge_bottom_up(&kids)
}

/// Grids of unit squares (2 triangles each) with corners at (x0, y0) and `n` squares a
/// side, at z = `bend` · i · j (0: flat), as one mesh: test data for the tree's modules.
#[cfg(test)]
pub(crate) fn grids(specs: &[(f64, f64, u32)], bend: f64) -> Mesh {
    use crate::geom::P3;
    use crate::scene::Face;
    let mut vertices = Vec::new();
    let mut faces = Vec::new();
    for &(x0, y0, n) in specs {
        let base = vertices.len() as u32;
        for j in 0..=n {
            for i in 0..=n {
                vertices.push(P3::new(x0 + i as f64, y0 + j as f64, bend * (i * j) as f64));
            }
        }
        let at = |i: u32, j: u32| base + j * (n + 1) + i;
        for j in 0..n {
            for i in 0..n {
                faces.push(Face::new(vec![at(i, j), at(i + 1, j), at(i + 1, j + 1)]));
                faces.push(Face::new(vec![at(i, j), at(i + 1, j + 1), at(i, j + 1)]));
            }
        }
    }
    Mesh {
        vertices,
        faces,
        closed: false,
        solidity: None,
        caps: Vec::new(),
        proven: None,
        pieces: None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::prepare::trees::binary;

    /// Two grids of `n` × `n` unit squares (gently curved) 50 apart, and a 3 × 3 island
    /// far from both.
    fn scene_mesh(n: u32) -> Mesh {
        grids(&[(0.0, 0.0, n), (50.0, 0.0, n), (25.0, 30.0, 3)], 0.1)
    }

    /// Every node's faces are its children's, its CBOX holds its faces, leaves hold at most
    /// LEAF_FACES, and the root holds every face once.
    fn check(tree: &ObjectTree, mesh: &Mesh) {
        let mut all = tree.faces.clone();
        all.sort_unstable();
        assert_eq!(all, (0..mesh.faces.len() as u32).collect::<Vec<_>>());
        assert_eq!(tree.nodes[0].faces, 0..mesh.faces.len() as u32);
        for (k, n) in tree.nodes.iter().enumerate() {
            for &f in tree.faces_of(k as u32) {
                for &v in &mesh.faces[f as usize].vertices {
                    assert!(n.cbox.contains(&mesh.vertices[v as usize]));
                }
            }
            match n.children {
                Some([l, r]) => {
                    let (l, r) = (&tree.nodes[l as usize], &tree.nodes[r as usize]);
                    assert_eq!((n.faces.start, l.faces.end), (l.faces.start, r.faces.start));
                    assert_eq!(r.faces.end, n.faces.end);
                    assert!(!l.faces.is_empty() && !r.faces.is_empty());
                }
                None => assert!(n.faces.len() <= binary::LEAF_FACES),
            }
        }
    }

    #[test]
    fn both_trees_partition_the_faces() {
        let m = scene_mesh(6);
        for kind in [HierarchyKind::Simplify, HierarchyKind::Median] {
            let t = ObjectTree::build(&m, kind);
            check(&t, &m);
            let s = t.shape();
            assert_eq!(s.nodes, 2 * s.leaves - 1);
        }
    }

    #[test]
    fn islands_are_components_at_the_top_of_the_simplify_tree() {
        let m = scene_mesh(6);
        let t = ObjectTree::build(&m, HierarchyKind::Simplify);
        // The two grids and the island are apart at the coarsest level.
        assert!(
            t.components.per_level[0] >= 3,
            "{:?}",
            t.components.per_level
        );
        // The smallest merged box first: the two grids merge (a box 56 x 6 x 3.6) before
        // either takes the island (a box 28 x 33 x 3.6), so the island is a child of the root.
        let [l, r] = t.nodes[0].children.unwrap();
        assert!(t.nodes[l as usize].component && t.nodes[r as usize].component);
        let sizes = [l, r].map(|c| t.nodes[c as usize].faces.len());
        assert!(sizes.contains(&144) && sizes.contains(&18), "{sizes:?}");
        // The median tree cuts the island's side at the median instead.
        let med = ObjectTree::build(&m, HierarchyKind::Median);
        assert!(med.components.nodes.is_empty());
        assert_eq!(med.shape().component_nodes, 0);
        let [l, r] = med.nodes[0].children.unwrap();
        let sizes = [l, r].map(|c| med.nodes[c as usize].faces.len());
        assert_eq!(sizes, [81, 81]);
    }
}
