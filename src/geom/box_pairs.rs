//! Pairs of overlapping axis-aligned 3D boxes, found with a uniform grid: each pair once,
//! in ascending order, in time near-linear in the boxes for meshes of similar-sized faces.
//!
//! Every box is entered in the grid cells it overlaps; a pair is reported only from the cell
//! that holds the least corner of the two boxes' intersection, which both boxes overlap, so
//! each overlapping pair is found exactly once. Overlap is closed (touching boxes overlap).

use rayon::prelude::*;
use smallvec::SmallVec;

use crate::count::Span;

/// A box as [min, max].
pub(crate) type Bounds3 = [[f64; 3]; 2];

/// Above this many boxes the sorts and the cells run on all threads (small meshes stay off
/// the thread pool: 200k one-box objects would each wait on it).
const PARALLEL_ABOVE: usize = 1024;

/// Boxes a thread takes at a time in the passes over all boxes.
const CHUNK: usize = 4096;

/// Most grid cells a box enters, on average: bounds the grid's memory.
const MAX_CELLS_PER_BOX: f64 = 8.0;

#[cfg(test)]
/// Indices `(i, j)`, `i < j`, of every pair of overlapping boxes among `boxes`, ascending.
/// Boxes with a NaN or an empty extent are ignored.
pub(crate) fn overlapping_pairs(boxes: &[Bounds3]) -> Vec<(u32, u32)> {
    filter_map_pairs(boxes, |i, j| Some((i, j)), Span::NONE)
}

/// `f(i, j)` of every pair of overlapping boxes (`i < j`), the `Some` results in ascending
/// pair order, without keeping the pairs themselves (a mesh has many, few of which matter).
///
/// The work goes to `span` as it is done, slab by slab ([`slabs`]): the boxes entered in
/// the slab's cells and sorted first, then its cells by chunks (most of the work); then the
/// results sorted (none: [`Span::NONE`]).
pub(crate) fn filter_map_pairs<T: Send>(
    boxes: &[Bounds3],
    f: impl Fn(u32, u32) -> Option<T> + Sync,
    span: Span,
) -> Vec<T> {
    filter_map_pairs_of(boxes.len(), |i| boxes[i as usize], f, span)
}

/// [`filter_map_pairs`] of the `n` boxes `box_of(0..n)`, made when needed instead of
/// kept: for callers whose boxes cost less to remake than to hold (a face's box from its
/// corners, at ten million faces). `box_of` must give the same box every time.
pub(crate) fn filter_map_pairs_of<T: Send>(
    n: usize,
    box_of: impl Fn(u32) -> Bounds3 + Sync,
    f: impl Fn(u32, u32) -> Option<T> + Sync,
    span: Span,
) -> Vec<T> {
    pairs_in_slabs(n, box_of, f, span, SLAB_ENTRIES)
}

/// [`filter_map_pairs_of`] with slabs of at most about `slab_entries` grid entries.
fn pairs_in_slabs<T: Send>(
    n: usize,
    box_of: impl Fn(u32) -> Bounds3 + Sync,
    f: impl Fn(u32, u32) -> Option<T> + Sync,
    span: Span,
    slab_entries: usize,
) -> Vec<T> {
    // In fixed chunks, joined in order on all threads (few boxes stay off the thread pool:
    // a solid's many small searches would each wait on it).
    let ids: Vec<u32> = crate::chunked::flat_map(n, CHUNK, |r, out| {
        out.extend(r.map(|i| i as u32).filter(|&i| valid(&box_of(i))))
    });
    let Some((grid, entered)) = Grid::fit(&box_of, n, &ids) else {
        return Vec::new();
    };
    let parallel = ids.len() > PARALLEL_ABOVE;
    // The cell of each box's least corner: the cell of the least corner of two boxes'
    // intersection is their componentwise max (cells are monotone in the coordinates), so
    // no pair needs a float-to-cell conversion. Filled with the first slab's entries.
    let mut lo_cell = vec![[0u16; 3]; n];
    let slabs = slabs(&grid, &box_of, &ids, entered, slab_entries, parallel);
    let mut found: Vec<((u32, u32), T)> = Vec::new();
    let part = 0.95 / slabs.len() as f64;
    for (s, xs) in slabs.iter().enumerate() {
        let slab = span.span(part * s as f64, part * (s + 1) as f64);
        let lows = (s == 0).then_some(lo_cell.as_mut_slice());
        let entries = enter_all(&grid, &box_of, &ids, xs, lows, parallel, &slab);
        found.append(&mut slab_pairs(
            &grid, &box_of, &f, &lo_cell, entries, parallel, &slab,
        ));
    }
    span.reach(0.95);
    if parallel {
        found.par_sort_unstable_by_key(|x| x.0);
    } else {
        found.sort_unstable_by_key(|x| x.0);
    }
    span.finish();
    found.into_iter().map(|x| x.1).collect()
}

