//! A progress bar on standard error, drawn from the library's counts: only on a terminal,
//! and only once a run has taken more than a moment; it never touches standard output or
//! the results.

use std::io::{IsTerminal, Write};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use kepler_hsr::stats::{Phase, Unit};

/// Least time between two redraws.
const REDRAW: Duration = Duration::from_millis(100);

/// Width of the bar in characters.
const WIDTH: usize = 30;

/// A progress bar for `total` units of work.
#[derive(Debug)]
pub struct Bar {
    label: String,
    total: usize,
    unit: Unit,
    start: Instant,
    delay: Duration,
    enabled: bool,
    last: Option<Instant>,
}

impl Bar {
    /// A bar that shows itself after `delay`, if standard error is a terminal.
    pub fn new(label: &str, total: usize, delay: Duration) -> Bar {
        Bar {
            label: label.to_string(),
            total,
            unit: Unit::Items,
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
        let secs = elapsed.as_secs_f64();
        let text = line(&self.label, done, self.total, self.unit, secs, msg);
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

/// One line of the bar: `label [#####.....] done/total unit  elapsed  message`.
pub fn line(label: &str, done: usize, total: usize, unit: Unit, secs: f64, msg: &str) -> String {
    if total == 0 {
        // A stage that does not count its work: its name and the time so far.
        return format!("{label} {secs:.1}s {msg}");
    }
    let done = done.min(total);
    let filled = (WIDTH * done).checked_div(total).unwrap_or(WIDTH);
    format!(
        "{label} [{}{}] {} {secs:.1}s {msg}",
        "#".repeat(filled),
        ".".repeat(WIDTH - filled),
        amounts(done, total, unit)
    )
}

/// `done/total` in the unit: bytes in the total's multiple of 1000 (`21.2/52.9 MB`), other
/// units each in three figures (`412k/1.00M faces`; a stage's own items without a name).
pub fn amounts(done: usize, total: usize, unit: Unit) -> String {
    match unit {
        Unit::Items => format!("{}/{}", short(done), short(total)),
        Unit::Bytes => {
            let (scale, prefix) = scale(total);
            let part = |n: usize| figures(n as f64 / scale);
            format!("{}/{} {prefix}B", part(done), part(total))
        }
        _ => format!("{}/{} {}", short(done), short(total), unit.name()),
    }
}

/// A count in three figures with a k, M or G suffix (exact below 10,000).
fn short(n: usize) -> String {
    if n < 10_000 {
        return n.to_string();
    }
    let (scale, prefix) = scale(n);
    format!("{}{prefix}", figures(n as f64 / scale))
}

/// The multiple of 1000 to show `n` in (so that three figures of it stay below 1000),
/// with its prefix.
fn scale(n: usize) -> (f64, &'static str) {
    match n {
        0..1_000 => (1.0, ""),
        1_000..999_500 => (1e3, "k"),
        999_500..999_500_000 => (1e6, "M"),
        _ => (1e9, "G"),
    }
}

/// `x` (below 999.5) in three significant figures.
fn figures(x: f64) -> String {
    match x {
        x if x >= 99.95 => format!("{x:.0}"),
        x if x >= 9.995 => format!("{x:.1}"),
        x => format!("{x:.2}"),
    }
}

/// What the bar calls the current phase of a render: `stage` or `stage: phase`.
pub fn phase_label(progress: &kepler_hsr::Progress) -> String {
    match progress.phase() {
        Phase::Whole => progress.stage().name().to_string(),
        p => format!("{}: {}", progress.stage().name(), p.name()),
    }
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

/// Runs `work` while a bar follows a render's `progress` (its stage and phase, and done of
/// total where the phase counts, with the time the phase has left at its rate so far), drawn
/// from a watcher thread that wakes every 100 ms (and at once when the work ends); on a
/// non-terminal no thread is started at all. The bar's clock runs from `start` (the
/// command's start, so that it goes on across bars), and the bar shows itself once `delay`
/// has passed since.
pub fn follow<T: Send>(
    progress: &kepler_hsr::Progress,
    start: Instant,
    delay: Duration,
    work: impl FnOnce() -> T + Send,
) -> T {
    let mut bar = Bar::new("render", 0, delay);
    bar.start = start;
    if !bar.enabled {
        return work();
    }
    let stop = AtomicBool::new(false);
    std::thread::scope(|s| {
        let watcher = s.spawn(|| {
            // When the phase shown began: its rate so far gives the time it has left.
            let mut phase_start = Instant::now();
            let mut entered = progress.entered();
            while !stop.load(Ordering::Relaxed) {
                let now = progress.entered();
                let (done, total) = progress.counts();
                if now != entered || bar.total != total {
                    entered = now;
                    bar.label = phase_label(progress);
                    bar.total = total;
                    bar.unit = progress.phase().unit();
                    phase_start = Instant::now();
                }
                let left = eta(done, total, phase_start.elapsed().as_secs_f64());
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
            line("bench", 15, 30, Unit::Items, 1.25, "x"),
            format!("bench [{}{}] 15/30 1.2s x", "#".repeat(15), ".".repeat(15))
        );
        assert_eq!(line("view", 0, 0, Unit::Faces, 2.0, "x"), "view 2.0s x");
        assert!(line("v", 9, 3, Unit::Items, 0.0, "").contains("3/3"));
        assert!(line("p", 5, 10, Unit::Faces, 0.0, "").contains("] 5/10 faces 0.0s"));
    }

    #[test]
    fn amounts_read_at_a_glance() {
        assert_eq!(amounts(21_234_567, 52_971_402, Unit::Bytes), "21.2/53.0 MB");
        assert_eq!(amounts(512, 900, Unit::Bytes), "512/900 B");
        assert_eq!(amounts(412_345, 1_002_528, Unit::Faces), "412k/1.00M faces");
        assert_eq!(amounts(9_999, 14_391_072, Unit::Edges), "9999/14.4M edges");
        assert_eq!(amounts(12_345, 99_999, Unit::Faces), "12.3k/100k faces");
        assert_eq!(amounts(999_700, 999_999, Unit::Faces), "1.00M/1.00M faces");
        assert_eq!(amounts(7, 9, Unit::Items), "7/9");
        assert_eq!(amounts(15_949, 1_002_528, Unit::Items), "15.9k/1.00M");
    }

    #[test]
    fn the_label_names_the_phase() {
        let p = kepler_hsr::Progress::new();
        p.enter(kepler_hsr::stats::Stage::Visibility, 3);
        assert_eq!(phase_label(&p), "visibility");
        p.enter_phase(kepler_hsr::stats::Stage::Prepare, Phase::Solidity, 3);
        assert_eq!(phase_label(&p), "prepare: solidity");
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
        let v = follow(&p, Instant::now(), Duration::ZERO, || {
            p.enter(kepler_hsr::stats::Stage::Visibility, 3);
            7
        });
        assert_eq!(v, 7);
        assert_eq!(p.counts(), (0, 3));
    }
}
