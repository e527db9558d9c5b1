//! A stable sort of a big list by a small whole-number rank (a vertex, a position), then a
//! key within one rank, in linear time on all threads: the items are dealt into buckets of
//! rank ranges in fixed chunks, and each bucket is counted into its place.
//!
//! The result is the list sorted stably by (rank, key): one list whatever the thread count
//! and however the buckets fall. A comparison sort of a mesh's 30 million edge traversals
//! spends most of its time comparing, and its first partition runs on one thread; counting
//! by rank does neither. Ranks must be dense (at most a few times the list's length) for the
//! counts to be cheap; ties of rank are sorted by key, so a list of few ranks is still
//! sorted, by comparisons.

use rayon::prelude::*;

/// Items per bucket of rank ranges, on average (a bucket's counts stay in cache).
const BUCKET: usize = 1 << 16;

/// Items per chunk dealt into buckets on one thread.
const DEALT: usize = 1 << 16;

/// Most ranks counted per item (beyond, the ranks are too sparse to count: compared).
const DENSE: u64 = 4;

/// `v` sorted stably by `(rank(x), key(x))`: by counting on all threads where `v` is longer
/// than a bucket, in one pass of counts otherwise; where the ranks are sparse (the greatest
/// above [`DENSE`] times the length), by a stable comparison sort on all threads.
pub(crate) fn sort_by_rank<T, K>(
    v: &mut [T],
    rank: impl Fn(&T) -> u32 + Sync,
    key: impl Fn(&T) -> K + Sync,
) where
    T: Clone + Send + Sync,
    K: Ord,
{
    let n = v.len();
    let parallel = n > BUCKET && rayon::current_num_threads() > 1;
    let top = if parallel {
        v.par_iter().with_min_len(BUCKET).map(&rank).max()
    } else {
        v.iter().map(&rank).max()
    };
    let Some(top) = top else {
        return;
    };
    let width = u64::from(top) + 1;
    if width > DENSE * n as u64 + 64 {
        v.par_sort_by_key(|x| (rank(x), key(x)));
        return;
    }
    if !parallel {
        let items = v.to_vec();
        counted(&[&items], v, 0, width as usize, &rank, &key);
        return;
    }
    // Buckets of equal rank ranges, as many as the length asks: ranks [lo(k), lo(k + 1)).
    let buckets = n.div_ceil(BUCKET) as u64;
    let bucket = |x: &T| (u64::from(rank(x)) * buckets / width) as usize;
    let lo = |k: u64| (k * width).div_ceil(buckets) as u32;
    // Each chunk's items dealt into the buckets, in order.
    let dealt: Vec<Vec<Vec<T>>> = v
        .par_chunks(DEALT)
        .map(|chunk| {
            let mut parts = vec![Vec::new(); buckets as usize];
            for x in chunk {
                parts[bucket(x)].push(x.clone());
            }
            parts
        })
        .collect();
    // By bucket: its parts in chunk order, and its place in `v`.
    let mut columns: Vec<Vec<Vec<T>>> = (0..buckets)
        .map(|_| Vec::with_capacity(dealt.len()))
        .collect();
    for parts in dealt {
        for (k, part) in parts.into_iter().enumerate() {
            columns[k].push(part);
        }
    }
    let mut places = Vec::with_capacity(columns.len());
    let mut rest = &mut v[..];
    for c in &columns {
        let (here, after) = rest.split_at_mut(c.iter().map(Vec::len).sum());
        places.push(here);
        rest = after;
    }
    columns
        .into_par_iter()
        .zip(places)
        .enumerate()
        .for_each(|(k, (column, place))| {
            let parts: Vec<&[T]> = column.iter().map(Vec::as_slice).collect();
            let (from, to) = (lo(k as u64), lo(k as u64 + 1));
            counted(&parts, place, from, (to - from) as usize, &rank, &key);
        });
}

/// Above this many items [`sort_distinct_by_rank`] deals them into buckets in place.
const IN_PLACE_ABOVE: usize = 1 << 20;

/// [`sort_by_rank`] of a list whose items' `(rank, key)` are all distinct (so its order is
/// the one sort order, stable or not), with no copy of the list beside it where it is long
/// (above [`IN_PLACE_ABOVE`]): the items are swapped into their buckets of rank ranges in
/// place (an American flag pass, on one thread, after counting on all), then each bucket is
/// counted into order on all threads through a copy of itself alone.
pub(crate) fn sort_distinct_by_rank<T, K>(
    v: &mut [T],
    rank: impl Fn(&T) -> u32 + Sync,
    key: impl Fn(&T) -> K + Sync,
) where
    T: Clone + Send + Sync,
    K: Ord,
{
    let n = v.len();
    if n <= IN_PLACE_ABOVE {
        return sort_by_rank(v, rank, key);
    }
    let Some(top) = v.par_iter().with_min_len(BUCKET).map(&rank).max() else {
        return;
    };
    let width = u64::from(top) + 1;
    if width > DENSE * n as u64 + 64 {
        v.par_sort_unstable_by_key(|x| (rank(x), key(x)));
        return;
    }
    let buckets = n.div_ceil(BUCKET) as u64;
    let bucket = |x: &T| (u64::from(rank(x)) * buckets / width) as usize;
    let lo = |k: u64| (k * width).div_ceil(buckets) as u32;
    // Items a bucket, summed over chunks in integers: the same in any order.
    let zero = || vec![0usize; buckets as usize];
    let add = |mut c: Vec<usize>, chunk: &[T]| {
        chunk.iter().for_each(|x| c[bucket(x)] += 1);
        c
    };
    let merge = |mut a: Vec<usize>, b: Vec<usize>| {
        a.iter_mut().zip(&b).for_each(|(a, b)| *a += b);
        a
    };
    let counts = v.par_chunks(DEALT).fold(zero, add).reduce(zero, merge);
    deal_in_place(v, &bucket, &counts);
    let mut places = Vec::with_capacity(counts.len());
    let mut rest = &mut v[..];
    for &c in &counts {
        let (here, after) = std::mem::take(&mut rest).split_at_mut(c);
        places.push(here);
        rest = after;
    }
    places.into_par_iter().enumerate().for_each(|(k, place)| {
        let items = place.to_vec();
        let (from, to) = (lo(k as u64), lo(k as u64 + 1));
        counted(&[&items], place, from, (to - from) as usize, &rank, &key);
    });
}

