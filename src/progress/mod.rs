//! Where a run is, shared with a watcher thread (a progress bar): the stage and its phase,
//! and units done of the phase's total. Workers add to an atomic counter once per chunk of
//! work, never per item, and nothing they compute reads it: watching never changes a result.
//!
//! - [`stage`]: the stages, their phases and what each phase counts.
//! - `cursor`: a sequential pass through a file, counted by its position in bytes.
//! - `share`: a piece of work that fills a fixed share of a phase's count (one mesh's faces
//!   of all the meshes a phase handles), by steps or by fractions.
//! - `lane`: work run beside other work of its stage (the picture beside the JSON), whose
//!   phases reach the bar once the work ahead is done.

mod cursor;
mod lane;
mod share;
pub mod stage;

use std::sync::atomic::{AtomicU8, AtomicUsize, Ordering};
use std::sync::{Mutex, PoisonError};
use std::time::{Duration, Instant};

pub(crate) use cursor::Cursor;
pub(crate) use lane::Lane;
pub(crate) use share::{Share, Span, Steps};

pub use stage::{Phase, Stage, Unit};

/// Items a loop does between two adds to the shared counter ([`Progress::tick`]).
pub const CHUNK: usize = 1024;

/// True when item `i` (from 0) of a loop is the last of a [`CHUNK`]: where a chunked count
/// adds the chunk.
#[inline]
fn ends_chunk(i: usize) -> bool {
    (i + 1).is_multiple_of(CHUNK)
}

/// Where a phase's units done are added: the [`Progress`] itself, or a [`Lane`] that holds
/// them until its phase is shown.
pub(crate) trait Tally: Sync + std::fmt::Debug {
    /// Adds `n` units done to the current phase.
    fn add(&self, n: usize);

    /// Counts item `i` (from 0) of a loop as done: one add of [`CHUNK`] as each chunk's
    /// last item is done, so a hot loop pays a division, not an add, per item; after the
    /// loop, [`Tally::tick_rest`] adds the items of the last, partial chunk.
    #[inline]
    fn tick(&self, i: usize) {
        if ends_chunk(i) {
            self.add(CHUNK);
        }
    }

    /// Adds what [`Tally::tick`] left uncounted of a loop of `n` items.
    fn tick_rest(&self, n: usize) {
        self.add(n % CHUNK);
    }
}

impl Tally for Progress {
    fn add(&self, n: usize) {
        Progress::add(self, n);
    }
}

/// Where a run is: the current stage and phase and, for phases that count, units done of a
/// total. Plain atomics, and a log of the phases entered (touched only on entering one).
#[derive(Debug, Default)]
pub struct Progress {
    stage: AtomicU8,
    phase: AtomicU8,
    done: AtomicUsize,
    total: AtomicUsize,
    /// Phases entered so far: a watcher sees a new phase begin even when its name and total
    /// are those of the last.
    entered: AtomicUsize,
    log: Mutex<Log>,
}

/// The phases a run has been through.
#[derive(Debug, Default)]
struct Log {
    ended: Vec<PhaseCount>,
    current: Option<(PhaseCount, Instant)>,
}

/// One phase as counted: what it counted to, of its total, and how long it took (so far,
/// for the current one).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PhaseCount {
    /// The stage.
    pub stage: Stage,
    /// The phase of the stage.
    pub phase: Phase,
    /// Units done.
    pub done: usize,
    /// Units in all (0: the phase does not count).
    pub total: usize,
    /// Wall time in the phase.
    pub time: Duration,
}

impl Progress {
    /// A new, idle progress (stage [`Stage::Load`], nothing counted).
    pub fn new() -> Progress {
        Progress::default()
    }

    /// The current stage.
    pub fn stage(&self) -> Stage {
        Stage::ALL[usize::from(self.stage.load(Ordering::Relaxed)).min(Stage::ALL.len() - 1)]
    }

    /// The current phase of the stage.
    pub fn phase(&self) -> Phase {
        Phase::ALL[usize::from(self.phase.load(Ordering::Relaxed)).min(Phase::ALL.len() - 1)]
    }

