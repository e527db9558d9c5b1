//! Plates: faces of many corners, strictly convex, that the solidity test meets as wholes, so the pairs of their many triangles with their neighbours' are never
//! enumerated one by one (a 65536-gon cap against its 65536 side quads made millions).
//!
//! The argument. Let F be a face whose corners all lie on one plane P (exact orient3d) and
//! whose projection is strictly convex (exact orient2d), triangulated with corners of F only.
//! Let u be a triangle of another face such that
//! - each corner of u is either a corner of F (the same vertex index) or strictly on one
//!   side of P, the same side for all of them;
//! - u has at most two corners of F, and when two, they are consecutive in F (an edge).
//!
//! Then u ∩ P is the hull of u's corners on F: nothing, a corner p, or an edge pq of F. A
//! triangle t of F meets the line of an edge of F only in that edge (F is strictly convex),
//! and holds a corner of F only as one of its own corners (corners of F are extreme points),
//! so t ∩ u lies in the corners and edge that t and u share: the pair does not cross. Only
//! triangles not so placed are tested against F's triangles, pair by pair.
//!
//! A strictly convex face whose corners are not exactly on one plane (a turned cap: rounding
//! moves them off it) is a plate too, met through its slab ([`super::slab`]: the range of
//! n·x over its corners, rounding bounded). A triangle wholly beyond the slab cannot meet
//! it. A triangle standing on an edge pq (or a corner p) of it, the rest beyond the slab,
//! meets the slab only in a sliver by pq, inside a box B. In the projection along the
//! plate's dominant axis (exact coordinates) the plate is a strictly convex polygon Q, and
//! a triangle of the plate without p or q as corners projects into the hull of Q's other
//! corners, whose edge nearest pq is the chord from p's predecessor to q's successor: when
//! B's projected rectangle lies strictly on p's side of that chord, only the plate's
//! triangles at p and q can meet the triangle, and only they are tested.

use std::ops::Range;

use rayon::prelude::*;

use crate::geom::box_tree::BoxTree;
use crate::geom::{newell, orient2d, orient3d, Box3, P3};
use crate::scene::triangulate::{projection_axes, strictly_convex_face};
use crate::scene::Mesh;

use super::slab::Slab;
use super::{Tri, Tris};

/// Faces of more corners than this are plates when strictly convex; smaller ones go through
/// the grid with everything else.
pub(super) const PLATE_ABOVE: usize = 64;

/// A plate and where its triangles are.
pub(super) struct Plate {
    /// Its triangles (contiguous in the surface's list).
    pub(super) tris: Range<u32>,
    /// The box of its corners.
    pub(super) bounds: Box3,
    /// Three corners spanning its plane, when every corner lies exactly on it.
    plane: Option<[P3; 3]>,
    /// The range of n·x over its corners.
    slab: Slab,
    /// (vertex index, position in the face) of every corner, by vertex index.
    corners: Vec<(u32, u32)>,
    /// Its corners in order, projected along its dominant axis (exact coordinates).
    ring: Vec<[f64; 2]>,
    /// The coordinates kept by that projection.
    axes: (usize, usize),
}

/// The plates of `mesh`, by face, given its surface triangles and their faces (ascending).
pub(super) fn find(mesh: &Mesh, face_of: &[u32]) -> Vec<Plate> {
    let mut out = Vec::new();
    let mut start = 0;
    while start < face_of.len() {
        let f = face_of[start];
        let end = start + face_of[start..].iter().take_while(|&&g| g == f).count();
        let v = &mesh.faces[f as usize].vertices;
        if v.len() > PLATE_ABOVE {
            let pts: Vec<P3> = v.iter().map(|&k| mesh.vertices[k as usize]).collect();
            let normal = newell(&pts);
            if strictly_convex_face(&pts, &normal) {
                let mut corners: Vec<(u32, u32)> =
                    v.iter().enumerate().map(|(i, &k)| (k, i as u32)).collect();
                corners.sort_unstable();
                let (x, y, _) = projection_axes(&normal);
                out.push(Plate {
                    tris: start as u32..end as u32,
                    bounds: Box3::from_points(pts.iter()),
                    plane: planar(&pts),
                    slab: Slab::of(&pts, normal),
                    corners,
                    ring: pts.iter().map(|p| [p[x], p[y]]).collect(),
                    axes: (x, y),
                });
            }
        }
        start = end;
    }
    out
}

