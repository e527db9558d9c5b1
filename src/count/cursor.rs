//! A sequential pass through a file's bytes, counted by its position: the counter moves
//! once per [`STEP`] bytes, not per line or value read.

use super::Count;

/// Bytes a pass goes between two adds to the shared counter.
pub(crate) const STEP: usize = 1 << 16;

/// Where a sequential pass is in a file, passed on to a count of bytes.
#[derive(Debug)]
pub(crate) struct Cursor<'p> {
    count: Count<'p>,
    counted: usize,
}

impl<'p> Cursor<'p> {
    /// A pass at the start of the file.
    pub(crate) fn new(count: Count<'p>) -> Cursor<'p> {
        Cursor { count, counted: 0 }
    }

    /// The pass has read the file up to byte `at`.
    #[inline]
    pub(crate) fn at(&mut self, at: usize) {
        if at >= self.counted + STEP {
            self.count.add(at - self.counted);
            self.counted = at;
        }
    }

    /// The pass has read all `len` bytes of the file.
    pub(crate) fn finish(&mut self, len: usize) {
        if len > self.counted {
            self.count.add(len - self.counted);
            self.counted = len;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::{AtomicUsize, Ordering};

    #[test]
    fn a_cursor_counts_in_steps_then_to_the_end() {
        let p = AtomicUsize::new(0);
        let mut c = Cursor::new(Count::to(&p));
        c.at(STEP - 1);
        assert_eq!(p.load(Ordering::Relaxed), 0);
        c.at(STEP + 10);
        assert_eq!(p.load(Ordering::Relaxed), STEP + 10);
        c.finish(3 * STEP);
        c.finish(3 * STEP);
        assert_eq!(p.load(Ordering::Relaxed), 3 * STEP);
    }
}
