//! INBOXes, boxes proven inside an object's closed solids: fills the INBOX of every object
//! lacking one, convex meshes by optimisation, other closed meshes by growing, groups from
//! their parts, instances through their transform.

pub(crate) mod convex;
pub(crate) mod grow;
pub(crate) mod halfspace;
pub(crate) mod place;
pub(crate) mod solid;

use std::collections::HashMap;
use std::sync::Arc;

use crate::count::Count;
use crate::geom::{Box3, P3, V3};
use crate::scene::{Content, Mesh, Object};

use self::convex::{convex_inbox, is_convex};
use self::grow::grown_inbox;
use self::place::place_box;
use self::solid::Triangles;

/// Computes an INBOX for every object of the tree that has none, keeping explicit ones.
/// Prototypes shared by instances are prepared once and stay shared.
///
/// The faces of each mesh go to `done` as its INBOX is found.
pub(crate) fn compute_inboxes(root: &mut Object, done: Count) {
    fill(root, &mut HashMap::new(), done);
}

/// Prepared prototypes, by the address of the original.
type Prepared = HashMap<usize, Arc<Object>>;

fn fill(obj: &mut Object, made: &mut Prepared, done: Count) {
    let computed = match &mut obj.content {
        Content::Mesh(m) => obj
            .inbox
            .is_none()
            .then(|| {
                let b = mesh_inbox(m);
                done.add(m.faces.len());
                b
            })
            .flatten(),
        Content::Subobjects(subs) => {
            for s in subs.iter_mut() {
                fill(s, made, done);
            }
            largest(subs.iter().filter_map(|s| s.inbox))
        }
        Content::Instance(i) => {
            i.prototype = prepared(&i.prototype, made, done);
            i.prototype.inbox.and_then(|b| place_box(&b, &i.transform))
        }
    };
    if obj.inbox.is_none() {
        obj.inbox = computed;
    }
}

/// The prototype with its inboxes computed, made once per distinct prototype.
fn prepared(proto: &Arc<Object>, made: &mut Prepared, done: Count) -> Arc<Object> {
    let key = Arc::as_ptr(proto) as usize;
    if let Some(p) = made.get(&key) {
        return p.clone();
    }
    let mut copy = (**proto).clone();
    fill(&mut copy, made, done);
    let p = Arc::new(copy);
    made.insert(key, p.clone());
    p
}

fn largest(boxes: impl Iterator<Item = Box3>) -> Option<Box3> {
    boxes
        .filter(Box3::has_interior)
        .max_by(|a, b| a.volume().total_cmp(&b.volume()))
}

/// The INBOX of one mesh: None unless it is a closed solid with interior.
pub(crate) fn mesh_inbox(mesh: &Mesh) -> Option<Box3> {
    if !mesh.closed || mesh.vertices.is_empty() {
        return None;
    }
    let tris = Triangles::of(mesh)?;
    if is_convex(mesh, tris.flipped) {
        if let Some(b) = convex_inbox(mesh, &tris) {
            return Some(b);
        }
    }
    let cbox = Box3::from_points(mesh.vertices.iter());
    let n = mesh.vertices.len() as f64;
    let centroid = P3::from(mesh.vertices.iter().map(|p| p.coords).sum::<V3>() / n);
    grown_inbox(&tris, &cbox, &centroid)
}
