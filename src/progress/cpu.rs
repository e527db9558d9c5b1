//! The process's CPU time, read where the system tells it, so a run can say how much of its
//! wall time its stages spent on several threads.

use std::time::{Duration, Instant};

/// CPU time this process's threads have run, summed, those that have ended included (the
/// system's process CPU clock, `CLOCK_PROCESS_CPUTIME_ID`); `None` where the system does not
/// say.
///
/// One system call, whatever the number of threads (the stages read it at both ends, with or
/// without `--stats`). Reading it brings the calling thread's own count up to date; another
/// thread's moves on only when it is switched out or at a scheduler tick (4 ms here), but at
/// a stage's ends the pool's other threads are waiting for work (they sleep, or yield
/// between looks), so theirs are fresh too.
pub fn process_cpu_time() -> Option<Duration> {
    #[cfg(unix)]
    {
        let mut t = libc::timespec {
            tv_sec: 0,
            tv_nsec: 0,
        };
        // SAFETY: clock_gettime writes one timespec through a pointer to a live, owned one.
        if unsafe { libc::clock_gettime(libc::CLOCK_PROCESS_CPUTIME_ID, &mut t) } != 0 {
            return None;
        }
        let s = u64::try_from(t.tv_sec).ok()?;
        Some(Duration::new(s, u32::try_from(t.tv_nsec).ok()?))
    }
    #[cfg(not(unix))]
    {
        None
    }
}

/// A stage's wall time and, where the system tells it, its CPU time (all threads).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Spent {
    /// Wall-clock time.
    pub wall: Duration,
    /// CPU time of the process's threads together; `None` where the system does not say.
    pub cpu: Option<Duration>,
}

/// A stage being timed: started with [`Stopwatch::start`], read with [`Stopwatch::stop`].
#[derive(Debug, Clone, Copy)]
pub struct Stopwatch {
    wall: Instant,
    cpu: Option<Duration>,
}

impl Stopwatch {
    /// Starts both clocks.
    pub fn start() -> Stopwatch {
        Stopwatch {
            cpu: process_cpu_time(),
            wall: Instant::now(),
        }
    }

    /// The wall time since the start, and the CPU time when both ends were read.
    pub fn stop(self) -> Spent {
        let wall = self.wall.elapsed();
        let now = process_cpu_time();
        Spent {
            wall,
            cpu: self.cpu.zip(now).map(|(a, b)| b.saturating_sub(a)),
        }
    }
}

/// The threads a render's parallel stages run on (rayon's pool: `RAYON_NUM_THREADS`, else
/// one a core).
pub fn worker_threads() -> usize {
    rayon::current_num_threads()
}

/// The share of a stage's wall time `wall` that ran on one thread, from its CPU time `cpu` on
/// `threads` threads, had the rest run on all of them (Amdahl's model: cpu = wall (s + (1 - s)
/// threads)); clamped to [0, 1]; 1 on one thread or for a stage too short to say.
pub fn serial_share(wall: Duration, cpu: Duration, threads: usize) -> f64 {
    let (w, c) = (wall.as_secs_f64(), cpu.as_secs_f64());
    if threads < 2 || w <= 0.0 {
        return 1.0;
    }
    let t = threads as f64;
    ((t - c / w) / (t - 1.0)).clamp(0.0, 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The CPU time, in nanoseconds, of the thread whose `/proc` folder is `task`.
    fn task_cpu_ns(task: &std::path::Path) -> Option<u64> {
        let text = std::fs::read_to_string(task.join("schedstat")).ok()?;
        text.split_whitespace().next()?.parse().ok()
    }

    #[test]
    fn cpu_time_grows_with_work_on_linux() {
        // This thread's own clock (other tests' threads come and go in the process's sum).
        let me = std::path::Path::new("/proc/thread-self");
        let Some(a) = task_cpu_ns(me) else {
            return;
        };
        let (mut x, t) = (0u64, std::time::Instant::now());
        let grew = loop {
            for _ in 0..100_000 {
                x = std::hint::black_box(x.wrapping_mul(31).wrapping_add(7));
            }
            if task_cpu_ns(me).is_some_and(|b| b >= a + 10_000_000) {
                break true;
            }
            if t.elapsed() > Duration::from_secs(20) {
                break false;
            }
        };
        assert!(grew, "the CPU time did not move in 20 s of spinning");
        let all = process_cpu_time().expect("the process's threads");
        assert!(
            all >= Duration::from_nanos(a + 10_000_000),
            "{all:?} holds this thread's"
        );
    }

    #[test]
    fn serial_share_follows_amdahl() {
        let s =
            |w: u64, c: u64, t| serial_share(Duration::from_millis(w), Duration::from_millis(c), t);
        assert_eq!(s(100, 100, 2), 1.0);
        assert_eq!(s(100, 200, 2), 0.0);
        assert!((s(100, 150, 2) - 0.5).abs() < 1e-12);
        assert!((s(100, 400, 16) - 12.0 / 15.0).abs() < 1e-12);
        assert_eq!(s(100, 50, 2), 1.0);
        assert_eq!(s(100, 900, 2), 0.0);
        assert_eq!(s(100, 100, 1), 1.0);
    }
}
