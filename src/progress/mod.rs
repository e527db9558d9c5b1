//! Where a run is, shared with a watcher thread (a progress bar): the stage and its phase,
//! and units done of the phase's total. Only the stage entry points (load, prepare) and the
//! pipeline enter stages and phases, with their totals; the algorithms they run are handed
//! a [`Count`] of the current phase and only add units done to it, once per chunk of work,
//! and nothing they compute reads it: watching never changes a result.
//!
//! - [`stage`]: the stages, their phases and what each phase counts.
//! - `lane`: work run beside other work of its stage (the picture beside the JSON), whose
//!   phases reach the bar once the work ahead is done.

pub(crate) mod cpu;
mod lane;
pub(crate) mod stage;

use std::sync::atomic::{AtomicU8, AtomicUsize, Ordering};
use std::sync::{Mutex, PoisonError};
use std::time::{Duration, Instant};

use crate::count::{Count, Tally};
pub(crate) use lane::Lane;

pub(crate) use stage::{Phase, Stage};

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

    /// The count of the current phase's units done, for its algorithms to add to.
    pub(crate) fn count(&self) -> Count<'_> {
        Count::to(self)
    }

    /// Adds `n` units done.
    pub fn add(&self, n: usize) {
        self.done.fetch_add(n, Ordering::Relaxed);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_count_adds_to_the_current_phase() {
        let p = Progress::new();
        p.enter_phase(Stage::View, Phase::Project, 5000);
        p.count().add(4000);
        assert_eq!(p.counts(), (4000, 5000));
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
