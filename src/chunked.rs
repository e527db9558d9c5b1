//! Lists built on all threads in fixed chunks and joined in order: the same list, item for
//! item, as one pass on one thread, for any number of threads.
//!
//! The chunks depend only on the list's length and the chunk size, never on the thread
//! count, and the chunks' parts are joined in chunk order; on one thread (or for a list of
//! one chunk) the one pass runs as it is, off the thread pool. The join itself runs on all
//! threads: each item is copied to its place by whichever thread takes its range of places.

use std::ops::Range;

use rayon::prelude::*;

/// Items per chunk where a caller has no better size: large enough that the pool's overhead
/// per chunk is lost in the work, small enough that a million-item list gives hundreds.
pub(crate) const CHUNK: usize = 8192;

/// What `each` appends for every range of `0..n`, in order: `each` is called once per
/// chunk of `chunk` indices (the last one shorter) and must append for a range exactly what
/// it appends for its indices one by one, so that the chunks' parts joined are one pass's
/// list. On one thread, or where `n` is at most one chunk, that one pass runs.
pub(crate) fn flat_map<T, F>(n: usize, chunk: usize, each: F) -> Vec<T>
where
    T: Clone + Send + Sync,
    F: Fn(Range<usize>, &mut Vec<T>) + Sync,
{
    let chunk = chunk.max(1);
    if n <= chunk || rayon::current_num_threads() == 1 {
        let mut out = Vec::new();
        each(0..n, &mut out);
        return out;
    }
    let parts: Vec<Vec<T>> = (0..n.div_ceil(chunk))
        .into_par_iter()
        .map(|c| {
            let mut part = Vec::new();
            each(c * chunk..((c + 1) * chunk).min(n), &mut part);
            part
        })
        .collect();
    concat_freeing(parts)
}

/// What `each` writes for every range of `0..n`, in order, in a list made at its size:
/// `size(r)` must be exactly the number of items `each(r, out)` writes, and `each` is
/// given a slice of that many to fill. The ranges are fixed chunks of `chunk` indices, each
/// filled in its own place on all threads (on one thread, or for one chunk, one after
/// another): unlike [`flat_map`], no parts are held beside the list while it is joined.
pub(crate) fn fill<T, S, F>(n: usize, chunk: usize, size: S, each: F) -> Vec<T>
where
    T: Default + Clone + Send + Sync,
    S: Fn(Range<usize>) -> usize + Sync,
    F: Fn(Range<usize>, &mut [T]) + Sync,
{
    let chunk = chunk.max(1);
    let range = |c: usize| c * chunk..((c + 1) * chunk).min(n);
    let chunks = n.div_ceil(chunk);
    let serial = chunks <= 1 || rayon::current_num_threads() == 1;
    let sizes: Vec<usize> = if serial {
        (0..chunks).map(|c| size(range(c))).collect()
    } else {
        (0..chunks)
            .into_par_iter()
            .map(|c| size(range(c)))
            .collect()
    };
    // The list's places made (their pages first touched) on all threads.
    let total = sizes.iter().sum();
    let mut out = Vec::with_capacity(total);
    if serial {
        out.resize(total, T::default());
    } else {
        out.par_extend(
            (0..total)
                .into_par_iter()
                .with_min_len(CHUNK)
                .map(|_| T::default()),
        );
    }
    let mut places: Vec<(usize, &mut [T])> = Vec::with_capacity(chunks);
    let mut rest = out.as_mut_slice();
    for (c, &k) in sizes.iter().enumerate() {
        let (mine, tail) = std::mem::take(&mut rest).split_at_mut(k);
        places.push((c, mine));
        rest = tail;
    }
    let run = |(c, place): (usize, &mut [T])| each(range(c), place);
    if serial {
        places.into_iter().for_each(run);
    } else {
        places.into_par_iter().for_each(run);
    }
    out
}

