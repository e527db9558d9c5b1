//! Edge topology of a face set: closedness and consistent orientation.

use rayon::prelude::*;

use super::object::Face;
use super::union_find::UnionFind;

/// True when every undirected edge is used by exactly two faces, once in each direction:
/// the faces bound a closed, consistently oriented solid.
pub(crate) fn is_closed_oriented(faces: &[Face]) -> bool {
    edge_topology(faces) == Topology::Closed
}

/// How the edges of a face set join up.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Topology {
    /// Every edge used by exactly two faces, once in each direction.
    Closed,
    /// Some edge used by one face only (and none used inconsistently).
    Open,
    /// Some edge used twice in one direction, or by more than two faces.
    Inconsistent,
}

/// Classifies the edges of `faces` (an empty set is open). Every traversal of an edge,
/// undirected with its direction, is sorted by edge; the faces are closed exactly when every
/// edge comes twice, once each way. Once twice the same way, or three times, is
/// inconsistent; once only, open (unless it runs from a vertex to itself, its own reverse).
/// No hashing and no search: one sort and one pass.
pub(crate) fn edge_topology(faces: &[Face]) -> Topology {
    Traversals::of(faces).topology()
}

/// Every traversal of an edge by a face set, sorted by undirected edge: the traversals of
/// one edge are neighbours in the list (no hashing, no search). Made once, it gives both
/// the edge topology and the pieces (the solidity test needs both of one mesh).
#[derive(Debug)]
pub(crate) struct Traversals {
    items: Vec<Traversal>,
    /// How many faces traverse them.
    faces: usize,
}

/// One face's traversal of one edge.
#[derive(Debug, Clone, Copy)]
struct Traversal {
    /// The edge: its two vertices packed, least first.
    edge: u64,
    face: u32,
    /// From the lesser vertex to the greater.
    forward: bool,
}

impl Traversals {
    /// The traversals of `faces`' edges, sorted by edge (within an edge, in an order nothing
    /// reads: the topology counts directions, the pieces join faces).
    pub(crate) fn of(faces: &[Face]) -> Traversals {
        Traversals {
            items: Traversals::numbered(faces, 0),
            faces: faces.len(),
        }
    }

    /// The traversals of `faces` numbered from `first`, sorted by edge and, within an
    /// edge, by face.
    fn numbered(faces: &[Face], first: u32) -> Vec<Traversal> {
        // In fixed chunks of faces on all threads, joined in face order.
        let mut items = crate::chunked::flat_map(faces.len(), CHUNK, |r, items| {
            items.reserve(faces[r.clone()].iter().map(|f| f.vertices.len()).sum());
            for k in r {
                let v = &faces[k].vertices;
                let n = v.len();
                for i in 0..n {
                    let (a, b) = (v[i], v[(i + 1) % n]);
                    items.push(Traversal {
                        edge: (a.min(b) as u64) << 32 | a.max(b) as u64,
                        face: first + k as u32,
                        forward: a < b,
                    });
                }
            }
        });
        let pair = |t: &Traversal| ((t.edge >> 32) as u32, t.edge as u32);
        sort_by_pair(&mut items, pair, |t| (t.edge, t.face));
        items
    }

    /// The traversals of these faces and of `more` after them (numbered from this set's
    /// face count on): [`Traversals::of`] the faces joined, made by sorting only `more`'s
    /// and merging them in (a mesh and its few caps: a merge is linear where a sort of the
    /// whole is not). Both lists are sorted by edge, then face, and `more`'s faces number
    /// after all of these, so the merge is that order; on all threads, in fixed chunks of
    /// this list, each taking the items of `more` that fall between its first item and the
    /// next chunk's.
    pub(crate) fn with_faces(&self, more: &[Face]) -> Traversals {
        let added = Traversals::numbered(more, self.faces as u32);
        let key = |t: &Traversal| (t.edge, t.face);
        let (a, b) = (&self.items, &added);
        // Where the items of `b` that go before a[i] end (all of them past the end).
        let cut = |i: usize| match a.get(i) {
            Some(x) => b.partition_point(|t| key(t) < key(x)),
            None => b.len(),
        };
        let items = crate::chunked::flat_map(a.len(), MERGED_CHUNK, |r, out| {
            // The first chunk takes the items of `b` before all of `a` too.
            let from = if r.start == 0 { 0 } else { cut(r.start) };
            let (mut i, mut j, end) = (r.start, from, cut(r.end));
            out.reserve(r.len() + end - from);
            while i < r.end || j < end {
                if j == end || (i < r.end && key(&a[i]) <= key(&b[j])) {
                    out.push(a[i]);
                    i += 1;
                } else {
                    out.push(b[j]);
                    j += 1;
                }
            }
        });
        Traversals {
            items,
            faces: self.faces + more.len(),
        }
    }

