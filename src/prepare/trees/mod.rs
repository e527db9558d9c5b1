//! Object trees for the flat meshes of a scene (paper 002): every leaf mesh large enough to
//! need one gets its B(T) once, in its own frame (a prototype's once for all its
//! placements), and, when the scene has inboxes at all, an INBOX per large component of a
//! closed mesh: the subobjects Franklin's pruning needs, which a flat mesh lacks.
//!
//! - [`bvtree`]: B(T) of one mesh, built from its simplified versions.
//! - [`fcs`]: floating-cell simplification of the vertices (section 4.1).
//! - [`widths`]: cell widths from the edge-length distribution (section 5).
//! - [`parts`]: parts of a simplified model, steps A1-A4, B1-B2, C1 (section 4.2).
//! - [`components`]: the component tree C(T) (sections 3, 4.2).
//! - [`binary`]: C(T) to a binary tree bottom-up, top-down below the leaf components (4.3).

pub(crate) mod binary;
pub(crate) mod bvtree;
pub(crate) mod components;
pub(crate) mod fcs;
pub(crate) mod parts;
pub(crate) mod widths;

use std::collections::{HashMap, HashSet};
use std::sync::Arc;

use crate::count::Count;
use crate::geom::{Box3, P3};
use crate::scene::{Content, Mesh, Object};

use self::bvtree::{HierarchyKind, ObjectTree};
use crate::prepare::inbox::grow::grown_inbox_in;
use crate::prepare::inbox::solid::Triangles;

/// Meshes with fewer faces keep the view's median split (a tree would cost more than it saves).
pub(crate) const MIN_FACES: usize = 256;
/// Components with fewer faces than this (and than [`INBOX_SHARE`] of the mesh) get no INBOX.
pub(crate) const INBOX_MIN_FACES: usize = 64;
/// Least share of the mesh's faces for a component to get an INBOX.
pub(crate) const INBOX_SHARE: f64 = 1.0 / 64.0;

/// Attaches a tree of `kind` to every leaf mesh of at least [`MIN_FACES`] faces that has none
/// (with `shared_only`, only to meshes of prototypes placed more than once); with `inboxes`,
/// closed meshes' large components get inboxes too.
///
/// The faces of each mesh go to `done` as its tree is built.
pub(crate) fn attach_trees(
    root: &mut Object,
    kind: HierarchyKind,
    inboxes: bool,
    shared_only: bool,
    done: Count,
) {
    attach_of(root, kind, inboxes, shared_only, done).attach(root, false);
}

/// The faces of the meshes [`attach_trees`] gives a tree (a shared prototype's once): the
/// total of its count.
pub(crate) fn planned_faces(root: &Object, shared_only: bool) -> usize {
    let w = attach_of(
        root,
        HierarchyKind::Simplify,
        false,
        shared_only,
        Count::NONE,
    );
    w.planned(root, false, &mut HashSet::new())
}

/// The walk that attaches trees below `root`.
fn attach_of<'p>(
    root: &Object,
    kind: HierarchyKind,
    inboxes: bool,
    shared_only: bool,
    done: Count<'p>,
) -> Attach<'p> {
    let mut placements = HashMap::new();
    count_placements(root, &mut placements);
    Attach {
        kind,
        inboxes,
        shared_only,
        placements,
        done: HashMap::new(),
        faces_done: done,
    }
}

/// How often each prototype (by address) is placed.
fn count_placements(obj: &Object, out: &mut HashMap<usize, usize>) {
    match &obj.content {
        Content::Mesh(_) => {}
        Content::Subobjects(subs) => subs.iter().for_each(|s| count_placements(s, out)),
        Content::Instance(i) => {
            let n = out.entry(Arc::as_ptr(&i.prototype) as usize).or_default();
            *n += 1;
            if *n == 1 {
                count_placements(&i.prototype, out);
            }
        }
    }
}

/// The walk attaching trees, with the prototypes already prepared (by address).
struct Attach<'p> {
    kind: HierarchyKind,
    inboxes: bool,
    shared_only: bool,
    placements: HashMap<usize, usize>,
    done: HashMap<usize, Arc<Object>>,
    /// The faces whose trees are built.
    faces_done: Count<'p>,
}

