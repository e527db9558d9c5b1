//! `kepler diff A.json B.json`: two `kepler-visible/1` sets compared face by face without a
//! scene (`kepler_hsr::check::diff`), and the report format and exit statuses it shares with
//! `kepler check`.
//!
//! Every face visible in either set is judged by one rule: the area of the symmetric
//! difference of its two regions relative to the larger of its two visible areas and a floor
//! of 1e-12 of the larger set's total visible area; it is listed when that exceeds `--tol`,
//! as changed, added (visible in B only) or removed (visible in A only).

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Result;
use clap::{Args, ValueEnum};
use kepler_hsr::check::{diff, Comparison, VisibleSet};

use super::out;

/// What the exit statuses of `check` and `diff` mean (shown after their `--help`).
pub(crate) const EXIT_STATUS: &str = "Exit status: 0 when every face is within the \
tolerance, 1 when some face changed by more than it (added and removed faces included), 2 on \
a usage error or a file that cannot be read or parsed (named with its line).";

/// Arguments of `kepler diff`.
#[derive(Args, Debug)]
#[command(after_help = EXIT_STATUS)]
pub(crate) struct DiffArgs {
    /// The golden (expected) kepler-visible/1 file.
    #[arg(value_name = "A.json")]
    pub(crate) golden: PathBuf,
    /// The current kepler-visible/1 file, compared with A.
    #[arg(value_name = "B.json")]
    pub(crate) current: PathBuf,
    /// Largest allowed change of a face's visible region: the area of the symmetric difference
    /// relative to the face's larger visible area (at least 1e-12 of the larger set's visible
    /// area). The same for changed, added and removed faces.
    #[arg(
        long,
        value_name = "T",
        default_value_t = 1e-9,
        allow_negative_numbers = true
    )]
    pub(crate) tol: f64,
    /// How to print the report: lines of text, or kepler-diff/1 JSON on standard output.
    #[arg(long, value_name = "FORMAT", default_value = "text")]
    pub(crate) report: Report,
}

/// The report formats of `check` and `diff`.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Report {
    /// One line per changed face, then a summary.
    Text,
    /// kepler-diff/1 JSON: every changed face with its areas, symmetric difference and
    /// relative change.
    Json,
}

/// Runs `kepler diff`: errors are reported here and exit 2.
pub(crate) fn run(a: DiffArgs) -> Result<ExitCode> {
    Ok(exit_2_on_error(compare_files(&a)))
}

/// The comparison of the two files, printed; its exit status.
fn compare_files(a: &DiffArgs) -> Result<ExitCode> {
    check_tol(a.tol)?;
    let golden = VisibleSet::read(&a.golden)?;
    let current = VisibleSet::read(&a.current)?;
    Ok(print_report(&diff(&golden, &current, a.tol), a.report))
}

/// Refuses a tolerance that is negative or not finite.
pub(crate) fn check_tol(tol: f64) -> Result<()> {
    if !(tol >= 0.0 && tol.is_finite()) {
        anyhow::bail!("--tol {tol}: expected a finite number >= 0");
    }
    Ok(())
}

/// Prints the report in `format`; exit 0 when the sets are the same, else 1.
pub(crate) fn print_report(report: &Comparison, format: Report) -> ExitCode {
    let text = match format {
        Report::Text => report.to_text(),
        Report::Json => report.to_json(),
    };
    out(text.trim_end_matches('\n'));
    if report.is_same() {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    }
}

/// The exit status of a command whose errors exit 2 (printed as `error: ...`), so that they
/// are not taken for 1, "changed".
pub(crate) fn exit_2_on_error(result: Result<ExitCode>) -> ExitCode {
    result.unwrap_or_else(|e| {
        eprintln!("error: {e:#}");
        ExitCode::from(2)
    })
}
