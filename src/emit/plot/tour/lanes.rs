//! The kicks of a layer's pen-order search tried on many copies of its tour at once, with
//! the tour that making them one after the other gives, whatever the number of copies.
//!
//! A kick that gains nothing is undone, so until the first kick that gains, every kick
//! starts from the same tour: those kicks can be tried side by side, each on its own copy,
//! and read in kick order afterwards. The copies share out the next kicks as they come, a
//! round ends at the first that gains, and that one is replayed on the other copies.

use std::sync::atomic::{AtomicUsize, Ordering};

use rayon::prelude::*;

use super::{Bridge, Tour, Trial, KICK_CHUNK, KICK_STALL};
use crate::count::Steps;

/// Bytes of tour copies the kicks may take in all (a copy is 17 bytes a position).
const LANE_BYTES: usize = 64 << 20;

/// Kicks of a layer under which they are made one after the other.
const LANE_KICKS: usize = 32;

/// How many copies of a tour of `n` positions to try its `kicks` kicks on at once: one a
/// thread, within [`LANE_BYTES`], and one where there are few kicks. Every layer's plan
/// takes as many, though layers are planned side by side: a lane no thread runs takes no
/// kick (the kicks go to the lanes as they come), it only follows the kept ones.
pub(super) fn lanes(n: usize, kicks: usize) -> usize {
    if kicks < LANE_KICKS {
        return 1;
    }
    rayon::current_num_threads()
        .min(LANE_BYTES / (17 * n.max(1)))
        .max(1)
}

impl<'a> Tour<'a> {
    /// The kicks `bridges` as [`Tour::kicks`] makes them, tried on `lanes` copies of the
    /// tour at once, and the same tour as theirs whatever `lanes`: a kick that gains nothing
    /// leaves the tour as it was, so up to the first that gains, every kick starts from the
    /// tour one tour would have had. Each round, the copies take the next kicks in turn
    /// ([`Tour::try_kicks`]) until one gains; the results are read in kick order, the
    /// first that gains is kept on every copy (the others undo their own and replay its
    /// reversals, at the start of the next round), and the kicks after it are tried again
    /// in the next round. A kick whose local search might have run out of moves on one tour
    /// (the round's moves before it and its own above the budget left) is made again alone,
    /// and so are the kicks after it.
    pub(super) fn kicks_in_lanes(
        &mut self,
        bridges: &[Bridge],
        budget: &mut usize,
        kicked: &Steps,
        lanes: usize,
    ) {
        let mut others: Vec<Tour<'a>> = (1..lanes).into_par_iter().map(|_| self.copy()).collect();
        let (mut failed, mut k) = (0, 0);
        // The last round's kept kick (its lane) and its reversals.
        let (mut kept, mut replay): (Option<usize>, Vec<(usize, usize)>) = (None, Vec::new());
        loop {
            let left = *budget;
            // The kicks the round may make: up to where a stall would stop them.
            let end = bridges.len().min(k + KICK_STALL.saturating_sub(failed));
            let go = k < end && left > 0;
            let (next, stop) = (AtomicUsize::new(k), AtomicUsize::new(end));
            let mut tours: Vec<&mut Tour<'a>> = std::iter::once(&mut *self)
                .chain(others.iter_mut())
                .collect();
            // Each lane ends its last round, then tries kicks.
            let tried: Vec<Vec<(usize, Trial)>> = tours
                .par_iter_mut()
                .enumerate()
                .map(|(i, t)| {
                    t.settle(kept == Some(i), &replay);
                    if !go {
                        return Vec::new();
                    }
                    t.try_kicks(bridges, (&next, &stop), left)
                })
                .collect();
            if !go {
                return;
            }
            // The round's kicks by their order: every one before the first that gained.
            let made = stop.load(Ordering::Relaxed).saturating_sub(k);
            let mut trials: Vec<Option<(usize, &Trial)>> = vec![None; made];
            for (lane, list) in tried.iter().enumerate() {
                for (i, trial) in list {
                    if let Some(slot) = trials.get_mut(i - k) {
                        *slot = Some((lane, trial));
                    }
                }
            }
            // Read in kick order, as one tour makes them.
            kept = None;
            let mut alone = false;
            for trial in &trials {
                if *budget == 0 || failed == KICK_STALL {
                    break;
                }
                let Some((lane, trial)) = *trial else {
                    alone = true; // not reached: every kick of the round was tried
                    break;
                };
                if trial.moves > *budget {
                    alone = true;
                    break;
                }
                kicked.tick_in(k, KICK_CHUNK);
                k += 1;
                *budget -= trial.moves;
                if tours[lane].gains(trial) {
                    kept = Some(lane);
                    failed = 0;
                    break;
                }
                failed += 1;
            }
            replay = kept.map_or_else(Vec::new, |i| tours[i].log.clone().unwrap_or_default());
            if alone {
                // The rest on this tour alone, from the tour before the round's kicks.
                self.settle(false, &[]);
                self.kicks(bridges, (k, failed), budget, kicked);
                return;
            }
        }
    }

