//! Where the command's work runs: on one of rayon's threads, so that each stage's parallel
//! steps are queued and taken up there instead of handed into the pool from outside.
//!
//! A thread outside the pool that starts a parallel step injects it into the pool and waits
//! on a latch until a worker, woken for it, has run it; every step of every stage pays that
//! hand-over, and the data moves to another core's cache and back. Run on a worker, the
//! steps go on its own queue and the same thread takes them up when no other is free.
//! One thread, whole process, together with the one-call process clock and the last view
//! left to the exit: the hidden-line SVG of teapot 0.93x the CPU of before, twocubes 0.78x,
//! nefertiti's JSON + SVG 0.99x (`docs/history/issue35-session14.md`).

/// The stack of the pool's threads: a main thread's usual, so that work moved from `main`
/// keeps the stack it had (rayon's default is a spawned thread's 2 MiB).
pub const STACK: usize = 8 << 20;

/// Sets up rayon's global pool with [`STACK`] (its size as rayon decides: `RAYON_NUM_THREADS`,
/// else one thread a core). Call it first thing in `main`; where a pool is already set up,
/// that one stays.
pub fn set_up() {
    let _ = rayon::ThreadPoolBuilder::new()
        .stack_size(STACK)
        .build_global();
}

/// Runs `work` on one of the pool's threads and returns what it gives (on this thread when
/// it is one of them already).
pub fn on_pool<R: Send>(work: impl FnOnce() -> R + Send) -> R {
    rayon::scope(|_| work())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn work_runs_on_a_pool_thread_and_returns() {
        let (index, value) = on_pool(|| (rayon::current_thread_index(), 7));
        assert!(index.is_some(), "the work ran outside the pool");
        assert_eq!(value, 7);
    }
}
