//! Proven solids: a mesh whose back faces may be culled, decided exactly once per prototype.
//!
//! Culling a back face is safe when the faces bound their inside the way the culling
//! argument needs (docs/numerics.md, "Back-face culling"): with w(x) the winding number of
//! one edge-connected piece of the surface around x, a back face of that piece is hidden by
//! a front face of the same piece whenever w ≥ 0 everywhere and the eye lies where w = 0.
//! Pieces may pass through one another (they only hide more). A mesh is proven
//! [`Solidity::Solid`] when
//! - every edge is used by exactly two faces, once in each direction (closed, consistently
//!   oriented: w is an integer off the surface);
//! - every face triangulates into non-degenerate triangles (exact ear clipping);
//! - no two triangles of one edge-connected piece meet except in the vertices and edges they
//!   share (exact triangle tests over a grid broad phase; long planar convex faces met as
//!   wholes, `solidity/plates.rs`): each piece is embedded, so its w is 0 or ±1;
//! - every edge-connected piece has positive signed volume (outward), decided exactly: then
//!   its w is 0 or +1.
//!
//! An open mesh is then offered to [`self::caps`]: with its holes capped it may still be
//! proven a solid, and its back faces culled away from the caps.
//!
//! Anything else keeps two-sided faces: correct, only slower.

use std::collections::HashMap;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::Arc;

use num_bigint::BigInt;
use num_traits::{Signed, Zero};

use rayon::prelude::*;

pub(crate) mod caps;
pub(crate) mod pieces;

use pieces::Crossings;
mod plates;
mod slab;
mod slits;

use crate::count::{Count, Share, Span};
use crate::geom::box_pairs::{filter_map_pairs, overlap, Bounds3};
use crate::geom::box_tree::BoxTree;
use crate::geom::tri_intersect::{plane_axes, segment_meets_triangle, triangles_intersect};
use crate::geom::{newell, orient2d, orient3d, Box3, P3};
use crate::scene::topology::{Pieces, Topology, Traversals};
use crate::scene::triangulate::ear_clip_simple;
use crate::scene::{CapFailure, Content, Face, Mesh, Object, Solidity};

/// A triangle of a mesh's surface: vertex indices and their points.
#[derive(Debug, Clone, Copy)]
struct Tri {
    v: [u32; 3],
    p: [P3; 3],
}

/// A surface's triangles as the tests read them: each one's corners (12 bytes a triangle,
/// kept), its points read from the mesh when a test asks ([`Tris::at`]).
#[derive(Debug, Clone, Copy)]
struct Tris<'a> {
    corners: &'a [[u32; 3]],
    points: &'a [P3],
}

impl Tris<'_> {
    /// How many triangles.
    fn len(&self) -> usize {
        self.corners.len()
    }

    /// Triangle `t` with its points.
    fn at(&self, t: u32) -> Tri {
        let v = self.corners[t as usize];
        Tri {
            v,
            p: v.map(|k| self.points[k as usize]),
        }
    }
}

#[cfg(test)]
/// Decides the solidity of one mesh (exact).
pub(crate) fn solidity(mesh: &Mesh) -> Solidity {
    examine(mesh).solidity
}

/// A closed mesh's surface as the solidity tests see it, built once and handed from test to
/// test: its triangles with each one's face, the faces that give none, and its pieces.
#[derive(Debug)]
pub(crate) struct Surface {
    /// Its triangles' corners (the points are the mesh's).
    tris: Vec<[u32; 3]>,
    face_of: Vec<u32>,
    /// Faces that are not simple or have a flat triangle (ascending): they give no triangles.
    flat: Vec<u32>,
    pieces: Pieces,
}

impl Surface {
    /// The surface of `mesh` (closed and consistent), filling `span`: most of it as the
    /// faces are triangulated, the rest as the pieces are found.
    fn of(mesh: &Mesh, pieces: Pieces, span: Span) -> Surface {
        let (tris, face_of, flat) = triangulate(mesh, span.span(0.0, 0.6));
        Surface {
            tris,
            face_of,
            flat,
            pieces,
        }
    }

    /// The edge-connected piece of face `f`.
    fn piece(&self, f: u32) -> usize {
        self.pieces.of_face[f as usize] as usize
    }

    /// The face pairs of one piece whose triangles cross, testing only pairs with a face
    /// passing `suspect`. `mesh` is the mesh this surface is of; the search fills `span`.
    pub(crate) fn crossing(
        &self,
        mesh: &Mesh,
        suspect: impl Fn(u32) -> bool + Sync,
        span: Span,
    ) -> Vec<[u32; 2]> {
        self.crossing_until(mesh, suspect, None, span)
    }

    /// [`Self::crossing`] with an early exit by `groups` of faces ([`examine_until`]).
    pub(crate) fn crossing_until(
        &self,
        mesh: &Mesh,
        suspect: impl Fn(u32) -> bool + Sync,
        groups: Option<&[u32]>,
        span: Span,
    ) -> Vec<[u32; 2]> {
        let face_of = &self.face_of;
        let groups = groups.map(|g| Groups::new(face_of.iter().map(|&f| g[f as usize]).collect()));
        crossing_pairs(
            mesh,
            &self.tris,
            face_of,
            &self.pieces.of_face,
            |t| suspect(face_of[t as usize]),
            groups.as_ref(),
            span,
        )
        .into_iter()
        .map(|(i, j)| [face_of[i as usize], face_of[j as usize]])
        .collect()
    }

    /// By piece: whether its signed volume is positive (exact), decided for the pieces
    /// passing `wanted` (false for the others). `mesh` is the mesh this surface is of.
    fn outward(&self, mesh: &Mesh, wanted: impl Fn(usize) -> bool) -> Vec<bool> {
        let at = |t: usize| self.tris[t].map(|k| mesh.vertices[k as usize]);
        if self.pieces.count == 1 {
            // One piece (most closed meshes): every triangle, summed on all threads.
            return vec![wanted(0) && volume_sign_of(self.tris.len(), at) > 0];
        }
        let mut by_piece: Vec<Vec<usize>> = vec![Vec::new(); self.pieces.count];
        for (t, &f) in self.face_of.iter().enumerate() {
            by_piece[self.piece(f)].push(t);
        }
        by_piece
            .iter()
            .enumerate()
            .map(|(k, ts)| wanted(k) && volume_sign(ts.iter().map(|&t| at(t))) > 0)
            .collect()
    }
}

