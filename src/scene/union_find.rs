//! Connected sets by a union-find joined on all threads, each set's root its least member.

use std::sync::atomic::{AtomicU32, Ordering::Relaxed};

use rayon::prelude::*;

use crate::chunked::CHUNK;

/// Disjoint sets of `0..n`, joined from any thread. A root is only ever linked below a lesser
/// root, so every parent is less than its child (no cycle can form) and every set's root is
/// its least member: the sets, their roots and [`UnionFind::numbered`] do not depend on the
/// order of the joins, nor on the number of threads.
///
/// Relaxed atomics suffice: each slot only ever holds its member or an ancestor of it in its
/// own set (a join links a root found unlinked by compare-and-swap; path halving writes a
/// grandparent read from the chain), so a stale read is still a valid ancestor, and the
/// thread pool's join orders the joins before [`UnionFind::numbered`] reads.
#[derive(Debug)]
pub(crate) struct UnionFind {
    parent: Vec<AtomicU32>,
}

impl UnionFind {
    /// `n` sets of one member each.
    pub(crate) fn new(n: usize) -> UnionFind {
        UnionFind {
            parent: crate::chunked::map(n, |k| AtomicU32::new(k as u32)),
        }
    }

    /// The root of `x`'s set, halving the path walked.
    pub(crate) fn find(&self, mut x: u32) -> u32 {
        loop {
            let p = self.parent[x as usize].load(Relaxed);
            if p == x {
                return x;
            }
            let g = self.parent[p as usize].load(Relaxed);
            if g != p {
                // Lost races leave `x`'s parent as it was: still an ancestor.
                let _ = self.parent[x as usize].compare_exchange_weak(p, g, Relaxed, Relaxed);
            }
            x = g;
        }
    }

    /// Joins the sets of `a` and `b`: the greater root is linked below the lesser, if it is
    /// still a root (else found again).
    pub(crate) fn join(&self, a: u32, b: u32) {
        let (mut a, mut b) = (a, b);
        loop {
            (a, b) = (self.find(a), self.find(b));
            if a == b {
                return;
            }
            let (lo, hi) = (a.min(b), a.max(b));
            let linked = self.parent[hi as usize].compare_exchange(hi, lo, Relaxed, Relaxed);
            if linked.is_ok() {
                return;
            }
        }
    }

    /// By member, the number of its set, the sets numbered from 0 in order of their least
    /// members; and how many sets there are. On all threads in fixed chunks of members.
    pub(crate) fn numbered(self) -> (Vec<u32>, usize) {
        let n = self.parent.len();
        let mut of: Vec<u32> = crate::chunked::map(n, |k| self.find(k as u32));
        // Sets starting before each chunk.
        let roots: Vec<usize> = if n > CHUNK {
            of.par_chunks(CHUNK)
                .enumerate()
                .map(|(c, r)| is_root(c, r).count())
                .collect()
        } else {
            vec![is_root(0, &of).count()]
        };
        let before: Vec<usize> = roots
            .iter()
            .scan(0, |s, &k| {
                *s += k;
                Some(*s - k)
            })
            .collect();
        // By root, its set's number; read by every member below.
        let mut label = vec![0u32; n];
        let label_chunk = |(c, l): (usize, &mut [u32])| {
            let r = &of[c * CHUNK..c * CHUNK + l.len()];
            for (k, i) in is_root(c, r).enumerate() {
                l[i] = (before[c] + k) as u32;
            }
        };
        if n > CHUNK {
            label
                .par_chunks_mut(CHUNK)
                .enumerate()
                .for_each(label_chunk);
        } else {
            label.chunks_mut(CHUNK).enumerate().for_each(label_chunk);
        }
        let relabel = |r: &mut u32| *r = label[*r as usize];
        if n > CHUNK {
            of.par_iter_mut().with_min_len(CHUNK).for_each(relabel);
        } else {
            of.iter_mut().for_each(relabel);
        }
        (of, roots.iter().sum())
    }
}

/// The places in `r`, chunk `c` of the roots by member, of the members that are roots.
fn is_root(c: usize, r: &[u32]) -> impl Iterator<Item = usize> + '_ {
    let first = c * CHUNK;
    (0..r.len()).filter(move |&i| r[i] == (first + i) as u32)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::chunked::pool;
    use crate::geom::rng::XorShift;

    /// The sets numbered one join at a time with a plain union-find and a first-seen table.
    fn by_hand(n: usize, joins: &[(u32, u32)]) -> (Vec<u32>, usize) {
        let mut parent: Vec<usize> = (0..n).collect();
        fn root(p: &mut [usize], mut x: usize) -> usize {
            while p[x] != x {
                p[x] = p[p[x]];
                x = p[x];
            }
            x
        }
        for &(a, b) in joins {
            let (ra, rb) = (root(&mut parent, a as usize), root(&mut parent, b as usize));
            parent[ra] = rb;
        }
        let mut number = vec![u32::MAX; n];
        let mut count = 0;
        let of = (0..n)
            .map(|k| {
                let r = root(&mut parent, k);
                if number[r] == u32::MAX {
                    number[r] = count;
                    count += 1;
                }
                number[r]
            })
            .collect();
        (of, count as usize)
    }

    #[test]
    fn sets_joined_on_several_threads_are_numbered_as_one_at_a_time() {
        let mut rng = XorShift::new(7);
        // Few and many joins, sets across chunk ends, a chain joined from its far end.
        for (n, joins) in [
            (10, 4),
            (3 * CHUNK + 17, 500),
            (5 * CHUNK, 5 * CHUNK),
            (40_000, 60_000),
        ] {
            let mut js: Vec<(u32, u32)> = (0..joins)
                .map(|_| (rng.below(n) as u32, rng.below(n) as u32))
                .collect();
            if n > CHUNK {
                js.extend((1..200).rev().map(|k| (k * 97, (k - 1) * 97)));
            }
            let want = by_hand(n, &js);
            assert!(
                want.1 > 1 && want.1 < n,
                "a test of both joins and sets apart"
            );
            for threads in [1, 3] {
                let got = pool(threads).install(|| {
                    let u = UnionFind::new(n);
                    js.par_iter().for_each(|&(a, b)| u.join(a, b));
                    u.numbered()
                });
                assert_eq!(got, want, "{n} members, {threads} threads");
            }
        }
    }
}
