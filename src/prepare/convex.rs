//! INBOX of a convex closed mesh: the largest-volume axis-aligned box inside it, found by a
//! convex optimisation over its face planes, shrunk a little and verified exactly.

use crate::geom::{newell_indexed, Box3, P3, V3};
use crate::scene::Mesh;

use super::halfspace::largest_box;
use super::solid::{shrink, Triangles};

/// Relative distance (of the mesh's size) a vertex may lie in front of a neighbouring face's
/// plane while the mesh still counts as convex. Only the choice of method depends on it:
/// the result is verified exactly whatever it decides.
const CONVEX_TOL: f64 = 1e-9;

/// Relative shrinks tried, in order, until the box verifies.
const SHRINKS: [f64; 4] = [1e-9, 1e-7, 1e-5, 1e-3];

/// True when every vertex of every face sharing a vertex with a face lies on or behind that
/// face's plane (within `CONVEX_TOL`): local convexity, which for a closed, consistently
/// oriented surface means convexity.
pub fn is_convex(mesh: &Mesh, flipped: bool) -> bool {
    let cbox = Box3::from_points(mesh.vertices.iter());
    let scale = cbox.size().iter().fold(0.0f64, |a, &b| a.max(b));
    let mut incident: Vec<Vec<u32>> = vec![Vec::new(); mesh.vertices.len()];
    for (k, f) in mesh.faces.iter().enumerate() {
        for &v in &f.vertices {
            incident[v as usize].push(k as u32);
        }
    }
    let sign = if flipped { -1.0 } else { 1.0 };
    mesh.faces.iter().all(|f| {
        let n = newell_indexed(&mesh.vertices, &f.vertices) * sign;
        let len = n.norm();
        if len == 0.0 {
            return false;
        }
        let n = n / len;
        let d = f
            .vertices
            .iter()
            .map(|&v| n.dot(&mesh.vertices[v as usize].coords))
            .fold(f64::NEG_INFINITY, f64::max);
        f.vertices.iter().all(|&v| {
            incident[v as usize].iter().all(|&g| {
                mesh.faces[g as usize]
                    .vertices
                    .iter()
                    .all(|&w| n.dot(&mesh.vertices[w as usize].coords) <= d + CONVEX_TOL * scale)
            })
        })
    })
}

/// The largest box inside a convex mesh, verified to lie inside it; None when the
/// optimisation fails or no shrink of its result verifies.
pub fn convex_inbox(mesh: &Mesh, tris: &Triangles) -> Option<Box3> {
    let n = mesh.vertices.len() as f64;
    let centroid = P3::from(mesh.vertices.iter().map(|p| p.coords).sum::<V3>() / n);
    let best = largest_box(&tris.half_spaces(), &centroid)?;
    let verified = SHRINKS
        .iter()
        .map(|&eps| shrink(&best, eps))
        .find(|b| tris.box_in_kernel(b))?;
    let cbox = Box3::from_points(mesh.vertices.iter());
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
