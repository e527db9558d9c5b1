//! The component tree C(T) (paper 002 sections 3 and 4.2): the parts of the coarsest
//! simplified model divide the faces into components; each component is divided again into
//! sub-components by the parts of the next finer model, looking only at the elements its own
//! faces simplify to; and so on down the levels.

use rayon::prelude::*;

use crate::geom::Box3;
use crate::scene::Mesh;

use super::binary::area;
use super::fcs::{cell_order, cluster, grades};
use super::parts::face_parts;
use super::widths::cell_widths;
pub(crate) use crate::scene::object_tree::{Component, ComponentTree};

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
        // The simplified models are independent of each other: made in parallel.
        let reps: Vec<Vec<u32>> = t
            .widths
            .par_iter()
            .map(|&w| cluster(&mesh.vertices, &order, w))
            .collect();
        for (level, rep) in (1..=t.widths.len()).zip(reps) {
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
                let groups = absorb_small(groups, mesh);
                if groups.len() <= 1 {
                    next.push(c);
                    continue;
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

/// Least faces of a component, absolute and as a share of the component it divides.
pub(crate) const MIN_FACES: usize = 16;
/// Least share of the divided component's faces.
pub(crate) const MIN_SHARE: f64 = 0.02;

/// The parts of a component with the small ones (under [`MIN_FACES`] faces or [`MIN_SHARE`]
/// of the component) each given to the large part whose CBOX it grows least: a few faces
/// scattered over the surface (a point part of a vertex where parts meet) would otherwise
/// become a node whose box prunes nothing. The paper stops short of single polygons too.
/// One group or none left means the component is not divided.
fn absorb_small(groups: Vec<Vec<u32>>, mesh: &Mesh) -> Vec<Vec<u32>> {
    let total: usize = groups.iter().map(Vec::len).sum();
    let least = MIN_FACES.max((MIN_SHARE * total as f64).ceil() as usize);
    let cbox = |faces: &[u32]| {
        Box3::from_points(
            faces
                .iter()
                .flat_map(|&f| &mesh.faces[f as usize].vertices)
                .map(|&v| &mesh.vertices[v as usize]),
        )
    };
    let (mut large, small): (Vec<Vec<u32>>, Vec<Vec<u32>>) =
        groups.into_iter().partition(|g| g.len() >= least);
    if large.len() <= 1 {
        return Vec::new();
    }
    let mut boxes: Vec<Box3> = large.iter().map(|g| cbox(g)).collect();
    for g in small {
        let b = cbox(&g);
        // Growth of volume, then of area (flat parts have no volume).
        let grow = |k: usize| {
            let u = boxes[k].union(&b);
            (u.volume() - boxes[k].volume(), area(&u) - area(&boxes[k]))
        };
        let k = (0..large.len())
            .min_by(|&x, &y| {
                let (a, b) = (grow(x), grow(y));
                a.0.total_cmp(&b.0)
                    .then(a.1.total_cmp(&b.1))
                    .then(x.cmp(&y))
            })
            .unwrap_or(0);
        boxes[k] = boxes[k].union(&b);
        large[k].extend(g);
    }
    for g in &mut large {
        g.sort_unstable();
    }
    large
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two flat 4 × 4 grids of unit squares (32 triangles each), 100 apart.
    fn two_islands() -> Mesh {
        super::super::bvtree::grids(&[(0.0, 0.0, 4), (100.0, 0.0, 4)], 0.0)
    }

    #[test]
    fn separate_islands_become_components_and_partition_the_faces() {
        let m = two_islands();
        // Width 20: each island is within one ball around its first corner and collapses to
        // a point: two points of no triangle, two parts (C1).
        let t = ComponentTree::with_widths(&m, vec![20.0, 0.5]);
        assert_eq!(t.per_level, vec![2, 0]);
        assert_eq!(t.clusters, vec![2, 50]);
        assert_eq!(t.nodes[0].children, vec![1, 2]);
        assert_eq!(t.nodes[1].faces, (0..32).collect::<Vec<u32>>());
        assert_eq!(t.nodes[2].faces, (32..64).collect::<Vec<u32>>());
        // At width 0.5 every vertex is its own cluster: each island stays one part.
        assert_eq!(t.leaves(), vec![1, 2]);
        let fc = t.face_component(64);
        assert!(fc[..32].iter().all(|&c| c == 0) && fc[32..].iter().all(|&c| c == 1));
    }

    #[test]
    fn small_parts_join_the_large_part_they_grow_least() {
        let m = two_islands();
        let big: Vec<u32> = (0..32).collect();
        let other: Vec<u32> = (32..60).collect();
        // Two faces of the far island alone are too small a part: they join that island's
        // large part, whose box they do not grow.
        let g = absorb_small(vec![big.clone(), other.clone(), vec![60, 61]], &m);
        assert_eq!(g.len(), 2);
        assert_eq!(g[1], (32..62).collect::<Vec<u32>>());
        // A single large part: no division.
        assert!(absorb_small(vec![big, vec![62, 63]], &m).is_empty());
    }
}
