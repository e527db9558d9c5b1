//! Intersection curves: where two faces interpenetrate, the segments of their planes'
//! intersection line that lie inside both faces.
//!
//! Candidate pairs come from a uniform grid over the faces' world boxes; side-of-plane
//! decisions use the exact `robust::orient3d`. A vertex exactly on the other plane counts as
//! on its positive side (symbolic perturbation), so crossings always pair up.

use std::ops::Range;

use rayon::prelude::*;

use crate::chunked::flat_map;
use crate::count::{Count, Share};
use crate::geom::box_pairs::{filter_map_pairs_of, overlap, Bounds3};
use crate::geom::coarse;
#[cfg(test)]
use crate::geom::newell;
use crate::geom::{orient3d_refs, Corners, P3, V3};
use crate::scene::FaceId;

use super::edges::{Edge, EdgeKind};
use super::world::{WorldFaces, NO_PIECE};

/// Every intersection segment between pairs of faces that cross (both faces with vertices
/// strictly on both sides of the other's plane); `keep(f)` filters faces worth testing.
///
/// The faces go to `done` as they are done: the faces that can cross nothing set aside
/// first, then the search of the pairs left.
pub(crate) fn intersection_edges(
    world: &WorldFaces,
    keep: impl Fn(FaceId) -> bool + Sync,
    done: Count,
) -> Vec<Edge> {
    let share = Share::new(done, world.faces.len());
    let faces = &world.faces;
    let cand: Vec<u32> = flat_map(faces.len(), CHUNK, |r, out| {
        out.extend(
            r.map(|f| f as u32)
                .filter(|&f| keep(FaceId(f)) && faces[f as usize].len >= 3),
        )
    });
    // Per face, once: whether it is flat (exactly: every corner on the plane of its
    // reference points). The reference points are found again where a pair is tested (not
    // held: 12 bytes a face).
    let cand_flat: Vec<bool> = cand
        .par_iter()
        .map(|&f| {
            let p = world.points_of(f as usize);
            let rp = plane_refs(p).map(|k| p[k as usize]);
            p.len() == 3 || p.iter().all(|q| orient3d_refs(&rp, q) == 0.0)
        })
        .collect();
    // Faces that can cross nothing are not paired at all.
    let alone = alone(world, &cand, &cand_flat);
    // The candidates left, in order (each list in chunks on all threads).
    let left = |r: Range<usize>| r.filter(|&k| !alone[k]);
    let ids: Vec<u32> = flat_map(cand.len(), CHUNK, |r, out| {
        out.extend(left(r).map(|k| cand[k]))
    });
    let flat: Vec<bool> = flat_map(cand.len(), CHUNK, |r, out| {
        out.extend(left(r).map(|k| cand_flat[k]))
    });
    drop((alone, cand, cand_flat));
    // The faces of many corners, by position, with their corners sorted (so that a pair's
    // adjacency costs what the smaller face has, not the product).
    let sorted: Vec<(u32, Vec<u32>)> = flat_map(ids.len(), CHUNK, |r, out| {
        out.extend(
            r.filter(|&i| faces[ids[i] as usize].len as usize > SORT_ABOVE)
                .map(|i| {
                    let mut s = world.vertices_of(ids[i] as usize).to_vec();
                    s.sort_unstable();
                    (i as u32, s)
                }),
        )
    });
    let sorted_of = |i: usize| -> Option<&[u32]> {
        let k = sorted.binary_search_by_key(&(i as u32), |e| e.0).ok()?;
        Some(sorted[k].1.as_slice())
    };
    let side = |i: usize| {
        let f = ids[i] as usize;
        Side::new(world.points_of(f), &faces[f].normal)
    };
    // Results come in ascending (position, position) pair order, so in (face, face) order:
    // fixed whatever the thread count.
    share.reach(0.2);
    // The boxes of the pair search: held rounded outward to f32 (24 bytes a face instead
    // of 48), up to HELD_BOXES faces and where every bound is a finite f32; else remade from
    // the corners whenever the grid asks. Rounded, the grid finds every pair whose exact
    // boxes overlap and a few more, told apart on the exact boxes before the crossing test.
    let box_of = |i: u32| world.bbox_of(ids[i as usize] as usize);
    let coarse: Option<Vec<CoarseBox>> = (ids.len() <= HELD_BOXES)
        .then(|| {
            (0..ids.len() as u32)
                .into_par_iter()
                .with_min_len(1 << 12)
                .map(|i| coarse_box(&box_of(i)))
                .collect::<Vec<_>>()
        })
        .filter(|c| {
            c.par_iter()
                .with_min_len(1 << 12)
                .all(|b| b.iter().flatten().all(|x| !x.is_infinite()))
        });
    let rounded = coarse.is_some();
    // The pair test of the grid below, by positions in `ids`.
    let pair = |i: u32, j: u32| {
        let (i, j) = (i as usize, j as usize);
        let (lo, hi) = (ids[i] as usize, ids[j] as usize);
        let piece = world.clean_piece[lo];
        // Flat faces of one piece proven free of self-intersection meet in nothing but
        // shared vertices and edges: no curve to find. (The proof is on the faces'
        // triangles; a face off its plane is not the union of its triangles.)
        let clean = piece != NO_PIECE && piece == world.clean_piece[hi] && flat[i] && flat[j];
        // Boxes that meet only rounded: no crossing.
        let apart = || rounded && !overlap(&box_of(i as u32), &box_of(j as u32));
        let segs = if clean || adjacent(world, lo, hi, sorted_of(i), sorted_of(j)) || apart() {
            Vec::new()
        } else {
            cross_with(&side(i), &side(j))
        };
        (!segs.is_empty()).then(|| {
            segs.into_iter()
                .map(|seg| Edge {
                    leaf: faces[lo].leaf,
                    ends: seg,
                    faces: vec![FaceId(lo as u32), FaceId(hi as u32)],
                    kind: EdgeKind::Intersection,
                })
                .collect::<Vec<_>>()
        })
    };
    let found = match &coarse {
        Some(boxes) => filter_map_pairs_of(
            ids.len(),
            |i| widen(&boxes[i as usize]),
            pair,
            share.span(0.2, 1.0),
        ),
        None => filter_map_pairs_of(ids.len(), box_of, pair, share.span(0.2, 1.0)),
    };
    share.finish();
    found.into_iter().flatten().collect()
}