/// A mesh's solidity and, where it fails on faces, which ones.
#[derive(Debug)]
pub(crate) struct Examined {
    /// The decision.
    pub(crate) solidity: Solidity,
    /// For [`Solidity::Degenerate`]: the faces that are not simple or have a flat triangle.
    pub(crate) degenerate: Vec<u32>,
    /// For [`Solidity::SelfIntersecting`]: the faces of every crossing pair of triangles
    /// tested (empty after an [`Solidity::InsideOut`] or [`Solidity::Solid`]: none crossed).
    pub(crate) crossing: Vec<[u32; 2]>,
    /// The surface tested, where the mesh is closed and consistent.
    pub(crate) surface: Option<Surface>,
    /// Where the mesh is open ([`Solidity::Open`]): the traversals of its edges, for
    /// [`caps::capping_open`] to find the holes and make the capped mesh's by a merge.
    pub(crate) open: Option<Traversals>,
}

#[cfg(test)]
/// [`solidity`], saying which faces fail.
pub(crate) fn examine(mesh: &Mesh) -> Examined {
    examine_where(mesh, |_| true)
}

#[cfg(test)]
/// [`examine`], testing for crossings only the pairs of triangles where one's face passes
/// `suspect` (the others known not to cross).
pub(crate) fn examine_where(mesh: &Mesh, suspect: impl Fn(u32) -> bool + Sync) -> Examined {
    let traversals = Traversals::of(&mesh.faces);
    examine_until(mesh, traversals, suspect, None, Span::NONE)
}

/// [`examine_where`], where the suspect faces fall in `groups` (by face, [`NO_GROUP`] for
/// none): once a pair of a group is found crossing, its other pairs are not tested. Then the
/// crossing list holds at least one pair of every group that crosses and none of any other,
/// but not every pair, and the count in [`Solidity::SelfIntersecting`] is of the pairs found.
/// The tests fill `span` in the shares of time they take on large meshes: the edges matched,
/// the triangles made, then the pairs searched (most of it, unless the search is only of a
/// few suspects in `groups`, which is quick). `traversals` are those of `mesh`'s faces
/// ([`Traversals::of`], or made by a merge): one sort of the edges for both the topology
/// and, of a closed mesh, its pieces.
pub(crate) fn examine_until(
    mesh: &Mesh,
    traversals: Traversals,
    suspect: impl Fn(u32) -> bool + Sync,
    groups: Option<&[u32]>,
    span: Span,
) -> Examined {
    let mut e = Examined {
        solidity: Solidity::Solid,
        degenerate: Vec::new(),
        crossing: Vec::new(),
        surface: None,
        open: None,
    };
    // Where the edges matched and the triangles made end, as fractions of the span.
    let (matched, made) = if groups.is_some() {
        (0.35, 0.9)
    } else {
        (0.12, 0.3)
    };
    span.reach(matched);
    match traversals.topology() {
        Topology::Open => {
            e.solidity = Solidity::Open(CapFailure::NotTried);
            e.open = Some(traversals);
        }
        Topology::Inconsistent => e.solidity = Solidity::Inconsistent,
        Topology::Closed => {
            // Freed before the triangles are made.
            let pieces = traversals.pieces();
            drop(traversals);
            let surface = Surface::of(mesh, pieces, span.span(matched, made));
            span.reach(made);
            if !surface.flat.is_empty() {
                e.solidity = Solidity::Degenerate;
                e.degenerate = surface.flat.clone();
            } else {
                let searched = span.span(made, 0.98);
                e.crossing = surface.crossing_until(mesh, suspect, groups, searched);
                if !e.crossing.is_empty() {
                    e.solidity = Solidity::SelfIntersecting(e.crossing.len() as u64);
                } else if !surface.outward(mesh, |_| true).iter().all(|&o| o) {
                    e.solidity = Solidity::InsideOut;
                }
            }
            e.surface = Some(surface);
        }
    }
    span.finish();
    e
}

/// Fills [`Mesh::solidity`] of `mesh`, and for an open mesh whose holes cap into a solid
/// ([`self::caps`]), its [`Mesh::caps`]; where the whole is not a solid, the pieces that
/// are ([`Mesh::proven`], [`pieces`]) with their caps.
///
/// Its faces go to `done` as the tests are done: a closed mesh's test is nearly all of the
/// work; an open mesh's is only its edges matched (a tenth), and its capping the rest.
pub(crate) fn decide(mesh: &mut Mesh, done: Count) {
    let n = mesh.faces.len();
    let share = Share::new(done, n);
    let test = if mesh.closed { 0.97 } else { 0.1 };
    let traversals = Traversals::of(&mesh.faces);
    let whole = examine_until(mesh, traversals, |_| true, None, share.span(0.0, test));
    let pieces = share.span(0.97, 1.0);
    let (s, proven) = match whole.solidity {
        // `examine` found the edges open (only that makes the whole `Open`), and kept them.
        Solidity::Open(_) => match self::caps::capping_open(
            mesh,
            &whole.open.unwrap_or_else(|| Traversals::of(&mesh.faces)),
            share.span(test, 0.97),
        ) {
            Ok(caps) => {
                mesh.caps = caps.triangles;
                (Solidity::Capped(caps.loops), None)
            }
            Err((why, failed)) => (
                Solidity::Open(why),
                failed.and_then(|f| {
                    pieces::proven_pieces(&f.mesh, &f.surface, n, f.crossings(), pieces)
                }),
            ),
        },
        s @ (Solidity::SelfIntersecting(_) | Solidity::InsideOut | Solidity::Degenerate) => {
            // Past the flat faces every pair was tested: the crossing list is complete.
            let known = if s == Solidity::Degenerate {
                Crossings::Some(&[])
            } else {
                Crossings::All(&whole.crossing)
            };
            let proof = whole
                .surface
                .as_ref()
                .and_then(|surface| pieces::proven_pieces(mesh, surface, n, known, pieces));
            (s, proof)
        }
        s => {
            // A solid's pieces, kept for the line drawing (they are the mesh's own).
            if s.is_solid() {
                mesh.pieces = whole.surface.map(|surface| Arc::new(surface.pieces));
            }
            (s, None)
        }
    };
    if let Some((p, caps)) = proven {
        mesh.proven = Some(p);
        mesh.caps = caps;
    }
    mesh.solidity = Some(s);
    share.finish();
}

