//! Units of work done, counted by an algorithm for whoever watches (the pipeline's
//! progress): an algorithm adds to the [`Count`] it is handed once per chunk of work, never
//! per item, and knows nothing of bars, shares or phases; nothing it computes reads it.
//!
//! - `cursor`: a sequential pass through a file, counted by its position in bytes.
//! - `share`: a piece of work filling a fixed share of a count by fractions (the passes not
//!   yet reduced to plain counts of their own units).

mod cursor;
mod share;

pub(crate) use cursor::Cursor;
pub(crate) use share::{Share, Span, Steps};

use std::fmt::Debug;
use std::sync::atomic::{AtomicUsize, Ordering};

/// Items a loop does between two adds to a [`Count`] ([`Count::tick`]).
pub(crate) const CHUNK: usize = 1024;

/// Where counted units go: a plain atomic counter, or whatever a watcher reads.
pub(crate) trait Tally: Sync + Debug {
    /// Adds `n` units done.
    fn add(&self, n: usize);
}

impl Tally for AtomicUsize {
    fn add(&self, n: usize) {
        self.fetch_add(n, Ordering::Relaxed);
    }
}

/// A counter of units done that an algorithm is handed; [`Count::NONE`] (the default)
/// counts nothing and costs nothing. (Public but unnameable outside the crate: the load
/// functions that still are public take one; callers outside pass `Default::default()`.)
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Count<'a>(Option<&'a dyn Tally>);

impl<'a> Count<'a> {
    /// Counts nothing.
    pub(crate) const NONE: Count<'static> = Count(None);

    /// Counts into `tally`.
    pub(crate) fn to(tally: &'a dyn Tally) -> Count<'a> {
        Count(Some(tally))
    }

    /// Adds `n` units done.
    #[inline]
    pub(crate) fn add(self, n: usize) {
        if let (Some(t), true) = (self.0, n > 0) {
            t.add(n);
        }
    }

    /// Counts item `i` (from 0) of a loop as done: one add of [`CHUNK`] as each chunk's
    /// last item is done, so a hot loop pays a division, not an add, per item; after the
    /// loop, [`Count::tick_rest`] adds the items of the last, partial chunk.
    #[inline]
    pub(crate) fn tick(self, i: usize) {
        self.tick_in(i, CHUNK);
    }

    /// Counts item `i` (from 0) of a loop as done, adding once per `chunk` items: for loops
    /// of few, long items, where [`CHUNK`] would move the count too seldom.
    #[inline]
    pub(crate) fn tick_in(self, i: usize, chunk: usize) {
        if self.0.is_some() && (i + 1).is_multiple_of(chunk) {
            self.add(chunk);
        }
    }

    /// Adds what [`Count::tick`] left uncounted of a loop of `n` items.
    pub(crate) fn tick_rest(self, n: usize) {
        self.add(n % CHUNK);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ticks_add_up_to_the_items_whatever_their_order() {
        let done = AtomicUsize::new(0);
        let count = Count::to(&done);
        for i in (0..5000).rev() {
            count.tick(i);
        }
        assert_eq!(done.load(Ordering::Relaxed), 4 * CHUNK);
        count.tick_rest(5000);
        assert_eq!(done.load(Ordering::Relaxed), 5000);
        Count::NONE.add(3);
    }
}
