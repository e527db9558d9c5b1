//! BV-tree collision (paper 002 section 4.3, as RAPID does it): two placed meshes meet when a
//! walk down both object trees at once reaches a pair of leaves with a pair of intersecting
//! triangles; a pair of nodes whose bounding volumes are apart is never entered.
//!
//! Bounding volume: each node's CBOX in its mesh's own frame, carried into the world by the
//! placement as an oriented box (a parallelepiped under scaling or shear), and tested against
//! the other node's by the separating-axis theorem on its 15 axes (the 3 + 3 face normals and
//! the 9 cross products of edge directions), as RAPID tests OBBs. A pair is declared apart
//! only when the gap exceeds a relative margin far above the rounding of those dot products,
//! so no meeting pair is ever skipped; the exact triangle test decides.

use crate::geom::{newell, Box3, M4, P3, V3};
use crate::prepare::trees::bvtree::ObjectTree;
use crate::scene::triangulate::ear_clip;
use crate::scene::Mesh;

use super::interfere::triangles_intersect;

/// Relative margin of the separating-axis test.
const MARGIN: f64 = 1e-9;

/// The triangles of every face of a mesh, as local vertex indices (ear-clipped once per mesh;
/// both the tree walk and the brute-force comparison use these, so they test the same
/// triangles).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct FaceTriangles {
    /// Face `f`'s triangles are `tris[starts[f]..starts[f + 1]]`.
    pub starts: Vec<u32>,
    /// Triangles (vertex indices of the mesh).
    pub tris: Vec<[u32; 3]>,
}

impl FaceTriangles {
    /// The triangles of every face of `mesh` (degenerate ones dropped).
    pub fn of(mesh: &Mesh) -> FaceTriangles {
        let mut out = FaceTriangles {
            starts: Vec::with_capacity(mesh.faces.len() + 1),
            tris: Vec::with_capacity(mesh.faces.len()),
        };
        out.starts.push(0);
        for f in &mesh.faces {
            let v = &f.vertices;
            let pts: Vec<P3> = v.iter().map(|&k| mesh.vertices[k as usize]).collect();
            if v.len() == 3 {
                out.tris.push([v[0], v[1], v[2]]);
            } else {
                for [a, b, c] in ear_clip(&pts, &newell(&pts)) {
                    out.tris.push([v[a], v[b], v[c]]);
                }
            }
            out.starts.push(out.tris.len() as u32);
        }
        out
    }

    /// The triangles of face `f`.
    pub fn of_face(&self, f: u32) -> &[[u32; 3]] {
        &self.tris[self.starts[f as usize] as usize..self.starts[f as usize + 1] as usize]
    }
}

/// A mesh placed in the world with its tree and triangles.
#[derive(Debug, Clone, Copy)]
pub struct Placed<'a> {
    /// The mesh (its own frame).
    pub mesh: &'a Mesh,
    /// Its object tree.
    pub tree: &'a ObjectTree,
    /// Its faces' triangles.
    pub tris: &'a FaceTriangles,
    /// Its placement: own frame to world.
    pub transform: M4,
}

impl Placed<'_> {
    /// World triangle `t` (world coordinates as [`crate::scene::Leaf::world_vertex`] gives them).
    fn triangle(&self, t: &[u32; 3]) -> [P3; 3] {
        t.map(|v| {
            self.transform
                .transform_point(&self.mesh.vertices[v as usize])
        })
    }

    /// Node `n`'s CBOX in the world: centre and three half-edge vectors.
    fn oriented(&self, n: u32) -> Oriented {
        let b = &self.tree.nodes[n as usize].cbox;
        let half = (b.hi - b.lo) * 0.5;
        let l = self.transform.fixed_view::<3, 3>(0, 0);
        Oriented {
            centre: self
                .transform
                .transform_point(&P3::from((b.lo.coords + b.hi.coords) * 0.5)),
            axes: [0, 1, 2].map(|k| l.column(k) * half[k]),
        }
    }
}

/// A parallelepiped: centre and half-edge vectors.
#[derive(Debug, Clone, Copy)]
struct Oriented {
    centre: P3,
    axes: [V3; 3],
}

impl Oriented {
    /// Half the extent along `n` (unnormalised).
    fn radius(&self, n: &V3) -> f64 {
        self.axes.iter().map(|a| a.dot(n).abs()).sum()
    }

    /// A size measure (squared half-diagonal), to choose which node to descend.
    fn size(&self) -> f64 {
        self.axes.iter().map(|a| a.norm_squared()).sum()
    }
}

