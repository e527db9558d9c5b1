//! `kepler render`: the exact visible region of every face, written as JSON (and pictures).

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::{Duration, Instant};

use anyhow::Result;
use clap::Args;
use kepler::emit::to_json;
use kepler::view::View;
use kepler::visibility::{solve, PassOptions};

use super::{load_only, prepare, write, CameraArgs};

/// Arguments of `kepler render`.
#[derive(Args, Debug)]
pub struct RenderArgs {
    /// Scene file (.kdl) or mesh (.obj, .stl, .ply).
    pub scene: PathBuf,
    /// Write the kepler-visible/1 visible-polygon set here.
    #[arg(long, value_name = "F")]
    pub json: Option<PathBuf>,
    #[command(flatten)]
    pub camera: CameraArgs,
    /// Print the time of each stage and the pruning counters.
    #[arg(long)]
    pub stats: bool,
    /// Render without inboxes (for comparison).
    #[arg(long)]
    pub no_inbox: bool,
    /// Do not print warnings.
    #[arg(long, short)]
    pub quiet: bool,
}

/// Runs `kepler render`.
pub fn run(a: RenderArgs) -> Result<ExitCode> {
    let mut times: Vec<(&str, Duration)> = Vec::new();
    let t = Instant::now();
    let mut scene = load_only(&a.scene, a.quiet)?;
    times.push(("load", t.elapsed()));
    let t = Instant::now();
    prepare(&mut scene);
    times.push(("prepare", t.elapsed()));
    let t = Instant::now();
    let camera = a.camera.camera(&scene)?;
    let view = View::new(&scene, camera);
    times.push(("view", t.elapsed()));
    let t = Instant::now();
    let vis = solve(
        &view,
        PassOptions {
            use_inbox: !a.no_inbox,
        },
    );
    times.push(("visibility", t.elapsed()));
    let t = Instant::now();
    if let Some(path) = &a.json {
        write(path, to_json(&view, &vis, None))?;
    }
    times.push(("emit", t.elapsed()));
    if a.stats {
        eprintln!("faces: {}", scene.face_count());
        for (name, d) in &times {
            eprintln!("time {name:<11} {:>10.3} ms", d.as_secs_f64() * 1e3);
        }
        for (name, v) in vis.counters.lines() {
            eprintln!("{name:<45} {v}");
        }
    }
    Ok(ExitCode::SUCCESS)
}