/// `f(i)` for every `i` in `0..n`, in order: on all threads (an indexed collect) where `n` is
/// more than a chunk, else in one pass off the thread pool (a small mesh's lists would each
/// wait on it).
pub(crate) fn map<T: Send, F: Fn(usize) -> T + Sync + Send>(n: usize, f: F) -> Vec<T> {
    if n <= CHUNK || rayon::current_num_threads() == 1 {
        return (0..n).map(f).collect();
    }
    (0..n).into_par_iter().with_min_len(CHUNK).map(f).collect()
}

/// `out` with `f(i)` appended for every `i` in `0..n`, in order: as [`map`], on all threads
/// where `n` is more than a chunk.
pub(crate) fn extend_map<T: Send, F: Fn(usize) -> T + Sync + Send>(
    out: &mut Vec<T>,
    n: usize,
    f: F,
) {
    if n <= CHUNK || rayon::current_num_threads() == 1 {
        out.extend((0..n).map(f));
        return;
    }
    out.par_extend((0..n).into_par_iter().with_min_len(CHUNK).map(f));
}

/// `f(i, &mut v[i])` for every item of `v`: on all threads in fixed chunks where `v` is
/// longer than a chunk, else in one pass off the thread pool (each call touches its own
/// item only, so the items are those of one pass).
pub(crate) fn for_each_mut<T: Send, F: Fn(usize, &mut T) + Sync + Send>(v: &mut [T], f: F) {
    if v.len() <= CHUNK || rayon::current_num_threads() == 1 {
        v.iter_mut().enumerate().for_each(|(i, x)| f(i, x));
        return;
    }
    v.par_chunks_mut(CHUNK).enumerate().for_each(|(c, part)| {
        let at = c * CHUNK;
        part.iter_mut().enumerate().for_each(|(i, x)| f(at + i, x));
    });
}

/// The least `i` in `0..n` for which `bad(i)` holds: on all threads where `n` is more than a
/// chunk (the first found in index order, whichever thread finds it), else in one pass.
pub(crate) fn position_first<F: Fn(usize) -> bool + Sync + Send>(
    n: usize,
    bad: F,
) -> Option<usize> {
    if n <= CHUNK || rayon::current_num_threads() == 1 {
        return (0..n).position(bad);
    }
    (0..n)
        .into_par_iter()
        .with_min_len(CHUNK)
        .position_first(bad)
}

/// Parts joined at a time by [`concat_freeing`]: a few chunks of work for each thread.
const PARTS_AT_ONCE: usize = 16;

/// The parts one after another, copied on all threads (on one thread, one after another:
/// [`extend_concat`] into a new list), each few parts freed as soon as they are copied, so
/// that the list and its parts are not all held at once (the list's pages are touched only
/// as it is filled, and the parts' memory goes back to the allocator as they are done).
pub(crate) fn concat_freeing<T: Clone + Send + Sync>(mut parts: Vec<Vec<T>>) -> Vec<T> {
    let mut out = Vec::with_capacity(parts.iter().map(Vec::len).sum());
    for group in parts.chunks_mut(PARTS_AT_ONCE) {
        let slices: Vec<&[T]> = group.iter().map(Vec::as_slice).collect();
        extend_concat(&mut out, &slices);
        group.iter_mut().for_each(|p| *p = Vec::new());
    }
    out
}

/// `out` with the parts appended one after another, copied on all threads (on one thread,
/// or for a few items, one after another): [`concat_freeing`] into a list that already has
/// items.
pub(crate) fn extend_concat<T: Clone + Send + Sync>(out: &mut Vec<T>, parts: &[&[T]]) {
    let mut starts = Vec::with_capacity(parts.len() + 1);
    let mut total = 0;
    for p in parts {
        starts.push(total);
        total += p.len();
    }
    starts.push(total);
    out.reserve(total);
    if total <= CHUNK || rayon::current_num_threads() == 1 {
        for p in parts {
            out.extend_from_slice(p);
        }
        return;
    }
    // Each run of places walks its parts with a cursor: a search only where a run starts.
    out.par_extend((0..total).into_par_iter().with_min_len(CHUNK).map_init(
        || 0usize,
        |k, i| {
            if !(starts[*k] <= i && i < starts[*k + 1]) {
                // The last part beginning at or before i (an empty part begins where the
                // next does, so this one holds i).
                *k = starts.partition_point(|&s| s <= i) - 1;
            }
            parts[*k][i - starts[*k]].clone()
        },
    ));
}