/// True when the two parallelepipeds are apart along one of the 15 axes (with margin).
fn apart(a: &Oriented, b: &Oriented) -> bool {
    let d = b.centre - a.centre;
    let test = |n: V3| {
        let (ra, rb, dd) = (a.radius(&n), b.radius(&n), d.dot(&n).abs());
        dd > (ra + rb) + MARGIN * (ra + rb + dd)
    };
    let face = |o: &Oriented, i: usize| o.axes[(i + 1) % 3].cross(&o.axes[(i + 2) % 3]);
    (0..3).any(|i| test(face(a, i)))
        || (0..3).any(|i| test(face(b, i)))
        || (0..3).any(|i| (0..3).any(|j| test(a.axes[i].cross(&b.axes[j]))))
}

/// What a walk did.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct CollideStats {
    /// Pairs of nodes whose bounding volumes were tested (the paper's nodes traversed).
    pub bv_tests: u64,
    /// Exact triangle-triangle tests.
    pub triangle_tests: u64,
}

impl std::ops::AddAssign for CollideStats {
    fn add_assign(&mut self, o: CollideStats) {
        self.bv_tests += o.bv_tests;
        self.triangle_tests += o.triangle_tests;
    }
}

/// True when some face of `a` meets some face of `b` (closed sets: touching counts).
pub fn collide(a: &Placed, b: &Placed, stats: &mut CollideStats) -> bool {
    if a.tree.nodes.is_empty() || b.tree.nodes.is_empty() {
        return false;
    }
    let mut stack = vec![(0u32, 0u32)];
    while let Some((na, nb)) = stack.pop() {
        stats.bv_tests += 1;
        let (oa, ob) = (a.oriented(na), b.oriented(nb));
        if apart(&oa, &ob) {
            continue;
        }
        let (ka, kb) = (
            a.tree.nodes[na as usize].children,
            b.tree.nodes[nb as usize].children,
        );
        match (ka, kb) {
            (None, None) => {
                if leaves_meet(a, na, b, nb, stats) {
                    return true;
                }
            }
            (Some([l, r]), None) => stack.extend([(r, nb), (l, nb)]),
            (None, Some([l, r])) => stack.extend([(na, r), (na, l)]),
            (Some([l, r]), Some([p, q])) => {
                if oa.size() >= ob.size() {
                    stack.extend([(r, nb), (l, nb)]);
                } else {
                    stack.extend([(na, q), (na, p)]);
                }
            }
        }
    }
    false
}

/// The same answer as [`collide`] without trees, for checking: every world triangle of each
/// mesh that meets the other's world CBOX, swept along x, each overlapping pair tested exactly.
pub fn collide_brute(a: &Placed, b: &Placed, stats: &mut CollideStats) -> bool {
    let world = |p: &Placed| -> Vec<([P3; 3], Box3)> {
        p.tris
            .tris
            .iter()
            .map(|t| p.triangle(t))
            .filter(proper)
            .map(|t| (t, Box3::from_points(t.iter())))
            .collect()
    };
    let (ta, tb) = (world(a), world(b));
    let hull = |v: &[([P3; 3], Box3)]| v.iter().fold(Box3::empty(), |h, t| h.union(&t.1));
    let meets = |x: &Box3, y: &Box3| (0..3).all(|k| x.lo[k] <= y.hi[k] && y.lo[k] <= x.hi[k]);
    let (ha, hb) = (hull(&ta), hull(&tb));
    let near = |v: Vec<([P3; 3], Box3)>, other: &Box3| {
        let mut v: Vec<_> = v.into_iter().filter(|t| meets(&t.1, other)).collect();
        v.sort_by(|x, y| x.1.lo.x.total_cmp(&y.1.lo.x));
        v
    };
    let (na, nb) = (near(ta, &hb), near(tb, &ha));
    let mut start = 0;
    for (t, bt) in &na {
        while start < nb.len() && nb[start].1.hi.x < bt.lo.x {
            start += 1;
        }
        for (u, bu) in &nb[start..] {
            if bu.lo.x > bt.hi.x {
                break;
            }
            if meets(bt, bu) {
                stats.triangle_tests += 1;
                if triangles_intersect(t, u) {
                    return true;
                }
            }
        }
    }
    false
}

