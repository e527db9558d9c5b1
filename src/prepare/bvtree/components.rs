//! The component tree C(T) (paper 002 sections 3 and 4.2): the parts of the coarsest
//! simplified model divide the faces into components; each component is divided again into
//! sub-components by the parts of the next finer model, looking only at the elements its own
//! faces simplify to; and so on down the levels.

use crate::scene::Mesh;

use super::fcs::{cell_order, cluster, grades};
use super::parts::face_parts;
use super::widths::cell_widths;

/// A node of C(T): a component (a set of the original faces).
#[derive(Debug, Clone, PartialEq)]
pub struct Component {
    /// Level of the simplified model that made it (0: the whole mesh, 1: the coarsest model).
    pub level: usize,
    /// Its faces (local face indices, ascending).
    pub faces: Vec<u32>,
    /// Its sub-components (indices into [`ComponentTree::nodes`]); empty for a leaf.
    pub children: Vec<u32>,
}

/// C(T) with the simplified models that made it.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ComponentTree {
    /// Cell width of each simplified model, coarsest first.
    pub widths: Vec<f64>,
    /// Vertices left in each simplified model (clusters).
    pub clusters: Vec<usize>,
    /// Components made from each simplified model (new nodes of that level).
    pub per_level: Vec<usize>,
    /// The nodes; the root (all faces) is node 0.
    pub nodes: Vec<Component>,
}

impl ComponentTree {
    /// C(T) of a mesh from its simplified models at the widths of its edge lengths.
    pub fn build(mesh: &Mesh) -> ComponentTree {
        Self::with_widths(mesh, cell_widths(mesh))
    }

    /// C(T) from simplified models of the given cell widths, coarsest first.
    pub fn with_widths(mesh: &Mesh, widths: Vec<f64>) -> ComponentTree {
        let order = cell_order(&grades(mesh));
        let mut t = ComponentTree {
            widths,
            clusters: Vec::new(),
            per_level: Vec::new(),
            nodes: vec![Component {
                level: 0,
                faces: (0..mesh.faces.len() as u32).collect(),
                children: Vec::new(),
            }],
        };
        let mut leaves = vec![0u32];
        for level in 1..=t.widths.len() {
            let rep = cluster(&mesh.vertices, &order, t.widths[level - 1]);
            let mut reps: Vec<u32> = rep.clone();
            reps.sort_unstable();
            reps.dedup();
            t.clusters.push(reps.len());
            let mut next = Vec::new();
            let mut made = 0;
            for &c in &leaves {
                let parts = face_parts(&t.nodes[c as usize].faces, mesh, &rep);
                let count = parts.iter().max().map_or(0, |&p| p as usize + 1);
                if count <= 1 {
                    next.push(c);
                    continue;
                }
                let mut groups: Vec<Vec<u32>> = vec![Vec::new(); count];
                for (&f, &p) in t.nodes[c as usize].faces.iter().zip(&parts) {
                    groups[p as usize].push(f);
                }
                for faces in groups {
                    let id = t.nodes.len() as u32;
                    t.nodes.push(Component {
                        level,
                        faces,
                        children: Vec::new(),
                    });
                    t.nodes[c as usize].children.push(id);
                    next.push(id);
                    made += 1;
                }
            }
            t.per_level.push(made);
            leaves = next;
        }
        t
    }

    /// The leaf components, in tree order.
    pub fn leaves(&self) -> Vec<u32> {
        let mut out = Vec::new();
        let mut stack = vec![0u32];
        while let Some(c) = stack.pop() {
            let ch = &self.nodes[c as usize].children;
            if ch.is_empty() {
                out.push(c);
            } else {
                stack.extend(ch.iter().rev());
            }
        }
        out
    }

    /// The leaf component of every face (an index into [`ComponentTree::leaves`]).
    pub fn face_component(&self, faces: usize) -> Vec<u32> {
        let mut out = vec![0u32; faces];
        for (k, &c) in self.leaves().iter().enumerate() {
            for &f in &self.nodes[c as usize].faces {
                out[f as usize] = k as u32;
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::P3;
    use crate::scene::Face;

    /// Two squares of 2 triangles each, far apart, and a long thin strip joining nothing.
    fn two_islands() -> Mesh {
        let mut vertices = Vec::new();
        let mut faces = Vec::new();
        for x0 in [0.0, 100.0] {
            let k = vertices.len() as u32;
            vertices.extend([
                P3::new(x0, 0., 0.),
                P3::new(x0 + 1., 0., 0.),
                P3::new(x0 + 1., 1., 0.),
                P3::new(x0, 1., 0.),
            ]);
            faces.push(Face::new(vec![k, k + 1, k + 2]));
            faces.push(Face::new(vec![k, k + 2, k + 3]));
        }
        Mesh {
            vertices,
            faces,
            closed: false,
        }
    }

    #[test]
    fn separate_islands_become_components_and_partition_the_faces() {
        let m = two_islands();
        // Width 5: each island collapses to a point; two points of no triangle: two parts (C1).
        let t = ComponentTree::with_widths(&m, vec![5.0, 0.5]);
        assert_eq!(t.per_level, vec![2, 0]);
        assert_eq!(t.clusters, vec![2, 8]);
        assert_eq!(t.nodes[0].children, vec![1, 2]);
        assert_eq!(t.nodes[1].faces, vec![0, 1]);
        assert_eq!(t.nodes[2].faces, vec![2, 3]);
        // At width 0.5 each island is two triangles sharing a side: one part, no split.
        assert_eq!(t.leaves(), vec![1, 2]);
        assert_eq!(t.face_component(4), vec![0, 0, 1, 1]);
    }
}
