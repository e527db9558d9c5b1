//! INBOXes, boxes proven inside an object's closed solids: fills the INBOX of every object
//! lacking one, convex meshes by optimisation, other closed meshes by growing, groups from
//! their parts, instances through their transform.

pub mod convex;
pub mod grow;
pub mod halfspace;
pub mod place;
pub mod solid;

use std::collections::HashMap;
use std::sync::Arc;

use crate::geom::{Box3, P3, V3};
use crate::progress::{Phase, Progress, Stage};
use crate::scene::{Content, Mesh, Object};

use self::convex::{convex_inbox, is_convex};
use self::grow::grown_inbox;
use self::place::place_box;
use self::solid::Triangles;

/// Computes an INBOX for every object of the tree that has none, keeping explicit ones.
/// Prototypes shared by instances are prepared once and stay shared.
pub fn compute_inboxes(root: &mut Object) {
    compute_inboxes_counted(root, &Progress::new());
}

/// [`compute_inboxes`] as the prepare stage's phase [`Phase::Inboxes`], counting the faces
/// of each mesh as its INBOX is found.
pub(crate) fn compute_inboxes_counted(root: &mut Object, progress: &Progress) {
    let faces = root.distinct_faces_where(&|obj, _| obj.inbox.is_none());
    progress.enter_phase(Stage::Prepare, Phase::Inboxes, faces);
    let mut done = HashMap::new();
    fill(root, &mut done, progress);
}

/// Prepared prototypes, by the address of the original.
type Prepared = HashMap<usize, Arc<Object>>;

fn fill(obj: &mut Object, done: &mut Prepared, progress: &Progress) {
    let computed = match &mut obj.content {
        Content::Mesh(m) => obj
            .inbox
            .is_none()
            .then(|| {
                let b = mesh_inbox(m);
                progress.add(m.faces.len());
                b
            })
            .flatten(),
        Content::Subobjects(subs) => {
            for s in subs.iter_mut() {
                fill(s, done, progress);
            }
            largest(subs.iter().filter_map(|s| s.inbox))
        }
        Content::Instance(i) => {
            i.prototype = prepared(&i.prototype, done, progress);
            i.prototype.inbox.and_then(|b| place_box(&b, &i.transform))
        }
    };
    if obj.inbox.is_none() {
        obj.inbox = computed;
    }
}

/// The prototype with its inboxes computed, made once per distinct prototype.
fn prepared(proto: &Arc<Object>, done: &mut Prepared, progress: &Progress) -> Arc<Object> {
    let key = Arc::as_ptr(proto) as usize;
    if let Some(p) = done.get(&key) {
        return p.clone();
    }
    let mut copy = (**proto).clone();
    fill(&mut copy, done, progress);
    let p = Arc::new(copy);
    done.insert(key, p.clone());
    p
}

fn largest(boxes: impl Iterator<Item = Box3>) -> Option<Box3> {
    boxes
        .filter(Box3::has_interior)
        .max_by(|a, b| a.volume().total_cmp(&b.volume()))
}

/// The INBOX of one mesh: None unless it is a closed solid with interior.
pub fn mesh_inbox(mesh: &Mesh) -> Option<Box3> {
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