/// Exact tests of every triangle pair of two leaves.
fn leaves_meet(a: &Placed, na: u32, b: &Placed, nb: u32, stats: &mut CollideStats) -> bool {
    let tb: Vec<[P3; 3]> = b
        .tree
        .faces_of(nb)
        .iter()
        .flat_map(|&f| b.tris.of_face(f))
        .map(|t| b.triangle(t))
        .filter(proper)
        .collect();
    let boxes: Vec<Box3> = tb.iter().map(|t| Box3::from_points(t.iter())).collect();
    for &f in a.tree.faces_of(na) {
        for t in a.tris.of_face(f) {
            let ta = a.triangle(t);
            if !proper(&ta) {
                continue;
            }
            let ba = Box3::from_points(ta.iter());
            for (u, bu) in tb.iter().zip(&boxes) {
                if (0..3).any(|k| ba.lo[k] > bu.hi[k] || bu.lo[k] > ba.hi[k]) {
                    continue;
                }
                stats.triangle_tests += 1;
                if triangles_intersect(&ta, u) {
                    return true;
                }
            }
        }
    }
    false
}

/// True for a triangle with area in the world (degenerate ones are left out, as by the
/// brute-force comparison).
fn proper(p: &[P3; 3]) -> bool {
    (p[1] - p[0]).cross(&(p[2] - p[0])) != V3::zeros()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::prepare::trees::bvtree::HierarchyKind;
    use crate::scene::Face;

    /// A closed octahedron of radius 1 at the origin.
    fn octahedron() -> Mesh {
        let v = [
            [1., 0., 0.],
            [-1., 0., 0.],
            [0., 1., 0.],
            [0., -1., 0.],
            [0., 0., 1.],
            [0., 0., -1.],
        ]
        .map(|c| P3::new(c[0], c[1], c[2]));
        let f = [
            [0, 2, 4],
            [2, 1, 4],
            [1, 3, 4],
            [3, 0, 4],
            [2, 0, 5],
            [1, 2, 5],
            [3, 1, 5],
            [0, 3, 5],
        ];
        Mesh {
            vertices: v.to_vec(),
            faces: f.iter().map(Face::new).collect(),
            closed: true,
            solidity: None,
            caps: Vec::new(),
            proven: None,
            pieces: None,
        }
    }

    #[test]
    fn octahedra_meet_touch_and_part() {
        let m = octahedron();
        let tris = FaceTriangles::of(&m);
        let tree = ObjectTree::build(&m, HierarchyKind::Median);
        let at = |x: f64, rot: f64| Placed {
            mesh: &m,
            tree: &tree,
            tris: &tris,
            transform: nalgebra::Translation3::new(x, 0., 0.).to_homogeneous()
                * nalgebra::Rotation3::from_axis_angle(&V3::z_axis(), rot).to_homogeneous(),
        };
        let mut s = CollideStats::default();
        assert!(collide(&at(0., 0.), &at(1.5, 0.), &mut s));
        // Tips touching at (1, 0, 0): closed sets meet.
        assert!(collide(&at(0., 0.), &at(2., 0.), &mut s));
        assert!(!collide(&at(0., 0.), &at(2.0001, 0.), &mut s));
        // Turned about z, 2.5 apart: each lies within 1 of its centre.
        assert!(!collide(&at(0., 0.), &at(2.5, 0.3), &mut s));
        assert!(s.bv_tests > 0 && s.triangle_tests > 0);
        for (x, r) in [(1.5, 0.), (2., 0.), (2.0001, 0.), (2.5, 0.3), (1.9, 1.0)] {
            let (p, q) = (at(0., 0.), at(x, r));
            assert_eq!(
                collide(&p, &q, &mut s),
                collide_brute(&p, &q, &mut s),
                "{x} {r}"
            );
        }
    }

    #[test]
    fn oriented_boxes_apart_only_when_a_plane_separates_them() {
        let unit = |c: [f64; 3], axes: [V3; 3]| Oriented {
            centre: P3::new(c[0], c[1], c[2]),
            axes,
        };
        let id = [V3::x(), V3::y(), V3::z()];
        assert!(!apart(&unit([0., 0., 0.], id), &unit([2., 0., 0.], id)));
        assert!(apart(&unit([0., 0., 0.], id), &unit([2.001, 0., 0.], id)));
        // A cube turned 45° about z reaches √2 along x: at 2.4 it meets, at 2.42 not.
        let r = std::f64::consts::FRAC_1_SQRT_2;
        let turned = [V3::new(r, r, 0.), V3::new(-r, r, 0.), V3::z()];
        assert!(!apart(
            &unit([0., 0., 0.], id),
            &unit([2.4, 0., 0.], turned)
        ));
        assert!(apart(
            &unit([0., 0., 0.], id),
            &unit([2.42, 0., 0.], turned)
        ));
        // Scaled axes (a placement with scaling): half-widths 2 along x.
        let wide = [V3::x() * 2.0, V3::y(), V3::z()];
        assert!(!apart(&unit([0., 0., 0.], wide), &unit([3., 0., 0.], id)));
        assert!(apart(&unit([0., 0., 0.], wide), &unit([3.01, 0., 0.], id)));
    }
}