/// Three corners spanning the plane of `pts` when every corner lies exactly on it. A face in
/// a coordinate plane (a primitive's cap) is known planar from one coordinate; any other is
/// checked with orient3d, corner by corner, on all threads.
fn planar(pts: &[P3]) -> Option<[P3; 3]> {
    let n = pts.len();
    let refs = [pts[0], pts[n / 3], pts[2 * n / 3]];
    let flat = |k: usize| pts.iter().all(|p| p[k] == pts[0][k]);
    if (0..3).any(flat) {
        return Some(refs);
    }
    let on = |p: &P3| orient3d(&refs[0], &refs[1], &refs[2], p) == 0.0;
    pts.par_iter().all(on).then_some(refs)
}

impl Plate {
    /// Exact: triangle `u` (of another face) is placed so that it crosses no triangle of the
    /// plate (the module's argument).
    pub(super) fn clear_of(&self, u: &Tri) -> bool {
        match &self.plane {
            Some(refs) => self.clear_of_plane(refs, u),
            None => self.slab.beyond(&u.p),
        }
    }

    /// [`Plate::clear_of`] for a plate exactly on one plane (the module's first argument).
    fn clear_of_plane(&self, refs: &[P3; 3], u: &Tri) -> bool {
        let mut on = [0u32; 3];
        let mut count = 0;
        let mut side = 0.0;
        for (k, p) in u.v.iter().zip(&u.p) {
            if let Ok(i) = self.corners.binary_search_by_key(k, |c| c.0) {
                on[count] = self.corners[i].1;
                count += 1;
                continue;
            }
            // (signum would call 0 positive.)
            let s = orient3d(&refs[0], &refs[1], &refs[2], p);
            if s == 0.0 || (side != 0.0 && (s > 0.0) != (side > 0.0)) {
                return false;
            }
            side = s;
        }
        let n = self.corners.len() as u32;
        match count {
            0 | 1 => true,
            2 => {
                let d = on[0].abs_diff(on[1]);
                d == 1 || d == n - 1
            }
            _ => false,
        }
    }

    /// The pairs (plate triangle, u) among `candidates` that `cross` says cross, for the
    /// candidates not [`Plate::clear_of`] the plate; `boxes` are every triangle's bounds.
    pub(super) fn crossings(
        &self,
        tris: &Tris,
        boxes: &[Box3],
        candidates: &[u32],
        cross: impl Fn(u32, u32) -> bool + Sync,
    ) -> Vec<(u32, u32)> {
        let unclear: Vec<u32> = candidates
            .par_iter()
            .copied()
            .filter(|&u| !self.clear_of(&tris.at(u)))
            .collect();
        if unclear.is_empty() {
            return Vec::new();
        }
        // Triangles standing on an edge or corner are tested against the plate's triangles
        // there; the rest against those whose boxes meet theirs. Each index is built only if
        // some triangle needs it.
        let (standing, loose): (Vec<_>, Vec<_>) = unclear
            .par_iter()
            .map(|&u| (u, self.standing_on(&tris.at(u))))
            .partition(|(_, on)| on.is_some());
        let test = |t: u32, u: u32| cross(t, u).then(|| (t.min(u), t.max(u)));
        let mut hits: Vec<(u32, u32)> = Vec::new();
        if !standing.is_empty() {
            let at = self.triangles_at(tris);
            let at_corner = |e: u32| {
                let from = at.partition_point(|x| x.0 < e);
                at[from..].iter().take_while(move |x| x.0 == e).map(|x| x.1)
            };
            hits.par_extend(standing.par_iter().flat_map_iter(|&(u, on)| {
                let [a, b] = on.expect("standing");
                let mut near: Vec<u32> = at_corner(a).chain(at_corner(b)).collect();
                near.sort_unstable();
                near.dedup();
                near.into_iter().filter_map(move |t| test(t, u))
            }));
        }
        if !loose.is_empty() {
            let own = &boxes[self.tris.start as usize..self.tris.end as usize];
            let tree = BoxTree::new(own);
            hits.par_extend(loose.par_iter().flat_map_iter(|&(u, _)| {
                let mut found = Vec::new();
                tree.any_meeting(own, &boxes[u as usize], |k| {
                    found.extend(test(self.tris.start + k, u));
                    false
                });
                found
            }));
        }
        hits
    }

