//! `kepler render`: the exact visible region of every face, written as JSON (and pictures).

use std::borrow::Cow;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::{Duration, Instant};

use anyhow::{bail, Result};
use clap::{Args, ValueEnum};
use kepler_hsr::lines::{EdgeOptions, EdgeSet, LineOptions};
use kepler_hsr::plot::Rect;
use kepler_hsr::stats::{Spent, Stage, Stopwatch};
use kepler_hsr::{
    render, render_to, Camera, Outputs, Progress, Projection, RenderOptions, Rendered, Scene,
};

use super::bar::follow;
use super::output::OutputFiles;
use super::plot_args::PlotArgs;
use super::sheet::Sheet;
use super::views::{numbered, read_views};
use super::{print_warnings, CameraArgs};

/// A render that has taken this long shows a progress bar (on a terminal).
const PROGRESS_AFTER: Duration = Duration::from_millis(500);

/// Arguments of `kepler render`.
#[derive(Args, Debug)]
pub(crate) struct RenderArgs {
    /// Scene file (.kdl), mesh (.obj, .stl, .ply) or modeller's scene (.gltf, .glb, .3mf).
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
    /// Pixels along the PNG's longer side; without --page, also the SVG page's longer side
    /// in CSS pixels (1/96 in). Pen widths are in mm and do not change with it.
    #[arg(long, value_name = "PX", default_value_t = 1024,
          value_parser = clap::value_parser!(u32).range(1..=32768))]
    pub(crate) size: u32,
    /// Which edges to draw: feature (silhouettes, borders, creases, intersections) or all.
    /// Given, the JSON carries the lines too. [default: feature]
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
    /// Draw hidden lines too (grey dashes, each dash a stroke, on their own layer).
    #[arg(long)]
    pub(crate) hidden: bool,
    /// Fill visible faces, flat shaded, under the lines (for the screen: use --hatch to plot).
    #[arg(long)]
    pub(crate) fill: bool,
    #[command(flatten)]
    pub(crate) plot: Box<PlotArgs>,
    #[command(flatten)]
    pub(crate) camera: CameraArgs,
    /// Render every view of this file (one line of camera flags per view) into numbered
    /// outputs (F.svg becomes F-001.svg, ...), preparing the scene once.
    #[arg(long, value_name = "FILE", conflicts_with = "turntable")]
    pub(crate) views: Option<PathBuf>,
    /// Render N views a full turn about the vertical axis (the up in force: --up, the scene
    /// camera's, or auto) through the scene's centre, from the camera the other flags ask
    /// for, into numbered outputs, all framed alike.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=10000))]
    pub(crate) turntable: Option<u32>,
    /// Render only shard I of K of --turntable or --views (I from 1 to K): the views I,
    /// I+K, I+2K, ... (strided, so that every shard gets views from all round the scene and
    /// the shards take about as long), under the same numbered names as the whole run; the
    /// K shards together write exactly the whole run's files.
    #[arg(long, value_name = "I/K", conflicts_with = "sheet")]
    pub(crate) shard: Option<String>,
    /// Lay the views of --turntable or --views on one page, COLS across and ROWS down, in
    /// reading order, each cell framed alike (a turntable's shared frame; a views file's
    /// orthographic views one frame size round the projected CBOX, so all at one scale)
    /// inside its own --margin: one SVG and one PNG (the page, or without --page square
    /// cells whose sheet is --size pixels along its longer side); the JSON stays one
    /// numbered file per view.
    #[arg(long, value_name = "COLSxROWS")]
    pub(crate) sheet: Option<String>,
    /// Print the time of each stage and the pruning counters.
    #[arg(long)]
    pub(crate) stats: bool,
    /// Render without inboxes (for comparison).
    #[arg(long)]
    pub(crate) no_inbox: bool,
    /// Cut the scene with the plane through PX,PY,PZ with normal NX,NY,NZ, removing the
    /// side the normal points to; each closed solid cut gets its section faces (JSON
    /// `"section": true`, drawn hatched on layer 7). Repeatable: every plane removes its side.
    #[arg(long, value_name = "PX,PY,PZ,NX,NY,NZ", allow_hyphen_values = true)]
    pub(crate) section: Vec<String>,
    /// Style objects by path: a KDL file of `style "PATH-OR-PATTERN" pen=N weight=MM
    /// occlude-only=#true` nodes (`*` matches any run of characters), applied after the
    /// scene file's own `style` nodes; for OBJ groups, STL/PLY files and other scenes
    /// without styles of their own.
    #[arg(long, value_name = "FILE")]
    pub(crate) styles: Option<PathBuf>,
    #[command(flatten)]
    pub(crate) lod: super::tribox::LodArgs,
    #[command(flatten)]
    pub(crate) hierarchy: super::hierarchy_arg::HierarchyArgs,
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
    pub(crate) fn options(&self) -> Result<RenderOptions> {
        Ok(RenderOptions {
            lines: self.line_options()?,
            outputs: Outputs {
                json: self.json.is_some(),
                json_lines: self.edges.is_some() || self.hidden,
                svg: self.svg.is_some(),
                png: self.png.is_some(),
                drawing: false,
                picture: self.plot.options(self.size, self.fill)?,
            },
            no_inbox: self.no_inbox,
            lod: self.lod.options(self.size)?,
            hierarchy: self.hierarchy.kind(),
            sections: self
                .section
                .iter()
                .map(|s| parse_section(s))
                .collect::<Result<_>>()?,
        })
    }
}

