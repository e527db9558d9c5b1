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

/// The time left in a counted stage that has done `done` of `total` in `stage_secs`, at the
/// rate so far; None before there is a rate to go by (nothing done, or under a second in).
pub fn eta(done: usize, total: usize, stage_secs: f64) -> Option<f64> {
    (done > 0 && done <= total && stage_secs >= 1.0)
        .then(|| stage_secs * (total - done) as f64 / done as f64)
}

/// `eta 1m05s`-style text for a number of seconds.
pub fn eta_text(secs: f64) -> String {
    let s = secs.round() as u64;
    if s >= 60 {
        format!("eta {}m{:02}s", s / 60, s % 60)
    } else {
        format!("eta {s}s")
    }
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
            // When the stage shown began: its rate so far gives the time it has left.
            let mut stage_start = Instant::now();
            while !stop.load(Ordering::Relaxed) {
                let (done, total) = progress.counts();
                let label = progress.stage().name();
                if bar.label != label || bar.total != total {
                    bar.label = label.to_string();
                    bar.total = total;
                    stage_start = Instant::now();
                }
                let left = eta(done, total, stage_start.elapsed().as_secs_f64());
                bar.update(done, &left.map(eta_text).unwrap_or_default());
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
    fn eta_follows_the_rate_so_far() {
        assert_eq!(eta(25, 100, 10.0), Some(30.0));
        assert_eq!(eta(100, 100, 10.0), Some(0.0));
        assert_eq!(eta(0, 100, 10.0), None, "no rate yet");
        assert_eq!(eta(50, 100, 0.5), None, "too early to say");
        assert_eq!(eta_text(30.0), "eta 30s");
        assert_eq!(eta_text(65.4), "eta 1m05s");
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
