//! Work run beside other work of the same stage, one bar for both: the lane's phases reach
//! the progress only once the work ahead of it is done, taking over mid-phase with what is
//! left of the phase it is in.
//!
//! The emit stage writes the JSON and builds the picture side by side, and a progress shows
//! one phase at a time. The JSON goes first on the bar (it entered its phase before either
//! started); the picture runs in a lane behind it. While the JSON runs, the picture's phases
//! and counts stay in the lane. When the JSON is done, [`Lane::release`] enters the picture's
//! current phase on the progress, its total being the units the phase has still to count,
//! so the bar's rate (and its ETA) is that of the work still to do; later phases go straight
//! to the progress. A picture finished before the JSON never shows.

use std::sync::{Mutex, PoisonError};

use super::{Phase, Progress, Stage};
use crate::count::{Count, Tally};

/// A piece of work whose phases reach `progress` once nothing runs ahead of it.
#[derive(Debug)]
pub(crate) struct Lane<'p> {
    progress: &'p Progress,
    state: Mutex<State>,
}

/// Where a lane is.
#[derive(Debug)]
struct State {
    /// Nothing runs ahead any more: phases and counts go to the progress.
    open: bool,
    /// The phase entered while held back: stage, phase, total and units counted so far.
    held: Option<(Stage, Phase, usize, usize)>,
}

impl<'p> Lane<'p> {
    /// A lane with nothing ahead of it: its phases go straight to `progress`.
    pub(crate) fn open(progress: &'p Progress) -> Lane<'p> {
        Lane::with(progress, true)
    }

    /// A lane behind other work that counts in `progress`, until [`Lane::release`].
    pub(crate) fn behind(progress: &'p Progress) -> Lane<'p> {
        Lane::with(progress, false)
    }

    fn with(progress: &'p Progress, open: bool) -> Lane<'p> {
        Lane {
            progress,
            state: Mutex::new(State { open, held: None }),
        }
    }

    /// Enters a phase of the lane's work, of `total` units (shown once the lane is open).
    pub(crate) fn enter_phase(&self, stage: Stage, phase: Phase, total: usize) {
        let mut s = self.lock();
        if s.open {
            self.progress.enter_phase(stage, phase, total);
        } else {
            s.held = Some((stage, phase, total, 0));
        }
    }

    /// The work ahead is done: the lane's current phase goes on the progress with the units
    /// it has left to count (none when the phase is complete, or there is none).
    pub(crate) fn release(&self) {
        let mut s = self.lock();
        s.open = true;
        if let Some((stage, phase, total, done)) = s.held.take() {
            if done < total {
                self.progress.enter_phase(stage, phase, total - done);
            }
        }
    }

    /// The count of the lane's current phase, for its algorithms to add to.
    pub(crate) fn count(&self) -> Count<'_> {
        Count::to(self)
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, State> {
        self.state.lock().unwrap_or_else(PoisonError::into_inner)
    }
}

impl Tally for Lane<'_> {
    /// Counts `n` units of the lane's current phase: on the progress once open, held
    /// before (never past the phase's total, so what is left at release is exact).
    fn add(&self, n: usize) {
        let mut s = self.lock();
        if s.open {
            self.progress.add(n);
        } else if let Some(held) = &mut s.held {
            held.3 = (held.3 + n).min(held.2);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_open_lane_counts_on_the_progress() {
        let p = Progress::new();
        let lane = Lane::open(&p);
        lane.enter_phase(Stage::Emit, Phase::Order, 10);
        lane.add(4);
        assert_eq!((p.phase(), p.counts()), (Phase::Order, (4, 10)));
    }

    #[test]
    fn a_lane_behind_takes_over_with_what_is_left() {
        let p = Progress::new();
        p.enter_phase(Stage::Emit, Phase::Json, 5);
        let lane = Lane::behind(&p);
        lane.enter_phase(Stage::Emit, Phase::Dedup, 100);
        lane.add(100);
        lane.enter_phase(Stage::Emit, Phase::Join, 50);
        lane.add(20);
        p.add(5);
        assert_eq!((p.phase(), p.counts()), (Phase::Json, (5, 5)));
        lane.release();
        assert_eq!((p.phase(), p.counts()), (Phase::Join, (0, 30)));
        lane.add(30);
        lane.enter_phase(Stage::Emit, Phase::Order, 7);
        lane.add(7);
        let log: Vec<_> = p
            .phases()
            .iter()
            .map(|c| (c.phase, c.done, c.total))
            .collect();
        assert_eq!(
            log,
            [
                (Phase::Json, 5, 5),
                (Phase::Join, 30, 30),
                (Phase::Order, 7, 7)
            ]
        );
    }

    #[test]
    fn a_lane_done_before_release_never_shows() {
        let p = Progress::new();
        p.enter_phase(Stage::Emit, Phase::Json, 5);
        let lane = Lane::behind(&p);
        lane.enter_phase(Stage::Emit, Phase::Order, 3);
        lane.add(3);
        lane.release();
        assert_eq!(p.entered(), 1);
        assert_eq!(p.phase(), Phase::Json);
    }
}
