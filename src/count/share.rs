//! A share of a count filled by one piece of work: a phase over many meshes gives each mesh
//! its faces' worth, and the mesh's passes fill it by fractions ([`Span`]) or by steps
//! ([`Steps`]), never past it; when the work is done the share is full, whatever the passes
//! counted. (For the passes not yet reduced to plain counts of their own units.)

use std::sync::atomic::{AtomicUsize, Ordering};

use super::{Count, CHUNK};

/// True when item `i` (from 0) of a loop is the last of a [`CHUNK`].
#[inline]
fn ends_chunk(i: usize) -> bool {
    (i + 1).is_multiple_of(CHUNK)
}

/// `units` of a phase's count, filled by one piece of work.
#[derive(Debug)]
pub(crate) struct Share<'p> {
    count: Count<'p>,
    units: usize,
    /// Units counted so far (may run past `units`; only `units` reach the progress).
    given: AtomicUsize,
}

impl<'p> Share<'p> {
    /// A share of `units` of `count`, nothing counted yet.
    pub(crate) fn new(count: Count<'p>, units: usize) -> Share<'p> {
        Share {
            count,
            units,
            given: AtomicUsize::new(0),
        }
    }

    /// Fills the share up to `fraction` of its units (never back): the work is that far.
    pub(crate) fn reach(&self, fraction: f64) {
        let target = (self.units as f64 * fraction.clamp(0.0, 1.0)) as usize;
        let old = self.given.fetch_max(target, Ordering::Relaxed);
        self.give(old, old.max(target));
    }

    /// The work is done: the whole share is counted.
    pub(crate) fn finish(&self) {
        self.reach(1.0);
    }

    /// The part of the share from `lo` to `hi` (fractions), for one pass of the work.
    pub(crate) fn span(&self, lo: f64, hi: f64) -> Span<'_> {
        Span {
            share: Some(self),
            lo,
            hi,
        }
    }

    /// Passes on the units the count moved by from `old` to `new`, within the share (the
    /// moves of all callers chain, so what reaches the progress adds up to the share).
    fn give(&self, old: usize, new: usize) {
        let n = new.min(self.units) - old.min(self.units);
        if n > 0 {
            self.count.add(n);
        }
    }
}

/// The part of a [`Share`] one pass of the work fills, from fraction `lo` to `hi` of it.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Span<'s> {
    /// None: the span counts nothing.
    share: Option<&'s Share<'s>>,
    lo: f64,
    hi: f64,
}

impl<'s> Span<'s> {
    /// A span that counts nothing.
    pub(crate) const NONE: Span<'static> = Span {
        share: None,
        lo: 0.0,
        hi: 1.0,
    };

    /// The pass is `fraction` done.
    pub(crate) fn reach(&self, fraction: f64) {
        if let Some(share) = self.share {
            share.reach(self.lo + (self.hi - self.lo) * fraction.clamp(0.0, 1.0));
        }
    }

    /// The pass is done.
    pub(crate) fn finish(&self) {
        self.reach(1.0);
    }

    /// The part of this span from `lo` to `hi` (fractions of it), for a sub-pass.
    pub(crate) fn span(&self, lo: f64, hi: f64) -> Span<'s> {
        let at = |f: f64| self.lo + (self.hi - self.lo) * f;
        Span {
            share: self.share,
            lo: at(lo),
            hi: at(hi),
        }
    }

    /// The span counted in `n` steps (a loop of `n` items).
    pub(crate) fn steps(&self, n: usize) -> Steps<'s> {
        Steps {
            span: *self,
            n,
            done: AtomicUsize::new(0),
        }
    }
}

/// A [`Span`] filled by `n` steps, counted as they are done (in any order, on any thread).
#[derive(Debug)]
pub(crate) struct Steps<'s> {
    span: Span<'s>,
    n: usize,
    done: AtomicUsize,
}

impl Steps<'_> {
    /// Counts `k` more steps done.
    pub(crate) fn add(&self, k: usize) {
        let done = self.done.fetch_add(k, Ordering::Relaxed) + k;
        let fraction = if self.n == 0 {
            1.0
        } else {
            done as f64 / self.n as f64
        };
        self.span.reach(fraction);
    }

    /// Counts step `i` (from 0) done, adding once per [`CHUNK`] steps; the span's
    /// [`Span::finish`] counts the rest.
    #[inline]
    pub(crate) fn tick(&self, i: usize) {
        if ends_chunk(i) {
            self.add(CHUNK);
        }
    }

    /// Counts step `i` (from 0) done, adding once per `chunk` steps: for loops of few,
    /// long steps, where [`CHUNK`] would move the bar too seldom.
    #[inline]
    pub(crate) fn tick_in(&self, i: usize, chunk: usize) {
        if (i + 1).is_multiple_of(chunk) {
            self.add(chunk);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::progress::{Phase, Progress, Stage};

    /// A share of `units` of `p`'s current phase.
    fn share(p: &Progress, units: usize) -> Share<'_> {
        Share::new(p.count(), units)
    }

    #[test]
    fn a_share_never_counts_past_its_units() {
        let p = Progress::new();
        p.enter_phase(Stage::Prepare, Phase::Solidity, 150);
        let a = share(&p, 100);
        a.reach(0.6);
        a.reach(0.5);
        assert_eq!(p.counts().0, 60, "reach never goes back");
        a.reach(1.3);
        assert_eq!(p.counts().0, 100);
        a.finish();
        let b = share(&p, 50);
        b.span(0.5, 1.0).span(0.0, 0.5).reach(1.0);
        assert_eq!(p.counts().0, 137, "three quarters of 50, rounded down");
        b.finish();
        assert_eq!(p.counts(), (150, 150));
    }

    #[test]
    fn steps_fill_their_span_in_any_order() {
        let p = Progress::new();
        p.enter_phase(Stage::Lines, Phase::Intersections, 1000);
        let s = share(&p, 1000);
        let half = s.span(0.0, 0.5);
        let steps = half.steps(4 * CHUNK);
        for i in (0..4 * CHUNK).rev() {
            steps.tick(i);
        }
        assert_eq!(p.counts().0, 500);
        s.span(0.5, 1.0).steps(0).add(0);
        assert_eq!(p.counts().0, 1000, "no steps: the span is done at once");
    }

    #[test]
    fn small_chunks_move_the_count_sooner() {
        let p = Progress::new();
        p.enter_phase(Stage::Emit, Phase::Order, 100);
        let s = share(&p, 100);
        let steps = s.span(0.0, 1.0).steps(40);
        for i in 0..19 {
            steps.tick_in(i, 8);
        }
        assert_eq!(p.counts().0, 40, "two chunks of 8 of 40 steps");
    }
}