/// Fills [`Mesh::solidity`] of every mesh below `root` that has none; each shared prototype
/// is decided once and stays shared.
///
/// Each mesh decided goes to `done` with its faces, as its share of the count fills.
pub(crate) fn mark_solids(root: &mut Object, done: Count) {
    let mut marked = HashMap::new();
    mark(root, &mut marked, done);
}

/// Prototypes already marked, by the address of the original.
type Marked = HashMap<usize, Arc<Object>>;

fn mark(obj: &mut Object, marked: &mut Marked, done: Count) {
    match &mut obj.content {
        Content::Mesh(m) => {
            if m.solidity.is_none() {
                decide(m, done);
            }
        }
        Content::Subobjects(subs) => subs.iter_mut().for_each(|s| mark(s, marked, done)),
        Content::Instance(i) => {
            let key = Arc::as_ptr(&i.prototype) as usize;
            let p = match marked.get(&key) {
                Some(p) => p.clone(),
                None => {
                    let mut copy = (*i.prototype).clone();
                    mark(&mut copy, marked, done);
                    let p = Arc::new(copy);
                    marked.insert(key, p.clone());
                    p
                }
            };
            i.prototype = p;
        }
    }
}

/// The surface as triangles (exact ear clipping of every face; a warped face's triangles are
/// the view's planar pieces), with each triangle's face, and the faces that give none (not
/// simple, or a flat triangle; ascending).
/// The chunks of faces fill `span` as they are done.
fn triangulate(mesh: &Mesh, span: Span) -> Triangulated {
    let done = span.steps(mesh.faces.len());
    let chunk = |(c, faces): (usize, &[Face])| {
        let mut part = (Vec::with_capacity(faces.len()), Vec::new(), Vec::new());
        for (k, f) in faces.iter().enumerate() {
            triangulate_face(mesh, f, (c * TRIANGULATED_CHUNK + k) as u32, &mut part);
        }
        done.add(faces.len());
        part
    };
    if mesh.faces.len() <= TRIANGULATED_CHUNK {
        // A small mesh stays off the thread pool (many one-box objects would each wait on it).
        return chunk((0, &mesh.faces));
    }
    // In chunks of faces on all threads, joined in face order: the same lists as one pass.
    let parts: Vec<Triangulated> = mesh
        .faces
        .par_chunks(TRIANGULATED_CHUNK)
        .enumerate()
        .map(chunk)
        .collect();
    // Joined on all threads, each few parts freed as soon as they are copied (at a million
    // faces the triangles and their parts were the prepare stage's peak, held together).
    let (mut tris, mut face_of, mut flat) = (Vec::new(), Vec::new(), Vec::new());
    for (t, f, b) in parts {
        tris.push(t);
        face_of.push(f);
        flat.push(b);
    }
    let (tris, (face_of, flat)) = rayon::join(
        || crate::chunked::concat_freeing(tris),
        || rayon::join(|| crate::chunked::concat_freeing(face_of), || flat.concat()),
    );
    (tris, face_of, flat)
}

/// A surface's triangles (their corners), each one's face, and the faces that give none.
type Triangulated = (Vec<[u32; 3]>, Vec<u32>, Vec<u32>);

/// Faces per chunk of [`triangulate`].
const TRIANGULATED_CHUNK: usize = 4096;

/// Appends face `k`'s triangles and their face to `out.0` and `out.1`, or `k` to `out.2`
/// when it gives none.
fn triangulate_face(mesh: &Mesh, f: &Face, k: u32, out: &mut Triangulated) {
    let (tris, face_of, bad) = out;
    let at = |v: u32| mesh.vertices[v as usize];
    if let [a, b, c] = f.vertices[..] {
        // A triangle, the usual case: no ear clipping, no allocation.
        if degenerate(&[at(a), at(b), at(c)]) {
            bad.push(k);
        } else {
            tris.push([a, b, c]);
            face_of.push(k);
        }
        return;
    }
    let pts: Vec<P3> = f.vertices.iter().map(|&v| at(v)).collect();
    let Some(local) = ear_clip_simple(&pts, &newell(&pts)) else {
        bad.push(k);
        return;
    };
    if local.iter().any(|t| degenerate(&t.map(|i| pts[i]))) {
        // A face with a flat triangle gives none.
        bad.push(k);
    } else {
        tris.extend(local.iter().map(|t| t.map(|i| f.vertices[i])));
        face_of.resize(tris.len(), k);
    }
}

/// Exact: the three points are collinear (every coordinate-plane projection is degenerate).
pub(crate) fn degenerate(p: &[P3; 3]) -> bool {
    [(0, 1), (1, 2), (2, 0)]
        .iter()
        .all(|&(x, y)| orient2d([p[0][x], p[0][y]], [p[1][x], p[1][y]], [p[2][x], p[2][y]]) == 0.0)
}

/// The triangle pairs of one piece (`piece_of`, by face) with a triangle passing `suspect`
/// that meet other than in shared vertices and edges, ascending. Plates ([`plates`]: long planar convex faces) are met as
/// wholes; the other triangles pair up through the grid, or, with few suspects (a tenth of
/// the triangles or fewer), each suspect is scanned against every box.
///
/// Two triangles of one face (`face_of`) are never tested: they are lifts of triangles of one
/// exact triangulation of the face's projection (ear clipping, or a tiling proven exactly),
/// whose projections meet only in shared corners and edges, and the projection is one-to-one
/// on the face, so the lifts meet only there too.
fn crossing_pairs(
    mesh: &Mesh,
    tris: &[[u32; 3]],
    face_of: &[u32],
    piece_of: &[u32],
    suspect: impl Fn(u32) -> bool + Sync,
    groups: Option<&Groups>,
    span: Span,
) -> Vec<(u32, u32)> {
    let tris = Tris {
        corners: tris,
        points: &mesh.vertices,
    };
    // Per triangle on all threads (in order: an indexed collect; a small mesh off the pool).
    let boxes: Vec<Bounds3> = crate::chunked::map(tris.len(), |t| {
        let t = tris.at(t as u32);
        let lo = std::array::from_fn(|k| t.p[0][k].min(t.p[1][k]).min(t.p[2][k]));
        let hi = std::array::from_fn(|k| t.p[0][k].max(t.p[1][k]).max(t.p[2][k]));
        [lo, hi]
    });
    let is: Vec<bool> = crate::chunked::map(tris.len(), |t| suspect(t as u32));
    let crosses = |i: u32, j: u32| {
        let (f, g) = (face_of[i as usize], face_of[j as usize]);
        f != g && piece_of[f as usize] == piece_of[g as usize] && cross(&tris.at(i), &tris.at(j))
    };
    let plates = plates::find(mesh, face_of);
    let mut found = if plates.is_empty() {
        grid_pairs(&boxes, &is, &crosses, groups, span)
    } else {
        // Plate triangles leave the grid (an absent box is ignored there).
        let mut rest = boxes.clone();
        for p in &plates {
            rest[p.tris.start as usize..p.tris.end as usize].fill([[f64::NAN; 3]; 2]);
        }
        let mut found = grid_pairs(&rest, &is, &crosses, groups, span.span(0.0, 0.9));
        found.extend(plate_pairs(&plates, &tris, &boxes, &is, &crosses));
        found.sort_unstable();
        found.dedup();
        found
    };
    found.shrink_to_fit();
    span.finish();
    found
}

