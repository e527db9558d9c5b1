//! A sequential pass through a file's bytes, counted by its position: the counter moves
//! once per [`STEP`] bytes, not per line or value read.

use super::Progress;

/// Bytes a pass goes between two adds to the shared counter.
pub(crate) const STEP: usize = 1 << 16;

/// Where a sequential pass is in a file, passed on to a progress counting bytes.
#[derive(Debug)]
pub(crate) struct Cursor<'p> {
    progress: &'p Progress,
    counted: usize,
}

impl<'p> Cursor<'p> {
    /// A pass at the start of the file.
    pub(crate) fn new(progress: &'p Progress) -> Cursor<'p> {
        Cursor {
            progress,
            counted: 0,
        }
    }

    /// The pass has read the file up to byte `at`.
    #[inline]
    pub(crate) fn at(&mut self, at: usize) {
        if at >= self.counted + STEP {
            self.progress.add(at - self.counted);
            self.counted = at;
        }
    }

    /// The pass has read all `len` bytes of the file.
    pub(crate) fn finish(&mut self, len: usize) {
        if len > self.counted {
            self.progress.add(len - self.counted);
            self.counted = len;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::progress::{Phase, Stage};

    #[test]
    fn a_cursor_counts_in_steps_then_to_the_end() {
        let p = Progress::new();
        p.enter_phase(Stage::Load, Phase::Parse, 3 * STEP);
        let mut c = Cursor::new(&p);
        c.at(STEP - 1);
        assert_eq!(p.counts().0, 0);
        c.at(STEP + 10);
        assert_eq!(p.counts().0, STEP + 10);
        c.finish(3 * STEP);
        c.finish(3 * STEP);
        assert_eq!(p.counts(), (3 * STEP, 3 * STEP));
    }
}
