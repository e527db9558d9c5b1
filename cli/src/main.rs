//! The `kepler` command: render, query, flatten and inspect polyhedral scenes.

use std::process::ExitCode;

fn main() -> ExitCode {
    kepler_cli::memory::map_big_blocks();
    kepler_cli::pool::set_up();
    let cli = kepler_cli::suggest::parse();
    match kepler_cli::pool::on_pool(|| kepler_cli::run(cli)) {
        Ok(code) => code,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::FAILURE
        }
    }
}