/// [`crossing_pairs`] of the triangles with a (non-NaN) box, through the grid, filling
/// `span` as the boxes are searched.
fn grid_pairs(
    boxes: &[Bounds3],
    is: &[bool],
    crosses: &(impl Fn(u32, u32) -> bool + Sync),
    groups: Option<&Groups>,
    span: Span,
) -> Vec<(u32, u32)> {
    let few: Vec<u32> = crate::chunked::flat_map(boxes.len(), crate::chunked::CHUNK, |r, few| {
        few.extend(r.filter(|&i| is[i]).map(|i| i as u32))
    });
    if few.len() * 10 > boxes.len() {
        return filter_map_pairs(
            boxes,
            |i, j| ((is[i as usize] || is[j as usize]) && crosses(i, j)).then_some((i, j)),
            span,
        );
    }
    let wanted = |i: u32, j: u32| j != i && (!is[j as usize] || j > i) && crosses(i, j);
    let mut found: Vec<(u32, u32)> = if few.len() <= SCANNED_SUSPECTS {
        few.par_iter()
            .flat_map_iter(|&i| {
                (0..boxes.len() as u32)
                    .filter(move |&j| overlap(&boxes[i as usize], &boxes[j as usize]))
                    .filter(move |&j| wanted(i, j))
                    .map(move |j| (i.min(j), i.max(j)))
            })
            .collect()
    } else {
        // Many suspects go in a tree that every present box searches (an absent one meets
        // nothing), instead of each suspect scanning every box: the same pairs.
        let as_box = |b: &Bounds3| Box3::new(P3::from(b[0]), P3::from(b[1]));
        let few: Vec<u32> = few
            .into_iter()
            .filter(|&i| !boxes[i as usize][0][0].is_nan())
            .collect();
        let suspects: Vec<Box3> = few.iter().map(|&i| as_box(&boxes[i as usize])).collect();
        let tree = BoxTree::new(&suspects);
        let searched = span.span(0.1, 1.0).steps(boxes.len());
        // The whole search may stop once every group has crossed only when every suspect
        // is in a group (an ungrouped suspect's pairs must all be tested).
        let stops = groups.filter(|g| few.iter().all(|&i| g.grouped(i)));
        (0..boxes.len() as u32)
            .into_par_iter()
            .filter(|&j| !boxes[j as usize][0][0].is_nan())
            .flat_map_iter(|j| {
                searched.tick(j as usize);
                let mut near = Vec::new();
                if stops.is_some_and(Groups::all_crossed) {
                    return near;
                }
                tree.any_meeting(&suspects, &as_box(&boxes[j as usize]), |u| {
                    let i = few[u as usize];
                    if groups.is_some_and(|g| g.settled(i, j)) {
                        return false;
                    }
                    if wanted(i, j) {
                        near.push((i.min(j), i.max(j)));
                        if let Some(g) = groups {
                            g.cross(i, j);
                        }
                    }
                    false
                });
                near
            })
            .collect()
    };
    found.sort_unstable();
    found
}

/// Up to this many suspect triangles, each finds its neighbours by scanning every box.
const SCANNED_SUSPECTS: usize = 16;

/// A face or triangle in no group of an early-exit crossing search ([`examine_until`]).
pub(crate) const NO_GROUP: u32 = u32::MAX;

/// The groups of an early-exit crossing search (the holes whose caps are tested): each
/// triangle's group, and whether the group is known to cross. A pair is skipped when every
/// group it touches is known to cross, so each group that has a crossing pair is found to
/// cross and no other, whatever the order the threads take (the pairs found may differ).
#[derive(Debug)]
pub(crate) struct Groups {
    /// By triangle: its group, or [`NO_GROUP`].
    of: Vec<u32>,
    /// By group: a crossing pair of it has been found.
    crossed: Vec<AtomicBool>,
    /// Groups of some triangle not yet found crossing (at 0 the search may stop).
    left: AtomicUsize,
}

impl Groups {
    fn new(of: Vec<u32>) -> Groups {
        let mut present: Vec<u32> = of.iter().copied().filter(|&g| g != NO_GROUP).collect();
        present.sort_unstable();
        present.dedup();
        let count = present.last().map_or(0, |&g| g as usize + 1);
        Groups {
            of,
            crossed: (0..count).map(|_| AtomicBool::new(false)).collect(),
            left: AtomicUsize::new(present.len()),
        }
    }

    /// Every group has been found crossing.
    fn all_crossed(&self) -> bool {
        self.left.load(Ordering::Relaxed) == 0
    }

    fn grouped(&self, t: u32) -> bool {
        self.of[t as usize] != NO_GROUP
    }

    fn known(&self, t: u32) -> bool {
        let g = self.of[t as usize];
        g == NO_GROUP || self.crossed[g as usize].load(Ordering::Relaxed)
    }

    /// True when the pair need not be tested: every group it touches has crossed (and it
    /// touches one).
    fn settled(&self, i: u32, j: u32) -> bool {
        (self.grouped(i) || self.grouped(j)) && self.known(i) && self.known(j)
    }

    /// Records the crossing pair (i, j).
    fn cross(&self, i: u32, j: u32) {
        for t in [i, j] {
            let g = self.of[t as usize];
            if g != NO_GROUP && !self.crossed[g as usize].swap(true, Ordering::Relaxed) {
                self.left.fetch_sub(1, Ordering::Relaxed);
            }
        }
    }
}

