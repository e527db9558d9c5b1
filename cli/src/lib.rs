//! The `kepler` command line: argument definitions and a thin run of each subcommand over the
//! library (`kepler_hsr`), which does all the work; errors become messages here (anyhow).

pub mod bar;
mod camera_args;
mod check;
mod components;
mod diff;
pub mod embed;
mod flatten;
mod hierarchy_arg;
mod info;
pub mod memory;
mod output;
mod plot_args;
pub mod pool;
mod query;
mod render;
mod sheet;
pub mod suggest;
mod tribox;
mod views;

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::Result;
use clap::{Parser, Subcommand};
use kepler_hsr::{LoadOptions, Scene};

use camera_args::CameraArgs;
use output::write;

/// kepler: exact hidden-surface removal for polyhedral scenes.
#[derive(Parser, Debug)]
#[command(name = "kepler", version, about, long_about = None)]
pub struct Cli {
    #[command(subcommand)]
    command: Command,
    /// Refuse scenes with more faces than this once their instances are placed (counted
    /// before anything is expanded). The default fits a render in 24 GiB of memory.
    #[arg(long, global = true, value_name = "N", default_value_t = LoadOptions::DEFAULT_MAX_FACES)]
    max_faces: usize,
    /// Refuse includes and mesh files of a scene file whose real path (symlinks and `..`
    /// resolved) is not under DIR.
    #[arg(long, global = true, value_name = "DIR")]
    include_root: Option<PathBuf>,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Compute the exact visible region of every face and write SVG, PNG or JSON.
    Render(render::RenderArgs),
    /// Ask INCLUDE, VISP or VISOBJ questions about a scene.
    Query(query::QueryArgs),
    /// Write the scene as one OBJ: world coordinates, one `o` group per object, global face order.
    Flatten(flatten::FlattenArgs),
    /// Show the object tree with counts, boxes and closedness.
    Info(info::InfoArgs),
    /// Re-render and compare the visible-polygon set with a golden file (exit 1 on changes).
    Check(check::CheckArgs),
    /// Compare two kepler-visible/1 files face by face (exit 0 same, 1 changed, 2 usage).
    Diff(diff::DiffArgs),
    /// Hierarchical tribox substitutes at each level (OBJ, SVG) and the paper's Table 1.
    Tribox(tribox::TriboxArgs),
}

/// Runs a parsed command line.
pub fn run(cli: Cli) -> Result<ExitCode> {
    let opts = cli.load_options();
    match cli.command {
        Command::Render(a) => render::run(a, &opts),
        Command::Query(a) => query::run(a, &opts),
        Command::Flatten(a) => flatten::run(a, &opts),
        Command::Info(a) => info::run(a, &opts),
        Command::Check(a) => check::run(a, &opts),
        Command::Diff(a) => diff::run(a),
        Command::Tribox(a) => tribox::run(a, &opts),
    }
}

impl Cli {
    /// The load options the global flags ask for.
    fn load_options(&self) -> LoadOptions {
        LoadOptions {
            max_faces: self.max_faces,
            include_root: self.include_root.clone(),
        }
    }
}

/// Loads a scene and runs the prepare stage (solidity, INBOXes, object trees), printing
/// warnings to standard error.
fn load(path: &Path, quiet: bool, opts: &LoadOptions) -> Result<Scene> {
    load_with(path, quiet, opts, &kepler_hsr::PrepareOptions::default())
}

/// [`load`] with the prepare stage's options.
fn load_with(
    path: &Path,
    quiet: bool,
    opts: &LoadOptions,
    prepare: &kepler_hsr::PrepareOptions,
) -> Result<Scene> {
    let mut scene = load_only(path, quiet, opts)?;
    kepler_hsr::prepare(&mut scene, prepare, &kepler_hsr::Progress::default());
    Ok(scene)
}

/// Loads a scene without preparing it, printing its warnings to standard error.
fn load_only(path: &Path, quiet: bool, opts: &LoadOptions) -> Result<Scene> {
    let mut warnings = Vec::new();
    let scene =
        kepler_hsr::load_scene(path, opts, &mut warnings, &kepler_hsr::Progress::default())?;
    if !quiet {
        print_warnings(&warnings);
    }
    Ok(scene)
}

/// Prints warnings, at most 20 in full and a count of the rest.
fn print_warnings(warnings: &[kepler_hsr::Warning]) {
    for w in warnings.iter().take(20) {
        eprintln!("{w}");
    }
    if warnings.len() > 20 {
        eprintln!("warning: ... and {} more", warnings.len() - 20);
    }
}

/// Prints to standard output; a closed pipe (`kepler info | head`) is not an error.
fn out(text: &str) {
    use std::io::Write;
    let mut o = std::io::stdout().lock();
    let _ = o
        .write_all(text.as_bytes())
        .and_then(|_| o.write_all(b"\n"));
}