/// Most grid entries held at a time (128 MiB): above, the grid is entered and searched a
/// slab of cells at a time. Each slab enters its boxes by going over all of them (their
/// boxes remade), so slabs are few: at 4 MiB the 10M-face terrain's line drawing had about
/// sixty and took 18.8 s instead of 8.2 (two threads); at this size it has two.
const SLAB_ENTRIES: usize = 1 << 24;

/// The grid's cells cut along x into slabs of at most about `limit` entries each (a column
/// of more is a slab of its own), as ranges of x cells; one slab of the whole grid when all
/// its `entered` entries fit. A pair is found in the cell of its intersection's
/// least corner, in one slab: slab by slab, the same pairs are found, and only one slab's
/// entries and runs are held.
fn slabs(
    grid: &Grid,
    box_of: &(impl Fn(u32) -> Bounds3 + Sync),
    ids: &[u32],
    entered: u128,
    limit: usize,
    parallel: bool,
) -> Vec<std::ops::Range<u64>> {
    let columns = grid.dims[0];
    if entered <= limit as u128 {
        return std::iter::once(0..columns).collect();
    }
    // Entries a column, summed in integers: the same in any order.
    let add = |mut h: Vec<u64>, chunk: &[u32]| {
        for &i in chunk {
            let [lo, hi] = grid.cell_range(&box_of(i));
            let across = (hi[1] - lo[1] + 1) * (hi[2] - lo[2] + 1);
            for x in lo[0]..=hi[0] {
                h[x as usize] += across;
            }
        }
        h
    };
    let zero = || vec![0u64; columns as usize];
    let merge = |mut a: Vec<u64>, b: Vec<u64>| {
        a.iter_mut().zip(&b).for_each(|(a, b)| *a += b);
        a
    };
    let per_column = if parallel {
        ids.par_chunks(CHUNK).fold(zero, add).reduce(zero, merge)
    } else {
        ids.chunks(CHUNK).fold(zero(), add)
    };
    let mut out = Vec::new();
    let (mut from, mut held) = (0u64, 0u64);
    for (x, &c) in per_column.iter().enumerate() {
        let x = x as u64;
        if held > 0 && held + c > limit as u64 {
            out.push(from..x);
            (from, held) = (x, 0);
        }
        held += c;
    }
    out.push(from..columns);
    out
}