/// Up to this many plates, each finds its neighbours by scanning every box.
const SCANNED_PLATES: usize = 8;

/// [`crossing_pairs`] with a triangle on a plate: each plate against the triangles whose
/// boxes meet its box (by a scan, or in a tree over all of them when plates are many), pair
/// by pair only for those not clear of it.
fn plate_pairs(
    plates: &[plates::Plate],
    tris: &Tris,
    boxes: &[Bounds3],
    is: &[bool],
    crosses: &(impl Fn(u32, u32) -> bool + Sync),
) -> Vec<(u32, u32)> {
    let all: Vec<Box3> = boxes
        .iter()
        .map(|b| Box3::new(P3::from(b[0]), P3::from(b[1])))
        .collect();
    // A few plates scan the boxes; many search a tree (built only then).
    let tree = (plates.len() > SCANNED_PLATES).then(|| BoxTree::new(&all));
    plates
        .iter()
        .flat_map(|p| {
            let plate_suspect = is[p.tris.start as usize];
            let wanted = |u: u32| !p.tris.contains(&u) && (plate_suspect || is[u as usize]);
            let candidates: Vec<u32> = match &tree {
                Some(tree) => {
                    let mut c = Vec::new();
                    tree.any_meeting(&all, &p.bounds, |u| {
                        if wanted(u) {
                            c.push(u);
                        }
                        false
                    });
                    c
                }
                None => {
                    let pb: Bounds3 = [p.bounds.lo.coords.into(), p.bounds.hi.coords.into()];
                    (0..boxes.len() as u32)
                        .into_par_iter()
                        .filter(|&u| wanted(u) && overlap(&boxes[u as usize], &pb))
                        .collect()
                }
            };
            p.crossings(tris, &all, &candidates, crosses)
        })
        .collect()
}

/// Exact: triangles `t` and `u` (non-degenerate, of one mesh) meet other than in the
/// vertices and edge they share.
fn cross(t: &Tri, u: &Tri) -> bool {
    // The shared corners, without allocating (this runs for every pair of nearby triangles).
    let mut shared = [(0usize, 0usize); 9];
    let mut n = 0;
    for i in 0..3 {
        for j in 0..3 {
            if t.v[i] == u.v[j] {
                shared[n] = (i, j);
                n += 1;
            }
        }
    }
    match n {
        0 => triangles_intersect(&t.p, &u.p),
        1 => {
            let (i, j) = shared[0];
            touch_beyond_vertex(t, i, u, j)
        }
        2 => {
            let (a, b) = (shared[0].0, shared[1].0);
            let (c, d) = (3 - a - b, 3 - shared[0].1 - shared[1].1);
            fold_over_edge(&t.p[a], &t.p[b], &t.p[c], &u.p[d])
        }
        _ => true, // the same triangle twice
    }
}

/// Triangles sharing the edge ab, with third vertices c (of t) and d (of u): they meet beyond
/// the edge only when coplanar with c and d on the same side of ab (non-coplanar triangles
/// meet exactly in their common line, which holds only the edge).
fn fold_over_edge(a: &P3, b: &P3, c: &P3, d: &P3) -> bool {
    if orient3d(a, b, c, d) != 0.0 {
        return false;
    }
    let (x, y) = plane_axes(&[*a, *b, *c]);
    let q = |p: &P3| [p[x], p[y]];
    let (sc, sd) = (orient2d(q(a), q(b), q(c)), orient2d(q(a), q(b), q(d)));
    (sc > 0.0) == (sd > 0.0)
}

/// Triangles sharing one vertex, t.p\[i\] = u.p\[j\] = v: they meet elsewhere exactly when
/// the edge of one opposite v meets the other (non-coplanar: the meet is a segment from v
/// along the planes' common line, ending on an opposite edge), or, coplanar, when their
/// angles at v overlap.
fn touch_beyond_vertex(t: &Tri, i: usize, u: &Tri, j: usize) -> bool {
    let v = t.p[i];
    let (a, b) = (t.p[(i + 1) % 3], t.p[(i + 2) % 3]);
    let (c, d) = (u.p[(j + 1) % 3], u.p[(j + 2) % 3]);
    // One triangle's other corners strictly on one side of the other's plane: they meet
    // in v alone (the cheap answer for most neighbours; no exact zero is needed for it).
    let (sc, sd) = (orient3d(&v, &a, &b, &c), orient3d(&v, &a, &b, &d));
    if sc * sd > 0.0 {
        return false;
    }
    let (sa, sb) = (orient3d(&v, &c, &d, &a), orient3d(&v, &c, &d, &b));
    if sa * sb > 0.0 {
        return false;
    }
    let coplanar = sc == 0.0 && sd == 0.0;
    if !coplanar {
        return segment_meets_triangle(&a, &b, &u.p) || segment_meets_triangle(&c, &d, &t.p);
    }
    let (x, y) = plane_axes(&t.p);
    let q = |p: &P3| [p[x], p[y]];
    let (v, a, b, c, d) = (q(&v), q(&a), q(&b), q(&c), q(&d));
    in_cone(v, a, b, c) || in_cone(v, a, b, d) || in_cone(v, c, d, a) || in_cone(v, c, d, b)
}

/// Exact: `p` (≠ v) lies in the closed convex angle at `v` between rays va and vb (a, b, v
/// not collinear).
fn in_cone(v: [f64; 2], a: [f64; 2], b: [f64; 2], p: [f64; 2]) -> bool {
    let s = orient2d(v, a, b).signum();
    orient2d(v, a, p) * s >= 0.0 && orient2d(v, p, b) * s >= 0.0
}

/// Exact sign of the signed volume of closed triangles (+1 outward, -1 inward, 0 none): a
/// floating-point sum with a proven error bound, and a big-integer sum where that bound
/// does not decide.
pub(crate) fn volume_sign(tris: impl Iterator<Item = [P3; 3]> + Clone) -> i32 {
    let Some(o) = tris.clone().next().map(|t| t[0]) else {
        return 0;
    };
    let (sum, perm, n) = volume_terms(tris.clone(), o);
    filtered_sign(sum, perm, n).unwrap_or_else(|| exact_volume_sign(tris))
}

