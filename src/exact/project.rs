//! The scene's planar pieces projected exactly: world points (f64, as the scene defines
//! them) through the camera matrix (f64 entries) in rationals, clipped exactly at the near
//! plane, each with its exact depth plane. Faces are two-sided; nothing is culled.

use crate::geom::P3;
use crate::scene::Scene;
use crate::view::screen::planar_pieces;
use crate::view::{Camera, Projection};

use super::rational::{box_of, orient, q, QPt, Q};

/// One planar piece of a face, projected exactly.
#[derive(Debug, Clone)]
pub(crate) struct ExactPiece {
    /// Global face id.
    pub face: u32,
    /// The projected ring (either orientation).
    pub ring: Vec<QPt>,
    /// Depth z = a x + b y + c over the screen (larger is nearer).
    pub plane: [Q; 3],
    /// f64 bounds holding the ring.
    pub rect: [f64; 4],
}

impl ExactPiece {
    /// Depth at a screen point.
    pub(crate) fn depth(&self, p: &QPt) -> Q {
        &self.plane[0] * &p.x + &self.plane[1] * &p.y + &self.plane[2]
    }
}

/// Every piece of every face that shows area (edge-on pieces and pieces wholly behind the
/// near plane show none and hide nothing), in global face order.
pub(crate) fn exact_pieces(scene: &Scene, camera: &Camera) -> Vec<ExactPiece> {
    let m: Vec<Vec<Q>> = (0..4)
        .map(|r| (0..4).map(|c| q(camera.matrix[(r, c)])).collect())
        .collect();
    let near = q(camera.near);
    let persp = camera.projection == Projection::Perspective;
    let mut out = Vec::new();
    let removed = |f: u32| {
        scene
            .section
            .as_ref()
            .is_some_and(|s| s.removed.binary_search(&f).is_ok())
    };
    for leaf in scene.leaves() {
        let world: Vec<P3> = (0..leaf.mesh.vertices.len() as u32)
            .map(|k| leaf.world_vertex(k))
            .collect();
        let clip: Vec<[Q; 4]> = world.iter().map(|p| homogeneous(&m, p)).collect();
        for (k, f) in leaf.mesh.faces.iter().enumerate() {
            let face = (leaf.first_face + k) as u32;
            // A face a section cut removed whole is not in the scene (it keeps its id only).
            if removed(face) {
                continue;
            }
            for piece in planar_pieces(&f.vertices, &world) {
                let mut poly: Vec<[Q; 4]> =
                    piece.iter().map(|&v| clip[v as usize].clone()).collect();
                if persp {
                    poly = clip_near(&poly, &near);
                }
                let pts: Vec<[Q; 3]> = poly
                    .iter()
                    .map(|h| {
                        if persp {
                            [&h[0] / &h[3], &h[1] / &h[3], &h[2] / &h[3]]
                        } else {
                            [h[0].clone(), h[1].clone(), h[2].clone()]
                        }
                    })
                    .collect();
                if let Some(p) = piece_of(face, &pts) {
                    out.push(p);
                }
            }
        }
    }
    out
}

/// M · (p, 1), exactly.
fn homogeneous(m: &[Vec<Q>], p: &P3) -> [Q; 4] {
    let c = [q(p.x), q(p.y), q(p.z), Q::int(1)];
    std::array::from_fn(|r| m[r].iter().zip(&c).fold(Q::int(0), |s, (a, b)| s + a * b))
}

/// The polygon clipped to w ≥ near (Sutherland–Hodgman, exact).
fn clip_near(poly: &[[Q; 4]], near: &Q) -> Vec<[Q; 4]> {
    let n = poly.len();
    let mut out = Vec::with_capacity(n + 2);
    let zero = Q::int(0);
    for i in 0..n {
        let (a, b) = (&poly[i], &poly[(i + 1) % n]);
        let (da, db) = (&a[3] - near, &b[3] - near);
        if da >= zero {
            out.push(a.clone());
        }
        if (da >= zero) != (db >= zero) {
            let t = &da / (&da - &db);
            out.push(std::array::from_fn(|k| &a[k] + &t * (&b[k] - &a[k])));
        }
    }
    if out.len() < 3 {
        out.clear();
    }
    out
}

/// The piece with its depth plane, or None when it shows no area (collinear in screen).
fn piece_of(face: u32, pts: &[[Q; 3]]) -> Option<ExactPiece> {
    let ring: Vec<QPt> = pts
        .iter()
        .map(|p| QPt {
            x: p[0].clone(),
            y: p[1].clone(),
        })
        .collect();
    let n = ring.len();
    // Three points with a nonzero turn span the plane.
    let (i, j, k) = (0..n)
        .flat_map(|j| (j + 1..n).map(move |k| (0, j, k)))
        .find(|&(i, j, k)| orient(&ring[i], &ring[j], &ring[k]) != 0)?;
    let (p0, p1, p2) = (&pts[i], &pts[j], &pts[k]);
    let (x1, y1, z1) = (&p1[0] - &p0[0], &p1[1] - &p0[1], &p1[2] - &p0[2]);
    let (x2, y2, z2) = (&p2[0] - &p0[0], &p2[1] - &p0[1], &p2[2] - &p0[2]);
    let det = &x1 * &y2 - &x2 * &y1;
    let a = (&z1 * &y2 - &z2 * &y1) / &det;
    let b = (&x1 * &z2 - &x2 * &z1) / &det;
    let c = &p0[2] - &a * &p0[0] - &b * &p0[1];
    let rect = box_of(&ring);
    Some(ExactPiece {
        face,
        ring,
        plane: [a, b, c],
        rect,
    })
}
