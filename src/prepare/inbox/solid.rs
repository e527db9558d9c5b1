//! Geometry of a closed mesh shared by the inbox methods: orientation, triangles, face
//! planes, and the exact test that a box lies on the inner side of every face.

use rayon::prelude::*;

use crate::geom::{orient2d, orient3d_refs, Box3, P3, V3};
use crate::scene::Mesh;

use super::halfspace::HalfSpace;
use crate::scene::triangulate::balanced;

/// Meshes of more triangles than this are tested on all threads.
const PARALLEL_ABOVE: usize = 8192;

/// Faces of more corners than this are cut into balanced triangles instead of a fan.
const BALANCED_ABOVE: usize = 64;

/// A mesh's faces as triangles (a fan, or balanced for long faces), oriented so that the solid's inside is on their
/// negative side (normal = (b − a) × (c − a) points out).
#[derive(Debug, Clone)]
pub(crate) struct Triangles {
    /// The triangles.
    pub tris: Vec<[P3; 3]>,
    /// True when the mesh's faces were oriented inward (the triangles are flipped).
    pub flipped: bool,
}

impl Triangles {
    /// The triangles of every face, flipped when the mesh is oriented inward. None when
    /// the signed volume is zero (no interior).
    pub(crate) fn of(mesh: &Mesh) -> Option<Triangles> {
        let mut tris = Vec::with_capacity(mesh.faces.len() * 2);
        for f in &mesh.faces {
            let v = &f.vertices;
            let at = |i: usize| mesh.vertices[v[i] as usize];
            if v.len() > BALANCED_ABOVE {
                // The same 2-chain as the fan, but a box near the face meets few of its
                // triangles' boxes (a fan's all reach its first corner).
                tris.extend(balanced(v.len()).iter().map(|t| t.map(at)));
                continue;
            }
            for i in 1..v.len().saturating_sub(1) {
                tris.push([at(0), at(i), at(i + 1)]);
            }
        }
        let volume = signed_volume(&tris);
        if !(volume.abs() > 0.0 && volume.is_finite()) {
            return None;
        }
        let flipped = volume < 0.0;
        if flipped {
            for t in &mut tris {
                t.swap(1, 2);
            }
        }
        Some(Triangles { tris, flipped })
    }

    /// Exact test: every corner of `b` is on the inner side of (or on) every triangle's
    /// plane. Such a box lies in the kernel of the polyhedron, hence inside it. Per triangle
    /// only the corner farthest along its normal is tested (exact `orient3d`); on an axis
    /// where the normal's sign is within rounding of zero, both corners are.
    pub(crate) fn box_in_kernel(&self, b: &Box3) -> bool {
        let inner = |t: &[P3; 3]| axis_plane_side(t, b).unwrap_or_else(|| box_behind(t, b));
        // A yes or no: the same answer on any number of threads.
        if self.tris.len() > PARALLEL_ABOVE {
            self.tris.par_iter().all(inner)
        } else {
            self.tris.iter().all(inner)
        }
    }

    /// One half-space per triangle (Newell normal of the triangle, offset through its vertices).
    pub(crate) fn half_spaces(&self) -> Vec<HalfSpace> {
        self.tris
            .iter()
            .filter_map(|t| {
                let n: V3 = (t[1] - t[0]).cross(&(t[2] - t[0]));
                let len = n.norm();
                (len > 0.0).then(|| {
                    let n = n / len;
                    let d = t
                        .iter()
                        .map(|p| n.dot(&p.coords))
                        .fold(f64::INFINITY, f64::min);
                    HalfSpace {
                        normal: n,
                        offset: d,
                    }
                })
            })
            .collect()
    }
}

/// The signed volume enclosed by triangles (positive when they face outward).
fn signed_volume(tris: &[[P3; 3]]) -> f64 {
    let o = tris.first().map_or(P3::origin(), |t| t[0]);
    tris.iter()
        .map(|t| (t[0] - o).dot(&(t[1] - o).cross(&(t[2] - o))))
        .sum::<f64>()
        / 6.0
}