/// [`volume_sign`] of the `n` triangles `tri(0..n)`, their sums made in fixed chunks on all
/// threads where there are many (a closed mesh of one piece is one sum over every triangle)
/// and added in chunk order: the same sums, so the same decision, on any thread count.
pub(crate) fn volume_sign_of(n: usize, tri: impl Fn(usize) -> [P3; 3] + Sync) -> i32 {
    let chunk = crate::chunked::CHUNK;
    if n <= chunk || rayon::current_num_threads() == 1 {
        return volume_sign((0..n).map(&tri));
    }
    let o = tri(0)[0];
    let part = |c: usize| volume_terms((c * chunk..((c + 1) * chunk).min(n)).map(&tri), o);
    let parts: Vec<(f64, f64, usize)> = (0..n.div_ceil(chunk)).into_par_iter().map(part).collect();
    let (sum, perm, m) = parts
        .iter()
        .fold((0.0, 0.0, 0), |a, b| (a.0 + b.0, a.1 + b.1, a.2 + b.2));
    filtered_sign(sum, perm, m).unwrap_or_else(|| exact_volume_sign((0..n).map(&tri)))
}

/// Six times the triangles' volume relative to `o` (Σ det(a − o, b − o, c − o)) rounded,
/// the sum of the determinants' permanents, and the number of triangles.
fn volume_terms(tris: impl Iterator<Item = [P3; 3]>, o: P3) -> (f64, f64, usize) {
    let (mut sum, mut perm, mut n) = (0.0f64, 0.0f64, 0usize);
    for t in tris {
        let [a, b, c] = t.map(|p| p - o);
        let cx = [
            b.y * c.z - b.z * c.y,
            b.z * c.x - b.x * c.z,
            b.x * c.y - b.y * c.x,
        ];
        let px = [
            (b.y * c.z).abs() + (b.z * c.y).abs(),
            (b.z * c.x).abs() + (b.x * c.z).abs(),
            (b.x * c.y).abs() + (b.y * c.x).abs(),
        ];
        sum += a.x * cx[0] + a.y * cx[1] + a.z * cx[2];
        perm += a.x.abs() * px[0] + a.y.abs() * px[1] + a.z.abs() * px[2];
        n += 1;
    }
    (sum, perm, n)
}

/// The sign of a volume sum of `n` terms where its error bound decides it. Each difference
/// has a relative rounding error ≤ ε, each 3×3 determinant (6 products of 3, 5 sums) adds
/// ≤ 10ε of its permanent, and a sum of n terms (one running sum, or running sums of chunks
/// added together: each term passes fewer than n additions) ≤ nε of Σ|terms|: the total
/// error is below (n + 16) ε Σ permanents (1% spare for the bound's own rounding).
fn filtered_sign(sum: f64, perm: f64, n: usize) -> Option<i32> {
    let bound = (n as f64 + 16.0) * f64::EPSILON * perm * 1.01;
    (sum.abs() > bound).then_some(if sum > 0.0 { 1 } else { -1 })
}

/// Sign of Σ det(a, b, c) over the triangles, in big integers: every coordinate is an
/// integer multiple of the least power of two among them.
fn exact_volume_sign(tris: impl Iterator<Item = [P3; 3]> + Clone) -> i32 {
    let coords = tris
        .clone()
        .flat_map(|t| t.into_iter().flat_map(|p| [p.x, p.y, p.z]));
    let lsb = coords
        .filter(|c| *c != 0.0)
        .map(|c| decompose(c).1)
        .min()
        .unwrap_or(0);
    let big = |c: f64| -> BigInt {
        if c == 0.0 {
            return BigInt::zero();
        }
        let (m, e) = decompose(c);
        BigInt::from(m) << ((e - lsb) as usize)
    };
    let mut total = BigInt::zero();
    for t in tris {
        let [a, b, c] = t.map(|p| [big(p.x), big(p.y), big(p.z)]);
        let cx0 = &b[1] * &c[2] - &b[2] * &c[1];
        let cx1 = &b[2] * &c[0] - &b[0] * &c[2];
        let cx2 = &b[0] * &c[1] - &b[1] * &c[0];
        total += &a[0] * cx0 + &a[1] * cx1 + &a[2] * cx2;
    }
    if total.is_zero() {
        0
    } else if total.is_positive() {
        1
    } else {
        -1
    }
}

