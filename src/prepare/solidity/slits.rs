//! T-junction cracks closed for the solidity proof: a hole whose corners all lie on one line
//! (a slit: what remains where a mesh's zero-area triangle a, m, b was dropped, with m on
//! the edge ab of the face across) is closed by splitting the edges that span it.
//!
//! Each boundary edge u→v of a slit gets, between u and v, the slit's corners that lie
//! strictly between them on the line, in order. A triangle stays the same point set with a
//! corner added on its side (and stays planar: the new corner is on the line of an edge), so
//! the split mesh is the mesh itself, only with the crack's edges matched. If it then proves
//! a solid ([`super::caps`]), its winding number is the mesh's: the crack has no area to
//! show anything through, and the culling argument of [`super::caps`] holds with no cap
//! over it. Only triangles are split (a warped polygon split anew would be another surface
//! than the view's pieces of it); a slit along anything else stays refused.

use std::collections::HashMap;

use crate::scene::{Face, FaceIndices, Mesh};

/// The faces of `mesh` with the edges spanning each of `slits` (loops of vertices, each
/// following its boundary edges backwards, every corner on one line) split at the slit's
/// corners between their ends; None where such an edge is not on a triangle.
pub(super) fn close_slits(mesh: &Mesh, slits: &[Vec<u32>]) -> Option<Vec<Face>> {
    // The face edge u→v of each loop step v→u, with the corners to insert, from u to v.
    let mut inserts: HashMap<(u32, u32), Vec<u32>> = HashMap::new();
    for lp in slits {
        let key = line_order(mesh, lp);
        for i in 0..lp.len() {
            let (v, u) = (lp[i], lp[(i + 1) % lp.len()]);
            let (ku, kv) = (key(u), key(v));
            let mut between: Vec<u32> = lp
                .iter()
                .copied()
                .filter(|&w| {
                    let kw = key(w);
                    kw > ku.min(kv) && kw < ku.max(kv)
                })
                .collect();
            between.sort_by(|&a, &b| key(a).total_cmp(&key(b)));
            between.dedup();
            if ku > kv {
                between.reverse();
            }
            if !between.is_empty() {
                inserts.insert((u, v), between);
            }
        }
    }
    // A face edge is looked up only where it starts at a slit's corner.
    let mut starts = vec![false; mesh.vertices.len()];
    inserts.keys().for_each(|&(u, _)| starts[u as usize] = true);
    let spans = |f: &Face, i: usize| {
        let (u, v) = (f.vertices[i], f.vertices[(i + 1) % f.vertices.len()]);
        starts[u as usize].then(|| inserts.get(&(u, v))).flatten()
    };
    // Each face's spanning edges: only triangles are split, and each such edge must be
    // found once.
    let faces = &mesh.faces;
    let spanned = |f: &Face| {
        (0..f.vertices.len())
            .filter(|&i| spans(f, i).is_some())
            .count()
    };
    let counts: Vec<u8> = crate::chunked::map(faces.len(), |k| spanned(&faces[k]).min(3) as u8);
    let mut found = 0;
    for (f, &c) in faces.iter().zip(&counts) {
        if c > 0 && f.vertices.len() != 3 {
            return None;
        }
        found += usize::from(c);
    }
    (found == inserts.len()).then(|| {
        crate::chunked::map(faces.len(), |k| {
            let mut f = faces[k].clone();
            if counts[k] > 0 {
                let mut out = FaceIndices::new();
                for i in 0..f.vertices.len() {
                    out.push(f.vertices[i]);
                    out.extend(spans(&f, i).into_iter().flatten().copied());
                }
                f.vertices = out;
            }
            f
        })
    })
}

/// A key ordering the loop's corners along their line: the coordinate on which the loop's
/// two farthest-apart corners (its first and the one farthest from it) differ most. Points
/// on a line differ in that coordinate whenever they differ at all, so the order is exact.
fn line_order<'a>(mesh: &'a Mesh, lp: &[u32]) -> impl Fn(u32) -> f64 + 'a {
    let p = |v: u32| mesh.vertices[v as usize];
    let a = p(lp[0]);
    let far = lp
        .iter()
        .map(|&v| p(v))
        .max_by(|x, y| (x - a).norm_squared().total_cmp(&(y - a).norm_squared()))
        .unwrap_or(a);
    let d = far - a;
    let axis = d.iamax();
    let sign = if d[axis] < 0.0 { -1.0 } else { 1.0 };
    move |v: u32| sign * mesh.vertices[v as usize][axis]
}