/// The box scaled about its centre by `1 − eps` on every axis.
pub(crate) fn shrink(b: &Box3, eps: f64) -> Box3 {
    let c = b.center();
    let mut out = *b;
    for i in 0..3 {
        let h = 0.5 * (b.hi[i] - b.lo[i]) * (1.0 - eps);
        out.lo[i] = c[i] - h;
        out.hi[i] = c[i] + h;
    }
    out
}

/// Exact: every corner of `b` is on the inner side of (or on) triangle `t`'s plane. Only the
/// corner farthest along its normal is tested (exact `orient3d`); on an axis where the
/// normal's sign is within rounding of zero, both corners are.
fn box_behind(t: &[P3; 3], b: &Box3) -> bool {
    let (e1, e2) = (t[1] - t[0], t[2] - t[0]);
    let n = e1.cross(&e2);
    // Each component of the f64 cross product is within this of the exact one.
    let err = 1e-12 * e1.norm() * e2.norm();
    let both: [[f64; 2]; 3] = std::array::from_fn(|i| [b.lo[i], b.hi[i]]);
    let c: [&[f64]; 3] = std::array::from_fn(|i| {
        if n[i] > err {
            &both[i][1..]
        } else if n[i] < -err {
            &both[i][..1]
        } else {
            &both[i][..]
        }
    });
    // orient3d > 0: the point lies below the counter-clockwise triangle, i.e. inside.
    c[0].iter().all(|&x| {
        c[1].iter().all(|&y| {
            c[2].iter()
                .all(|&z| orient3d_refs(t, &P3::new(x, y, z)) >= 0.0)
        })
    })
}

/// [`box_behind`] for a triangle in a plane x_k = c (its three corners share coordinate k
/// exactly), without orient3d: orient3d(t, p) = n·(t0 − p) = n_k (c − p_k), and the sign of
/// n_k is the exact orient2d of the corners' other two coordinates (in cyclic order). A box
/// lying on such a plane (an INBOX snapped to a primitive's cap) would otherwise cost an
/// exact-zero orient3d per corner per triangle. None for any other triangle.
fn axis_plane_side(t: &[P3; 3], b: &Box3) -> Option<bool> {
    let k = (0..3).find(|&k| t[0][k] == t[1][k] && t[1][k] == t[2][k])?;
    let (i, j) = ((k + 1) % 3, (k + 2) % 3);
    let turn = orient2d([t[0][i], t[0][j]], [t[1][i], t[1][j]], [t[2][i], t[2][j]]);
    let c = t[0][k];
    Some(if turn > 0.0 {
        b.hi[k] <= c
    } else if turn < 0.0 {
        b.lo[k] >= c
    } else {
        true
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::rng::XorShift;

    #[test]
    fn axis_planes_are_decided_as_orient3d_decides_them() {
        // Triangles in planes x, y or z = const (both windings), boxes on, across and off them.
        let mut rng = XorShift::new(9);
        let v = |rng: &mut XorShift| rng.below(5) as f64 - 2.0;
        let (mut inside, mut outside) = (0, 0);
        for _ in 0..20000 {
            let k = rng.below(3);
            let c = v(&mut rng);
            let mut t = [P3::origin(); 3];
            for p in &mut t {
                for a in 0..3 {
                    p[a] = if a == k { c } else { v(&mut rng) };
                }
            }
            let (lo, hi) = (
                P3::new(v(&mut rng), v(&mut rng), v(&mut rng)),
                P3::new(v(&mut rng), v(&mut rng), v(&mut rng)),
            );
            let b = Box3::new(lo.inf(&hi), lo.sup(&hi));
            let fast = axis_plane_side(&t, &b).expect("an axis plane");
            assert_eq!(fast, box_behind(&t, &b), "{t:?} {b:?}");
            inside += usize::from(fast);
            outside += usize::from(!fast);
        }
        assert!(inside > 1000 && outside > 1000, "{inside} {outside}");
        let tilted = [
            P3::new(0., 0., 0.),
            P3::new(1., 0., 1.),
            P3::new(0., 1., 0.),
        ];
        assert!(axis_plane_side(&tilted, &Box3::new(P3::origin(), P3::new(1., 1., 1.))).is_none());
    }
}