/// `out` with the parts' items moved to its end one after another (each part left holding
/// defaults), on all threads: for items owning heap memory (a face's corner list), which a
/// copy would allocate anew. On one thread, or for a few items, one after another.
pub(crate) fn extend_taken<T: Default + Send>(out: &mut Vec<T>, parts: Vec<&mut [T]>) {
    let total: usize = parts.iter().map(|p| p.len()).sum();
    out.reserve(total);
    if total <= CHUNK || rayon::current_num_threads() == 1 {
        for p in parts {
            out.extend(p.iter_mut().map(std::mem::take));
        }
        return;
    }
    // Places made on all threads (their pages first touched there), then filled part by part.
    let old = out.len();
    out.par_extend(
        (0..total)
            .into_par_iter()
            .with_min_len(CHUNK)
            .map(|_| T::default()),
    );
    let mut places = Vec::with_capacity(parts.len());
    let mut rest = &mut out[old..];
    for p in &parts {
        let (here, after) = rest.split_at_mut(p.len());
        places.push(here);
        rest = after;
    }
    places.into_par_iter().zip(parts).for_each(|(to, from)| {
        to.par_iter_mut()
            .with_min_len(CHUNK)
            .zip(from.par_iter_mut())
            .for_each(|(t, f)| *t = std::mem::take(f));
    });
}

/// Drops the items of `v` on all threads (each a heap allocation of its own, say: a
/// million faces' corner lists take as long to free as to make).
pub(crate) fn drop_all<T: Send>(v: Vec<T>) {
    if v.len() <= CHUNK || rayon::current_num_threads() == 1 {
        return;
    }
    v.into_par_iter().with_min_len(CHUNK).for_each(drop);
}