/// `f(i, j)` of the overlapping pairs first met in the cells of `entries` (one slab's), with
/// their pairs, in no set order; the entries are freed as soon as the cells are found. The
/// cells go to `slab` from its fifth on.
fn slab_pairs<T: Send>(
    grid: &Grid,
    box_of: &(impl Fn(u32) -> Bounds3 + Sync),
    f: &(impl Fn(u32, u32) -> Option<T> + Sync),
    lo_cell: &[[u16; 3]],
    mut entries: Vec<u64>,
    parallel: bool,
    slab: &Span,
) -> Vec<((u32, u32), T)> {
    let shift = grid.id_bits;
    if parallel {
        entries.par_sort_unstable();
    } else {
        entries.sort_unstable();
    }
    slab.reach(0.2);
    // The cells are found chunk by chunk of entries as they are searched (not held: a run's
    // range was 16 bytes, about a quarter of the entries' own memory on a terrain).
    let chunks = entries.len().div_ceil(crate::chunked::CHUNK);
    let cells = slab.span(0.2, 1.0).steps(entries.len());
    let (entries, cells) = (&entries, &cells);
    let id = |e: u64| (e & ((1 << shift) - 1)) as u32;
    // The pairs first met in one cell (a run of equal keys), each member's box made once.
    let in_cell = move |r: &std::ops::Range<usize>| {
        let cell = &entries[r.clone()];
        let key = cell[0] >> shift;
        let members: SmallVec<[(u32, Bounds3); 16]> =
            cell.iter().map(|&e| (id(e), box_of(id(e)))).collect();
        let mut found = Vec::new();
        for (a, (i, bi)) in members.iter().enumerate() {
            let ci = &lo_cell[*i as usize];
            for (j, bj) in &members[a + 1..] {
                let cj = &lo_cell[*j as usize];
                // Met first here: the least corner of the boxes' meet lies in this cell.
                if !overlap(bi, bj)
                    || grid.key(std::array::from_fn(|k| u64::from(ci[k].max(cj[k])))) != key
                {
                    continue;
                }
                let p = (*i.min(j), *i.max(j));
                if let Some(t) = f(p.0, p.1) {
                    found.push((p, t));
                }
            }
        }
        found
    };
    // The cells whose runs start in each chunk of entries, the chunk's entries counted as
    // it is started.
    let counted = |c: usize| {
        let from = c * crate::chunked::CHUNK;
        let to = (from + crate::chunked::CHUNK).min(entries.len());
        cells.add(to - from);
        (from..to)
            .filter_map(move |start| run_at(entries, shift, start))
            .flat_map(move |r| in_cell(&r))
    };
    let found = if parallel {
        (0..chunks).into_par_iter().flat_map_iter(counted).collect()
    } else {
        (0..chunks).flat_map(counted).collect()
    };
    slab.finish();
    found
}

/// Every box's entries (cell key, box) in the cells of x in `xs` packed in one word, key
/// above box (sorting the words sorts by key then box, as sorting the pairs would, in half
/// the memory), in box order and each box's in cell order; and each box's least cell into
/// `lo_cell` when given.
///
/// The entries are counted first, so that the list is made at its size and filled in place,
/// each sub-chunk of `CHUNK` boxes into its own slice (on all threads where `parallel`): no
/// parts held beside the list while they are joined, no list grown by doubling. The same
/// list for any thread count. A tick of `span`'s first tenth per `CHUNK * 64` boxes.
fn enter_all(
    grid: &Grid,
    box_of: &(impl Fn(u32) -> Bounds3 + Sync),
    ids: &[u32],
    xs: &std::ops::Range<u64>,
    lo_cell: Option<&mut [[u16; 3]]>,
    parallel: bool,
    span: &Span,
) -> Vec<u64> {
    let shift = grid.id_bits;
    let range = |i: u32| grid.cell_range(&box_of(i));
    // A box's cells in the slab (none: x from above its last).
    let clipped = |[mut lo, mut hi]: [[u64; 3]; 2]| {
        lo[0] = lo[0].max(xs.start);
        hi[0] = hi[0].min(xs.end - 1);
        [lo, hi]
    };
    let cells_in = |[lo, hi]: [[u64; 3]; 2]| {
        if lo[0] > hi[0] {
            return 0;
        }
        (0..3)
            .map(|k| (hi[k] - lo[k] + 1) as usize)
            .product::<usize>()
    };
    let subs: Vec<&[u32]> = ids.chunks(CHUNK).collect();
    let count = |sub: &&[u32]| {
        sub.iter()
            .map(|&i| cells_in(clipped(range(i))))
            .sum::<usize>()
    };
    let counts: Vec<usize> = if parallel {
        subs.par_iter().map(count).collect()
    } else {
        subs.iter().map(count).collect()
    };
    let mut entries = vec![0u64; counts.iter().sum()];
    // Each sub-chunk's own slices: of the entries (its count), and of the least cells (from
    // its first box to its last: ids ascend, so the runs do not overlap).
    let mut slices: Vec<Slot> = Vec::with_capacity(subs.len());
    let lows = lo_cell.is_some();
    let mut cells = lo_cell.unwrap_or_default();
    let (mut rest, mut cells_from) = (entries.as_mut_slice(), 0usize);
    for (sub, &c) in subs.iter().zip(&counts) {
        let (mine, tail) = std::mem::take(&mut rest).split_at_mut(c);
        let end = sub[sub.len() - 1] as usize + 1;
        let split = if lows { end - cells_from } else { 0 };
        let (here, after) = std::mem::take(&mut cells).split_at_mut(split);
        slices.push(Slot {
            entries: mine,
            lows: here,
            from: cells_from,
        });
        (rest, cells, cells_from) = (tail, after, end);
    }
    // A sub-chunk's entries and its boxes' least cells, into its slices.
    let fill = |(sub, slot): (&&[u32], &mut Slot)| {
        let Slot {
            entries: out,
            lows,
            from,
        } = slot;
        let mut at = 0;
        for &i in sub.iter() {
            let [lo, hi] = range(i);
            if let Some(low) = lows.get_mut(i as usize - *from) {
                *low = lo.map(|c| c as u16);
            }
            let [lo, hi] = clipped([lo, hi]);
            for x in lo[0]..=hi[0] {
                for y in lo[1]..=hi[1] {
                    for z in lo[2]..=hi[2] {
                        out[at] = grid.key([x, y, z]) << shift | u64::from(i);
                        at += 1;
                    }
                }
            }
        }
        debug_assert_eq!(at, out.len(), "counted as entered");
    };
    let entered = span.span(0.0, 0.1).steps(ids.len());
    for (c, (group, outs)) in subs.chunks(64).zip(slices.chunks_mut(64)).enumerate() {
        if parallel {
            group.par_iter().zip(outs.par_iter_mut()).for_each(fill);
        } else {
            group.iter().zip(outs.iter_mut()).for_each(fill);
        }
        entered.tick_in(c, 1);
    }
    entries
}

