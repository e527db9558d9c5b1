//! Strokes whose ends are each other's nearest, tied into chains drawn in a row: the pen-order
//! search ([`super::tour`]) then plans the chains, far fewer than the strokes where hidden
//! lines are dashed.
//!
//! Two ends of different strokes are tied when each is the other's nearest end of another
//! stroke (by distance, then slot: a total order, so "nearest" is one end and the ties are a
//! matching). Along a dashed hidden line with nothing else near, every dash's end and the
//! next dash's start are such a pair, so the line's dashes become one chain, as an order of
//! whole lines would draw them; where hidden lines lie closer together than the dash gap the
//! nearest end is on the other line and the dashes stay apart, so the search can still hop
//! across, which an order of whole lines cannot (it left dense meshes' travel twice as long).
//! A good tour takes the edge between mutual nearest ends nearly always; the search then
//! works on chains, with each chain's two outer ends. Deterministic: the nearest ends come
//! from the fixed grid of [`Buckets`], each found on its own, and chains are walked in stroke
//! order.

use rayon::prelude::*;

use crate::geom::poly2::Pt2;

use super::tour::{Buckets, Candidates};

/// Slots a task of the parallel nearest-end search takes.
const PAIR_TASK: usize = 4096;

/// How much farther than the nearest end the second nearest must be, at both ends of a tie:
/// only clear pairs are tied (along a lone dashed line the next dash's start is one gap from
/// a dash's end, the end before it a dash and a gap). Every mutual pair tied (1.0), the
/// shared meshes' hidden layers drew up to 8.3% more pen-up travel (suzanne); with 1.5 at
/// most 1.2% more (cow), with 2.0 at most 0.8% but fewer ties.
const CLEAR: f64 = 1.5;

/// Strokes tied into chains: each chain its strokes in drawing order, with their directions
/// (true: drawn end to start).
pub(crate) struct Chains {
    /// Chain c's strokes are `strokes[start[c]..start[c + 1]]`.
    start: Vec<usize>,
    /// (stroke, reversed), chain by chain.
    strokes: Vec<(usize, bool)>,
}

impl Chains {
    /// How many chains.
    pub(crate) fn len(&self) -> usize {
        self.start.len() - 1
    }

    /// Chain c's strokes in drawing order.
    fn of(&self, c: usize) -> &[(usize, bool)] {
        &self.strokes[self.start[c]..self.start[c + 1]]
    }

    /// Each chain's first start and last end, drawn forward.
    pub(crate) fn ends(&self, ends: &[[Pt2; 2]]) -> Vec<[Pt2; 2]> {
        (0..self.len())
            .map(|c| {
                let s = self.of(c);
                let (f, l) = (s[0], s[s.len() - 1]);
                [ends[f.0][usize::from(f.1)], ends[l.0][usize::from(!l.1)]]
            })
            .collect()
    }

    /// The strokes in the order of chains `order` (chain, reversed), a reversed chain drawn
    /// from its last stroke back, each of them turned round.
    pub(crate) fn expand(&self, order: &[(usize, bool)]) -> Vec<(usize, bool)> {
        let mut out = Vec::with_capacity(self.strokes.len());
        for &(c, rev) in order {
            let s = self.of(c);
            if rev {
                out.extend(s.iter().rev().map(|&(i, r)| (i, !r)));
            } else {
                out.extend_from_slice(s);
            }
        }
        out
    }
}

/// The chains of strokes `ends` (start, end): ends of different strokes that are each
/// other's nearest, clearly ([`CLEAR`]), and both `tieable`, are drawn one after the other.
/// A closed ring of ties is opened before its lowest stroke.
pub(crate) fn chains(ends: &[[Pt2; 2]], tieable: &[bool]) -> Chains {
    let tie = ties(ends, tieable);
    let n = ends.len();
    let mut seen = vec![false; n];
    let mut start = vec![0];
    let mut strokes = Vec::with_capacity(n);
    // Open chains first, from an end without a tie (its start when both are free), in stroke
    // order; then what is left, rings, each opened before its lowest stroke.
    let free = |s: usize| tie[s] == u32::MAX;
    for open in [true, false] {
        for i in 0..n {
            if seen[i] {
                continue;
            }
            let entry = match (free(2 * i), free(2 * i + 1)) {
                (true, _) => 2 * i,
                (false, true) => 2 * i + 1,
                (false, false) if !open => 2 * i,
                _ => continue,
            };
            walk(entry, &tie, &mut seen, &mut strokes);
            start.push(strokes.len());
        }
    }
    Chains { start, strokes }
}

