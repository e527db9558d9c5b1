//! Interference of objects: the pairs whose triboxes meet (the 18-comparison test), and of
//! those the pairs whose faces really intersect, decided exactly with `robust::orient3d`.
//!
//! Faces are closed sets: objects that touch (a shared vertex, an edge on a face) intersect.

use std::collections::HashMap;
use std::sync::Arc;

pub(crate) use crate::geom::tri_intersect::triangles_intersect;
use crate::geom::{P3, V3};
use crate::prepare::trees::bvtree::{HierarchyKind, ObjectTree};
use crate::prepare::trees::leaf_trees;
use crate::scene::{Leaf, Mesh, Scene};

use super::bounds::Tribox;
use super::collide::{collide, CollideStats, FaceTriangles, Placed};

/// The answer for one scene.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Interference {
    /// Object paths (the leaves, instances expanded), in global face order.
    pub objects: Vec<String>,
    /// Pairs of objects in all.
    pub pairs: usize,
    /// Pairs whose CBOXes meet (for comparison).
    pub cbox_meet: usize,
    /// Pairs whose triboxes meet, each with whether their faces intersect.
    pub tribox_meet: Vec<(usize, usize, bool)>,
    /// Exact triangle-triangle tests made.
    pub triangle_tests: u64,
    /// Pairs of tree nodes whose bounding volumes were tested (tree walks only).
    pub bv_tests: u64,
}

/// How the faces of two objects whose triboxes meet are compared.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Method {
    /// No tree: the triangles of each near the other's tribox, swept along x (every pair of
    /// leaf triangles that could meet).
    Brute,
    /// Walk the two objects' trees of this kind at once ([`collide`]).
    Tree(HierarchyKind),
}

/// A world triangle of an object with its tribox.
struct Tri {
    p: [P3; 3],
    t: Tribox,
}

#[cfg(test)]
/// Interference of every pair of leaf objects of `scene`, without trees.
pub(crate) fn interfere(scene: &Scene) -> Interference {
    interfere_with(scene, Method::Brute)
}

/// Interference of every pair of leaf objects of `scene`, faces compared by `method`. The
/// answers are the same whatever the method: both test the same triangles exactly.
pub(crate) fn interfere_with(scene: &Scene, method: Method) -> Interference {
    let leaves = scene.leaves();
    let trees = object_trees(scene, &leaves, method);
    let mut triangles: HashMap<usize, FaceTriangles> = HashMap::new();
    for l in &leaves {
        triangles
            .entry(l.mesh as *const Mesh as usize)
            .or_insert_with(|| FaceTriangles::of(l.mesh));
    }
    let tri_of = |l: &Leaf| &triangles[&(l.mesh as *const Mesh as usize)];
    let tris: Vec<Vec<Tri>> = leaves
        .iter()
        .map(|l| {
            tri_of(l)
                .tris
                .iter()
                .map(|t| t.map(|v| l.world_vertex(v)))
                .filter(|p| (p[1] - p[0]).cross(&(p[2] - p[0])) != V3::zeros())
                .map(|p| Tri {
                    p,
                    t: Tribox::from_points(p.iter()),
                })
                .collect()
        })
        .collect();
    let boxes: Vec<Tribox> = tris
        .iter()
        .map(|ts| ts.iter().fold(Tribox::empty(), |a, t| a.merge(&t.t)))
        .collect();
    let mut r = Interference {
        objects: leaves.iter().map(|l| l.path.clone()).collect(),
        ..Interference::default()
    };
    let placed = |k: usize| {
        trees.get(k).map(|t| Placed {
            mesh: leaves[k].mesh,
            tree: t,
            tris: tri_of(&leaves[k]),
            transform: leaves[k].transform,
        })
    };
    for i in 0..leaves.len() {
        for j in i + 1..leaves.len() {
            r.pairs += 1;
            let (a, b) = (&boxes[i], &boxes[j]);
            if (0..3).all(|k| a.lo[k] <= b.hi[k] && b.lo[k] <= a.hi[k]) {
                r.cbox_meet += 1;
            }
            if a.interferes(b) {
                let hit = match (placed(i), placed(j)) {
                    (Some(pa), Some(pb)) => {
                        let mut s = CollideStats::default();
                        let hit = collide(&pa, &pb, &mut s);
                        r.bv_tests += s.bv_tests;
                        r.triangle_tests += s.triangle_tests;
                        hit
                    }
                    _ => faces_intersect(&tris[i], &tris[j], a, b, &mut r.triangle_tests),
                };
                r.tribox_meet.push((i, j, hit));
            }
        }
    }
    r
}

