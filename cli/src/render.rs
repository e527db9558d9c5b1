//! `kepler render`: the exact visible region of every face, written as JSON (and pictures).

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::{Duration, Instant};

use anyhow::Result;
use clap::{Args, ValueEnum};
use kepler_hsr::{
    render_with, EdgeOptions, EdgeSet, LineOptions, Outputs, PictureOptions, Progress,
    RenderOptions, Stage,
};

use super::progress::follow;
use super::{print_warnings, write, CameraArgs};

/// A render that has taken this long shows a progress bar (on a terminal).
const PROGRESS_AFTER: Duration = Duration::from_millis(500);

/// Arguments of `kepler render`.
#[derive(Args, Debug)]
pub(crate) struct RenderArgs {
    /// Scene file (.kdl) or mesh (.obj, .stl, .ply).
    pub(crate) scene: PathBuf,
    /// Write the kepler-visible/1 visible-polygon set here (with `lines` when --edges or
    /// --hidden is given).
    #[arg(long, value_name = "F")]
    pub(crate) json: Option<PathBuf>,
    /// Write an SVG line drawing here.
    #[arg(long, value_name = "F")]
    pub(crate) svg: Option<PathBuf>,
    /// Write a PNG picture here.
    #[arg(long, value_name = "F")]
    pub(crate) png: Option<PathBuf>,
    /// Pixels along the picture's longer side (PNG; SVG width/height).
    #[arg(long, value_name = "PX", default_value_t = 1024,
          value_parser = clap::value_parser!(u32).range(1..=32768))]
    pub(crate) size: u32,
    /// Which edges to draw: feature (silhouettes, borders, creases, intersections) or all.
    #[arg(long, value_enum, value_name = "SET")]
    pub(crate) edges: Option<EdgesArg>,
    /// Crease threshold: dihedral angle in degrees above which an edge is a crease.
    #[arg(
        long,
        value_name = "DEG",
        default_value_t = 30.0,
        allow_negative_numbers = true
    )]
    pub(crate) crease: f64,
    /// Draw hidden lines too (dashed grey).
    #[arg(long)]
    pub(crate) hidden: bool,
    /// Fill visible faces, flat shaded, under the lines.
    #[arg(long)]
    pub(crate) fill: bool,
    #[command(flatten)]
    pub(crate) camera: CameraArgs,
    /// Print the time of each stage and the pruning counters.
    #[arg(long)]
    pub(crate) stats: bool,
    /// Render without inboxes (for comparison).
    #[arg(long)]
    pub(crate) no_inbox: bool,
    #[command(flatten)]
    pub(crate) lod: super::tribox::LodArgs,
    /// Do not print warnings.
    #[arg(long, short)]
    pub(crate) quiet: bool,
}

/// `--edges` values.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum EdgesArg {
    /// Silhouettes, borders, creases and intersection curves.
    Feature,
    /// Every polygon edge.
    All,
}

impl RenderArgs {
    /// The line options the flags ask for.
    fn line_options(&self) -> Result<LineOptions> {
        if !(self.crease.is_finite() && (0.0..=180.0).contains(&self.crease)) {
            anyhow::bail!(
                "--crease {}: expected degrees between 0 and 180",
                self.crease
            );
        }
        Ok(LineOptions {
            edges: EdgeOptions {
                set: match self.edges {
                    Some(EdgesArg::All) => EdgeSet::All,
                    _ => EdgeSet::Feature,
                },
                crease_deg: self.crease,
            },
            hidden: self.hidden,
        })
    }

    /// The render options the flags ask for.
    fn options(&self) -> Result<RenderOptions> {
        Ok(RenderOptions {
            lines: self.line_options()?,
            outputs: Outputs {
                json: self.json.is_some(),
                json_lines: self.edges.is_some() || self.hidden,
                svg: self.svg.is_some(),
                png: self.png.is_some(),
                drawing: false,
                picture: PictureOptions {
                    size: self.size,
                    fill: self.fill,
                },
            },
            no_inbox: self.no_inbox,
            lod: self.lod.options(self.size)?,
        })
    }
}

/// Runs `kepler render`.
pub(crate) fn run(a: RenderArgs, load_opts: &kepler_hsr::LoadOptions) -> Result<ExitCode> {
    if a.json.is_none() && a.svg.is_none() && a.png.is_none() {
        anyhow::bail!("nothing to write: give --json F, --svg F or --png F");
    }
    let opts = a.options()?;
    a.camera.check()?;
    let start = Instant::now();
    // The bar follows loading and preparing too: a big scene shows a sign of life from the
    // start. Load warnings wait until the bar is gone.
    let progress = Progress::new();
    let mut warnings = Vec::new();
    let (scene, load, prepare) = follow(&progress, PROGRESS_AFTER, || -> Result<_> {
        let t = Instant::now();
        let mut scene = kepler_hsr::load_scene_with(&a.scene, load_opts, &mut warnings)?;
        let load = t.elapsed();
        progress.enter(Stage::Prepare, 0);
        let t = Instant::now();
        kepler_hsr::prepare(&mut scene);
        Ok((scene, load, t.elapsed()))
    })?;
    if !a.quiet {
        print_warnings(&warnings);
    }
    let camera = a.camera.camera(&scene)?;
    let delay = PROGRESS_AFTER.saturating_sub(start.elapsed());
    let r = follow(&progress, delay, || {
        render_with(&scene, &camera, &opts, Some(&progress))
    })?;
    if !a.quiet {
        print_warnings(&r.warnings);
    }
    let t = Instant::now();
    for (path, bytes) in [
        (&a.json, r.json.as_ref().map(String::as_bytes)),
        (&a.svg, r.svg.as_ref().map(String::as_bytes)),
        (&a.png, r.png.as_deref()),
    ] {
        if let (Some(path), Some(bytes)) = (path, bytes) {
            write(path, bytes)?;
        }
    }
    let written = t.elapsed();
    if a.stats {
        eprintln!("faces: {}", scene.face_count());
        if let Some(l) = &r.stats.lod {
            eprintln!("{}", super::tribox::lod_report(l));
        }
        let mut times = vec![(Stage::Load.name(), load), (Stage::Prepare.name(), prepare)];
        times.extend(r.stats.times.iter().map(|(s, d)| (s.name(), *d)));
        times.push(("write", written));
        for (name, d) in &times {
            eprintln!("time {name:<11} {:>10.3} ms", d.as_secs_f64() * 1e3);
        }
        for (name, v) in r.stats.counters.lines() {
            eprintln!("{name:<45} {v}");
        }
    }
    Ok(ExitCode::SUCCESS)
}