/// A finite nonzero f64 as m · 2^e with an odd integer m.
pub(crate) fn decompose(x: f64) -> (i64, i32) {
    let bits = x.to_bits();
    let sign = if bits >> 63 == 1 { -1 } else { 1 };
    let exp = ((bits >> 52) & 0x7ff) as i32;
    let frac = (bits & ((1 << 52) - 1)) as i64;
    let (mut m, mut e) = if exp == 0 {
        (frac, -1074)
    } else {
        (frac | (1 << 52), exp - 1075)
    };
    let tz = m.trailing_zeros() as i32;
    m >>= tz;
    e += tz;
    (sign * m, e)
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::geom::PolyMesh;
    use crate::scene::cleanup::{cleanup, Origin};

    fn mesh(pts: &[[f64; 3]], faces: &[&[u32]]) -> Mesh {
        let raw = PolyMesh::new(
            pts.iter().map(|p| P3::new(p[0], p[1], p[2])).collect(),
            faces.iter().map(|f| f.to_vec()).collect(),
        );
        let origin = Origin {
            file: std::path::Path::new("t"),
            face_pos: &[],
        };
        cleanup(&raw, &origin, &mut Vec::new(), crate::count::Count::NONE).unwrap()
    }

    const TET: [[f64; 3]; 4] = [[0., 0., 0.], [1., 0., 0.], [0., 1., 0.], [0., 0., 1.]];
    const TET_OUT: [&[u32]; 4] = [&[0, 2, 1], &[0, 1, 3], &[0, 3, 2], &[1, 2, 3]];

    #[test]
    fn an_early_exit_finds_every_group_that_crosses() {
        // 90 suspects in 7 groups among 1000 random boxes; group 6 crosses nothing. With the
        // early exit the pairs found are some of all, and touch exactly the same groups.
        let mut rng = crate::geom::rng::XorShift::new(5);
        let n = 1000;
        let boxes: Vec<Bounds3> = (0..n)
            .map(|_| {
                let lo: [f64; 3] = std::array::from_fn(|_| rng.unit() * 10.0);
                [lo, std::array::from_fn(|k| lo[k] + rng.unit())]
            })
            .collect();
        let mut is = vec![false; n];
        let mut of = vec![NO_GROUP; n];
        for k in 0..90 {
            let t = (k * 11 + 5) % n;
            is[t] = true;
            of[t] = (k % 7) as u32;
        }
        let crosses = |i: u32, j: u32| {
            let quiet = |t: u32| of[t as usize] == 6;
            !(i + j).is_multiple_of(3) && !quiet(i) && !quiet(j)
        };
        let span = Span::NONE;
        let all = grid_pairs(&boxes, &is, &crosses, None, span);
        let groups = Groups::new(of.clone());
        let some = grid_pairs(&boxes, &is, &crosses, Some(&groups), span);
        assert!(some.iter().all(|p| all.binary_search(p).is_ok()));
        assert!(some.len() < all.len(), "the exit skipped pairs");
        let touched = |pairs: &[(u32, u32)]| {
            let mut g: Vec<u32> = pairs
                .iter()
                .flat_map(|&(i, j)| [of[i as usize], of[j as usize]])
                .filter(|&g| g != NO_GROUP)
                .collect();
            g.sort_unstable();
            g.dedup();
            g
        };
        assert_eq!(touched(&some), touched(&all));
        assert_eq!(touched(&all), [0, 1, 2, 3, 4, 5]);
    }

    #[test]
    fn suspects_find_the_same_pairs_by_scan_and_by_tree() {
        // Random boxes, some absent (NaN), a tenth or fewer suspect: whether each suspect
        // scans every box (few) or searches the tree (more), the pairs are those a full
        // comparison finds.
        let mut rng = crate::geom::rng::XorShift::new(11);
        for (n, suspects) in [(400, 5), (400, 17), (400, 40), (1000, 90)] {
            let mut boxes: Vec<Bounds3> = (0..n)
                .map(|_| {
                    let lo: [f64; 3] = std::array::from_fn(|_| rng.unit() * 10.0);
                    let hi = std::array::from_fn(|k| lo[k] + rng.unit());
                    [lo, hi]
                })
                .collect();
            boxes[7] = [[f64::NAN; 3]; 2];
            let mut is = vec![false; n];
            for k in 0..suspects {
                is[(k * 37 + 3) % n] = true;
            }
            is[7] = true;
            let odd = |i: u32, j: u32| !(i + j).is_multiple_of(3);
            let got = grid_pairs(&boxes, &is, &odd, None, Span::NONE);
            let mut want = Vec::new();
            for i in 0..n as u32 {
                for j in i + 1..n as u32 {
                    let (a, b) = (&boxes[i as usize], &boxes[j as usize]);
                    if (is[i as usize] || is[j as usize]) && overlap(a, b) && odd(i, j) {
                        want.push((i, j));
                    }
                }
            }
            assert!(!want.is_empty());
            assert_eq!(got, want, "{n} boxes, {suspects} suspects");
        }
    }

    #[test]
    fn outward_tetrahedron_and_cube_are_solid() {
        assert_eq!(solidity(&mesh(&TET, &TET_OUT)), Solidity::Solid);
        let cube = crate::primitives::cuboid(P3::new(0., 0., 0.), P3::new(1., 2., 3.));
        let origin = Origin {
            file: std::path::Path::new("t"),
            face_pos: &[],
        };
        let m = cleanup(&cube, &origin, &mut Vec::new(), crate::count::Count::NONE).unwrap();
        assert_eq!(solidity(&m), Solidity::Solid);
    }

    #[test]
    fn inside_out_open_and_inconsistent() {
        let inward: Vec<Vec<u32>> = TET_OUT
            .iter()
            .map(|f| f.iter().rev().copied().collect())
            .collect();
        let refs: Vec<&[u32]> = inward.iter().map(|f| f.as_slice()).collect();
        assert_eq!(solidity(&mesh(&TET, &refs)), Solidity::InsideOut);
        assert_eq!(
            solidity(&mesh(&TET, &TET_OUT[..3])),
            Solidity::Open(CapFailure::NotTried)
        );
        let mut flipped = TET_OUT.to_vec();
        flipped[0] = &[0, 1, 2];
        assert_eq!(solidity(&mesh(&TET, &flipped)), Solidity::Inconsistent);
    }

    #[test]
    fn outward_box_beside_an_inward_box_is_inside_out() {
        // The total volume is positive, but one piece is inside out: w = -1 inside it.
        let mut pts: Vec<[f64; 3]> = TET.to_vec();
        pts.extend(TET.iter().map(|p| [p[0] * 3. + 5., p[1] * 3., p[2] * 3.]));
        let mut faces: Vec<Vec<u32>> = TET_OUT
            .iter()
            .map(|f| f.iter().rev().copied().collect())
            .collect();
        faces.extend(TET_OUT.iter().map(|f| f.iter().map(|v| v + 4).collect()));
        let refs: Vec<&[u32]> = faces.iter().map(|f| f.as_slice()).collect();
        assert_eq!(solidity(&mesh(&pts, &refs)), Solidity::InsideOut);
    }

    #[test]
    fn two_crossing_tetrahedra_are_two_solid_pieces() {
        // Each piece is embedded and outward; they pass through one another, which only
        // hides more (the culling argument is piece by piece).
        let mut pts: Vec<[f64; 3]> = TET.to_vec();
        pts.extend(TET.iter().map(|p| [p[0] + 0.25, p[1] + 0.25, p[2] + 0.25]));
        let mut faces: Vec<Vec<u32>> = TET_OUT.iter().map(|f| f.to_vec()).collect();
        faces.extend(TET_OUT.iter().map(|f| f.iter().map(|v| v + 4).collect()));
        let refs: Vec<&[u32]> = faces.iter().map(|f| f.as_slice()).collect();
        assert_eq!(solidity(&mesh(&pts, &refs)), Solidity::Solid);
        // One of them inside out still fails, crossing or not.
        faces[4..].iter_mut().for_each(|f| f.reverse());
        let refs: Vec<&[u32]> = faces.iter().map(|f| f.as_slice()).collect();
        assert_eq!(solidity(&mesh(&pts, &refs)), Solidity::InsideOut);
    }

    /// One closed piece crossing itself: tetrahedron A's three sides, glued along its base
    /// edges to the reversed sides of tetrahedron B on the same base with apex (1/2, 1/2,
    /// 1/2). It is closed, consistent and of positive volume (1/6 - 1/12), and B's edge from
    /// the origin to its apex pierces A's face x + y + z = 1 at (1/3, 1/3, 1/3).
    pub(crate) fn crossing_piece() -> Mesh {
        let p = [
            [0., 0., 0.],
            [1., 0., 0.],
            [0., 1., 0.],
            [0., 0., 1.],
            [0.5, 0.5, 0.5],
        ];
        let f: [[u32; 3]; 6] = [
            [0, 1, 3],
            [0, 3, 2],
            [1, 2, 3],
            [4, 1, 0],
            [2, 4, 0],
            [4, 2, 1],
        ];
        Mesh {
            vertices: p.iter().map(|q| P3::new(q[0], q[1], q[2])).collect(),
            faces: f.iter().map(Face::new).collect(),
            ..Mesh::default()
        }
    }

    #[test]
    fn one_piece_crossing_itself_self_intersects() {
        let e = examine(&crossing_piece());
        assert!(matches!(e.solidity, Solidity::SelfIntersecting(n) if n > 0));
        assert!(e.crossing.contains(&[2, 4]) || e.crossing.contains(&[4, 2]));
    }

    #[test]
    fn folded_neighbours_self_intersect() {
        // Two triangles sharing an edge folded flat onto each other, closed by a third
        // point: the coplanar shared-edge case.
        assert!(fold_over_edge(
            &P3::new(0., 0., 0.),
            &P3::new(1., 0., 0.),
            &P3::new(0., 1., 0.),
            &P3::new(0.5, 1., 0.)
        ));
        assert!(!fold_over_edge(
            &P3::new(0., 0., 0.),
            &P3::new(1., 0., 0.),
            &P3::new(0., 1., 0.),
            &P3::new(0.5, -1., 0.)
        ));
        assert!(!fold_over_edge(
            &P3::new(0., 0., 0.),
            &P3::new(1., 0., 0.),
            &P3::new(0., 1., 0.),
            &P3::new(0.5, 1., 1e-300)
        ));
    }

    #[test]
    fn neighbours_sharing_a_vertex() {
        let t = |v: [u32; 3], p: [[f64; 3]; 3]| Tri {
            v,
            p: p.map(|q| P3::new(q[0], q[1], q[2])),
        };
        let base = t([0, 1, 2], [[0., 0., 0.], [2., 0., 0.], [0., 2., 0.]]);
        // Coplanar, angles apart at the shared vertex: fine.
        let apart = t([0, 3, 4], [[0., 0., 0.], [-1., 0., 0.], [0., -1., 0.]]);
        assert!(!cross(&base, &apart));
        // Coplanar, overlapping angles.
        let over = t([0, 3, 4], [[0., 0., 0.], [1., 1., 0.], [-1., 1., 0.]]);
        assert!(cross(&base, &over));
        // Coplanar, one edge along the other's edge, same direction.
        let along = t([0, 3, 4], [[0., 0., 0.], [1., 0., 0.], [0., -1., 0.]]);
        assert!(cross(&base, &along));
        // Not coplanar, standing on the vertex outside: fine; piercing: crosses.
        let stand = t([0, 3, 4], [[0., 0., 0.], [-1., -1., 1.], [-1., 0., 1.]]);
        assert!(!cross(&base, &stand));
        let pierce = t([0, 3, 4], [[0., 0., 0.], [1., 1., 1.], [1., 1., -1.]]);
        assert!(cross(&base, &pierce));
    }

    #[test]
    fn volume_sign_falls_back_to_big_integers() {
        // A thin tetrahedron far from the origin: the float filter cannot decide.
        let far = 1e9;
        let t = [
            [far, far, far],
            [far + 1e-6, far, far],
            [far, far + 1e-6, far],
            [far, far, far + 1e-6],
        ]
        .map(|p| P3::new(p[0], p[1], p[2]));
        let tris: Vec<[P3; 3]> = TET_OUT
            .iter()
            .map(|f| [t[f[0] as usize], t[f[1] as usize], t[f[2] as usize]])
            .collect();
        assert_eq!(volume_sign(tris.iter().copied()), 1);
        assert_eq!(exact_volume_sign(tris.iter().copied()), 1);
        let rev: Vec<[P3; 3]> = tris.iter().map(|t| [t[0], t[2], t[1]]).collect();
        assert_eq!(volume_sign(rev.iter().copied()), -1);
        assert_eq!(decompose(0.75), (3, -2));
        assert_eq!(decompose(-8.0), (-1, 3));
        assert_eq!(decompose(f64::MIN_POSITIVE / 4.0).1, -1024);
    }

    /// The sign summed in chunks on several threads is the one sum's: for many tetrahedra
    /// outward, inward, and each with its mirror (a zero the filter leaves to the exact sum).
    #[test]
    fn volume_sign_in_chunks_is_the_one_sum() {
        let tet = |k: usize, flip: bool| -> Vec<[P3; 3]> {
            let p = |v: usize| {
                let q = TET[v];
                P3::new(
                    q[0] + k as f64 * 0.37,
                    q[1] - k as f64 * 1e-3,
                    q[2] + (k % 7) as f64,
                )
            };
            (TET_OUT.iter())
                .map(|f| {
                    let t = [p(f[0] as usize), p(f[1] as usize), p(f[2] as usize)];
                    if flip {
                        [t[0], t[2], t[1]]
                    } else {
                        t
                    }
                })
                .collect()
        };
        let many = crate::chunked::CHUNK / 2 + 77;
        let outward: Vec<[P3; 3]> = (0..many).flat_map(|k| tet(k, false)).collect();
        let inward: Vec<[P3; 3]> = (0..many).flat_map(|k| tet(k, true)).collect();
        let both: Vec<[P3; 3]> = (0..many)
            .flat_map(|k| [tet(k, false), tet(k, true)].concat())
            .collect();
        for (tris, want) in [(&outward, 1), (&inward, -1), (&both, 0)] {
            assert_eq!(volume_sign(tris.iter().copied()), want);
            for threads in [1, 3] {
                let got = crate::chunked::pool(threads)
                    .install(|| volume_sign_of(tris.len(), |t| tris[t]));
                assert_eq!(got, want, "{threads} threads, {} triangles", tris.len());
            }
        }
    }
}
