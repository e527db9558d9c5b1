//! Object trees for the flat meshes of a scene (paper 002): every leaf mesh large enough to
//! need one gets its B(T) once, in its own frame (a prototype's once for all its
//! placements), and, when the scene has inboxes at all, an INBOX per large component of a
//! closed mesh: the subobjects Franklin's pruning needs, which a flat mesh lacks.

use std::collections::HashMap;
use std::sync::Arc;

use crate::geom::{Box3, P3};
use crate::scene::{Content, Mesh, Object};

use super::bvtree::{HierarchyKind, ObjectTree};
use super::grow::grown_inbox_in;
use super::solid::Triangles;

/// Meshes with fewer faces keep the view's median split (a tree would cost more than it saves).
pub const MIN_FACES: usize = 256;
/// Components with fewer faces than this (and than [`INBOX_SHARE`] of the mesh) get no INBOX.
pub const INBOX_MIN_FACES: usize = 64;
/// Least share of the mesh's faces for a component to get an INBOX.
pub const INBOX_SHARE: f64 = 1.0 / 64.0;

/// Attaches a tree of `kind` to every leaf mesh of at least [`MIN_FACES`] faces that has none;
/// with `inboxes`, closed meshes' large components get inboxes too.
pub fn attach_trees(root: &mut Object, kind: HierarchyKind, inboxes: bool) {
    let mut done = HashMap::new();
    attach(root, kind, inboxes, &mut done);
}

fn attach(
    obj: &mut Object,
    kind: HierarchyKind,
    inboxes: bool,
    done: &mut HashMap<usize, Arc<Object>>,
) {
    match &mut obj.content {
        Content::Mesh(m) => {
            if obj.tree.is_none() && m.faces.len() >= MIN_FACES {
                let mut t = ObjectTree::build(m, kind);
                if inboxes && m.closed {
                    component_inboxes(&mut t, m);
                }
                obj.tree = Some(Arc::new(t));
            }
        }
        Content::Subobjects(subs) => {
            for s in subs {
                attach(s, kind, inboxes, done);
            }
        }
        Content::Instance(i) => {
            let key = Arc::as_ptr(&i.prototype) as usize;
            let p = match done.get(&key) {
                Some(p) => p.clone(),
                None => {
                    let mut copy = (*i.prototype).clone();
                    attach(&mut copy, kind, inboxes, done);
                    let p = Arc::new(copy);
                    done.insert(key, p.clone());
                    p
                }
            };
            i.prototype = p;
        }
    }
}

/// An INBOX for every large component node below the root: a box grown inside the solid
/// within the component's CBOX.
pub fn component_inboxes(tree: &mut ObjectTree, mesh: &Mesh) {
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
pub fn leaf_trees(scene: &crate::scene::Scene) -> Vec<Option<Arc<ObjectTree>>> {
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