/// Walks a chain from end slot `entry`: the stroke drawn from it, then the stroke tied to its
/// other end, and so on until an end without a tie or a stroke already drawn.
fn walk(mut entry: usize, tie: &[u32], seen: &mut [bool], out: &mut Vec<(usize, bool)>) {
    loop {
        let i = entry / 2;
        seen[i] = true;
        out.push((i, entry % 2 == 1));
        let next = tie[entry ^ 1];
        if next == u32::MAX || seen[next as usize / 2] {
            return;
        }
        entry = next as usize;
    }
}

/// For each end slot (2i start, 2i + 1 end of stroke i), the slot tied to it, `u32::MAX` for
/// none: the two are each other's nearest end of another stroke, the second nearest of each
/// at least [`CLEAR`] times farther, and both strokes `tieable`.
fn ties(ends: &[[Pt2; 2]], tieable: &[bool]) -> Vec<u32> {
    let pts: Vec<Pt2> = ends.iter().flatten().copied().collect();
    let none = u32::MAX;
    if ends.len() < 2 || pts.len() > u32::MAX as usize / 2 || !tieable.contains(&true) {
        return vec![none; pts.len()];
    }
    let buckets = Buckets::new(&pts);
    let mut nearest = vec![none; pts.len()];
    nearest
        .par_chunks_mut(PAIR_TASK)
        .enumerate()
        .for_each(|(task, out)| {
            let mut candidates = Candidates::new();
            for (k, o) in out.iter_mut().enumerate() {
                let s = task * PAIR_TASK + k;
                if !tieable[s / 2] {
                    continue;
                }
                let found = buckets.nearest(s, pts[s], 2, &mut candidates);
                let [(d0, t), (d1, _)] = [found.found[0], found.found[1]];
                let clear = found.len == 1 || (found.len == 2 && d1 >= CLEAR * d0);
                if found.len > 0 && clear && tieable[t as usize / 2] {
                    *o = t;
                }
            }
        });
    (0..pts.len())
        .map(|s| {
            let t = nearest[s];
            let mutual = t != none && nearest[t as usize] == s as u32;
            if mutual {
                t
            } else {
                none
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::poly2::dist;

    fn check_permutation(c: &Chains, n: usize) {
        let mut all: Vec<usize> = c.strokes.iter().map(|s| s.0).collect();
        all.sort_unstable();
        assert_eq!(all, (0..n).collect::<Vec<_>>());
        assert!((0..c.len()).all(|k| !c.of(k).is_empty()));
    }

    #[test]
    fn a_dashed_line_is_one_chain_in_order() {
        // Ten dashes along x with unit gaps, shuffled, some reversed: one chain, drawn in a
        // row whichever way.
        let mut ends: Vec<[Pt2; 2]> = (0..10)
            .map(|k| {
                let x = 3.0 * f64::from(k);
                [[x, 0.0], [x + 2.0, 0.0]]
            })
            .collect();
        ends.swap(2, 7);
        ends.swap(0, 5);
        ends[3].reverse();
        ends[8].reverse();
        let c = chains(&ends, &[true; 10]);
        assert_eq!(c.len(), 1);
        check_permutation(&c, 10);
        // Not tieable: each dash its own chain.
        assert_eq!(chains(&ends, &[false; 10]).len(), 10);
        let order = c.expand(&[(0, false)]);
        let pts: Vec<[Pt2; 2]> = order
            .iter()
            .map(|&(i, r)| if r { [ends[i][1], ends[i][0]] } else { ends[i] })
            .collect();
        let travel: f64 = pts.windows(2).map(|w| dist(w[0][1], w[1][0])).sum();
        assert!((travel - 9.0).abs() < 1e-12, "{travel}");
        // Reversed, the same strokes the other way round, each turned.
        let back = c.expand(&[(0, true)]);
        let want: Vec<(usize, bool)> = order.iter().rev().map(|&(i, r)| (i, !r)).collect();
        assert_eq!(back, want);
        let e = c.ends(&ends)[0];
        assert_eq!(e, [pts[0][0], pts[9][1]]);
    }

    #[test]
    fn only_clear_mutual_nearest_ends_are_tied() {
        // b's start is nearest a's end, but a's end has c's start nearer still (by more than
        // half): a–c are tied, b stays alone.
        let ends = [
            [[0.0, 0.0], [1.0, 0.0]],  // a
            [[2.5, 0.0], [5.0, 0.0]],  // b: its start 1.5 from a's end
            [[1.0, 0.5], [1.0, 3.0]],  // c: its start 0.5 from a's end
            [[9.0, 9.0], [10.0, 9.0]], // d, far away
        ];
        let all = [true; 4];
        let t = ties(&ends, &all);
        assert_eq!((t[1], t[4]), (4, 1), "a's end and c's start");
        assert_eq!(t[2], u32::MAX, "b's start: its nearest is tied elsewhere");
        // b's start a little nearer: a's end's nearest is no longer clear, nothing is tied.
        let mut close = ends;
        close[1][0] = [1.6, 0.0];
        assert!(ties(&close, &all).iter().all(|&u| u == u32::MAX));
        // c not tieable: nothing tied to it.
        assert_eq!(ties(&ends, &[true, true, false, true])[1], u32::MAX);
        let c = chains(&ends, &all);
        check_permutation(&c, 4);
        assert!(c.strokes.windows(2).any(|w| w == [(0, false), (2, false)]));
    }

    #[test]
    fn a_ring_of_ties_is_opened_before_its_lowest_stroke() {
        // Four strokes round a square, ends a little apart at the corners: every corner tied,
        // a ring; it is opened at stroke 0.
        let g = 0.1;
        let ends = [
            [[3.0, 0.0 + g], [3.0, 3.0 - g]],
            [[0.0 + g, 0.0], [3.0 - g, 0.0]],
            [[0.0, 3.0 - g], [0.0, 0.0 + g]],
            [[3.0 - g, 3.0], [0.0 + g, 3.0]],
        ];
        let c = chains(&ends, &[true; 4]);
        assert_eq!(c.len(), 1);
        check_permutation(&c, 4);
        assert_eq!(c.of(0)[0], (0, false));
    }

    #[test]
    fn random_strokes_chain_into_a_permutation_deterministically() {
        let mut rng = crate::geom::rng::XorShift::new(21);
        for n in [1, 2, 3, 50, 3000, PAIR_TASK + 7] {
            let ends: Vec<[Pt2; 2]> = (0..n)
                .map(|_| {
                    let a = [rng.range(0.0, 100.0), rng.range(0.0, 100.0)];
                    [
                        a,
                        [a[0] + rng.range(-2.0, 2.0), a[1] + rng.range(-2.0, 2.0)],
                    ]
                })
                .collect();
            let tieable = vec![true; n];
            let c = chains(&ends, &tieable);
            check_permutation(&c, n);
            let order: Vec<(usize, bool)> = (0..c.len()).map(|k| (k, k % 2 == 1)).collect();
            let e = c.expand(&order);
            assert_eq!(e.len(), n);
            // Tied ends follow each other, and the ties are a matching.
            let t = ties(&ends, &tieable);
            for (s, &u) in t.iter().enumerate() {
                if u != u32::MAX {
                    assert_eq!(t[u as usize], s as u32);
                    assert_ne!(u as usize / 2, s / 2);
                }
            }
            let again = chains(&ends, &tieable);
            assert_eq!((again.start, again.strokes), (c.start, c.strokes));
        }
    }
}