/// Most candidate faces whose boxes are held for the pair search (384 MiB of boxes).
const HELD_BOXES: usize = 1 << 24;

/// A box rounded outward to f32: [min, max].
type CoarseBox = [[f32; 3]; 2];

/// `b` rounded outward to f32.
fn coarse_box(b: &Bounds3) -> CoarseBox {
    [b[0].map(coarse::down), b[1].map(coarse::up)]
}

/// A coarse box as the pair search takes it (the same values, in f64).
fn widen(b: &CoarseBox) -> Bounds3 {
    b.map(|c| c.map(f64::from))
}

/// Most clean pieces compared pairwise by [`alone`] (beyond, no face is left out).
const MAX_PIECES: usize = 4096;

/// By candidate face (`cand`, flat or not by `flat`): true when it is a flat face of a piece
/// proven free of self-intersection ([`WorldFaces::clean_piece`]) whose box meets the box
/// of no face outside that piece's flat faces. Such a face meets only faces of its own
/// piece, and those only in shared vertices and edges: it crosses nothing.
fn alone(world: &WorldFaces, cand: &[u32], flat: &[bool]) -> Vec<bool> {
    let join = |a: Option<Bounds3>, b: &Bounds3| match a {
        None => *b,
        Some(a) => [
            std::array::from_fn(|k| a[0][k].min(b[0][k])),
            std::array::from_fn(|k| a[1][k].max(b[1][k])),
        ],
    };
    // Each chunk of candidates: its runs of one clean piece's flat faces, each with their
    // box, and the box of its other faces (on all threads; boxes joined by least and
    // greatest, in any order the same).
    let chunk = |c: &[u32], k0: usize| {
        let (mut pieces, mut loose) = (Vec::new(), None);
        for (k, &f) in c.iter().enumerate() {
            let (p, b) = (world.clean_piece[f as usize], &world.bbox_of(f as usize));
            if p == NO_PIECE || !flat[k0 + k] {
                loose = Some(join(loose, b));
                continue;
            }
            match pieces.last_mut() {
                Some((q, qb)) if *q == p => *qb = join(Some(*qb), b),
                _ => pieces.push((p, *b)),
            }
        }
        (pieces, loose)
    };
    let parts: Vec<Runs> = if cand.len() <= CHUNK {
        vec![chunk(cand, 0)]
    } else {
        cand.par_chunks(CHUNK)
            .enumerate()
            .map(|(c, part)| chunk(part, c * CHUNK))
            .collect()
    };
    let mut pieces: Vec<(u32, Bounds3)> = Vec::new();
    let mut loose: Option<Bounds3> = None;
    for (p, l) in parts {
        pieces.extend(p);
        loose = l.map_or(loose, |l| Some(join(loose, &l)));
    }
    // A piece's faces are consecutive (numbered leaf by leaf), so each piece appears once
    // unless its faces interleave with another's (or span chunks): then merge the entries.
    pieces.sort_by_key(|e| e.0);
    pieces.dedup_by(|b, a| {
        let same = a.0 == b.0;
        if same {
            a.1 = join(Some(a.1), &b.1);
        }
        same
    });
    if pieces.len() > MAX_PIECES {
        return vec![false; cand.len()];
    }
    let apart = |i: usize| {
        let b = &pieces[i].1;
        loose.is_none_or(|l| !overlap(b, &l))
            && pieces
                .iter()
                .enumerate()
                .all(|(j, q)| j == i || !overlap(b, &q.1))
    };
    let isolated: Vec<u32> = (0..pieces.len())
        .filter(|&i| apart(i))
        .map(|i| pieces[i].0)
        .collect();
    crate::chunked::map(cand.len(), |k| {
        flat[k]
            && isolated
                .binary_search(&world.clean_piece[cand[k] as usize])
                .is_ok()
    })
}