/// A pool of `threads` threads, for tests that compare one thread with several.
#[cfg(test)]
pub(crate) fn pool(threads: usize) -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("a test's thread pool starts")
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A list whose items vary in number by index: 0 to 3 items each.
    fn each(r: Range<usize>, out: &mut Vec<(usize, u32)>) {
        for i in r {
            for j in 0..(i * 7 + 3) % 4 {
                out.push((i, j as u32));
            }
        }
    }

    #[test]
    fn fill_is_the_one_pass_list_on_any_thread_count() {
        // Index i writes i % 3 copies of i: chunks of uneven sizes, some empty.
        let size = |r: Range<usize>| r.map(|i| i % 3).sum();
        let each = |r: Range<usize>, out: &mut [usize]| {
            let mut at = 0;
            for i in r {
                for _ in 0..i % 3 {
                    out[at] = i;
                    at += 1;
                }
            }
            assert_eq!(at, out.len(), "sized as filled");
        };
        let one: Vec<usize> = (0..1000)
            .flat_map(|i| std::iter::repeat_n(i, i % 3))
            .collect();
        assert_eq!(one.len(), 999);
        for threads in [1, 3] {
            let got = pool(threads).install(|| fill(1000, 7, size, each));
            assert_eq!(got, one, "{threads} threads");
        }
        assert!(fill(0, 7, size, each).is_empty());
    }

    #[test]
    fn chunks_joined_are_the_one_pass_for_every_chunk_size() {
        let pool = pool(3);
        for n in [0, 1, 2, 5, 97, 20_000, 70_001] {
            let mut one = Vec::new();
            each(0..n, &mut one);
            for chunk in [1, 2, 3, 7, 64, 1000, CHUNK, n.max(1)] {
                let got = pool.install(|| flat_map(n, chunk, each));
                assert_eq!(got, one, "n {n}, chunk {chunk}");
            }
        }
    }

    #[test]
    fn map_on_all_threads_is_the_one_pass() {
        let pool = pool(3);
        for n in [0, 5, CHUNK + 1, 4 * CHUNK + 7] {
            let one: Vec<usize> = (0..n).map(|i| i * i % 1009).collect();
            assert_eq!(pool.install(|| map(n, |i| i * i % 1009)), one);
        }
    }

    #[test]
    fn each_item_on_all_threads_is_the_one_pass() {
        let pool = pool(3);
        for n in [0, 5, CHUNK + 1, 4 * CHUNK + 7] {
            let one: Vec<usize> = (0..n).map(|i| i * i % 1009 + 1).collect();
            let mut got = vec![1usize; n];
            pool.install(|| for_each_mut(&mut got, |i, x| *x += i * i % 1009));
            assert_eq!(got, one);
        }
    }

    #[test]
    fn concat_on_all_threads_is_the_parts_in_order() {
        let pool = pool(4);
        // Parts of every length, empty ones among them, many more items than CHUNK.
        let parts: Vec<Vec<u64>> = (0..400u64)
            .map(|k| (0..(k * 37 % 211)).map(|i| k << 32 | i).collect())
            .collect();
        assert!(parts.iter().map(Vec::len).sum::<usize>() > 4 * CHUNK);
        assert!(parts.iter().any(Vec::is_empty));
        let got = pool.install(|| concat_freeing(parts.clone()));
        assert_eq!(got, parts.concat());
    }

    #[test]
    fn extending_on_all_threads_appends_the_parts_in_order() {
        let pool = pool(3);
        let parts: Vec<Vec<u64>> = (0..300u64)
            .map(|k| (0..(k * 41 % 223)).map(|i| k << 32 | i).collect())
            .collect();
        assert!(parts.iter().map(Vec::len).sum::<usize>() > 3 * CHUNK);
        for head in [0, 5] {
            let mut want: Vec<u64> = (0..head).collect();
            want.extend(parts.concat());
            let mut copied: Vec<u64> = (0..head).collect();
            let slices: Vec<&[u64]> = parts.iter().map(|p| &p[..]).collect();
            pool.install(|| extend_concat(&mut copied, &slices));
            assert_eq!(copied, want);
            // Moved: heap-owning items, each part left holding empty lists.
            let mut owned: Vec<Vec<Vec<u64>>> = parts
                .iter()
                .map(|p| p.iter().map(|&x| vec![x; (x % 3) as usize]).collect())
                .collect();
            let wanted: Vec<Vec<u64>> = (0..head).map(|x| vec![x]).chain(owned.concat()).collect();
            let mut moved: Vec<Vec<u64>> = (0..head).map(|x| vec![x]).collect();
            let from: Vec<&mut [Vec<u64>]> = owned.iter_mut().map(|p| &mut p[..]).collect();
            pool.install(|| extend_taken(&mut moved, from));
            assert_eq!(moved, wanted);
            assert!(owned.iter().flatten().all(Vec::is_empty));
        }
    }

    #[test]
    fn the_first_found_on_all_threads_is_the_least() {
        let pool = pool(3);
        let n = 7 * CHUNK + 5;
        for want in [None, Some(0), Some(CHUNK - 1), Some(5 * CHUNK + 2)] {
            // Every index from `want` on holds (later chunks find theirs first, maybe).
            let got = pool.install(|| position_first(n, |i| want.is_some_and(|w| i >= w)));
            assert_eq!(got, want);
        }
    }

    #[test]
    fn dropping_on_all_threads_frees_every_item() {
        let pool = pool(2);
        let live = std::sync::Arc::new(());
        let v = vec![live.clone(); 3 * CHUNK];
        assert_eq!(std::sync::Arc::strong_count(&live), 3 * CHUNK + 1);
        pool.install(|| drop_all(v));
        assert_eq!(std::sync::Arc::strong_count(&live), 1);
    }
}