    /// Whether these faces with `more` beside them are certainly not closed: some edge `more`
    /// traverses is, with these faces' traversals of it, used once only (not from a vertex to
    /// itself), twice the same way, or more than twice. Exact and sound: those are that edge's
    /// traversals in [`Traversals::with_faces`]`(more)` too, so its [`Traversals::topology`]
    /// is then open or inconsistent. Where this says false it may still be either (an edge
    /// only these faces traverse, left open). A look-up an edge of `more` (a mesh's few caps),
    /// no merge.
    pub(crate) fn not_closed_with(&self, more: &[Face]) -> bool {
        let added = Traversals::numbered(more, self.faces as u32);
        // Each edge's look-up is a search of the whole list: on all threads.
        let groups: Vec<&[Traversal]> = added.chunk_by(|a, b| a.edge == b.edge).collect();
        let leaves_open = |k: usize| {
            let extra = groups[k];
            let edge = extra[0].edge;
            let from = self.items.partition_point(|t| t.edge < edge);
            let to = from + self.items[from..].partition_point(|t| t.edge == edge);
            let mut both = Vec::with_capacity(to - from + extra.len());
            both.extend_from_slice(&self.items[from..to]);
            both.extend_from_slice(extra);
            let (open, inconsistent) = edges_meet(&both);
            open || inconsistent
        };
        if groups.len() <= SEARCHES_A_TASK || rayon::current_num_threads() == 1 {
            return (0..groups.len()).any(leaves_open);
        }
        (0..groups.len())
            .into_par_iter()
            .with_min_len(SEARCHES_A_TASK)
            .any(leaves_open)
    }

    /// The edges one face alone traverses, each as that face's step `a → b` (an edge from a
    /// vertex to itself left out: it is its own reverse), in face order and, within a face,
    /// in corner order. Of an open, consistent mesh ([`Topology::Open`]), exactly its
    /// directed edges whose reverse no face has: the holes' boundaries. `faces` are the
    /// faces these traversals are of.
    pub(crate) fn once(&self, faces: &[Face]) -> Vec<(u32, u32)> {
        let step = |t: &Traversal| {
            let (lo, hi) = ((t.edge >> 32) as u32, t.edge as u32);
            let (a, b) = if t.forward { (lo, hi) } else { (hi, lo) };
            let v = &faces[t.face as usize].vertices;
            let n = v.len();
            let corner = (0..n)
                .find(|&i| v[i] == a && v[(i + 1) % n] == b)
                .expect("a traversal is a step of its face");
            (t.face, corner, a, b)
        };
        // In chunks of whole edges on all threads; the few steps then sorted.
        let mut steps: Vec<(u32, usize, u32, u32)> = self
            .by_whole_edges(|items| {
                items
                    .chunk_by(|a, b| a.edge == b.edge)
                    .filter(|t| t.len() == 1 && t[0].edge >> 32 != t[0].edge & 0xffff_ffff)
                    .map(|t| step(&t[0]))
                    .collect::<Vec<_>>()
            })
            .concat();
        steps.sort_unstable();
        steps.into_iter().map(|(_, _, a, b)| (a, b)).collect()
    }

    /// How the edges join up, as [`edge_topology`] says.
    pub(crate) fn topology(&self) -> Topology {
        if self.faces == 0 {
            return Topology::Open;
        }
        // By fixed chunks of whole edges; (open, inconsistent) or-ed, in any order.
        let (open, inconsistent) = self
            .by_whole_edges(edges_meet)
            .into_iter()
            .fold((false, false), |a, b| (a.0 || b.0, a.1 || b.1));
        if inconsistent {
            Topology::Inconsistent
        } else if open {
            Topology::Open
        } else {
            Topology::Closed
        }
    }

