//! Indices renumbered in order of first use (a file's vertices as a group's faces first use
//! them), on all threads: the same numbers, list for list, as one pass on one thread.
//!
//! A renumbering runs in rounds (an OBJ file's groups): an index keeps its number for the
//! rest of its round, and is numbered anew when a later round first uses it. The lists
//! (faces' corners) are cut into units of [`UNIT`] lists, fixed by the lists alone; each
//! unit finds the indices whose first use it holds (the least list number using an index
//! wins, a minimum that does not depend on which thread sees it first), the units' finds are
//! numbered in unit order, and every unit then rewrites its lists.

use std::sync::atomic::{AtomicU32, Ordering::Relaxed};

use rayon::prelude::*;

/// Lists per unit of work.
pub(crate) const UNIT: usize = 8192;

/// No list yet (a `first` entry), or no round yet (a `round` entry).
const NONE: u32 = u32::MAX;

/// A first use found and claimed by the list holding it.
const CLAIMED: u32 = u32::MAX - 1;

/// The numbers given so far to the indices `0..len()`.
#[derive(Debug, Default)]
pub(crate) struct Renumbering {
    /// Per index: the last round that numbered it ([`NONE`]: none).
    round: Vec<AtomicU32>,
    /// Per index: its number in that round.
    number: Vec<AtomicU32>,
    /// Per index, while a renumbering runs: the first list using it, or [`CLAIMED`].
    first: Vec<AtomicU32>,
}

impl Renumbering {
    /// Room for the indices below `n` (those added are not numbered in any round).
    pub(crate) fn grow(&mut self, n: usize) {
        // Made (their pages first touched) on all threads: 5M vertices on the 10M terrain.
        let more = n.saturating_sub(self.round.len());
        crate::chunked::extend_map(&mut self.round, more, |_| AtomicU32::new(NONE));
        crate::chunked::extend_map(&mut self.number, more, |_| AtomicU32::new(0));
    }

    /// Rewrites every index of the lists (each below the room grown, taken by `corners` from
    /// a list) to its number in round `round`: an index already numbered in this round keeps
    /// its number; the others get `next`, `next + 1`, ... in order of first use (list after
    /// list, part after part, and within a list in its order). The indices newly numbered,
    /// in that order.
    pub(crate) fn renumber<L: Send, F>(
        &mut self,
        round: u32,
        parts: &mut [&mut [L]],
        next: u32,
        corners: F,
    ) -> Vec<u32>
    where
        F: Fn(&mut L) -> &mut [u32] + Sync,
    {
        let total: usize = parts.iter().map(|p| p.len()).sum();
        if total <= UNIT || total >= CLAIMED as usize || rayon::current_num_threads() == 1 {
            return self.one_pass(round, parts, next, corners);
        }
        let more = self.round.len().saturating_sub(self.first.len());
        crate::chunked::extend_map(&mut self.first, more, |_| AtomicU32::new(NONE));
        // Units of lists, each with the number of its first list.
        let mut units: Vec<(u32, &mut [L])> = Vec::new();
        let mut at = 0;
        for p in parts.iter_mut() {
            for u in p.chunks_mut(UNIT) {
                let n = u.len();
                units.push((at as u32, u));
                at += n;
            }
        }
        let (rounds, firsts) = (&self.round, &self.first);
        let new = |g: u32| rounds[g as usize].load(Relaxed) != round;
        // The first list using each index new to the round.
        units.par_iter_mut().for_each(|(start, lists)| {
            for (j, l) in lists.iter_mut().enumerate() {
                for &g in corners(l).iter() {
                    if new(g) {
                        firsts[g as usize].fetch_min(*start + j as u32, Relaxed);
                    }
                }
            }
        });
        // Each unit's first uses, in order (only the first list using an index sees its
        // own number there, and claims it at its first corner using it).
        let found: Vec<Vec<u32>> = units
            .par_iter_mut()
            .map(|(start, lists)| {
                let mut found = Vec::new();
                for (j, l) in lists.iter_mut().enumerate() {
                    let me = *start + j as u32;
                    for &g in corners(l).iter() {
                        if new(g)
                            && firsts[g as usize]
                                .compare_exchange(me, CLAIMED, Relaxed, Relaxed)
                                .is_ok()
                        {
                            found.push(g);
                        }
                    }
                }
                found
            })
            .collect();
        let mut bases = Vec::with_capacity(found.len());
        let mut base = next;
        for f in &found {
            bases.push(base);
            base += f.len() as u32;
        }
        let numbers = &self.number;
        found.par_iter().zip(bases).for_each(|(f, base)| {
            for (k, &g) in f.iter().enumerate() {
                numbers[g as usize].store(base + k as u32, Relaxed);
                rounds[g as usize].store(round, Relaxed);
                firsts[g as usize].store(NONE, Relaxed);
            }
        });
        units.par_iter_mut().for_each(|(_, lists)| {
            for l in lists.iter_mut() {
                for g in corners(l).iter_mut() {
                    *g = numbers[*g as usize].load(Relaxed);
                }
            }
        });
        let slices: Vec<&[u32]> = found.iter().map(|f| &f[..]).collect();
        let mut out = Vec::new();
        crate::chunked::extend_concat(&mut out, &slices);
        out
    }