/// `v`'s items swapped into their buckets (bucket `k` holds `counts[k]` items, buckets in
/// order), each item moved once: every slot of a bucket not yet filled takes the item there
/// to its own bucket's next free slot, until the item it gets back is its own.
fn deal_in_place<T>(v: &mut [T], bucket: &impl Fn(&T) -> usize, counts: &[usize]) {
    let mut next = Vec::with_capacity(counts.len());
    let mut end = Vec::with_capacity(counts.len());
    let mut at = 0;
    for &c in counts {
        next.push(at);
        at += c;
        end.push(at);
    }
    for b in 0..counts.len() {
        while next[b] < end[b] {
            let mut d = bucket(&v[next[b]]);
            while d != b {
                v.swap(next[b], next[d]);
                next[d] += 1;
                d = bucket(&v[next[b]]);
            }
            next[b] += 1;
        }
    }
}

/// The items of `parts`, in order (every rank in `from..from + width`), into `out` sorted
/// stably by rank, then each run of one rank sorted stably by key.
fn counted<T: Clone, K: Ord>(
    parts: &[&[T]],
    out: &mut [T],
    from: u32,
    width: usize,
    rank: &impl Fn(&T) -> u32,
    key: &impl Fn(&T) -> K,
) {
    let slot = |x: &T| (rank(x) - from) as usize;
    // at[r]: where rank r's items start; while they are placed, the next one's place.
    let items = || parts.iter().flat_map(|p| p.iter());
    let mut at = vec![0usize; width + 1];
    for x in items() {
        at[slot(x) + 1] += 1;
    }
    for r in 1..at.len() {
        at[r] += at[r - 1];
    }
    for x in items() {
        let s = &mut at[slot(x)];
        out[*s] = x.clone();
        *s += 1;
    }
    // Now at[r] is where rank r's items end.
    let mut start = 0;
    for &end in &at[..width] {
        if end - start > 1 {
            out[start..end].sort_by_key(key);
        }
        start = end;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Items (rank, key, serial): ranks of every density (many ties, all distinct, few
    /// ranks), keys with ties, so that stability shows in the serials.
    fn items(n: usize, top: u32, keys: u32) -> Vec<(u32, u32, usize)> {
        let mut s = n as u64 * 31 + u64::from(top);
        let mut below = |m: u64| {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((s >> 33) % m) as u32
        };
        (0..n)
            .map(|i| (below(u64::from(top) + 1), below(u64::from(keys)), i))
            .collect()
    }

    #[test]
    fn ranks_counted_on_several_threads_are_the_stable_sort() {
        let pool = crate::chunked::pool;
        for (n, top, keys) in [
            (0, 0, 1),
            (5, 3, 2),
            (BUCKET, 10, 3),
            (3 * BUCKET + 77, 3 * BUCKET as u32, 4),
            (5 * BUCKET + 1, 7, 1000),
            (4 * BUCKET + 5, 40 * BUCKET as u32, 2),
            (2 * DEALT + 3, 0, 5),
            // Sparse ranks: compared.
            (BUCKET + 9, u32::MAX - 1, 3),
            (100, 1_000_000, 3),
        ] {
            let v = items(n, top, keys);
            let mut want = v.clone();
            want.sort_by_key(|x| (x.0, x.1));
            for threads in [1, 3] {
                let mut got = v.clone();
                pool(threads).install(|| sort_by_rank(&mut got, |x| x.0, |x| x.1));
                assert_eq!(got, want, "n {n}, top {top}, {threads} threads");
            }
        }
    }

    #[test]
    fn distinct_items_dealt_in_place_are_the_sort() {
        let pool = crate::chunked::pool;
        let n = IN_PLACE_ABOVE + 3 * BUCKET + 5;
        // (rank, key, serial): the serial makes every item distinct; ranks dense, with
        // ties, and sparse.
        for (top, keys) in [(n as u32 / 2, 4), (7, 1000), (u32::MAX - 1, 3)] {
            let v: Vec<(u32, (u32, usize))> = items(n, top, keys)
                .into_iter()
                .map(|(r, k, i)| (r, (k, i)))
                .collect();
            let mut want = v.clone();
            want.sort();
            for threads in [1, 3] {
                let mut got = v.clone();
                pool(threads).install(|| sort_distinct_by_rank(&mut got, |x| x.0, |x| x.1));
                assert!(got == want, "top {top}, {threads} threads");
            }
        }
    }
}