    /// The pieces of the faces connected through shared edges (a union-find over the faces
    /// of each edge, in fixed chunks of whole edges on all threads). They depend only on
    /// which faces share edges, not on order.
    pub(crate) fn pieces(&self) -> Pieces {
        let sets = UnionFind::new(self.faces);
        let join = |items: &[Traversal]| {
            for t in items.chunk_by(|a, b| a.edge == b.edge) {
                for w in t.windows(2) {
                    sets.join(w[0].face, w[1].face);
                }
            }
        };
        self.by_whole_edges(join);
        let (of_face, count) = sets.numbered();
        Pieces { of_face, count }
    }

    /// `each` run on the traversals in fixed chunks, on all threads where there are many,
    /// each chunk holding whole edges (those that start in it).
    fn by_whole_edges<R: Send>(&self, each: impl Fn(&[Traversal]) -> R + Sync) -> Vec<R> {
        let items = &self.items[..];
        if items.len() <= CHUNK || rayon::current_num_threads() == 1 {
            return vec![each(items)];
        }
        let start = |i: usize| {
            (i..items.len())
                .find(|&j| j == 0 || items[j - 1].edge != items[j].edge)
                .unwrap_or(items.len())
        };
        (0..items.len().div_ceil(CHUNK))
            .into_par_iter()
            .map(|c| {
                let end = ((c + 1) * CHUNK).min(items.len());
                each(&items[start(c * CHUNK)..start(end)])
            })
            .collect()
    }
}

/// Faces per chunk of [`Traversals::of`].
const CHUNK: usize = crate::chunked::CHUNK;

/// Traversals per chunk of [`Traversals::with_faces`]' merge (a few faces' worth each).
const MERGED_CHUNK: usize = 4 * crate::chunked::CHUNK;

/// Sorts on all threads when the list is long; short lists stay off the thread pool (200k
/// one-box objects would each wait on it).
pub(crate) fn sort<T: Ord + Send>(v: &mut [T]) {
    if v.len() > SORTED_IN_PARALLEL_ABOVE {
        v.par_sort_unstable();
    } else {
        v.sort_unstable();
    }
}

/// [`sort`] by a key.
pub(crate) fn sort_by_key<T: Send, K: Ord>(v: &mut [T], key: impl Fn(&T) -> K + Sync) {
    if v.len() > SORTED_IN_PARALLEL_ABOVE {
        v.par_sort_unstable_by_key(key);
    } else {
        v.sort_unstable_by_key(key);
    }
}

/// Above this many items [`sort`] and [`sort_by_key`] use all threads.
const SORTED_IN_PARALLEL_ABOVE: usize = 1 << 14;

/// Whether some edge of `items` (whole edges, sorted by edge) is used once only (open),
/// and whether some edge is used twice the same way or more than twice (inconsistent; the
/// search stops there).
fn edges_meet(items: &[Traversal]) -> (bool, bool) {
    let mut open = false;
    for t in items.chunk_by(|a, b| a.edge == b.edge) {
        let edge = t[0].edge;
        match t.len() {
            // An edge from a vertex to itself is its own reverse (as in `by_counts`).
            1 if edge >> 32 == edge & 0xffff_ffff => {}
            1 => open = true,
            2 if t[0].forward != t[1].forward => {}
            _ => return (open, true),
        }
    }
    (open, false)
}