/// A chunk's runs of one clean piece's flat faces with their boxes, and the box of its other
/// faces (see [`alone`]).
type Runs = (Vec<(u32, Bounds3)>, Option<Bounds3>);

/// Candidate faces per chunk of the lists made on all threads.
const CHUNK: usize = crate::chunked::CHUNK;

/// Faces with more corners than this are searched through a sorted copy.
const SORT_ABOVE: usize = 16;

/// Faces `f` and `g` of one leaf that share a vertex (neighbours meet, they do not cross);
/// `sf` and `sg` are their sorted corners, where made.
fn adjacent(
    world: &WorldFaces,
    f: usize,
    g: usize,
    sf: Option<&[u32]>,
    sg: Option<&[u32]>,
) -> bool {
    if world.faces[f].leaf != world.faces[g].leaf {
        return false;
    }
    let (vf, vg) = (world.vertices_of(f), world.vertices_of(g));
    let (small, big, sorted) = if vf.len() <= vg.len() {
        (vf, vg, sg)
    } else {
        (vg, vf, sf)
    };
    match sorted {
        Some(s) => small.iter().any(|v| s.binary_search(v).is_ok()),
        None => small.iter().any(|v| big.contains(v)),
    }
}

/// Three well-spread corners of a face's plane, as offsets into its points.
fn plane_refs(p: Corners) -> [u32; 3] {
    let a = p[0];
    let b = (0..p.len())
        .max_by(|&x, &y| {
            (p[x] - a)
                .norm_squared()
                .total_cmp(&(p[y] - a).norm_squared())
        })
        .unwrap_or(0);
    let ab = p[b] - a;
    let c = (0..p.len())
        .max_by(|&x, &y| {
            let ax = ab.cross(&(p[x] - a)).norm_squared();
            let ay = ab.cross(&(p[y] - a)).norm_squared();
            ax.total_cmp(&ay)
        })
        .unwrap_or(0);
    [0, b as u32, c as u32]
}

/// A face as [`cross_with`] reads it.
struct Side<'a> {
    /// Its corners.
    pts: Corners<'a>,
    /// Its Newell normal.
    normal: &'a V3,
    /// Three well-spread points of its plane.
    refs: [P3; 3],
}

impl<'a> Side<'a> {
    /// The face with corners `pts` and Newell normal `normal`.
    fn new(pts: Corners<'a>, normal: &'a V3) -> Self {
        let refs = plane_refs(pts).map(|k| pts[k as usize]);
        Side { pts, normal, refs }
    }
}

