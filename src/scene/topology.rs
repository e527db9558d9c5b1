//! Edge topology of a face set: closedness and consistent orientation.

use rayon::prelude::*;

use super::object::Face;

/// True when every undirected edge is used by exactly two faces, once in each direction:
/// the faces bound a closed, consistently oriented solid.
pub fn is_closed_oriented(faces: &[Face]) -> bool {
    edge_topology(faces) == Topology::Closed
}

/// How the edges of a face set join up.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Topology {
    /// Every edge used by exactly two faces, once in each direction.
    Closed,
    /// Some edge used by one face only (and none used inconsistently).
    Open,
    /// Some edge used twice in one direction, or by more than two faces.
    Inconsistent,
}

/// Classifies the edges of `faces` (an empty set is open). The directed edges are sorted as
/// packed integers, and so are their reverses: with no edge twice, the faces are closed
/// exactly when the two lists are equal (every edge's reverse is an edge, and reversing is
/// one-to-one). No hashing and no search: two sorts and one pass.
pub fn edge_topology(faces: &[Face]) -> Topology {
    if faces.is_empty() {
        return Topology::Open;
    }
    let corners: usize = faces.iter().map(|f| f.vertices.len()).sum();
    let mut edges: Vec<u64> = Vec::with_capacity(corners);
    for f in faces {
        let n = f.vertices.len();
        for i in 0..n {
            let (a, b) = (f.vertices[i], f.vertices[(i + 1) % n]);
            edges.push((a as u64) << 32 | b as u64);
        }
    }
    let mut reversed: Vec<u64> = edges.iter().map(|e| e.rotate_right(32)).collect();
    sort_edges(&mut edges, |&e| e);
    // A directed edge twice: used twice one way, or by more than two faces.
    if edges.windows(2).any(|w| w[0] == w[1]) {
        return Topology::Inconsistent;
    }
    sort_edges(&mut reversed, |&e| e);
    if edges == reversed {
        Topology::Closed
    } else {
        Topology::Open
    }
}

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

/// Sorts `v` by `key` through `bucket`, a small coarse key the order refines
/// (`bucket(x) < bucket(y)` implies `key(x) < key(y)`, as a packed edge's first vertex does):
/// a counting sort by bucket (scattered from a copy of the list), then each bucket's few
/// items sorted by `key`. Linear and on one thread, it beats a comparison sort on all threads
/// for a mesh's edge lists (a bunny render sorts 200k edges a dozen times: CPU 0.90 of the
/// whole render). Moving the items in place instead (an American flag sort) made the render
/// 14% slower: each swap waits on the last. Buckets sparser than [`DENSE_BUCKETS`] a item,
/// and lists longer than [`BUCKETED_UP_TO`] (whose copy raised the peak of a 600k-face
/// terrain by 8%, and of a 10M-face one too), go to [`sort_by_key`]. Items with equal keys
/// must be equal, so that the order is the one every sort gives.
pub(crate) fn sort_by_bucket<T: Clone + Send, K: Ord>(
    v: &mut [T],
    bucket: impl Fn(&T) -> u32,
    key: impl Fn(&T) -> K + Sync,
) {
    let n = v.len();
    let Some(top) = v.iter().map(&bucket).max() else {
        return;
    };
    if !(64..=BUCKETED_UP_TO).contains(&n) || top as usize > DENSE_BUCKETS * n {
        return sort_by_key(v, key);
    }
    // at[b]: where bucket b starts; while scattering, its next place (so, after, where
    // bucket b + 1 starts).
    let mut at = vec![0u32; top as usize + 2];
    for x in v.iter() {
        at[bucket(x) as usize + 1] += 1;
    }
    for b in 1..at.len() {
        at[b] += at[b - 1];
    }
    let items = v.to_vec();
    for x in items {
        let slot = &mut at[bucket(&x) as usize];
        v[*slot as usize] = x;
        *slot += 1;
    }
    // Bucket b now runs from at[b - 1] (0 for the first) to at[b].
    let mut lo = 0;
    for &hi in &at[..=top as usize] {
        if hi - lo > 1 {
            v[lo as usize..hi as usize].sort_unstable_by_key(&key);
        }
        lo = hi;
    }
}

