//! Boundary evaluation of a tribox (section 3): the chamfered block, the point p at each of
//! its 8 corners, the four cases, the vertices of equations (5)–(9), and the sub-lists
//! assembled into 18 faces.
//!
//! The tribox is the block B (the x, y, z bounds) with its edges chamfered by the six
//! diagonal directions. At a corner of B, in local coordinates X, Y, Z that point out of the
//! corner (X = ±x, …), the relevant planes are the three principal planes X = α_A, Y = α_B,
//! Z = α_C and the three chamfers X+Y = α_AB, X+Z = α_AC, Y+Z = α_BC. Their chamfers meet at
//! p (equations (2)–(4)); p is tested against the principal planes:
//!
//! - case 1, p inside all three: vertices p, v1 (5), v2 (6), v3 (7);
//! - case 2, p beyond X = α_A: v1, v3, and v2', v2'' on the X face ((8), (9));
//! - cases 3 and 4: the same with the roles of the axes rotated (beyond Y, beyond Z).
//!
//! Each corner appends its four vertices and one sub-list to each of its six faces; each
//! principal face joins four sub-lists, each chamfer face two. Faces are counter-clockwise
//! seen from outside. Degenerate (zero-length) edges and zero-area faces are kept, as in the
//! paper; [`Boundary::mesh`] removes them.
//!
//! The bounds must be tight (each plane touching the tribox), as those of a point set are;
//! [`crate::tribox::Tribox::boundary`] tightens them first.

use crate::geom::{newell_indexed, PolyMesh, P3};

use super::bounds::Tribox;

/// The paper's four topological configurations of a corner (Fig. 5).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub(crate) enum Case {
    /// p inside all three principal half-spaces: p is a vertex.
    One,
    /// p beyond the corner's x plane (α_A).
    Two,
    /// p beyond the corner's y plane (α_B).
    Three,
    /// p beyond the corner's z plane (α_C).
    Four,
}

/// Arithmetic done by one boundary evaluation, to compare with the paper's bound of
/// "24 shifts and at most 112 additions" (and at most 24 tests).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub(crate) struct OpCount {
    /// Additions and subtractions of bounds.
    pub additions: u32,
    /// Halvings (the paper's shifts).
    pub shifts: u32,
    /// Comparisons of p with a principal plane.
    pub tests: u32,
}

/// The boundary of a tribox: 32 vertices (4 per corner) and 18 faces, face `f` on plane `f`
/// (numbered as in [`crate::tribox::bounds`]). Faces may repeat vertices' positions.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Boundary {
    /// Vertices, four per corner in corner order.
    pub vertices: Vec<P3>,
    /// The 18 faces, counter-clockwise seen from outside, indexing `vertices`.
    pub faces: Vec<Vec<u32>>,
    /// The case of each corner; corner `c` has sign + on axis `a` when bit `a` of `c` is set.
    pub cases: [Case; 8],
    /// Operations performed.
    pub ops: OpCount,
}

/// Direction of the sum chamfer of axis pair (a, a+1): x+y, y+z, z+x.
const SUM_DIR: [usize; 3] = [3, 5, 4];
/// Direction of the difference chamfer of axis pair (a, a+1): y−x, z−y, x−z.
const DIFF_DIR: [usize; 3] = [7, 8, 6];
/// The axis with coefficient +1 in that difference direction.
const DIFF_POS: [usize; 3] = [1, 2, 0];

/// A vertex of a corner, named as in the paper's local picture.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Sym {
    /// The meeting point p of the three chamfers (case 1 only).
    P,
    /// On principal face a and the two chamfers containing a: v2 (a = X, eq. 6), v3 (Y,
    /// eq. 7), v1 (Z, eq. 5).
    W(usize),
    /// On principal face a, chamfer (a, b) and the chamfer opposite a: v2'' (a = X, b = Y,
    /// eq. 9), v2' (a = X, b = Z, eq. 8), and their rotations.
    W2(usize, usize),
}

impl Boundary {
    /// Evaluates the boundary of a tribox with tight bounds.
    pub(crate) fn evaluate(t: &Tribox) -> Boundary {
        let mut b = Builder::default();
        let mut cases = [Case::One; 8];
        for (c, case) in cases.iter_mut().enumerate() {
            *case = b.corner(t, c);
        }
        let faces = (0..18).map(|f| b.assemble(f)).collect();
        Boundary {
            vertices: b.vertices,
            faces,
            cases,
            ops: b.ops,
        }
    }

