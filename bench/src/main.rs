//! `kepler-bench`: the benchmark suite — stage times, peak memory, time against accuracy,
//! size and hidden complexity — as CSV, SVG charts and a table.

use std::process::ExitCode;

use clap::Parser;

/// kepler's benchmark suite.
#[derive(Parser, Debug)]
#[command(name = "kepler-bench", version, about, long_about = None)]
struct Cli {
    #[command(flatten)]
    args: kepler_bench::BenchArgs,
}

fn main() -> ExitCode {
    // The same allocator policy as the `kepler` command, and its work on a pool thread as the
    // command's: its numbers are the command's.
    kepler_cli::memory::map_big_blocks();
    kepler_cli::pool::set_up();
    let args = Cli::parse().args;
    match kepler_cli::pool::on_pool(|| kepler_bench::run(args)) {
        Ok(code) => code,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::FAILURE
        }
    }
}