/// Most buckets a item for which [`sort_by_bucket`] counts (beyond, it compares).
const DENSE_BUCKETS: usize = 4;

/// Longest list [`sort_by_bucket`] sorts by buckets (beyond, it compares on all threads).
const BUCKETED_UP_TO: usize = 1 << 20;

/// [`sort_by_bucket`] of packed edges `a << 32 | b` (or such an edge with a number), by the
/// first vertex.
pub(crate) fn sort_edges<T: Ord + Copy + Send>(v: &mut [T], edge: impl Fn(&T) -> u64) {
    sort_by_bucket(v, |x| (edge(x) >> 32) as u32, |x| *x);
}

/// Connected pieces of a mesh's faces through shared edges.
#[derive(Debug)]
pub(crate) struct Pieces {
    /// By face: its piece, numbered from 0 in order of first face.
    pub(crate) of_face: Vec<u32>,
    /// Number of pieces.
    pub(crate) count: usize,
}

/// The pieces of `faces` connected through shared edges (union-find over the sorted
/// undirected edges).
pub(crate) fn edge_pieces(faces: &[Face]) -> Pieces {
    let n = faces.len();
    let mut parent: Vec<u32> = (0..n as u32).collect();
    fn find(parent: &mut [u32], mut x: u32) -> u32 {
        while parent[x as usize] != x {
            parent[x as usize] = parent[parent[x as usize] as usize];
            x = parent[x as usize];
        }
        x
    }
    // Undirected edges with their faces, sorted: the faces of one edge are neighbours in the
    // list (no hashing). The pieces depend only on which faces share edges, not on order.
    let mut edges: Vec<(u64, u32)> = Vec::with_capacity(n * 3);
    for (k, f) in faces.iter().enumerate() {
        let m = f.vertices.len();
        for e in 0..m {
            let (a, b) = (f.vertices[e], f.vertices[(e + 1) % m]);
            edges.push(((a.min(b) as u64) << 32 | a.max(b) as u64, k as u32));
        }
    }
    sort_edges(&mut edges, |e| e.0);
    for w in edges.windows(2) {
        if w[0].0 == w[1].0 {
            let (ra, rb) = (find(&mut parent, w[0].1), find(&mut parent, w[1].1));
            parent[ra.max(rb) as usize] = ra.min(rb);
        }
    }
    let mut label = vec![u32::MAX; n];
    let mut of_face = vec![0; n];
    let mut count = 0;
    for (k, slot) in of_face.iter_mut().enumerate() {
        let r = find(&mut parent, k as u32) as usize;
        if label[r] == u32::MAX {
            label[r] = count as u32;
            count += 1;
        }
        *slot = label[r];
    }
    Pieces { of_face, count }
}

#[cfg(test)]
mod tests {
    use super::*;

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

    #[test]
    fn bucket_sort_is_the_sort() {
        let mut rng = crate::geom::rng::XorShift::new(7);
        for (n, verts) in [(0, 1), (5, 3), (100, 10), (5000, 900), (5000, 1 << 30)] {
            // Packed edges, duplicates among them, and with a number: the sort's own order.
            let mut edges: Vec<u64> = (0..n)
                .map(|_| (rng.below(verts) as u64) << 32 | rng.below(verts) as u64)
                .collect();
            let mut numbered: Vec<(u64, u32)> =
                edges.iter().map(|&e| (e, rng.below(50) as u32)).collect();
            let (mut want, mut want_numbered) = (edges.clone(), numbered.clone());
            want.sort_unstable();
            want_numbered.sort_unstable();
            sort_edges(&mut edges, |&e| e);
            sort_edges(&mut numbered, |e| e.0);
            assert_eq!(edges, want, "{n} edges over {verts} vertices");
            assert_eq!(numbered, want_numbered);
        }
        // A key finer than the bucket (unique keys, as half-edges have).
        let mut v: Vec<(u32, u32)> = (0..3000).map(|k| (rng.below(40) as u32, k)).collect();
        let mut want = v.clone();
        want.sort_unstable_by_key(|x| (x.0, std::cmp::Reverse(x.1)));
        sort_by_bucket(&mut v, |x| x.0, |x| (x.0, std::cmp::Reverse(x.1)));
        assert_eq!(v, want);
    }
}