    /// (corner position, plate triangle) for every corner of every plate triangle, sorted.
    fn triangles_at(&self, tris: &Tris) -> Vec<(u32, u32)> {
        let mut at: Vec<(u32, u32)> = (self.tris.start..self.tris.end)
            .flat_map(|t| {
                tris.corners[t as usize].map(|v| {
                    let i = self.corners.binary_search_by_key(&v, |c| c.0);
                    (i.map_or(u32::MAX, |i| self.corners[i].1), t)
                })
            })
            .collect();
        at.sort_unstable();
        at
    }

    /// The positions of the plate corners `u` stands on (an edge or one corner), when the
    /// plate's triangles without them cannot meet `u` (the module's slab argument); None
    /// when that is not shown.
    fn standing_on(&self, u: &Tri) -> Option<[u32; 2]> {
        let n = self.ring.len() as u32;
        let on: Vec<u32> =
            u.v.iter()
                .filter_map(|k| self.corners.binary_search_by_key(k, |c| c.0).ok())
                .map(|i| self.corners[i].1)
                .collect();
        // The corners in ring order: first, last (the same for one corner).
        let (a, b) = match on[..] {
            [a] => (a, a),
            [x, y] if (x + 1) % n == y => (x, y),
            [x, y] if (y + 1) % n == x => (y, x),
            _ => return None,
        };
        let (part, pad) = self.slab.part(&u.p)?;
        let (c1, c2) = (
            self.ring[((a + n - 1) % n) as usize],
            self.ring[((b + 1) % n) as usize],
        );
        let side = orient2d(c1, c2, self.ring[a as usize]);
        let (x, y) = self.axes;
        let beside = |p: [f64; 2]| {
            let s = orient2d(c1, c2, p);
            (s > 0.0 && side > 0.0) || (s < 0.0 && side < 0.0)
        };
        // Every corner of every point's padded square, projected.
        part.iter()
            .flat_map(|p| {
                [(-pad, -pad), (pad, -pad), (pad, pad), (-pad, pad)]
                    .map(|(dx, dy)| [p[x] + dx, p[y] + dy])
            })
            .all(beside)
            .then_some([a, b])
    }
}

#[cfg(test)]
mod tests {
    use super::super::{cross, crossing_pairs, examine, triangulate, Tri, Tris};
    use crate::count::Span;

    /// The triangles' corners and their faces of a mesh with no flat face.
    fn surface_corners(m: &Mesh) -> Option<(Vec<[u32; 3]>, Vec<u32>)> {
        let (tris, face_of, flat) = triangulate(m, Span::NONE);
        flat.is_empty().then_some((tris, face_of))
    }

    /// The triangles (with their points) and their faces of a mesh with no flat face.
    fn surface_triangles(m: &Mesh) -> Option<(Vec<Tri>, Vec<u32>)> {
        let (corners, face_of) = surface_corners(m)?;
        let tris = Tris {
            corners: &corners,
            points: &m.vertices,
        };
        Some((
            (0..tris.len() as u32).map(|t| tris.at(t)).collect(),
            face_of,
        ))
    }
    use super::*;
    use crate::geom::PolyMesh;
    use crate::scene::cleanup::{cleanup, Origin};
    use crate::scene::Solidity;

    fn mesh(pts: &[P3], faces: &[Vec<u32>]) -> Mesh {
        let raw = PolyMesh::new(pts.to_vec(), faces.to_vec());
        let origin = Origin {
            file: std::path::Path::new("t"),
            face_pos: &[],
        };
        cleanup(&raw, &origin, &mut Vec::new(), crate::count::Count::NONE).unwrap()
    }