    /// [`Renumbering::renumber`] as one pass on this thread.
    fn one_pass<L, F>(
        &mut self,
        round: u32,
        parts: &mut [&mut [L]],
        next: u32,
        corners: F,
    ) -> Vec<u32>
    where
        F: Fn(&mut L) -> &mut [u32],
    {
        let mut found = Vec::new();
        let mut next = next;
        for p in parts.iter_mut() {
            for l in p.iter_mut() {
                for g in corners(l).iter_mut() {
                    let k = *g as usize;
                    if *self.round[k].get_mut() != round {
                        *self.round[k].get_mut() = round;
                        *self.number[k].get_mut() = next;
                        found.push(*g);
                        next += 1;
                    }
                    *g = *self.number[k].get_mut();
                }
            }
        }
        found
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Lists of 0 to 5 indices below `n`, repeats within a list among them.
    fn lists(count: usize, n: u32, seed: u32) -> Vec<Vec<u32>> {
        (0..count as u32)
            .map(|i| {
                let h = i.wrapping_mul(2_654_435_761).wrapping_add(seed);
                (0..h % 6)
                    .map(|j| (h >> 3).wrapping_add(j * j * 7) % n)
                    .collect()
            })
            .collect()
    }

    /// Rounds over the same indices: each renumbered on 3 threads equals one pass.
    #[test]
    fn renumbered_on_several_threads_is_the_one_pass() {
        let pool = crate::chunked::pool(3);
        let n = 30_000;
        let rounds = [
            (0, lists(3 * UNIT + 17, n, 1)),
            (0, lists(UNIT / 2, n, 2)),
            (1, lists(5 * UNIT, n, 3)),
            (1, lists(2 * UNIT + 1, 50, 4)),
            (7, lists(10, n, 5)),
        ];
        let (mut one, mut many) = (Renumbering::default(), Renumbering::default());
        one.grow(n as usize);
        many.grow(n as usize);
        let mut next = 0;
        let mut round_was = 0;
        for (round, l) in rounds {
            if round != round_was {
                next = 0;
                round_was = round;
            }
            let (mut a, mut b) = (l.clone(), l);
            let cut = a.len() / 3;
            let (a1, a2) = a.split_at_mut(cut);
            let fa = one.one_pass(round, &mut [a1, a2], next, |l| &mut l[..]);
            let (b1, b2) = b.split_at_mut(cut);
            let fb = pool.install(|| many.renumber(round, &mut [b1, b2], next, |l| &mut l[..]));
            assert_eq!(fa, fb);
            assert_eq!(a, b);
            // Numbers count up from `next` in order of first use.
            let mut seen = std::collections::HashSet::new();
            for &g in a.iter().flatten() {
                if g >= next && seen.insert(g) {
                    assert_eq!(g, next + seen.len() as u32 - 1);
                }
            }
            next += fa.len() as u32;
        }
        assert!(many.first.iter().all(|f| f.load(Relaxed) == NONE));
    }
}