#[cfg(test)]
/// Segments of the intersection of the faces with corners `f` and `g` (empty unless they
/// cross).
pub(crate) fn cross(f: &[P3], g: &[P3]) -> Vec<[P3; 2]> {
    let (nf, ng) = (newell(f), newell(g));
    let all: Vec<u32> = (0..f.len().max(g.len()) as u32).collect();
    let (f, g) = (
        Corners::new(&all[..f.len()], f),
        Corners::new(&all[..g.len()], g),
    );
    cross_with(&Side::new(f, &nf), &Side::new(g, &ng))
}

/// [`cross`] of two faces with their normals and plane reference points. The smaller face
/// is classified first: a large face is scanned only for a pair whose other face does
/// cross its plane.
fn cross_with(f: &Side, g: &Side) -> Vec<[P3; 2]> {
    let signs = |pts: Corners, r: &[P3; 3]| -> Vec<f64> {
        pts.iter().map(|p| orient3d_refs(r, p)).collect()
    };
    let straddles = |s: &[f64]| s.iter().any(|&x| x < 0.0) && s.iter().any(|&x| x > 0.0);
    let (sf, sg) = if f.pts.len() <= g.pts.len() {
        let sf = signs(f.pts, &g.refs);
        if !straddles(&sf) {
            return Vec::new();
        }
        (sf, signs(g.pts, &f.refs))
    } else {
        let sg = signs(g.pts, &f.refs);
        if !straddles(&sg) {
            return Vec::new();
        }
        (signs(f.pts, &g.refs), sg)
    };
    if !straddles(&sf) || !straddles(&sg) {
        return Vec::new();
    }
    let dir = f.normal.cross(g.normal);
    if dir.norm_squared() == 0.0 {
        return Vec::new();
    }
    let a = spans(f.pts, &sf, &dir);
    let b = spans(g.pts, &sg, &dir);
    let mut out = Vec::new();
    let (mut i, mut j) = (0, 0);
    while i < a.len() && j < b.len() {
        let lo = if a[i][0].0 >= b[j][0].0 {
            a[i][0]
        } else {
            b[j][0]
        };
        let hi = if a[i][1].0 <= b[j][1].0 {
            a[i][1]
        } else {
            b[j][1]
        };
        if lo.0 < hi.0 {
            out.push([lo.1, hi.1]);
        }
        if a[i][1].0 <= b[j][1].0 {
            i += 1;
        } else {
            j += 1;
        }
    }
    out
}