/// A sub-chunk's share of [`enter_all`]'s outputs: its entries, and the least cells of the
/// boxes from its first to its last (`from` the first's id).
struct Slot<'a> {
    entries: &'a mut [u64],
    lows: &'a mut [[u16; 3]],
    from: usize,
}

/// True when the closed boxes share a point.
pub(crate) fn overlap(a: &Bounds3, b: &Bounds3) -> bool {
    (0..3).all(|k| a[0][k] <= b[1][k] && b[0][k] <= a[1][k])
}

fn valid(b: &Bounds3) -> bool {
    (0..3).all(|k| b[0][k] <= b[1][k] && b[0][k].is_finite() && b[1][k].is_finite())
}

/// The index range of equal keys (the bits above `shift`) in sorted entries that starts at
/// `start`, when one starts there and has two entries or more.
fn run_at(entries: &[u64], shift: u32, start: usize) -> Option<std::ops::Range<usize>> {
    let key = |i: usize| entries[i] >> shift;
    if start > 0 && key(start - 1) == key(start) {
        return None;
    }
    let k = key(start);
    let end = (start + 1..entries.len())
        .find(|&i| key(i) != k)
        .unwrap_or(entries.len());
    (end - start > 1).then_some(start..end)
}

#[cfg(test)]
/// Index ranges of equal keys (the bits above `shift`) in sorted entries, of two entries
/// or more ([`run_at`] at every entry), in fixed chunks of entries on all threads.
fn runs(entries: &[u64], shift: u32) -> Vec<std::ops::Range<usize>> {
    crate::chunked::flat_map(entries.len(), crate::chunked::CHUNK, |r, out| {
        out.extend(r.filter_map(|start| run_at(entries, shift, start)))
    })
}

/// Bits needed to write `n`.
fn bits(n: u64) -> u32 {
    u64::BITS - n.leading_zeros()
}

/// A uniform grid over the boxes' bounds.
struct Grid {
    origin: [f64; 3],
    inv_cell: f64,
    dims: [u64; 3],
    /// Bits of a box index in an entry (below the cell key).
    id_bits: u32,
}