/// Parses a `--section` value: six numbers, a point and a normal (not zero).
pub(crate) fn parse_section(s: &str) -> Result<(kepler_hsr::P3, kepler_hsr::V3)> {
    let parts: Vec<&str> = s.split(',').map(str::trim).collect();
    if parts.len() != 6 {
        bail!("--section {s}: expected six numbers PX,PY,PZ,NX,NY,NZ (a point and a normal)");
    }
    let mut v = [0.0; 6];
    for (k, p) in parts.iter().enumerate() {
        v[k] = p
            .parse::<f64>()
            .map_err(|_| anyhow::anyhow!("--section {s}: '{p}' is not a number"))?;
        if !v[k].is_finite() {
            bail!("--section {s}: '{p}' is not finite");
        }
        if v[k].abs() > 1e12 {
            bail!("--section {s}: '{p}' is beyond 1e12, the limit scene coordinates have");
        }
    }
    if v[3..].iter().all(|&x| x == 0.0) {
        bail!(
            "--section {s}: the normal {},{},{} is zero",
            v[3],
            v[4],
            v[5]
        );
    }
    Ok((
        kepler_hsr::P3::new(v[0], v[1], v[2]),
        kepler_hsr::V3::new(v[3], v[4], v[5]),
    ))
}

/// Runs `kepler render`.
pub(crate) fn run(a: RenderArgs, load_opts: &kepler_hsr::LoadOptions) -> Result<ExitCode> {
    if a.json.is_none() && a.svg.is_none() && a.png.is_none() {
        anyhow::bail!("nothing to write: give --json F, --svg F or --png F");
    }
    let opts = a.options()?;
    a.camera.check()?;
    let shard = a.shard()?;
    let sheet = a.sheet(&opts)?;
    // Every output path is checked (distinct, not an input, writable) before the work.
    let wanted: Vec<&std::path::Path> = [&a.json, &a.svg, &a.png]
        .into_iter()
        .flatten()
        .map(PathBuf::as_path)
        .collect();
    let mut inputs = vec![a.scene.as_path()];
    inputs.extend(a.styles.as_deref());
    inputs.extend(a.views.as_deref());
    let mut outs = OutputFiles::new(&inputs, &wanted)?;
    let start = Instant::now();
    // The bar follows loading and preparing too: a big scene shows a sign of life from the
    // start. Load warnings wait until the bar is gone.
    let progress = Progress::new();
    let mut warnings = Vec::new();
    let (scene, load, prepare) = follow(&progress, start, PROGRESS_AFTER, || -> Result<_> {
        let t = Stopwatch::start();
        let mut scene = kepler_hsr::load_scene(&a.scene, load_opts, &mut warnings, &progress)?;
        if let Some(f) = &a.styles {
            scene.load_styles(f)?;
        }
        let load = t.stop();
        let t = Stopwatch::start();
        let prep = a.hierarchy.prepare();
        kepler_hsr::prepare(&mut scene, &prep, &progress);
        if scene.face_count() >= crate::memory::TRIM_ABOVE_FACES {
            crate::memory::trim();
        }
        Ok((scene, load, t.stop()))
    })?;
    if !a.quiet {
        print_warnings(&warnings);
    }
    let (cameras, frames) = a.cameras(&scene, sheet.is_some())?;
    let many = a.views.is_some() || a.turntable.is_some();
    if let Some(sh) = &sheet {
        sh.check_views(cameras.len())?;
    }
    if let Some((i, of)) = shard {
        if i > cameras.len() && !a.quiet {
            eprintln!(
                "shard {i}/{of} of {} views: nothing to render",
                cameras.len()
            );
        }
    }
    let (mut svg_cells, mut png_cells) = (Vec::new(), Vec::new());
    for (k, camera) in cameras.iter().enumerate() {
        if shard.is_some_and(|(i, of)| k % of != i - 1) {
            continue;
        }
        let mut opts = opts.clone();
        opts.outputs.picture.frame = frames[k];
        if let Some(sh) = &sheet {
            opts.outputs.picture.page = Some(sh.cell_page());
            opts.outputs.picture.size = sh.cell_size(a.size);
        }
        let progress = Progress::new();
        let name = |path: &PathBuf| match many {
            true => numbered(path, k + 1, cameras.len()),
            false => path.clone(),
        };
        // The JSON goes to its file as it is made (a big scene's is never held whole).
        let mut json = a.json.as_ref().map(|p| outs.create(&name(p))).transpose()?;
        let r = follow(&progress, start, PROGRESS_AFTER, || match json.as_mut() {
            Some(f) => render_to(&scene, camera, &opts, f, &progress),
            None => render(&scene, camera, &opts, &progress),
        })
        .map_err(|e| match (e, &json) {
            (kepler_hsr::Error::Write(e), Some(f)) => f.named(e),
            (e, _) => e.into(),
        })?;
        if !a.quiet {
            print_warnings(&r.warnings);
        }
        let t = Stopwatch::start();
        if let Some(f) = json {
            outs.finish(f)?;
        }
        if sheet.is_some() {
            svg_cells.extend(r.svg.clone());
            png_cells.extend(r.png.clone());
        } else {
            for (path, bytes) in [
                (&a.svg, r.svg.as_ref().map(String::as_bytes)),
                (&a.png, r.png.as_deref()),
            ] {
                if let (Some(path), Some(bytes)) = (path, bytes) {
                    outs.write(&name(path), bytes)?;
                }
            }
        }
        let written = t.stop();
        if a.stats {
            if many {
                eprintln!("view {} of {}", k + 1, cameras.len());
            }
            let (load, prepare) = if k == 0 {
                (load, prepare)
            } else {
                Default::default()
            };
            print_stats(&scene, a.hierarchy.name(), &r, load, prepare, written);
        }
        if k + 1 == cameras.len() {
            leave(owned_parts(r));
        } else {
            drop_aside(owned_parts(r));
        }
    }
    leave(scene);
    if let Some(sh) = &sheet {
        if let Some(path) = &a.svg {
            outs.write(path, sh.svg(&svg_cells).as_bytes())?;
        }
        if let Some(path) = &a.png {
            let pic = &opts.outputs.picture;
            outs.write(path, &sh.png(&png_cells, pic.dpi, a.size, pic.background)?)?;
        }
    }
    // All outputs of the run (every view's, the sheet's) are put in place together, once
    // all are written.
    outs.commit()?;
    Ok(ExitCode::SUCCESS)
}