    /// Enclosed volume (divergence theorem over fan triangles; degenerate faces add 0).
    pub(crate) fn volume(&self) -> f64 {
        volume(&self.vertices, &self.faces)
    }

    /// Surface area (sum of the faces' vector-area lengths).
    pub(crate) fn area(&self) -> f64 {
        self.faces
            .iter()
            .map(|f| newell_indexed(&self.vertices, f).norm() * 0.5)
            .sum()
    }

    /// The boundary cleaned up (the paper's optional post-processing): vertices closer than
    /// rounding noise merged, zero-length edges removed, faces with fewer than three corners
    /// or zero area dropped, unused vertices dropped. A single point or a segment gives an
    /// empty mesh; a flat tribox gives its polygon twice, once per side.
    pub(crate) fn mesh(&self) -> PolyMesh {
        let eps = noise(&self.vertices);
        let (verts, remap) = merge_close(&self.vertices, eps);
        let mut faces = Vec::new();
        for f in &self.faces {
            let mut ring: Vec<u32> = Vec::with_capacity(f.len());
            for &v in f {
                let v = remap[v as usize];
                if ring.last() != Some(&v) {
                    ring.push(v);
                }
            }
            while ring.len() > 1 && ring.first() == ring.last() {
                ring.pop();
            }
            if ring.len() < 3 {
                continue;
            }
            let longest = (0..ring.len())
                .map(|i| {
                    (verts[ring[i] as usize] - verts[ring[(i + 1) % ring.len()] as usize]).norm()
                })
                .fold(0.0, f64::max);
            if newell_indexed(&verts, &ring).norm() * 0.5 <= eps * longest {
                continue;
            }
            faces.push(ring);
        }
        compact(verts, faces)
    }
}

/// Corner-by-corner construction state.
#[derive(Default)]
struct Builder {
    vertices: Vec<P3>,
    /// Sub-lists: `lists[face][corner]`.
    lists: [[Vec<u32>; 8]; 18],
    ops: OpCount,
}

impl Builder {
    /// Classifies corner `c`, appends its four vertices and its six sub-lists.
    fn corner(&mut self, t: &Tribox, c: usize) -> Case {
        let s: [f64; 3] = std::array::from_fn(|a| if c >> a & 1 == 1 { 1.0 } else { -1.0 });
        // Principal bounds α_A, α_B, α_C in local coordinates X_a = s_a x_a.
        let pa: [f64; 3] = std::array::from_fn(|a| t.offset(2 * a + usize::from(s[a] > 0.0)));
        // Chamfer q[a] on axes (a, a+1): α_AB, α_BC, α_CA.
        let qf: [usize; 3] = std::array::from_fn(|a| chamfer_face(&s, a));
        let q: [f64; 3] = qf.map(|f| t.offset(f));
        // Equations (2)–(4): p, the meeting point of the three chamfers.
        let sum = q[0] + q[2];
        let dif = q[0] - q[2];
        let p = [(sum - q[1]) * 0.5, (dif + q[1]) * 0.5, (q[1] - dif) * 0.5];
        self.ops.additions += 5;
        self.ops.shifts += 3;
        // The corner test.
        let mut beyond = None;
        for a in 0..3 {
            self.ops.tests += 1;
            if p[a] > pa[a] {
                beyond = Some(a);
                break;
            }
        }
        let case = match beyond {
            None => Case::One,
            Some(0) => Case::Two,
            Some(1) => Case::Three,
            Some(_) => Case::Four,
        };
        // The four vertices, local coordinates.
        let w = |a: usize| -> [f64; 3] {
            let mut v = [0.0; 3];
            v[a] = pa[a];
            v[(a + 1) % 3] = q[a] - pa[a];
            v[(a + 2) % 3] = q[(a + 2) % 3] - pa[a];
            v
        };
        let mut syms: Vec<(Sym, [f64; 3])> = Vec::with_capacity(4);
        match beyond {
            None => {
                syms.push((Sym::P, p));
                for a in 0..3 {
                    syms.push((Sym::W(a), w(a)));
                }
                self.ops.additions += 6;
            }
            Some(a) => {
                for b in [(a + 1) % 3, (a + 2) % 3] {
                    syms.push((Sym::W(b), w(b)));
                }
                // v2'' and v2' (equations (9) and (8)), sharing α_Q − α_A.
                let opposite = q[(a + 1) % 3];
                for (b, qab) in [((a + 1) % 3, q[a]), ((a + 2) % 3, q[(a + 2) % 3])] {
                    let mut v = [0.0; 3];
                    v[a] = pa[a];
                    v[b] = qab - pa[a];
                    v[3 - a - b] = opposite - v[b];
                    syms.push((Sym::W2(a, b), v));
                }
                self.ops.additions += 8;
            }
        }
        let base = self.vertices.len() as u32;
        for (_, v) in &syms {
            self.vertices
                .push(P3::new(s[0] * v[0], s[1] * v[1], s[2] * v[2]));
        }
        let index = |sym: Sym| -> u32 {
            base + syms
                .iter()
                .position(|(x, _)| *x == sym)
                .expect("corner vertex") as u32
        };
        let reflect = s[0] * s[1] * s[2] < 0.0;
        let mut put = |face: usize, list: Vec<Sym>| {
            let mut l: Vec<u32> = list.into_iter().map(index).collect();
            if reflect {
                l.reverse();
            }
            self.lists[face][c] = l;
        };
        for a in 0..3 {
            let (b, c3) = ((a + 1) % 3, (a + 2) % 3);
            // Principal face a: from its (a+1) side to its (a+2) side.
            let principal = if beyond == Some(a) {
                vec![Sym::W2(a, b), Sym::W2(a, c3)]
            } else {
                vec![Sym::W(a)]
            };
            put(2 * a + usize::from(s[a] > 0.0), principal);
            // Chamfer (a, a+1): from its (a+1) side to its a side.
            let chamfer = match beyond {
                None => vec![Sym::W(b), Sym::P, Sym::W(a)],
                Some(x) if x == a => vec![Sym::W(b), Sym::W2(a, b)],
                Some(x) if x == b => vec![Sym::W2(b, a), Sym::W(a)],
                Some(_) => vec![Sym::W(b), Sym::W2(c3, b), Sym::W2(c3, a), Sym::W(a)],
            };
            put(qf[a], chamfer);
        }
        case
    }