impl Attach<'_> {
    /// Whether a leaf mesh of `faces` faces (`shared` or not) without a tree gets one.
    fn wants(&self, faces: usize, shared: bool) -> bool {
        faces >= MIN_FACES && (shared || !self.shared_only)
    }

    /// Faces of the meshes [`Attach::attach`] will build trees for below `obj`, each
    /// prototype once (by the addresses in `seen`).
    fn planned(&self, obj: &Object, shared: bool, seen: &mut HashSet<usize>) -> usize {
        match &obj.content {
            Content::Mesh(m) if obj.tree.is_none() && self.wants(m.faces.len(), shared) => {
                m.faces.len()
            }
            Content::Mesh(_) => 0,
            Content::Subobjects(subs) => subs.iter().map(|s| self.planned(s, shared, seen)).sum(),
            Content::Instance(i) => {
                let key = Arc::as_ptr(&i.prototype) as usize;
                if !seen.insert(key) {
                    return 0;
                }
                let many = self.placements.get(&key).is_some_and(|&n| n >= 2);
                self.planned(&i.prototype, shared || many, seen)
            }
        }
    }

    /// Attaches below `obj`; `shared` tells whether it lies in a prototype placed more than once.
    fn attach(&mut self, obj: &mut Object, shared: bool) {
        match &mut obj.content {
            Content::Mesh(m) => {
                if obj.tree.is_none() && self.wants(m.faces.len(), shared) {
                    let mut t = ObjectTree::build(m, self.kind);
                    if self.inboxes && m.closed {
                        component_inboxes(&mut t, m);
                    }
                    obj.tree = Some(Arc::new(t));
                    self.faces_done.add(m.faces.len());
                }
            }
            Content::Subobjects(subs) => {
                for s in subs {
                    self.attach(s, shared);
                }
            }
            Content::Instance(i) => {
                let key = Arc::as_ptr(&i.prototype) as usize;
                let p = match self.done.get(&key) {
                    Some(p) => p.clone(),
                    None => {
                        let many = self.placements.get(&key).is_some_and(|&n| n >= 2);
                        let mut copy = (*i.prototype).clone();
                        self.attach(&mut copy, shared || many);
                        let p = Arc::new(copy);
                        self.done.insert(key, p.clone());
                        p
                    }
                };
                i.prototype = p;
            }
        }
    }
}

/// An INBOX for every large component node below the root: a box grown inside the solid
/// within the component's CBOX.
pub(crate) fn component_inboxes(tree: &mut ObjectTree, mesh: &Mesh) {
    let Some(tris) = Triangles::of(mesh) else {
        return;
    };
    let s = Box3::from_points(mesh.vertices.iter()).size();
    let scale = s[0].max(s[1]).max(s[2]);
    let least = (INBOX_SHARE * mesh.faces.len() as f64).max(INBOX_MIN_FACES as f64) as usize;
    for k in 1..tree.nodes.len() {
        let n = &tree.nodes[k];
        if !n.component || n.faces.len() < least || !n.cbox.has_interior() {
            continue;
        }
        let mut sum = P3::origin().coords;
        let mut count = 0.0;
        for &f in tree.faces_of(k as u32) {
            for &v in &mesh.faces[f as usize].vertices {
                sum += mesh.vertices[v as usize].coords;
                count += 1.0;
            }
        }
        let centroid = P3::from(sum / count);
        tree.nodes[k].inbox = grown_inbox_in(&tris, &n.cbox.clone(), &centroid, scale);
    }
}

/// The object tree of every leaf of `scene`, in [`crate::scene::Scene::leaves`] order (None
/// for meshes without one).
pub(crate) fn leaf_trees(scene: &crate::scene::Scene) -> Vec<Option<Arc<ObjectTree>>> {
    fn walk(o: &Object, out: &mut Vec<Option<Arc<ObjectTree>>>) {
        match &o.content {
            Content::Mesh(_) => out.push(o.tree.clone()),
            Content::Subobjects(subs) => subs.iter().for_each(|s| walk(s, out)),
            Content::Instance(i) => walk(&i.prototype, out),
        }
    }
    let mut out = Vec::new();
    walk(&scene.root, &mut out);
    out
}