    /// Units done of the current phase's total (0 of 0 when the phase does not count).
    pub fn counts(&self) -> (usize, usize) {
        (
            self.done.load(Ordering::Relaxed),
            self.total.load(Ordering::Relaxed),
        )
    }

    /// How many phases have been entered: it changes whenever a new one begins.
    pub fn entered(&self) -> usize {
        self.entered.load(Ordering::Relaxed)
    }

    /// Enters a stage as a whole, of `total` units (0: not counted).
    pub fn enter(&self, stage: Stage, total: usize) {
        self.enter_phase(stage, Phase::Whole, total);
    }

    /// Enters a phase of a stage, of `total` units of [`Phase::unit`] (0: not counted).
    pub fn enter_phase(&self, stage: Stage, phase: Phase, total: usize) {
        let now = Instant::now();
        let mut log = self.log.lock().unwrap_or_else(PoisonError::into_inner);
        if let Some((mut last, start)) = log.current.take() {
            last.done = self.done.load(Ordering::Relaxed);
            last.time = now - start;
            log.ended.push(last);
        }
        let count = PhaseCount {
            stage,
            phase,
            done: 0,
            total,
            time: Duration::ZERO,
        };
        log.current = Some((count, now));
        self.total.store(0, Ordering::Relaxed);
        self.done.store(0, Ordering::Relaxed);
        let index = |k: Option<usize>| k.unwrap_or(0) as u8;
        self.stage.store(
            index(Stage::ALL.iter().position(|&s| s == stage)),
            Ordering::Relaxed,
        );
        self.phase.store(
            index(Phase::ALL.iter().position(|&p| p == phase)),
            Ordering::Relaxed,
        );
        self.total.store(total, Ordering::Relaxed);
        self.entered.fetch_add(1, Ordering::Relaxed);
    }

    /// Every phase entered so far, in order, the current one last (counted to now).
    pub fn phases(&self) -> Vec<PhaseCount> {
        let log = self.log.lock().unwrap_or_else(PoisonError::into_inner);
        let mut out = log.ended.clone();
        if let Some((mut last, start)) = log.current {
            last.done = self.done.load(Ordering::Relaxed);
            last.time = start.elapsed();
            out.push(last);
        }
        out
    }

    /// The counter of units done, for the phase's workers to add to.
    pub fn done_counter(&self) -> &AtomicUsize {
        &self.done
    }

    /// Adds `n` units done.
    pub fn add(&self, n: usize) {
        self.done.fetch_add(n, Ordering::Relaxed);
    }

    /// Counts item `i` (from 0) of a loop as done: one atomic add of [`CHUNK`] as each
    /// chunk's last item is done; after the loop, [`Progress::tick_rest`] adds the items of
    /// the last, partial chunk.
    #[inline]
    pub fn tick(&self, i: usize) {
        Tally::tick(self, i);
    }

    /// Adds what [`Progress::tick`] left uncounted of a loop of `n` items.
    pub fn tick_rest(&self, n: usize) {
        Tally::tick_rest(self, n);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ticks_add_up_to_the_items_whatever_their_order() {
        let p = Progress::new();
        p.enter_phase(Stage::View, Phase::Project, 5000);
        for i in (0..5000).rev() {
            p.tick(i);
        }
        assert_eq!(p.counts(), (4 * CHUNK, 5000));
        p.tick_rest(5000);
        assert_eq!(p.counts(), (5000, 5000));
    }

    #[test]
    fn the_log_keeps_each_phase_with_its_count() {
        let p = Progress::new();
        assert!(p.phases().is_empty());
        p.enter_phase(Stage::Load, Phase::Parse, 10);
        p.add(10);
        let n = p.entered();
        p.enter(Stage::Visibility, 3);
        assert_eq!(p.entered(), n + 1);
        assert_eq!((p.stage(), p.phase()), (Stage::Visibility, Phase::Whole));
        p.add(2);
        let log: Vec<_> = p
            .phases()
            .iter()
            .map(|c| (c.stage, c.phase, c.done, c.total))
            .collect();
        assert_eq!(
            log,
            [
                (Stage::Load, Phase::Parse, 10, 10),
                (Stage::Visibility, Phase::Whole, 2, 3)
            ]
        );
    }
}