/// Frees `value` on a thread of its own. Freeing a render's many buffers one by one is
/// single-threaded work (about 3% of a mesh's render) that nothing waits for: the next view
/// renders meanwhile, or the process exits and the system takes the memory back at once.
/// Where no thread can be started, it is freed here.
fn drop_aside<T: Send + 'static>(value: T) {
    let _ = std::thread::Builder::new()
        .name("free".into())
        .spawn(move || drop(value));
}

/// Leaves `value` unfreed: the command is about to end, and the system takes the process's
/// memory back at once when it does. Freeing a render's buffers one by one costs about 3% of
/// its CPU, on a thread of its own or not.
fn leave<T>(value: T) {
    std::mem::forget(value);
}

/// What a render owns (all but the borrowed scene), to be freed elsewhere.
fn owned_parts(r: Rendered<'_>) -> impl Send + 'static {
    let Rendered {
        scene,
        view,
        visibility,
        drawing,
        json,
        svg,
        png,
        ..
    } = r;
    let substitute = match scene {
        Cow::Owned(s) => Some(s),
        Cow::Borrowed(_) => None,
    };
    (substitute, view, visibility, drawing, json, svg, png)
}

impl RenderArgs {
    /// `--shard I/K`, checked: (I, K) with 1 <= I <= K.
    fn shard(&self) -> Result<Option<(usize, usize)>> {
        let Some(spec) = &self.shard else {
            return Ok(None);
        };
        if self.views.is_none() && self.turntable.is_none() {
            bail!("--shard {spec} splits the views of --turntable N or --views FILE: give one");
        }
        let bad = || anyhow::anyhow!("--shard {spec}: expected I/K with 1 <= I <= K, e.g. 2/3");
        let (i, k) = spec.split_once('/').ok_or_else(bad)?;
        let (i, k): (usize, usize) = (
            i.trim().parse().map_err(|_| bad())?,
            k.trim().parse().map_err(|_| bad())?,
        );
        if !(1 <= i && i <= k) {
            return Err(bad());
        }
        Ok(Some((i, k)))
    }

    /// `--sheet COLSxROWS`, checked, on the page the flags ask for.
    fn sheet(&self, opts: &RenderOptions) -> Result<Option<Sheet>> {
        let Some(spec) = &self.sheet else {
            return Ok(None);
        };
        if self.views.is_none() && self.turntable.is_none() {
            bail!("--sheet {spec} lays out the views of --turntable N or --views FILE: give one");
        }
        if self.svg.is_none() && self.png.is_none() {
            bail!("--sheet {spec} makes a picture: give --svg F or --png F");
        }
        Ok(Some(Sheet::new(
            spec,
            opts.outputs.picture.page,
            self.size,
        )?))
    }

    /// The cameras to render (one, a views file's, or a turntable's) and the frame of each:
    /// a turntable's views share one; on a sheet, orthographic views of a views file share
    /// one frame size round their projected CBOX (one scale for all).
    pub(crate) fn cameras(
        &self,
        scene: &Scene,
        sheet: bool,
    ) -> Result<(Vec<Camera>, Vec<Option<Rect>>)> {
        let (cams, frame) = self.cameras_and_frame(scene)?;
        let frames = match frame {
            Some(f) => vec![Some(f); cams.len()],
            None if sheet && self.views.is_some() => common_frames(scene, &cams),
            None => vec![None; cams.len()],
        };
        Ok((cams, frames))
    }

    /// The cameras to render and, for a turntable, the one frame they share.
    fn cameras_and_frame(&self, scene: &Scene) -> Result<(Vec<Camera>, Option<Rect>)> {
        if let Some(file) = &self.views {
            if self.camera.any() || self.camera.fov.is_some() {
                bail!("--views gives every view its camera: leave out the camera flags");
            }
            let cams = read_views(file)?
                .iter()
                .enumerate()
                .map(|(i, v)| {
                    v.camera(scene)
                        .map_err(|e| anyhow::anyhow!("{}: view {}: {e}", file.display(), i + 1))
                })
                .collect::<Result<Vec<_>>>()?;
            return Ok((cams, None));
        }
        let base = self.camera.camera(scene)?;
        let Some(n) = self.turntable else {
            return Ok((vec![base], None));
        };
        let up = self.camera.axis(scene)?;
        let cams = base.turntable(scene, up, n as usize)?;
        Ok((cams, base.turntable_frame(scene, up)))
    }
}

/// One frame size for the orthographic views of a sheet: each view's frame is centred on its
/// projected CBOX and as wide and as high as the widest and highest of them, so that every
/// cell shows the scene at one scale. Perspective views (and an empty scene) get None: they fit
/// their own drawing.
fn common_frames(scene: &Scene, cams: &[Camera]) -> Vec<Option<Rect>> {
    let b = scene.cbox();
    let boxes: Vec<Option<Rect>> = cams
        .iter()
        .map(|c| {
            if c.projection != Projection::Orthographic || b.lo.x.is_nan() || b.lo.x > b.hi.x {
                return None;
            }
            let mut r = Rect::EMPTY;
            for k in 0..8 {
                let p = kepler_hsr::P3::new(
                    if k & 1 == 0 { b.lo.x } else { b.hi.x },
                    if k & 2 == 0 { b.lo.y } else { b.hi.y },
                    if k & 4 == 0 { b.lo.z } else { b.hi.z },
                );
                let q = c.project(&p);
                r.add([q[0], q[1]]);
            }
            Some(r)
        })
        .collect();
    let (w, h) = boxes.iter().flatten().fold((0.0f64, 0.0f64), |(w, h), r| {
        (w.max(r.width()), h.max(r.height()))
    });
    boxes
        .into_iter()
        .map(|r| {
            let r = r?;
            let (cx, cy) = (0.5 * (r.xmin + r.xmax), 0.5 * (r.ymin + r.ymax));
            (w > 0.0 && h > 0.0)
                .then(|| Rect::new(cx - 0.5 * w, cy - 0.5 * h, cx + 0.5 * w, cy + 0.5 * h))
        })
        .collect()
}

/// The stage table of `--stats`: wall and CPU time per stage, the share of its wall time
/// that ran on one thread ([`kepler_hsr::stats::serial_share`]), and the run's.
fn print_times(times: &[(&str, Spent)]) {
    let threads = kepler_hsr::stats::worker_threads();
    let ms = |d: Duration| d.as_secs_f64() * 1e3;
    let (mut wall, mut serial) = (0.0, 0.0);
    for (name, t) in times {
        let Some(cpu) = t.cpu else {
            eprintln!("time {name:<11} {:>10.3} ms", ms(t.wall));
            continue;
        };
        let share = kepler_hsr::stats::serial_share(t.wall, cpu, threads);
        wall += ms(t.wall);
        serial += share * ms(t.wall);
        eprintln!(
            "time {name:<11} {:>10.3} ms  cpu {:>10.3} ms  serial {:>5.1}%",
            ms(t.wall),
            ms(cpu),
            100.0 * share
        );
    }
    if wall > 0.0 {
        eprintln!(
            "serial share of the stages' wall time: {:.1}% on {threads} threads (Amdahl: the part of each stage's time that ran on one thread)",
            100.0 * serial / wall
        );
    }
}

/// `--stats`: stage times (wall, CPU and the serial share), pruning counters and what the
/// plot did.
fn print_stats(
    scene: &Scene,
    hierarchy: &str,
    r: &Rendered,
    load: Spent,
    prepare: Spent,
    written: Spent,
) {
    eprintln!("faces: {}", scene.face_count());
    eprintln!("hierarchy: {hierarchy}");
    if let Some(l) = &r.stats.lod {
        eprintln!("{}", super::tribox::lod_report(l));
    }
    let mut times = vec![(Stage::Load.name(), load), (Stage::Prepare.name(), prepare)];
    times.extend(r.stats.times.iter().map(|&(s, wall)| {
        let cpu = r.stats.cpu.iter().find(|c| c.0 == s).map(|c| c.1);
        (s.name(), Spent { wall, cpu })
    }));
    times.push(("write", written));
    print_times(&times);
    for (name, v) in r.stats.counters.lines() {
        eprintln!("{name:<45} {v}");
    }
    if let Some(p) = &r.stats.plot {
        let (mut strokes, mut drawn, mut travel) = (0, 0.0, 0.0);
        for l in &p.layers {
            eprintln!(
                "layer {} {:<14} {:>7} strokes {:>7} pen lifts  drawn {:>11.1} mm  travel {:>10.1} mm",
                l.number,
                l.name,
                l.strokes,
                l.strokes.saturating_sub(1),
                l.drawn_mm,
                l.travel_mm
            );
            strokes += l.strokes;
            drawn += l.drawn_mm;
            travel += l.travel_mm;
        }
        eprintln!(
            "plot: {} layers, {strokes} strokes, {} pen lifts, drawn {drawn:.1} mm, pen-up travel {travel:.1} mm",
            p.layers.len(),
            strokes.saturating_sub(p.layers.len()),
        );
        eprintln!(
            "plot: of {} segments, {} repeated or overlapped dropped whole, {} in part ({:.3} mm); \
             line outside the drawing area clipped away {:.1} mm",
            p.duplicates.segments,
            p.duplicates.dropped,
            p.duplicates.trimmed,
            p.duplicates.length,
            p.clipped_mm
        );
    }
}