impl crate::scene::Scene {
    /// The leaf component of every face of the scene's object trees (paper 002), in global
    /// face order: faces of meshes without a prepared tree get `None`.
    pub fn face_components(&self) -> Vec<Option<u32>> {
        let mut out = Vec::with_capacity(self.face_count());
        for (leaf, tree) in self.leaves().iter().zip(leaf_trees(self)) {
            let n = leaf.mesh.faces.len();
            match tree {
                Some(t) => out.extend(t.components.face_component(n).into_iter().map(Some)),
                None => out.extend(std::iter::repeat_n(None, n)),
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::{PolyMesh, V3};
    use crate::pipeline::{render, Outputs, RenderOptions};
    use crate::prepare::{prepare, PrepareOptions};
    use crate::scene::testing::leaf;
    use crate::scene::Scene;
    use crate::tribox::interfere::{interfere_with, Method};
    use crate::view::Camera;

    /// A closed, bumpy latitude-longitude sphere of radius about `r` at `c`: `n` rings of
    /// `2n` quads, split into triangles, triangle fans at the poles.
    fn sphere(n: u32, r: f64, c: V3) -> PolyMesh {
        let m = 2 * n;
        let mut v = vec![
            P3::from(c + V3::new(0., 0., r)),
            P3::from(c - V3::new(0., 0., r)),
        ];
        for i in 1..n {
            for j in 0..m {
                let (th, ph) = (
                    std::f64::consts::PI * f64::from(i) / f64::from(n),
                    std::f64::consts::TAU * f64::from(j) / f64::from(m),
                );
                let rr = r * (1.0 + 0.15 * (3.0 * ph).sin() * th.sin());
                v.push(P3::from(
                    c + V3::new(th.sin() * ph.cos(), th.sin() * ph.sin(), th.cos()) * rr,
                ));
            }
        }
        let at = |i: u32, j: u32| 2 + (i - 1) * m + (j % m);
        let mut f = Vec::new();
        for j in 0..m {
            f.push(vec![0, at(1, j), at(1, j + 1)]);
            f.push(vec![1, at(n - 1, j + 1), at(n - 1, j)]);
        }
        for i in 1..n - 1 {
            for j in 0..m {
                f.push(vec![at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
                f.push(vec![at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
            }
        }
        PolyMesh::new(v, f)
    }

    /// Three spheres of 2208 faces overlapping in depth and on the screen.
    fn spheres() -> Scene {
        let objs = (0..3)
            .map(|k| {
                let c = V3::new(0.8 * f64::from(k), 0.3 * f64::from(k), -1.5 * f64::from(k));
                leaf(&format!("s{k}"), &sphere(24, 1.0, c))
            })
            .collect();
        Scene::new(Object::group("", objs), "t".into())
    }

    fn prepared(kind: HierarchyKind) -> Scene {
        let mut s = spheres();
        prepare(
            &mut s,
            &PrepareOptions {
                hierarchy: Some(kind),
                ..PrepareOptions::default()
            },
            &crate::Progress::default(),
        );
        s
    }

    #[test]
    fn trees_are_prepared_once_per_mesh_and_answers_do_not_change() {
        let simplify = prepared(HierarchyKind::Simplify);
        let median = prepared(HierarchyKind::Median);
        let trees = leaf_trees(&simplify);
        assert_eq!(trees.len(), 3);
        for t in &trees {
            let t = t.as_ref().expect("a tree for every large mesh");
            assert_eq!(t.kind, HierarchyKind::Simplify);
            assert_eq!(t.faces.len(), 2208);
        }
        assert!(leaf_trees(&median).iter().all(Option::is_none));
        // By default a mesh drawn once keeps the per-view median split.
        let mut auto = spheres();
        prepare(
            &mut auto,
            &PrepareOptions::default(),
            &crate::Progress::default(),
        );
        assert!(leaf_trees(&auto).iter().all(Option::is_none));
        let json = |s: &Scene| {
            let outputs = Outputs {
                json: true,
                ..Outputs::default()
            };
            let cam = Camera::orthographic(V3::new(0.2, -0.1, -1.0), V3::y()).unwrap();
            let r = render(
                s,
                &cam,
                &RenderOptions {
                    outputs,
                    ..Default::default()
                },
                &crate::Progress::default(),
            )
            .unwrap();
            assert!(r.stats.counters.nodes_visited > 0);
            r.json.unwrap()
        };
        // The walk order differs; the visible-polygon sets are the same bytes.
        let (a, b) = (json(&simplify), json(&median));
        assert!(a.len() > 1000);
        assert_eq!(a, b);
    }

    #[test]
    fn interference_is_the_same_by_every_method() {
        let s = prepared(HierarchyKind::Simplify);
        let brute = interfere_with(&s, Method::Brute);
        assert!(brute.tribox_meet.iter().any(|p| p.2), "{brute:?}");
        for kind in [HierarchyKind::Simplify, HierarchyKind::Median] {
            let t = interfere_with(&s, Method::Tree(kind));
            assert_eq!(t.tribox_meet, brute.tribox_meet);
            assert!(t.bv_tests > 0);
        }
    }

    #[test]
    fn lod_draws_a_mesh_of_two_far_parts_as_a_tribox_per_part() {
        let mut two = sphere(12, 1.0, V3::zeros());
        two.append(&sphere(12, 1.0, V3::new(10., 0., 0.)));
        let mut s = Scene::new(Object::group("", vec![leaf("two", &two)]), "t".into());
        prepare(
            &mut s,
            &PrepareOptions {
                hierarchy: Some(HierarchyKind::Simplify),
                ..PrepareOptions::default()
            },
            &crate::Progress::default(),
        );
        let cam = Camera::three_quarter();
        let (out, stats) =
            crate::view::substitute(&s, &cam, &crate::view::LodOptions::new(1e9, 100));
        assert_eq!(stats.objects_replaced, 1);
        // One tribox would span the gap between the spheres; the components' do not.
        assert!(stats.triboxes >= 2, "{stats:?}");
        let sub = &out.root.subobjects()[0];
        assert!(sub.vertices().iter().all(|v| v.x < 1.5 || v.x > 8.5));
        // Without a tree: one tribox.
        let mut bare = Scene::new(Object::group("", vec![leaf("two", &two)]), "t".into());
        prepare(
            &mut bare,
            &PrepareOptions {
                hierarchy: Some(HierarchyKind::Median),
                ..PrepareOptions::default()
            },
            &crate::Progress::default(),
        );
        let (_, one) =
            crate::view::substitute(&bare, &cam, &crate::view::LodOptions::new(1e9, 100));
        assert_eq!(one.triboxes, 1);
    }
}