/// The spans of a polygon along the line where its signs `s` change, as (parameter, point)
/// pairs sorted along `dir`.
fn spans(p: Corners, s: &[f64], dir: &V3) -> Vec<[(f64, P3); 2]> {
    let n = p.len();
    let mut hits: Vec<(f64, P3)> = Vec::new();
    for i in 0..n {
        let j = (i + 1) % n;
        let (ni, nj) = (s[i] < 0.0, s[j] < 0.0);
        if ni == nj {
            continue;
        }
        let x = if s[j] == 0.0 {
            p[j]
        } else if s[i] == 0.0 {
            p[i]
        } else {
            let t = s[i] / (s[i] - s[j]);
            p[i] + (p[j] - p[i]) * t
        };
        hits.push((dir.dot(&x.coords), x));
    }
    hits.sort_by(|u, v| u.0.total_cmp(&v.0));
    hits.chunks_exact(2).map(|c| [c[0], c[1]]).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::emit::lines::world::WorldFace;

    fn pts(p: &[[f64; 3]]) -> Vec<P3> {
        p.iter().map(|p| P3::new(p[0], p[1], p[2])).collect()
    }

    /// World faces of (leaf, first vertex index, corners), with their normals: corner k is
    /// vertex `base + k` of the leaf (faces of a leaf that name one vertex give it one point).
    fn world(faces: &[(u32, u32, &[[f64; 3]])]) -> WorldFaces<'static> {
        let mut w = WorldFaces::default();
        let leaves = faces.iter().map(|f| f.0 as usize + 1).max().unwrap_or(0);
        let mut tables: Vec<Vec<P3>> = vec![Vec::new(); leaves];
        for &(leaf, base, corners) in faces {
            let points = pts(corners);
            w.faces.push(WorldFace {
                leaf,
                len: points.len() as u32,
                first: w.vertices.len(),
                normal: crate::scene::cleanup::FaceShape::of(&points).normal,
            });
            w.vertices.extend(base..base + points.len() as u32);
            let table = &mut tables[leaf as usize];
            for (k, p) in points.into_iter().enumerate() {
                let v = base as usize + k;
                if table.len() <= v {
                    table.resize(v + 1, P3::origin());
                }
                table[v] = p;
            }
            w.clean_piece.push(NO_PIECE);
        }
        for t in tables {
            w.leaf_first.push(w.points.len());
            w.points.extend(t);
        }
        w
    }

    const SQUARE: [[f64; 3]; 4] = [[0., 0., 0.], [2., 0., 0.], [2., 2., 0.], [0., 2., 0.]];

    #[test]
    fn two_crossing_squares() {
        // Horizontal square z = 0 over [0,2]^2; vertical square x = 1, y in [0.5,3], z in [-1,1].
        let upright = [[1., 0.5, -1.], [1., 3., -1.], [1., 3., 1.], [1., 0.5, 1.]];
        let segs = cross(&pts(&SQUARE), &pts(&upright));
        assert_eq!(segs.len(), 1);
        let mut e = [segs[0][0], segs[0][1]];
        e.sort_by(|p, q| p.y.total_cmp(&q.y));
        assert_eq!(e, [P3::new(1., 0.5, 0.), P3::new(1., 2., 0.)]);
        let mut w = world(&[(0, 0, &SQUARE), (1, 0, &upright)]);
        let all = intersection_edges(&w, |_| true, Count::NONE);
        assert_eq!(all.len(), 1);
        assert_eq!(all[0].faces, vec![FaceId(0), FaceId(1)]);
        // Faces of one piece known free of self-intersection are not tested (here the claim
        // is false on purpose, to show that it is what is used).
        w.clean_piece = vec![7, 7];
        assert!(intersection_edges(&w, |_| true, Count::NONE).is_empty());
        w.clean_piece = vec![7, 8];
        assert_eq!(intersection_edges(&w, |_| true, Count::NONE).len(), 1);
        // A face off its plane is not the union of the triangles the claim was proven on:
        // it is tested whatever the claim.
        w.clean_piece = vec![7, 7];
        w.points[2].z = 1e-3;
        assert_eq!(intersection_edges(&w, |_| true, Count::NONE).len(), 1);
    }

    #[test]
    fn faces_of_many_corners_share_a_vertex_through_their_sorted_copy() {
        // Two n-gons (n above SORT_ABOVE) of one leaf crossing at right angles: neighbours
        // when they share a vertex index (no curve), crossing faces when they do not.
        let n = SORT_ABOVE as u32 + 4;
        let ring = |f: &dyn Fn(f64, f64) -> [f64; 3]| -> Vec<[f64; 3]> {
            (0..n)
                .map(|k| {
                    let t = std::f64::consts::TAU * k as f64 / n as f64;
                    f(t.cos(), t.sin())
                })
                .collect()
        };
        let flat = ring(&|c, s| [c, s, 0.0]);
        let upright = ring(&|c, s| [c, 0.0, s]);
        let apart = world(&[(0, 0, &flat), (0, n, &upright)]);
        assert_eq!(intersection_edges(&apart, |_| true, Count::NONE).len(), 1);
        let sharing = world(&[(0, 0, &flat), (0, n - 1, &upright)]);
        assert!(intersection_edges(&sharing, |_| true, Count::NONE).is_empty());
        // Of different leaves, a shared index means nothing.
        let leaves = world(&[(0, 0, &flat), (1, n - 1, &upright)]);
        assert_eq!(intersection_edges(&leaves, |_| true, Count::NONE).len(), 1);
    }

    #[test]
    fn faces_alone_on_a_clean_piece_are_not_paired() {
        let sq = |z: f64| [[0., 0., z], [1., 0., z], [1., 1., z], [0., 1., z]];
        let far = |x: f64| [[x, 0., 0.], [x + 1., 0., 0.], [x, 1., 0.]];
        let mut w = world(&[
            (0, 0, &sq(0.)),
            (0, 4, &sq(0.5)),
            (1, 0, &far(5.)),
            (2, 0, &far(5.5)),
        ]);
        w.clean_piece = vec![0, 0, 1, NO_PIECE];
        let all = [0, 1, 2, 3];
        let flat = [true; 4];
        // Piece 0 is apart from everything; piece 1 overlaps the loose face 3.
        assert_eq!(alone(&w, &all, &flat), [true, true, false, false]);
        // A face off its plane is loose, and its own piece is near it.
        assert_eq!(alone(&w, &all, &[true, false, true, true]), [false; 4]);
        // Two clean pieces whose boxes meet are both paired.
        w.clean_piece = vec![0, 0, 1, 2];
        assert_eq!(alone(&w, &all, &flat), [true, true, false, false]);
        w.clean_piece = vec![0, 0, 1, 1];
        assert_eq!(alone(&w, &all, &flat), [true; 4]);
        // Only the candidates count.
        w.clean_piece = vec![0, 0, 1, NO_PIECE];
        assert_eq!(alone(&w, &[0, 2], &[true, true]), [true, true]);
    }

    /// Many chunks of candidates: clean pieces running across chunks and interleaved,
    /// loose faces and crossing pairs among them; the faces set aside and the curves found
    /// are those of one thread.
    #[test]
    fn lists_made_in_chunks_are_those_of_one_thread() {
        let n = 3 * CHUNK + 101;
        let corners: Vec<Vec<[f64; 3]>> = (0..n)
            .map(|k| {
                let x = (k / 2) as f64 * 3.0;
                if k % 2 == 0 {
                    vec![[x, 0., 0.], [x + 2., 0., 0.], [x + 2., 2., 0.], [x, 2., 0.]]
                } else {
                    // Upright across the last square where k % 6 == 1, beside it otherwise.
                    let y = if k % 6 == 1 { 1.0 } else { 2.5 };
                    vec![[x + 1., y, -1.], [x + 1., y, 1.], [x + 1.5, y, 1.]]
                }
            })
            .collect();
        let faces: Vec<(u32, u32, &[[f64; 3]])> = corners
            .iter()
            .enumerate()
            .map(|(k, c)| (0, 4 * k as u32, c.as_slice()))
            .collect();
        let mut w = world(&faces);
        // Pieces of 5,000 faces (across chunk ends), one piece's faces among another's, and
        // every 7th face loose.
        w.clean_piece = (0..n as u32)
            .map(|k| match k {
                _ if k % 7 == 0 => NO_PIECE,
                _ if k % 11 == 0 => 1,
                _ => k / 5000 + 2,
            })
            .collect();
        let cand: Vec<u32> = (0..n as u32).collect();
        let flat: Vec<bool> = (0..n).map(|k| k % 13 != 0).collect();
        let pool = crate::chunked::pool;
        let one = pool(1).install(|| alone(&w, &cand, &flat));
        assert_eq!(pool(3).install(|| alone(&w, &cand, &flat)), one);
        let curves = |w: &WorldFaces| -> Vec<String> {
            intersection_edges(w, |_| true, Count::NONE)
                .iter()
                .map(|e| format!("{e:?}"))
                .collect()
        };
        let found = pool(1).install(|| curves(&w));
        assert!(!found.is_empty());
        assert_eq!(pool(3).install(|| curves(&w)), found);
        // Pieces of 5,000 faces along x, apart, every face flat but one in the third chunk:
        // that face is loose, so only its piece's faces are paired.
        w.clean_piece = (0..n as u32).map(|k| k / 5000).collect();
        let odd = 2 * CHUNK + 5;
        let flat: Vec<bool> = (0..n).map(|k| k != odd).collect();
        let want: Vec<bool> = (0..n).map(|k| k / 5000 != odd / 5000).collect();
        assert!(want.iter().any(|&a| a) && !want.iter().all(|&a| a));
        for threads in [1, 3] {
            assert_eq!(pool(threads).install(|| alone(&w, &cand, &flat)), want);
        }
    }

    #[test]
    fn touching_faces_do_not_cross() {
        let g = [[1., 0., 0.], [1., 2., 0.], [1., 2., 1.], [1., 0., 1.]];
        assert!(cross(&pts(&SQUARE), &pts(&g)).is_empty());
    }

    #[test]
    fn plane_refs_spread_over_the_face() {
        // The farthest corner from the first, then the one farthest from that line.
        let p = pts(&[
            [0., 0., 0.],
            [1., 0., 0.],
            [3., 0., 0.],
            [1., 1., 0.],
            [2., 0.5, 0.],
        ]);
        let all: Vec<u32> = (0..p.len() as u32).collect();
        assert_eq!(plane_refs(Corners::new(&all, &p)), [0, 2, 3]);
    }
}