    /// One lane's part of a round of [`Tour::kicks_in_lanes`]: takes the next kick from
    /// `next` and tries it, undone when it gains nothing, until a kick gains (it stays made,
    /// and `stop` is lowered to it) or the kicks reach `stop`: the kicks tried, by index.
    fn try_kicks(
        &mut self,
        bridges: &[Bridge],
        (next, stop): (&AtomicUsize, &AtomicUsize),
        left: usize,
    ) -> Vec<(usize, Trial)> {
        let mut tried = Vec::new();
        loop {
            // Every kick before the lowest `stop` is taken by some lane and tried in full:
            // `stop` only falls, and a kick is given up only at or beyond it.
            let i = next.fetch_add(1, Ordering::Relaxed);
            if i >= stop.load(Ordering::Relaxed) {
                return tried;
            }
            // Each kick with the round's budget: the reading in kick order checks it.
            let mut budget = left;
            let trial = self.try_kick(bridges[i], &mut budget);
            let gains = self.gains(&trial);
            tried.push((i, trial));
            if gains {
                stop.fetch_min(i + 1, Ordering::Relaxed);
                return tried;
            }
            self.settle(false, &[]);
        }
    }

    /// A copy of the tour to try kicks on, with its own buffers.
    fn copy(&self) -> Tour<'a> {
        Tour {
            ends: self.ends,
            seq: self.seq.clone(),
            place: self.place.clone(),
            near: self.near,
            eps: self.eps,
            log: None,
            spare: Vec::new(),
            queued: self.queued.clone(),
            queue: std::collections::VecDeque::new(),
            longest: self.longest,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::tests::{cycle_cost, random_strokes};
    use super::super::*;

    #[test]
    fn kicks_in_lanes_make_the_one_tour_result() {
        // Every number of lanes gives the tour of kicks made one after the other: layers
        // where kicks stall, where reversals reach their bound, and budgets that run out
        // during the first search, during the kicks (a kick made again alone) or not at all.
        for (n, seed) in [(40, 21), (300, 22), (1500, 23), (6000, 24)] {
            let ends = random_strokes(n, seed);
            let near = neighbours(&ends, NEIGHBOURS, Span::NONE);
            let start = greedy(&ends, 0);
            for budget in [n / 2, n + 40, 2 * n, MOVES_PER_STROKE * n] {
                let tour = |lanes: usize| {
                    let mut t = Tour::new(&ends, &start, &near);
                    t.improve_in(FULL, Span::NONE, budget, lanes);
                    (t.order(), cycle_cost(&t))
                };
                let (one, cost) = tour(1);
                for lanes in [2, 3, 7, 16] {
                    let (order, c) = tour(lanes);
                    assert!(order == one, "n {n}, budget {budget}, {lanes} lanes");
                    assert_eq!(c.to_bits(), cost.to_bits());
                }
            }
        }
    }
}