    /// Face `f`'s loop: its sub-lists joined in corner order around the face.
    fn assemble(&self, f: usize) -> Vec<u32> {
        let k = f / 2;
        let corners: Vec<usize> = if k < 3 {
            principal_corners(k, f % 2 == 1).to_vec()
        } else {
            (0..8)
                .rev()
                .filter(|&c| !self.lists[f][c].is_empty())
                .collect()
        };
        corners
            .iter()
            .flat_map(|&c| self.lists[f][c].iter().copied())
            .collect()
    }
}

/// Face of the chamfer on axes (a, a+1) at the corner with signs `s`: the direction whose
/// ± multiple is s_a x_a + s_b x_b, on the side that bounds it from above.
fn chamfer_face(s: &[f64; 3], a: usize) -> usize {
    let b = (a + 1) % 3;
    let (dir, sign) = if s[a] == s[b] {
        (SUM_DIR[a], s[a])
    } else {
        (DIFF_DIR[a], s[DIFF_POS[a]])
    };
    2 * dir + usize::from(sign > 0.0)
}

/// The four corners of principal face (axis a, max side when `max`), counter-clockwise seen
/// from outside.
fn principal_corners(a: usize, max: bool) -> [usize; 4] {
    let (b, c) = ((a + 1) % 3, (a + 2) % 3);
    let mut seq = [(1, 0), (1, 1), (0, 1), (0, 0)];
    if !max {
        seq.reverse();
    }
    seq.map(|(sb, sc)| usize::from(max) << a | sb << b | sc << c)
}

/// Volume enclosed by closed, outward faces.
pub(crate) fn volume(verts: &[P3], faces: &[Vec<u32>]) -> f64 {
    let Some(r) = verts.first() else { return 0.0 };
    let mut v = 0.0;
    for f in faces {
        for i in 1..f.len().saturating_sub(1) {
            let a = verts[f[0] as usize] - r;
            let b = verts[f[i] as usize] - r;
            let c = verts[f[i + 1] as usize] - r;
            v += a.dot(&b.cross(&c));
        }
    }
    v / 6.0
}

/// Distance below which two computed vertices are the same point: 64 ulps of the largest
/// coordinate (each coordinate is at most two additions of bounds).
fn noise(verts: &[P3]) -> f64 {
    let scale = verts
        .iter()
        .flat_map(|p| p.iter().map(|c| c.abs()))
        .fold(0.0, f64::max);
    64.0 * f64::EPSILON * scale
}