/// Sorts `v` by `key`, whose order begins with `pair`'s (a packed edge's two vertices, say):
/// a stable least-significant-digit radix sort, two counting passes (by the pair's second
/// number, then by its first), each scattered between `v` and one copy of it. Linear, on one
/// thread and without a comparison, it beats a comparison sort on all threads for a mesh's
/// edge lists (a bunny render sorts 200k edges a dozen times). Being stable, it leaves items
/// with equal pairs in the order they came: callers must give them in `key`'s order (a face
/// or corner number counting up as the list is made, or items equal in all). Sorting by the
/// first number, then each vertex's few items by `key` (insertion sorts, their branches
/// mispredicted), cost the bunny's render 3.5% more CPU; moving the items in place (an
/// American flag sort) 14% more again: each swap waits on the last. On several threads a
/// list longer than [`PAIRS_RANKED_ABOVE`] is sorted that first way all the same
/// ([`crate::rank_sort`]), for its parts run side by side. Pairs sparser than
/// [`DENSE_BUCKETS`] a item, and lists longer than [`BUCKETED_UP_TO`] (whose copy raised the
/// peak of a 600k-face terrain by 8%, and of a 10M-face one too), go to [`sort_by_key`].
pub(crate) fn sort_by_pair<T: Clone + Send + Sync, K: Ord>(
    v: &mut [T],
    pair: impl Fn(&T) -> (u32, u32) + Sync,
    key: impl Fn(&T) -> K + Sync,
) {
    let n = v.len();
    if !(64..=BUCKETED_UP_TO).contains(&n) {
        return sort_by_key(v, key);
    }
    if n > PAIRS_RANKED_ABOVE && rayon::current_num_threads() > 1 {
        // On all threads: by the first number in buckets of its range, each bucket counted
        // into place (or compared, where the numbers are sparse), then each first number's
        // few items by the second, stably (so items with equal pairs keep their order).
        return crate::rank_sort::sort_by_rank(v, |x| pair(x).0, |x| pair(x).1);
    }
    let tops = v
        .iter()
        .map(&pair)
        .reduce(|a, b| (a.0.max(b.0), a.1.max(b.1)));
    let Some((first_top, second_top)) = tops else {
        return;
    };
    let dense = |top: u32| top as usize <= DENSE_BUCKETS * n;
    if !dense(first_top) || !dense(second_top) {
        return sort_by_key(v, key);
    }
    let mut copy = v.to_vec();
    scatter(v, &mut copy, |x| pair(x).1, second_top);
    scatter(&copy, v, |x| pair(x).0, first_top);
}

/// One counting pass of [`sort_by_pair`]: `from` into `to` by `digit` (at most `top`),
/// stably.
fn scatter<T: Clone>(from: &[T], to: &mut [T], digit: impl Fn(&T) -> u32, top: u32) {
    // at[d]: where digit d's items start; while scattering, the next one's place.
    let mut at = vec![0u32; top as usize + 2];
    for x in from {
        at[digit(x) as usize + 1] += 1;
    }
    for d in 1..at.len() {
        at[d] += at[d - 1];
    }
    for x in from {
        let slot = &mut at[digit(x) as usize];
        to[*slot as usize] = x.clone();
        *slot += 1;
    }
}

/// Most values of a pair's number a item for which [`sort_by_pair`] counts (beyond, it
/// compares).
const DENSE_BUCKETS: usize = 4;

/// Edges of `more` a task looks up in [`Traversals::not_closed_with`] (each two searches of
/// a long list: a 1M-face terrain's cap looks up 8,000 edges in 3M traversals).
const SEARCHES_A_TASK: usize = 256;

/// Longest list [`sort_by_pair`] counts (beyond, it compares on all threads).
const BUCKETED_UP_TO: usize = 1 << 20;

/// Above this many items, on more than one thread, [`sort_by_pair`] ranks by the first
/// number on all threads (a bucket of [`crate::rank_sort`]'s, 64k items, a thread): the two
/// counting passes on one thread were a mid-sized mesh's longest serial step (ogre's
/// 372k traversals, sorted four times: 30 ms of its 105 ms on one thread of two).
const PAIRS_RANKED_ABOVE: usize = 1 << 17;

/// Connected pieces of a mesh's faces through shared edges.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct Pieces {
    /// By face: its piece, numbered from 0 in order of first face.
    pub(crate) of_face: Vec<u32>,
    /// Number of pieces.
    pub(crate) count: usize,
}

