//! A progress bar on standard error: drawn only on a terminal, and only once a run has taken
//! more than a moment; it never touches standard output or the results.

use std::io::{IsTerminal, Write};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

/// Least time between two redraws.
const REDRAW: Duration = Duration::from_millis(100);

/// Width of the bar in characters.
const WIDTH: usize = 30;

/// A progress bar for `total` units of work.
#[derive(Debug)]
pub struct Progress {
    label: String,
    total: usize,
    start: Instant,
    delay: Duration,
    enabled: bool,
    last: Option<Instant>,
}

impl Progress {
    /// A bar that shows itself after `delay`, if standard error is a terminal.
    pub fn new(label: &str, total: usize, delay: Duration) -> Progress {
        Progress {
            label: label.to_string(),
            total,
            start: Instant::now(),
            delay,
            enabled: std::io::stderr().is_terminal(),
            last: None,
        }
    }

    /// Shows `done` of the total, with a message (at most every 100 ms).
    pub fn update(&mut self, done: usize, msg: &str) {
        let now = Instant::now();
        let elapsed = now - self.start;
        if !self.enabled || elapsed < self.delay || self.last.is_some_and(|t| now - t < REDRAW) {
            return;
        }
        self.last = Some(now);
        let text = line(&self.label, done, self.total, elapsed.as_secs_f64(), msg);
        let mut e = std::io::stderr().lock();
        let _ = write!(e, "\r{text}\x1b[K");
        let _ = e.flush();
    }

    /// Clears the bar, if it was drawn.
    pub fn finish(&mut self) {
        if self.last.is_some() {
            let mut e = std::io::stderr().lock();
            let _ = write!(e, "\r\x1b[K");
            let _ = e.flush();
            self.last = None;
        }
    }
}

/// One line of the bar: `label [#####.....] done/total  elapsed  message`.
pub fn line(label: &str, done: usize, total: usize, secs: f64, msg: &str) -> String {
    if total == 0 {
        // A stage that does not count its work: its name and the time so far.
        return format!("{label} {secs:.1}s {msg}");
    }
    let done = done.min(total);
    let filled = (WIDTH * done).checked_div(total).unwrap_or(WIDTH);
    format!(
        "{label} [{}{}] {done}/{total} {secs:.1}s {msg}",
        "#".repeat(filled),
        ".".repeat(WIDTH - filled)
    )
}

/// Runs `work` while a bar follows a render's `progress` (its stage, and done of total where
/// the stage counts), drawn from a watcher thread that wakes every 100 ms (and at once
/// when the work ends); on a non-terminal no thread is started at all.
pub fn follow<T: Send>(
    progress: &kepler_hsr::Progress,
    delay: Duration,
    work: impl FnOnce() -> T + Send,
) -> T {
    let mut bar = Progress::new("render", 0, delay);
    if !bar.enabled {
        return work();
    }
    let stop = AtomicBool::new(false);
    std::thread::scope(|s| {
        let watcher = s.spawn(|| {
            while !stop.load(Ordering::Relaxed) {
                let (done, total) = progress.counts();
                bar.label = progress.stage().name().to_string();
                bar.total = total;
                bar.update(done, "");
                std::thread::park_timeout(REDRAW);
            }
            bar.finish();
        });
        let out = work();
        stop.store(true, Ordering::Relaxed);
        watcher.thread().unpark();
        out
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bar_line_fills_in_proportion() {
        assert_eq!(
            line("bench", 15, 30, 1.25, "x"),
            format!("bench [{}{}] 15/30 1.2s x", "#".repeat(15), ".".repeat(15))
        );
        assert_eq!(line("view", 0, 0, 2.0, "x"), "view 2.0s x");
        assert!(line("v", 9, 3, 0.0, "").contains("3/3"));
    }

    #[test]
    fn follow_returns_the_work() {
        let p = kepler_hsr::Progress::new();
        let v = follow(&p, Duration::ZERO, || {
            p.enter(kepler_hsr::Stage::Visibility, 3);
            7
        });
        assert_eq!(v, 7);
        assert_eq!(p.counts(), (0, 3));
    }
}
