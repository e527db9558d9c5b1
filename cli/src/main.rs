//! The `kepler` command: render, query, flatten and inspect polyhedral scenes.

use std::process::ExitCode;

/// The stack of the pool's threads, the command's own among them: a main thread's usual
/// (the readers' recursion is bounded for that, not for a spawned thread's 2 MiB).
const STACK: usize = 8 << 20;

fn main() -> ExitCode {
    kepler_cli::memory::map_big_blocks();
    let cli = kepler_cli::suggest::parse();
    // The whole command runs on one of the pool's threads, so each stage's parallel steps
    // are queued and taken up there instead of handed in from outside the pool and waited
    // for: the data stays in one core's cache and no thread is woken to start a step. One
    // thread, whole process: teapot's hidden-line SVG 0.95x the CPU of running it here.
    // Where the pool cannot be set up, rayon makes its default one.
    let _ = rayon::ThreadPoolBuilder::new()
        .stack_size(STACK)
        .build_global();
    match rayon::scope(|_| kepler_cli::run(cli)) {
        Ok(code) => code,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::FAILURE
        }
    }
}