impl Grid {
    /// A grid whose cell is twice the mean box size (most boxes then enter one to four
    /// cells), coarsened until the boxes enter about
    /// `MAX_CELLS_PER_BOX` cells each on average, and until a cell's coordinates fit 16 bits
    /// and its key and a box index fit one 64-bit entry (a coarser grid finds the same pairs);
    /// with the number of entries the boxes make in it.
    fn fit(
        box_of: &(impl Fn(u32) -> Bounds3 + Sync),
        n: usize,
        ids: &[u32],
    ) -> Option<(Grid, u128)> {
        let first = box_of(*ids.first()?);
        // Bounds and the sum of box sizes by fixed chunks on all threads, the chunks'
        // sums added in order: the same grid for any thread count.
        let part = |chunk: &[u32]| {
            let (mut lo, mut hi, mut sum) = (first[0], first[1], 0.0);
            for &i in chunk {
                let b = &box_of(i);
                for k in 0..3 {
                    lo[k] = lo[k].min(b[0][k]);
                    hi[k] = hi[k].max(b[1][k]);
                }
                sum += (0..3).map(|k| b[1][k] - b[0][k]).fold(0.0, f64::max);
            }
            (lo, hi, sum)
        };
        let parts: Vec<([f64; 3], [f64; 3], f64)> = if ids.len() > PARALLEL_ABOVE {
            ids.par_chunks(CHUNK).map(part).collect()
        } else {
            ids.chunks(CHUNK).map(part).collect()
        };
        let (mut lo, mut hi, mut mean) = (first[0], first[1], 0.0);
        for (l, h, sum) in parts {
            for k in 0..3 {
                lo[k] = lo[k].min(l[k]);
                hi[k] = hi[k].max(h[k]);
            }
            mean += sum;
        }
        mean /= ids.len() as f64;
        let span = (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max);
        let mut cell = if mean > 0.0 {
            2.0 * mean
        } else {
            span.max(1.0)
        };
        cell = cell.max(span / 4096.0).max(f64::MIN_POSITIVE);
        loop {
            let g = Grid {
                origin: lo,
                inv_cell: 1.0 / cell,
                dims: std::array::from_fn(|k| ((hi[k] - lo[k]) / cell).floor() as u64 + 1),
                id_bits: bits(n as u64 - 1),
            };
            let keys = g.dims.iter().try_fold(1u64, |n, &d| n.checked_mul(d));
            let packs = g.dims.iter().all(|&d| d <= 1 << 16)
                && keys.is_some_and(|n| bits(n - 1) + g.id_bits <= 64);
            if !packs && cell < span {
                cell *= 2.0;
                continue;
            }
            // Counted in integers: the same sum in any order.
            let cells_of = |&i: &u32| {
                let [a, b] = g.cell_range(&box_of(i));
                (0..3)
                    .map(|k| u128::from(b[k] - a[k] + 1))
                    .product::<u128>()
            };
            let cells = if ids.len() > PARALLEL_ABOVE {
                ids.par_iter()
                    .with_min_len(CHUNK)
                    .map(cells_of)
                    .sum::<u128>()
            } else {
                ids.iter().map(cells_of).sum::<u128>()
            };
            if cells as f64 <= MAX_CELLS_PER_BOX * ids.len() as f64 || cell >= span {
                return Some((g, cells));
            }
            cell *= 2.0;
        }
    }

    /// The cell holding point `p` (clamped to the grid).
    fn cell(&self, p: &[f64; 3]) -> [u64; 3] {
        std::array::from_fn(|k| {
            let c = ((p[k] - self.origin[k]) * self.inv_cell).floor();
            (c.max(0.0) as u64).min(self.dims[k] - 1)
        })
    }

    fn cell_range(&self, b: &Bounds3) -> [[u64; 3]; 2] {
        [self.cell(&b[0]), self.cell(&b[1])]
    }

