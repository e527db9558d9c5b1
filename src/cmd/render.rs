//! `kepler render`: the exact visible region of every face, written as JSON (and pictures).

use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::atomic::AtomicUsize;
use std::time::{Duration, Instant};

use anyhow::Result;
use clap::{Args, ValueEnum};
use kepler::emit::{draw, to_json, Drawing, EdgeOptions, EdgeSet, LineOptions};
use kepler::scene::Scene;
use kepler::view::{Cull, View};
use kepler::visibility::{solve_counted, PassOptions};

use super::progress::follow;
use super::{load_only, write, CameraArgs};

/// A render that has taken this long shows a progress bar (on a terminal) for the visibility
/// stage.
const PROGRESS_AFTER: Duration = Duration::from_millis(500);

/// Arguments of `kepler render`.
#[derive(Args, Debug)]
pub struct RenderArgs {
    /// Scene file (.kdl) or mesh (.obj, .stl, .ply).
    pub scene: PathBuf,
    /// Write the kepler-visible/1 visible-polygon set here (with `lines` when --edges or
    /// --hidden is given).
    #[arg(long, value_name = "F")]
    pub json: Option<PathBuf>,
    /// Write an SVG line drawing here.
    #[arg(long, value_name = "F")]
    pub svg: Option<PathBuf>,
    /// Write a PNG picture here.
    #[arg(long, value_name = "F")]
    pub png: Option<PathBuf>,
    /// Pixels along the picture's longer side (PNG; SVG width/height).
    #[arg(long, value_name = "PX", default_value_t = 1024,
          value_parser = clap::value_parser!(u32).range(1..=32768))]
    pub size: u32,
    /// Which edges to draw: feature (silhouettes, borders, creases, intersections) or all.
    #[arg(long, value_enum, value_name = "SET")]
    pub edges: Option<EdgesArg>,
    /// Crease threshold: dihedral angle in degrees above which an edge is a crease.
    #[arg(long, value_name = "DEG", default_value_t = 30.0)]
    pub crease: f64,
    /// Draw hidden lines too (dashed grey).
    #[arg(long)]
    pub hidden: bool,
    /// Fill visible faces, flat shaded, under the lines.
    #[arg(long)]
    pub fill: bool,
    #[command(flatten)]
    pub camera: CameraArgs,
    /// Print the time of each stage and the pruning counters.
    #[arg(long)]
    pub stats: bool,
    /// Render without inboxes (for comparison).
    #[arg(long)]
    pub no_inbox: bool,
    #[command(flatten)]
    pub lod: super::tribox::LodArgs,
    /// Do not print warnings.
    #[arg(long, short)]
    pub quiet: bool,
}

/// `--edges` values.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum EdgesArg {
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
}

/// Writes the requested outputs.
fn emit(
    a: &RenderArgs,
    scene: &Scene,
    view: &View,
    vis: &kepler::visibility::Visibility,
) -> Result<()> {
    let json_lines = a.edges.is_some() || a.hidden;
    let pictures = a.svg.is_some() || a.png.is_some();
    let drawing = if pictures || (a.json.is_some() && json_lines) {
        draw(scene, view, vis, &a.line_options()?)
    } else {
        Drawing::default()
    };
    if let Some(path) = &a.json {
        let lines = json_lines.then(|| drawing.lines());
        write(path, to_json(view, vis, lines.as_ref()))?;
    }
    if pictures {
        let marks = kepler::emit::marks::face_marks(scene, view, vis);
        let pic = kepler::emit::picture::picture(view, vis, &drawing, &marks, a.fill);
        if let Some(path) = &a.svg {
            write(path, kepler::emit::svg::to_svg(&pic, a.size))?;
        }
        if let Some(path) = &a.png {
            write(path, kepler::emit::png::to_png(&pic, a.size)?)?;
        }
    }
    Ok(())
}

/// Runs `kepler render`.
pub fn run(a: RenderArgs) -> Result<ExitCode> {
    a.line_options()?;
    let start = Instant::now();
    let mut times: Vec<(&str, Duration)> = Vec::new();
    let t = Instant::now();
    let mut scene = load_only(&a.scene, a.quiet)?;
    times.push(("load", t.elapsed()));
    let camera = a.camera.camera(&scene)?;
    let t = Instant::now();
    let lod = a.lod.apply(&mut scene, &camera, a.size)?;
    if lod.is_some() {
        times.push(("lod", t.elapsed()));
    }
    let t = Instant::now();
    kepler::prepare::prepare(&mut scene);
    times.push(("prepare", t.elapsed()));
    let t = Instant::now();
    // Hidden lines need every face's facing, so they keep every face in the view.
    let cull = if a.no_inbox || a.hidden {
        Cull::none(&scene)
    } else {
        Cull::new(&scene, &camera)
    };
    times.push(("cull", t.elapsed()));
    let t = Instant::now();
    let view = View::from_cull(&scene, camera, &cull);
    drop(cull);
    times.push(("view", t.elapsed()));
    let t = Instant::now();
    let opts = PassOptions {
        use_inbox: !a.no_inbox,
    };
    let done = AtomicUsize::new(0);
    let delay = PROGRESS_AFTER.saturating_sub(start.elapsed());
    let pieces = view.screen.faces.len();
    let vis = follow("visibility", pieces, delay, &done, || {
        solve_counted(&view, opts, Some(&done))
    });
    times.push(("visibility", t.elapsed()));
    let t = Instant::now();
    // Emitting needs the screen faces, not the tree: free it before the drawing's own memory.
    let mut view = view;
    view.tree = Default::default();
    emit(&a, &scene, &view, &vis)?;
    times.push(("emit", t.elapsed()));
    if a.stats {
        eprintln!("faces: {}", scene.face_count());
        lod.iter().for_each(|l| eprintln!("{l}"));
        for (name, d) in &times {
            eprintln!("time {name:<11} {:>10.3} ms", d.as_secs_f64() * 1e3);
        }
        for (name, v) in vis.counters.lines() {
            eprintln!("{name:<45} {v}");
        }
    }
    Ok(ExitCode::SUCCESS)
}