/// Merges vertices within `eps` of an earlier one (first occurrence kept).
fn merge_close(verts: &[P3], eps: f64) -> (Vec<P3>, Vec<u32>) {
    let mut out: Vec<P3> = Vec::new();
    let remap = verts
        .iter()
        .map(|v| match out.iter().position(|o| (o - v).norm() <= eps) {
            Some(i) => i as u32,
            None => {
                out.push(*v);
                out.len() as u32 - 1
            }
        })
        .collect();
    (out, remap)
}

/// Drops unused vertices and renumbers.
fn compact(verts: Vec<P3>, mut faces: Vec<Vec<u32>>) -> PolyMesh {
    let mut new = vec![u32::MAX; verts.len()];
    let mut out = Vec::new();
    for f in &mut faces {
        for v in f.iter_mut() {
            if new[*v as usize] == u32::MAX {
                new[*v as usize] = out.len() as u32;
                out.push(verts[*v as usize]);
            }
            *v = new[*v as usize];
        }
    }
    PolyMesh::new(out, faces)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::{Box3, V3};

    fn tribox(pts: &[[f64; 3]]) -> Tribox {
        Tribox::from_points(
            pts.iter()
                .map(|p| P3::new(p[0], p[1], p[2]))
                .collect::<Vec<_>>()
                .iter(),
        )
    }

    #[test]
    fn cube_is_a_cube() {
        let t = Tribox::from_points(
            Box3::new(P3::new(0., 0., 0.), P3::new(1., 1., 1.))
                .corners()
                .iter(),
        );
        let b = t.boundary();
        assert_eq!(b.vertices.len(), 32);
        assert_eq!(b.faces.len(), 18);
        assert!((b.volume() - 1.0).abs() < 1e-15);
        let m = b.mesh();
        assert_eq!(m.vertices.len(), 8);
        assert_eq!(m.faces.len(), 6);
        // Every principal face is a unit square counter-clockwise from outside.
        for (i, f) in m.faces.iter().enumerate() {
            let n = newell_indexed(&m.vertices, f);
            assert!((n.norm() - 2.0).abs() < 1e-15, "face {i}");
            let c: V3 = f.iter().map(|&v| m.vertices[v as usize].coords).sum::<V3>() / 4.0;
            assert!(
                n.dot(&(c - V3::new(0.5, 0.5, 0.5))) > 0.0,
                "face {i} faces inward"
            );
        }
    }

    #[test]
    fn octahedron_corners_are_case_one_and_count_is_within_112() {
        let t = tribox(&[
            [1., 0., 0.],
            [-1., 0., 0.],
            [0., 1., 0.],
            [0., -1., 0.],
            [0., 0., 1.],
            [0., 0., -1.],
        ]);
        let b = t.boundary();
        assert!(b.ops.additions <= 112 && b.ops.shifts == 24 && b.ops.tests <= 24);
        // The tribox of the octahedron |x|+|y|+|z| <= 1 is {|x|+|y|, |x|+|z|, |y|+|z| <= 1}:
        // per octant the octahedron's tetrahedron (1/6) and a cap to (1/2, 1/2, 1/2) (1/12).
        assert!(b.cases.iter().all(|&c| c == Case::One));
        assert!((b.volume() - 2.0).abs() < 1e-15, "{}", b.volume());
        assert_eq!(b.mesh().faces.len(), 12);
    }

    #[test]
    fn corner_beyond_a_principal_plane_gives_cases_two_to_four() {
        // The unit cube cut by the chamfer opposite axis a: both corners of the cut edge have
        // p beyond the principal plane of axis a.
        for (a, case) in [(0, Case::Two), (1, Case::Three), (2, Case::Four)] {
            let cube = Box3::new(P3::new(0., 0., 0.), P3::new(1., 1., 1.)).corners();
            let (b, c) = ((a + 1) % 3, (a + 2) % 3);
            let pts: Vec<P3> = cube
                .iter()
                .filter(|p| p[b] + p[c] <= 1.0)
                .copied()
                .collect();
            let t = Tribox::from_points(pts.iter());
            let bd = t.boundary();
            assert_eq!(
                bd.cases.iter().filter(|&&x| x == case).count(),
                2,
                "{:?}",
                bd.cases
            );
            assert!((bd.volume() - 0.5).abs() < 1e-15, "{}", bd.volume());
            assert_eq!(bd.mesh().faces.len(), 5);
        }
    }

    #[test]
    fn single_point_cleans_to_nothing() {
        let t = tribox(&[[1., 2., 3.]]);
        let b = t.boundary();
        assert!(b.vertices.iter().all(|v| *v == P3::new(1., 2., 3.)));
        assert_eq!(b.volume(), 0.0);
        assert!(b.mesh().faces.is_empty());
    }
}
