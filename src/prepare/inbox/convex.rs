//! INBOX of a convex closed mesh: the largest-volume axis-aligned box inside it, found by a
//! convex optimisation over its face planes, shrunk a little and verified exactly.

use rayon::prelude::*;

use crate::geom::{newell_indexed, Box3, P3, V3};
use crate::scene::topology::sort;
use crate::scene::Mesh;

use super::halfspace::largest_box_within;
use super::solid::{shrink, Triangles};

/// Relative distance (of the mesh's size) a vertex may lie in front of a neighbouring face's
/// plane while the mesh still counts as convex. Only the choice of method depends on it:
/// the result is verified exactly whatever it decides.
const CONVEX_TOL: f64 = 1e-9;

/// Meshes of more faces than this are checked on all threads.
const PARALLEL_ABOVE: usize = 4096;

/// Relative shrinks tried, in order, until the box verifies.
const SHRINKS: [f64; 4] = [1e-9, 1e-7, 1e-5, 1e-3];

/// True when, across every edge, the faces meeting there bend away from each other: the
/// corners of the neighbouring face next to the edge lie on or behind the face's plane
/// (within `CONVEX_TOL` of the mesh's size). For a closed, consistently oriented surface this
/// local convexity means convexity. One pass over the edges: linear in the mesh's size, even
/// for faces of a million corners (a face is never scanned once per neighbour).
pub(crate) fn is_convex(mesh: &Mesh, flipped: bool) -> bool {
    let cbox = Box3::from_points(mesh.vertices.iter());
    let scale = cbox.size().iter().fold(0.0f64, |a, &b| a.max(b));
    let tol = CONVEX_TOL * scale;
    let sign = if flipped { -1.0 } else { 1.0 };
    let twins = EdgeTwins::of(mesh);
    let at = |f: &[u32], i: usize| mesh.vertices[f[i % f.len()] as usize].coords;
    let locally_convex = |(k, f): (usize, &crate::scene::Face)| {
        let n = newell_indexed(&mesh.vertices, &f.vertices) * sign;
        let len = n.norm();
        if len == 0.0 {
            return false;
        }
        let n = n / len;
        let v = &f.vertices;
        let d = v
            .iter()
            .map(|&k| n.dot(&mesh.vertices[k as usize].coords))
            .fold(f64::NEG_INFINITY, f64::max);
        let first = twins.first[k];
        (0..v.len()).all(|i| {
            let Some((g, j)) = twins.across(first + i) else {
                return false;
            };
            // The neighbour runs b -> a at position j: its corners before b and after a.
            let gv = &mesh.faces[g as usize].vertices;
            let (j, m) = (j as usize, gv.len());
            [at(gv, j + m - 1), at(gv, j + 2)]
                .iter()
                .all(|p| n.dot(p) <= d + tol)
        })
    };
    // A yes or no: the same answer on any number of threads.
    if mesh.faces.len() > PARALLEL_ABOVE {
        mesh.faces.par_iter().enumerate().all(locally_convex)
    } else {
        mesh.faces.iter().enumerate().all(locally_convex)
    }
}

/// The corner across each edge of a mesh: corner `first[f] + i` starts the edge from corner
/// `i` to `i + 1` of face `f`; its twin starts the same edge, run the other way, in the
/// neighbouring face. Built by sorting the undirected edges (linear-time lookups after one
/// sort; no hashing, no binary search per edge).
struct EdgeTwins {
    /// The first corner of each face.
    first: Vec<usize>,
    /// Each corner's face.
    face: Vec<u32>,
    /// Each corner's twin, or `u32::MAX` where the edge is not used exactly once each way.
    twin: Vec<u32>,
}

impl EdgeTwins {
    fn of(mesh: &Mesh) -> EdgeTwins {
        let mut first = Vec::with_capacity(mesh.faces.len());
        let mut face = Vec::new();
        // (undirected edge, corner, forward): forward when the edge runs low to high index.
        let mut ends: Vec<(u64, u32, bool)> = Vec::new();
        for (k, f) in mesh.faces.iter().enumerate() {
            first.push(face.len());
            let v = &f.vertices;
            for i in 0..v.len() {
                let (a, b) = (v[i], v[(i + 1) % v.len()]);
                let key = (a.min(b) as u64) << 32 | a.max(b) as u64;
                ends.push((key, face.len() as u32, a < b));
                face.push(k as u32);
            }
        }
        sort(&mut ends);
        let mut twin = vec![u32::MAX; face.len()];
        let mut i = 0;
        while i < ends.len() {
            let run = ends[i..].iter().take_while(|e| e.0 == ends[i].0).count();
            if run == 2 && ends[i].2 != ends[i + 1].2 {
                twin[ends[i].1 as usize] = ends[i + 1].1;
                twin[ends[i + 1].1 as usize] = ends[i].1;
            }
            i += run;
        }
        EdgeTwins { first, face, twin }
    }

    /// The face and position across the edge starting at `corner`, if it has one.
    fn across(&self, corner: usize) -> Option<(u32, u32)> {
        let t = *self.twin.get(corner)?;
        (t != u32::MAX).then(|| {
            let g = self.face[t as usize];
            (g, t - self.first[g as usize] as u32)
        })
    }
}

/// The largest box inside a convex mesh, verified to lie inside it; None when the
/// optimisation fails or no shrink of its result verifies.
pub(crate) fn convex_inbox(mesh: &Mesh, tris: &Triangles) -> Option<Box3> {
    let n = mesh.vertices.len() as f64;
    let centroid = P3::from(mesh.vertices.iter().map(|p| p.coords).sum::<V3>() / n);
    let cbox = Box3::from_points(mesh.vertices.iter());
    // A box (or any solid that fills its CBOX) is its own INBOX: one exact test, no search.
    if tris.box_in_kernel(&cbox) {
        return Some(cbox);
    }
    let best = largest_box_within(&tris.half_spaces(), &centroid, &cbox)?;
    let verified = SHRINKS
        .iter()
        .map(|&eps| shrink(&best, eps))
        .find(|b| tris.box_in_kernel(b))?;
    Some(snap_to(&verified, &cbox, tris))
}

/// Moves each side of `b` that lies within a hair of the same side of `cbox` onto it, when
/// the moved box still verifies (so the inbox of a box is the box itself).
fn snap_to(b: &Box3, cbox: &Box3, tris: &Triangles) -> Box3 {
    let mut out = *b;
    for i in 0..3 {
        let tol = 1e-6 * (cbox.hi[i] - cbox.lo[i]);
        for hi in [false, true] {
            let mut c = out;
            if hi && cbox.hi[i] - out.hi[i] < tol {
                c.hi[i] = cbox.hi[i];
            } else if !hi && out.lo[i] - cbox.lo[i] < tol {
                c.lo[i] = cbox.lo[i];
            } else {
                continue;
            }
            if tris.box_in_kernel(&c) {
                out = c;
            }
        }
    }
    out
}