/// The pieces of `faces` connected through shared edges ([`Traversals::pieces`]).
pub(crate) fn edge_pieces(faces: &[Face]) -> Pieces {
    Traversals::of(faces).pieces()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A closed `n` by `n` torus of quads, consistently oriented.
    fn torus(n: u32) -> Vec<Face> {
        let at = |i: u32, j: u32| (j % n) * n + i % n;
        (0..n * n)
            .map(|k| {
                let (i, j) = (k % n, k / n);
                Face::new([at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)])
            })
            .collect()
    }

    /// A quad as two triangles along its first diagonal, oriented like it.
    fn split_quad(q: Face) -> [Face; 2] {
        let v = &q.vertices;
        [Face::new([v[0], v[1], v[2]]), Face::new([v[0], v[2], v[3]])]
    }

    #[test]
    fn not_closed_with_is_sound_and_exact_for_a_closing_set() {
        // A closed 12x12 torus of triangles with faces taken away; `more` is a random choice
        // of the taken faces, some turned or repeated, or faces of the torus again. Whenever
        // the check says "not closed", the merged traversals' topology is not closed; the
        // taken faces themselves close it, and the check says so.
        let torus: Vec<Face> = torus(12).into_iter().flat_map(split_quad).collect();
        let mut rng = crate::geom::rng::XorShift::new(35);
        let (mut said_open, mut said_closed) = (0, 0);
        for round in 0..400 {
            let taken: Vec<usize> = (0..torus.len()).filter(|_| rng.below(9) == 0).collect();
            let kept: Vec<Face> = (0..torus.len())
                .filter(|f| !taken.contains(f))
                .map(|f| torus[f].clone())
                .collect();
            let base = Traversals::of(&kept);
            let mut more: Vec<Face> = taken.iter().map(|&f| torus[f].clone()).collect();
            if round % 4 != 0 {
                more.retain(|_| rng.below(5) != 0);
                for f in more.iter_mut() {
                    if rng.below(7) == 0 {
                        f.vertices.reverse();
                    }
                }
                if rng.below(3) == 0 {
                    more.push(torus[rng.below(torus.len())].clone());
                }
            }
            let merged = base.with_faces(&more).topology();
            if base.not_closed_with(&more) {
                assert_ne!(merged, Topology::Closed, "round {round}");
                said_open += 1;
            } else {
                said_closed += 1;
            }
            if round % 4 == 0 && !taken.is_empty() {
                assert!(!base.not_closed_with(&more), "round {round}");
                assert_eq!(merged, Topology::Closed, "round {round}");
            }
        }
        // Both answers were given many times: the test cannot pass on one of them alone.
        assert!(
            said_open > 100 && said_closed > 90,
            "{said_open} {said_closed}"
        );
    }

    #[test]
    fn topology_found_on_several_threads_is_the_one_thread_topology() {
        // A closed 100x100 torus of quads (40,000 traversals, chunks of edges), then opened
        // by a missing face, then made inconsistent by a face turned the other way, each
        // flaw in a late chunk.
        let torus = torus(100);
        let mut open = torus.clone();
        open.remove(9000);
        let mut inconsistent = open.clone();
        inconsistent[8000].vertices.reverse();
        let pool = crate::chunked::pool;
        for (faces, want) in [
            (torus, Topology::Closed),
            (open, Topology::Open),
            (inconsistent, Topology::Inconsistent),
        ] {
            let t = Traversals::of(&faces);
            assert!(t.items.len() > 3 * CHUNK);
            assert_eq!(pool(1).install(|| t.topology()), want);
            assert_eq!(pool(3).install(|| t.topology()), want);
        }
    }

    #[test]
    fn traversals_made_on_several_threads_are_the_one_thread_list() {
        // A strip of quads and triangles, many chunks of faces long.
        let faces: Vec<Face> = (0..3 * CHUNK as u32 + 77)
            .map(|k| {
                if k % 3 == 0 {
                    Face::new(vec![k, k + 1, k + 2])
                } else {
                    Face::new(vec![k, k + 1, k + 3, k + 2])
                }
            })
            .collect();
        let pool = crate::chunked::pool;
        let key = |t: &Traversals| -> Vec<(u64, u32, bool)> {
            t.items
                .iter()
                .map(|x| (x.edge, x.face, x.forward))
                .collect()
        };
        let one = pool(1).install(|| key(&Traversals::of(&faces)));
        assert_eq!(
            one.len(),
            faces.iter().map(|f| f.vertices.len()).sum::<usize>()
        );
        assert_eq!(pool(3).install(|| key(&Traversals::of(&faces))), one);
    }

    /// Each traversal as (edge, face, direction), in the list's order.
    fn listed(t: &Traversals) -> Vec<(u64, u32, bool)> {
        t.items
            .iter()
            .map(|x| (x.edge, x.face, x.forward))
            .collect()
    }

    /// A grid of `m` by `m` cells, consistently oriented: quads, some as two triangles and
    /// some with a corner repeated (an edge from a vertex to itself), every 7th cell left
    /// out (holes, some meeting at a corner).
    fn holed_grid(m: u32) -> Vec<Face> {
        let v = |i: u32, j: u32| j * (m + 1) + i;
        (0..m * m)
            .filter(|c| c % 7 != 3)
            .flat_map(|c| {
                let (i, j) = (c % m, c / m);
                let (a, b, d, e) = (v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j + 1));
                match c % 3 {
                    0 => vec![Face::new(vec![a, b, d, e])],
                    1 => vec![Face::new(vec![a, b, d]), Face::new(vec![a, d, e])],
                    _ => vec![Face::new(vec![a, b, b, d, e])],
                }
            })
            .collect()
    }

    #[test]
    fn merged_traversals_are_those_of_the_faces_joined() {
        let pool = crate::chunked::pool;
        let faces = holed_grid(300);
        assert!(faces.len() > 10 * CHUNK);
        for split in [0, 1, 5, faces.len() / 2, faces.len() - 3, faces.len()] {
            let whole = listed(&Traversals::of(&faces));
            for threads in [1, 3] {
                let merged = pool(threads)
                    .install(|| Traversals::of(&faces[..split]).with_faces(&faces[split..]));
                assert_eq!(merged.faces, faces.len());
                let got = listed(&merged);
                // Sorted by edge, then face, as `of` sorts: the same list; within one
                // face's traversals of one edge (a degenerate face's) in any order.
                let key = |l: &[(u64, u32, bool)]| l.iter().map(|x| (x.0, x.1)).collect::<Vec<_>>();
                assert_eq!(key(&got), key(&whole), "split {split}, {threads} threads");
                let (mut g, mut w) = (got.clone(), whole.clone());
                g.sort_unstable();
                w.sort_unstable();
                assert_eq!(g, w);
            }
        }
    }

    /// The directed edges whose reverse no face has, face by face, corner by corner: the
    /// holes' boundary as first written (one sorted list of directed edges searched).
    fn reverse_missing(faces: &[Face]) -> Vec<(u32, u32)> {
        let step = |f: &Face, i: usize| (f.vertices[i], f.vertices[(i + 1) % f.vertices.len()]);
        let mut directed: Vec<(u32, u32)> = faces
            .iter()
            .flat_map(|f| (0..f.vertices.len()).map(move |i| step(f, i)))
            .collect();
        directed.sort_unstable();
        faces
            .iter()
            .flat_map(|f| (0..f.vertices.len()).map(move |i| step(f, i)))
            .filter(|&(a, b)| directed.binary_search(&(b, a)).is_err())
            .collect()
    }

    #[test]
    fn edges_traversed_once_are_the_boundary_steps_in_face_order() {
        let strip = holed_grid(150);
        assert_eq!(edge_topology(&strip), Topology::Open);
        let once = Traversals::of(&strip).once(&strip);
        assert_eq!(once, reverse_missing(&strip));
        assert!(once.len() > strip.len() / 7, "{}", once.len());
        for skip in 0..4 {
            let mut open = tet(false);
            open.remove(skip);
            assert_eq!(Traversals::of(&open).once(&open), reverse_missing(&open));
        }
        let closed = tet(false);
        assert!(Traversals::of(&closed).once(&closed).is_empty());
    }

    fn tet(flip_one: bool) -> Vec<Face> {
        let mut f = vec![vec![0, 2, 1], vec![0, 1, 3], vec![1, 2, 3], vec![2, 0, 3]];
        if flip_one {
            f[0].reverse();
        }
        f.into_iter().map(Face::new).collect()
    }

    #[test]
    fn tetrahedron_closed_and_flipped_not() {
        assert!(is_closed_oriented(&tet(false)));
        assert!(!is_closed_oriented(&tet(true)));
        assert!(!is_closed_oriented(&tet(false)[..3]));
        assert_eq!(edge_topology(&tet(false)), Topology::Closed);
        assert_eq!(edge_topology(&tet(true)), Topology::Inconsistent);
        assert_eq!(edge_topology(&tet(false)[..3]), Topology::Open);
        assert_eq!(edge_topology(&[]), Topology::Open);
        // A corner repeated: its edge from a vertex to itself is its own reverse, once.
        let mut pinched = tet(false);
        pinched[0].vertices.insert(1, 0);
        assert_eq!(edge_topology(&pinched), by_counts(&pinched));
        assert_eq!(edge_topology(&pinched), Topology::Closed);
        pinched[1].vertices.insert(1, 0);
        assert_eq!(edge_topology(&pinched), by_counts(&pinched));
        assert_eq!(edge_topology(&pinched), Topology::Inconsistent);
    }

    /// The plain definition, by counting directed edges in a map.
    fn by_counts(faces: &[Face]) -> Topology {
        use std::collections::HashMap;
        let mut c: HashMap<(u32, u32), u32> = HashMap::new();
        for f in faces {
            let n = f.vertices.len();
            for i in 0..n {
                *c.entry((f.vertices[i], f.vertices[(i + 1) % n]))
                    .or_default() += 1;
            }
        }
        if faces.is_empty() {
            return Topology::Open;
        }
        let mut open = false;
        for (&(a, b), &k) in &c {
            match (k, c.get(&(b, a)).copied().unwrap_or(0)) {
                (1, 1) => {}
                (1, 0) => open = true,
                _ => return Topology::Inconsistent,
            }
        }
        if open {
            Topology::Open
        } else {
            Topology::Closed
        }
    }

    #[test]
    fn sorted_edges_agree_with_counting_on_random_face_sets() {
        let mut rng = crate::geom::rng::XorShift::new(5);
        let mut seen = [0usize; 3];
        for round in 0..400 {
            // Tetrahedra and octahedra with faces dropped, flipped or repeated at random.
            let mut faces = if round % 2 == 0 {
                tet(false)
            } else {
                octahedron()
            };
            if rng.below(3) == 0 {
                let k = rng.below(faces.len());
                faces.remove(k);
            }
            if rng.below(3) == 0 {
                let k = rng.below(faces.len());
                faces[k].vertices.reverse();
            }
            if rng.below(4) == 0 {
                let k = rng.below(faces.len());
                faces.push(faces[k].clone());
            }
            if rng.below(4) == 0 {
                // A corner repeated: an edge from a vertex to itself.
                let k = rng.below(faces.len());
                let v = faces[k].vertices[0];
                faces[k].vertices.insert(0, v);
            }
            let t = edge_topology(&faces);
            assert_eq!(t, by_counts(&faces), "{faces:?}");
            assert_eq!(is_closed_oriented(&faces), t == Topology::Closed);
            seen[t as usize] += 1;
        }
        assert!(seen.iter().all(|&n| n > 0), "{seen:?}");
    }

    fn octahedron() -> Vec<Face> {
        crate::primitives::by_name("octahedron")
            .unwrap()
            .faces
            .into_iter()
            .map(Face::new)
            .collect()
    }

    /// [`sort_by_pair`] of packed edges `a << 32 | b` (or such an edge with a number
    /// counting up in the list), by the edge.
    fn sort_edges<T: Ord + Copy + Send + Sync>(v: &mut [T], edge: impl Fn(&T) -> u64 + Sync) {
        sort_by_pair(v, |x| ((edge(x) >> 32) as u32, edge(x) as u32), |x| *x);
    }

    #[test]
    fn radix_sort_is_the_sort() {
        let mut rng = crate::geom::rng::XorShift::new(7);
        for (n, verts) in [(0, 1), (5, 3), (100, 10), (5000, 900), (5000, 1 << 30)] {
            // Packed edges, duplicates among them, and with a number counting up: the sort's
            // own order.
            let mut edges: Vec<u64> = (0..n)
                .map(|_| (rng.below(verts) as u64) << 32 | rng.below(verts) as u64)
                .collect();
            let mut numbered: Vec<(u64, u32)> = (edges.iter().copied()).zip(0..).collect();
            let (mut want, mut want_numbered) = (edges.clone(), numbered.clone());
            want.sort_unstable();
            want_numbered.sort_unstable();
            sort_edges(&mut edges, |&e| e);
            sort_edges(&mut numbered, |e| e.0);
            assert_eq!(edges, want, "{n} edges over {verts} vertices");
            assert_eq!(numbered, want_numbered);
        }
        // A key finer than the pair, in input order among equal pairs (as half-edges'
        // corners are): each pass must be stable; long lists on several threads too.
        for (n, firsts, seconds) in [
            (3000, 40, 30),
            (PAIRS_RANKED_ABOVE + 4321, 100_000, 100_000),
            (PAIRS_RANKED_ABOVE + 7, 50, 9),
        ] {
            let v: Vec<(u32, u32, usize)> = (0..n)
                .map(|k| (rng.below(firsts) as u32, rng.below(seconds) as u32, k))
                .collect();
            let mut want = v.clone();
            want.sort_unstable();
            for threads in [1, 3] {
                let mut got = v.clone();
                crate::chunked::pool(threads)
                    .install(|| sort_by_pair(&mut got, |x| (x.0, x.1), |x| *x));
                assert!(got == want, "{n} items, {threads} threads");
            }
        }
    }
}