    fn key(&self, c: [u64; 3]) -> u64 {
        (c[0] * self.dims[1] + c[1]) * self.dims[2] + c[2]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// All pairs by brute force.
    fn brute(boxes: &[Bounds3]) -> Vec<(u32, u32)> {
        let mut out = Vec::new();
        for i in 0..boxes.len() {
            for j in i + 1..boxes.len() {
                if valid(&boxes[i]) && valid(&boxes[j]) && overlap(&boxes[i], &boxes[j]) {
                    out.push((i as u32, j as u32));
                }
            }
        }
        out
    }

    #[test]
    fn grid_pairs_equal_brute_force() {
        let mut s = 0x1234_5678_u64;
        let mut next = move || {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            (s >> 11) as f64 / (1u64 << 53) as f64
        };
        for &(n, size) in &[(50, 0.1), (300, 0.05), (200, 0.5), (100, 0.0)] {
            let boxes: Vec<Bounds3> = (0..n)
                .map(|k| {
                    let p = [next(), next(), next() * 0.1];
                    // A few huge boxes and a few flat ones among the small.
                    let s = if k % 37 == 0 { 0.8 } else { size * next() };
                    let flat = if k % 11 == 0 { 0.0 } else { s };
                    [p, [p[0] + s, p[1] + s, p[2] + flat]]
                })
                .collect();
            assert_eq!(
                overlapping_pairs(&boxes),
                brute(&boxes),
                "n={n} size={size}"
            );
        }
    }

    #[test]
    fn entries_made_on_several_threads_give_the_one_thread_pairs() {
        // Enough boxes for several sub-chunks of CHUNK boxes, entered on three threads and on
        // one; and a few thousand, on three threads, against brute force.
        let mut s = 0x9e37_79b9_u64;
        let mut next = move || {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            (s >> 11) as f64 / (1u64 << 53) as f64
        };
        let boxes: Vec<Bounds3> = (0..5 * CHUNK + 123)
            .map(|k| {
                let p = [next(), next(), next() * 0.1];
                let s = if k % 997 == 0 { 0.3 } else { 0.004 * next() };
                [p, [p[0] + s, p[1] + s, p[2] + s]]
            })
            .collect();
        // Invalid boxes leave gaps in the boxes entered, at sub-chunk ends among others.
        let mut boxes = boxes;
        for k in [CHUNK - 1, CHUNK, 2 * CHUNK + 1, 4 * CHUNK - 1] {
            boxes[k][0][1] = f64::NAN;
        }
        let pool = crate::chunked::pool;
        let three = pool(3).install(|| overlapping_pairs(&boxes));
        assert!(three.len() > boxes.len() / 10, "the test finds pairs");
        assert_eq!(three, pool(1).install(|| overlapping_pairs(&boxes)));
        let few = &boxes[..3 * PARALLEL_ABOVE];
        assert_eq!(pool(3).install(|| overlapping_pairs(few)), brute(few));
        // Slab by slab (a few hundred entries each): the same pairs, in the same order.
        let by_slabs = |boxes: &[Bounds3], limit: usize| {
            let pair = |i, j| Some((i, j));
            pairs_in_slabs(boxes.len(), |i| boxes[i as usize], pair, Span::NONE, limit)
        };
        assert_eq!(pool(3).install(|| by_slabs(&boxes, 500)), three);
        assert_eq!(pool(1).install(|| by_slabs(&boxes, 500)), three);
        assert_eq!(pool(3).install(|| by_slabs(few, 100)), brute(few));
        assert_eq!(by_slabs(&boxes[..300], 10), brute(&boxes[..300]));
    }

    /// The runs found in chunks on three threads are those of one pass: runs of every
    /// length, some across chunk ends, one as long as a chunk.
    #[test]
    fn runs_found_on_several_threads_are_the_one_pass_runs() {
        let chunk = crate::chunked::CHUNK as u64;
        let mut entries: Vec<u64> = Vec::new();
        let (mut key, mut k) = (0u64, 0u64);
        while entries.len() < 3 * chunk as usize + 50 {
            let len = if k == 7 { chunk + 3 } else { (k * 7 + 3) % 11 };
            entries.extend((0..len).map(|i| key << 20 | i));
            (key, k) = (key + 1 + k % 2, k + 1);
        }
        let mut want = Vec::new();
        let mut start = 0;
        for i in 1..=entries.len() {
            if i == entries.len() || entries[i] >> 20 != entries[start] >> 20 {
                if i - start > 1 {
                    want.push(start..i);
                }
                start = i;
            }
        }
        assert!(want.iter().any(|r| r.len() > chunk as usize));
        let pool = crate::chunked::pool;
        assert_eq!(pool(1).install(|| runs(&entries, 20)), want);
        assert_eq!(pool(3).install(|| runs(&entries, 20)), want);
    }

    #[test]
    fn touching_and_invalid_boxes() {
        let unit = [[0., 0., 0.], [1., 1., 1.]];
        let touch = [[1., 0., 0.], [2., 1., 1.]];
        let nan = [[f64::NAN, 0., 0.], [1., 1., 1.]];
        assert_eq!(overlapping_pairs(&[unit, touch, nan]), vec![(0, 1)]);
        assert!(overlapping_pairs(&[]).is_empty());
        assert!(overlapping_pairs(&[unit]).is_empty());
    }
}