    /// A prism over a regular `n`-gon of radius 1, from z = 0 to z = 1, each point passed
    /// through `place`: its corners and outward faces.
    fn prism(n: u32, place: impl Fn(P3) -> P3) -> (Vec<P3>, Vec<Vec<u32>>) {
        let mut pts = Vec::new();
        for z in [0.0, 1.0] {
            for i in 0..n {
                let a = i as f64 * std::f64::consts::TAU / n as f64;
                pts.push(place(P3::new(a.cos(), a.sin(), z)));
            }
        }
        let mut faces = vec![(0..n).rev().collect::<Vec<u32>>(), (n..2 * n).collect()];
        for i in 0..n {
            let j = (i + 1) % n;
            faces.push(vec![i, j, n + j, n + i]);
        }
        (pts, faces)
    }

    /// Adds a tetrahedron (outward) with corners `c` to a mesh's lists.
    fn add_tet(pts: &mut Vec<P3>, faces: &mut Vec<Vec<u32>>, c: [P3; 4]) {
        let b = pts.len() as u32;
        pts.extend(c);
        for f in [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]] {
            faces.push(f.iter().map(|&k| b + k).collect());
        }
    }

    /// Every crossing pair, by testing every two triangles of different faces.
    fn brute(m: &Mesh) -> Vec<(u32, u32)> {
        let (tris, face_of) = surface_triangles(m).unwrap();
        let mut out = Vec::new();
        for i in 0..tris.len() {
            for j in i + 1..tris.len() {
                if face_of[i] != face_of[j] && cross(&tris[i], &tris[j]) {
                    out.push((i as u32, j as u32));
                }
            }
        }
        out
    }

    fn pairs(m: &Mesh) -> Vec<(u32, u32)> {
        let (tris, face_of) = surface_corners(m).unwrap();
        // One piece: every pair is tested, as `brute` tests them.
        let span = Span::NONE;
        crossing_pairs(
            m,
            &tris,
            &face_of,
            &vec![0; m.faces.len()],
            |_| true,
            None,
            span,
        )
    }

    fn plates_of(m: &Mesh) -> usize {
        let (_, face_of) = surface_triangles(m).unwrap();
        find(m, &face_of).len()
    }

    #[test]
    fn a_prism_has_two_plates_and_no_crossing() {
        let (pts, faces) = prism(100, |p| p);
        let m = mesh(&pts, &faces);
        assert_eq!(plates_of(&m), 2);
        assert!(pairs(&m).is_empty());
        assert!(brute(&m).is_empty());
        assert_eq!(examine(&m).solidity, Solidity::Solid);
    }

    #[test]
    fn a_tilted_prism_has_slab_plates_and_is_solid() {
        // Rotated corners are not exactly on one plane: the caps are plates met through their
        // slabs. The other cap lies beyond each slab; every side triangle stands on an edge
        // or a corner and is tested against the cap's triangles there only.
        let r = nalgebra::Rotation3::from_euler_angles(0.3, 0.7, 0.2);
        let (pts, faces) = prism(80, |p| r * p);
        let m = mesh(&pts, &faces);
        let (tris, face_of) = surface_triangles(&m).unwrap();
        let plates = find(&m, &face_of);
        assert_eq!(plates.len(), 2);
        assert!(plates.iter().all(|p| p.plane.is_none()));
        let (a, b) = (&plates[0], &plates[1]);
        assert!(a.tris.clone().all(|t| b.clear_of(&tris[t as usize])));
        assert!(b.tris.clone().all(|t| a.clear_of(&tris[t as usize])));
        let sides = (0..tris.len() as u32).filter(|t| !a.tris.contains(t) && !b.tris.contains(t));
        for t in sides {
            for p in [a, b] {
                let on = p.standing_on(&tris[t as usize]).expect("stands on the cap");
                assert!(on.iter().all(|&k| k < 80));
            }
        }
        assert!(pairs(&m).is_empty());
        assert_eq!(examine(&m).solidity, Solidity::Solid);
    }

    #[test]
    fn what_pierces_or_lies_on_a_plate_is_found() {
        let cases: [[P3; 4]; 3] = [
            // Through the top cap.
            [
                P3::new(0.1, 0.1, 0.5),
                P3::new(0.4, 0.1, 0.5),
                P3::new(0.1, 0.4, 0.5),
                P3::new(0.2, 0.2, 1.5),
            ],
            // A face lying in the top cap's plane, inside it (coplanar: not clear).
            [
                P3::new(0.1, 0.1, 1.0),
                P3::new(0.4, 0.1, 1.0),
                P3::new(0.1, 0.4, 1.0),
                P3::new(0.2, 0.2, 1.5),
            ],
            // Standing on the top cap from above, a corner on its interior.
            [
                P3::new(0.0, 0.0, 1.0),
                P3::new(0.4, 0.1, 1.3),
                P3::new(0.1, 0.4, 1.3),
                P3::new(0.2, 0.2, 1.5),
            ],
        ];
        for (k, c) in cases.into_iter().enumerate() {
            let (mut pts, mut faces) = prism(100, |p| p);
            add_tet(&mut pts, &mut faces, c);
            let m = mesh(&pts, &faces);
            assert_eq!(plates_of(&m), 2);
            let b = brute(&m);
            assert!(!b.is_empty(), "case {k}");
            assert_eq!(pairs(&m), b, "case {k}");
            // The tetrahedron is a piece of its own: pieces may pass through one another.
            assert_eq!(examine(&m).solidity, Solidity::Solid, "case {k}");
        }
    }

    #[test]
    fn neighbours_clear_of_a_plate_and_one_that_is_not() {
        let (pts, faces) = prism(100, |p| p);
        let m = mesh(&pts, &faces);
        let (tris, face_of) = surface_triangles(&m).unwrap();
        let plates = find(&m, &face_of);
        let top = plates
            .iter()
            .find(|p| p.bounds.lo.z == 1.0)
            .expect("the top cap is a plate");
        // Every side triangle is clear of the cap (an edge of it, or a corner, and the rest
        // strictly below).
        let sides =
            (0..tris.len()).filter(|&t| !plates.iter().any(|p| p.tris.contains(&(t as u32))));
        for t in sides {
            assert!(top.clear_of(&tris[t]), "side triangle {t}");
        }
        // A triangle on two corners of the cap that are not neighbours spans a chord: it
        // may cut the cap's triangles, so it is not clear.
        let v = |k: usize| m.faces[1].vertices[k];
        let chord = Tri {
            v: [v(0), v(50), u32::MAX],
            p: [
                m.vertices[v(0) as usize],
                m.vertices[v(50) as usize],
                P3::new(0.0, 0.0, 0.0),
            ],
        };
        assert!(!top.clear_of(&chord));
        // The same chord standing up from two neighbouring corners is clear.
        let edge = Tri {
            v: [v(0), v(1), u32::MAX],
            p: [
                m.vertices[v(0) as usize],
                m.vertices[v(1) as usize],
                P3::new(0.0, 0.0, 0.0),
            ],
        };
        assert!(top.clear_of(&edge));
    }

    #[test]
    fn random_tetrahedra_near_the_caps_agree_with_every_pair_tested() {
        let mut rng = crate::geom::rng::XorShift::new(0x9e37_79b9);
        let n = 70;
        let turn = nalgebra::Rotation3::from_euler_angles(0.1, -0.4, 0.9);
        for case in 0..60 {
            let (mut pts, mut faces) = prism(n, |p| p);
            for _ in 0..3 {
                let mut c = [P3::origin(); 4];
                for (k, p) in c.iter_mut().enumerate() {
                    *p = match rng.below(4) {
                        // Exactly in a cap's plane, or on a cap's corner.
                        0 => P3::new(rng.range(-1.0, 1.0), rng.range(-1.0, 1.0), 1.0),
                        1 => pts[n as usize + rng.below(n as usize)],
                        _ => P3::new(
                            rng.range(-1.2, 1.2),
                            rng.range(-1.2, 1.2),
                            rng.range(0.6, 1.4) + k as f64 * 1e-3,
                        ),
                    };
                }
                add_tet(&mut pts, &mut faces, c);
            }
            // A third of the cases turned: plates not exactly planar, met through slabs.
            if case % 3 == 2 {
                pts.iter_mut().for_each(|p| *p = turn * *p);
            }
            let m = mesh(&pts, &faces);
            let Some(_) = surface_triangles(&m) else {
                continue; // a flat tetrahedron: nothing to compare
            };
            assert_eq!(pairs(&m), brute(&m), "case {case}");
        }
    }
}