/// The object tree of every leaf for a tree method (the prepared one when it is of the
/// kind asked for, else one built here once per mesh); empty for [`Method::Brute`].
fn object_trees(scene: &Scene, leaves: &[Leaf], method: Method) -> Vec<Arc<ObjectTree>> {
    let Method::Tree(kind) = method else {
        return Vec::new();
    };
    let mut by_mesh: HashMap<usize, Arc<ObjectTree>> = HashMap::new();
    leaves
        .iter()
        .zip(leaf_trees(scene))
        .map(|(l, t)| match t.filter(|t| t.kind == kind) {
            Some(t) => t,
            None => by_mesh
                .entry(l.mesh as *const Mesh as usize)
                .or_insert_with(|| Arc::new(ObjectTree::build(l.mesh, kind)))
                .clone(),
        })
        .collect()
}

/// True when some triangle of `a` meets some triangle of `b`.
fn faces_intersect(a: &[Tri], b: &[Tri], ta: &Tribox, tb: &Tribox, tests: &mut u64) -> bool {
    // Only triangles meeting the other object's tribox can meet its triangles.
    let near = |ts: &[Tri], other: &Tribox| -> Vec<usize> {
        let mut v: Vec<usize> = (0..ts.len())
            .filter(|&i| ts[i].t.interferes(other))
            .collect();
        v.sort_by(|&x, &y| ts[x].t.lo[0].total_cmp(&ts[y].t.lo[0]));
        v
    };
    let (na, nb) = (near(a, tb), near(b, ta));
    // Sweep along x over both sorted lists.
    let mut start = 0;
    for &i in &na {
        let ti = &a[i];
        while start < nb.len() && b[nb[start]].t.hi[0] < ti.t.lo[0] {
            start += 1;
        }
        for &j in &nb[start..] {
            let tj = &b[j];
            if tj.t.lo[0] > ti.t.hi[0] {
                break;
            }
            if ti.t.interferes(&tj.t) {
                *tests += 1;
                if triangles_intersect(&ti.p, &tj.p) {
                    return true;
                }
            }
        }
    }
    false
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(x: f64, y: f64, z: f64) -> P3 {
        P3::new(x, y, z)
    }

    #[test]
    fn crossing_touching_and_apart_triangles() {
        let t = [p(0., 0., 0.), p(2., 0., 0.), p(0., 2., 0.)];
        // Pierces t.
        assert!(triangles_intersect(
            &t,
            &[p(0.5, 0.5, -1.), p(0.5, 0.5, 1.), p(3., 3., 0.5)]
        ));
        // Above t.
        assert!(!triangles_intersect(
            &t,
            &[p(0.5, 0.5, 1.), p(0.6, 0.5, 1.), p(0.5, 0.6, 2.)]
        ));
        // Touches t at a vertex on its edge.
        assert!(triangles_intersect(
            &t,
            &[p(1., 0., 0.), p(1., -1., 1.), p(1., -1., -1.)]
        ));
        // Coplanar, overlapping and apart.
        assert!(triangles_intersect(
            &t,
            &[p(0.5, 0.5, 0.), p(5., 0.5, 0.), p(0.5, 5., 0.)]
        ));
        assert!(!triangles_intersect(
            &t,
            &[p(3., 3., 0.), p(5., 3., 0.), p(3., 5., 0.)]
        ));
        // Its plane crosses t's plane beside t.
        assert!(!triangles_intersect(
            &t,
            &[p(3., 0., -1.), p(3., 0., 1.), p(3., 3., 0.)]
        ));
    }
}
