//! Rendering from another program (the Python package): render flags parsed exactly as
//! `kepler render` parses them, over a scene loaded and prepared once.
//!
//! The caller gives flags by the command's names (`--dir=-1,-2,-3`, `--hidden`,
//! `--page=a4`), so an option means the same in both places by construction, and the
//! outputs are the command's bytes for the same flags.

use std::path::{Path, PathBuf};

use anyhow::{bail, Result};
use clap::Parser;
use kepler_hsr::{Camera, LoadOptions, Progress, RenderOptions, Scene, Warning};

use super::render::RenderArgs;
use super::views::numbered;
use super::{Cli, Command};

/// A scene loaded and prepared for rendering, with the file it came from.
#[derive(Debug)]
pub struct Loaded {
    /// The scene, prepared as `kepler render` prepares it for the same `--hierarchy`.
    pub scene: Scene,
    /// The file it was read from (what the flags' errors and the camera name).
    pub path: PathBuf,
    /// The `--hierarchy` value it was prepared for (`None`: the default choice).
    pub hierarchy: Option<String>,
    /// What the reader had to say about the file.
    pub warnings: Vec<Warning>,
}

/// Which outputs one render makes.
#[derive(Clone, Copy, Debug, Default)]
pub struct Want {
    /// The `kepler-visible/1` JSON (`--json`).
    pub json: bool,
    /// The SVG drawing (`--svg`).
    pub svg: bool,
    /// The PNG picture (`--png`).
    pub png: bool,
}

/// What one render made: the outputs asked for, byte for byte what the command writes.
#[derive(Debug, Default)]
pub struct Made {
    /// The JSON, when asked for.
    pub json: Option<String>,
    /// The SVG, when asked for.
    pub svg: Option<String>,
    /// The PNG, when asked for.
    pub png: Option<Vec<u8>>,
    /// What the render had to say (an empty view, say).
    pub warnings: Vec<String>,
}

/// Loads `path` and prepares it as `kepler render PATH FLAGS` would, for the flags that
/// bear on loading and preparing (`--max-faces`, `--include-root`, `--hierarchy`, each
/// written `--name=value`).
pub fn load(path: &Path, flags: &[String]) -> Result<Loaded> {
    if let Some(f) = flags.iter().find(|f| !is_load_flag(f)) {
        bail!("`{f}` is not an option of loading: give it to render()");
    }
    let hierarchy = flags
        .iter()
        .find_map(|f| f.strip_prefix("--hierarchy="))
        .map(str::to_owned);
    let (a, load_opts) = parse(path, flags)?;
    let progress = Progress::default();
    let mut warnings = Vec::new();
    let mut scene = kepler_hsr::load_scene(path, &load_opts, &mut warnings, &progress)?;
    kepler_hsr::prepare(&mut scene, &a.hierarchy.prepare(), &progress);
    Ok(Loaded {
        scene,
        path: path.to_path_buf(),
        hierarchy,
        warnings,
    })
}

/// Whether `flag` (as `--name=value`) bears on loading or preparing.
fn is_load_flag(flag: &str) -> bool {
    ["--max-faces=", "--include-root=", "--hierarchy="]
        .iter()
        .any(|p| flag.starts_with(p))
}

/// Renders `loaded` for the render flags `flags`, making the outputs `want` asks for.
pub fn render(loaded: &Loaded, flags: &[String], want: Want) -> Result<Made> {
    let a = parse_for(loaded, flags)?;
    refuse_command_only(&a, true)?;
    let opts = options(&a, want)?;
    a.camera.check()?;
    let camera = a.camera.camera(&loaded.scene)?;
    made(&loaded.scene, &camera, &opts)
}

/// Checks `flags` as `kepler render PATH FLAGS` would before loading anything.
pub fn check_flags(path: &Path, flags: &[String], one_view: bool) -> Result<()> {
    let (a, _) = parse(path, flags)?;
    refuse_command_only(&a, one_view)?;
    a.options()?;
    a.camera.check()
}

/// How many views `--turntable N` or `--views FILE` in `flags` makes (1 without either).
pub fn frame_count(loaded: &Loaded, flags: &[String]) -> Result<usize> {
    let a = parse_for(loaded, flags)?;
    refuse_command_only(&a, false)?;
    Ok(a.cameras(&loaded.scene, false)?.0.len())
}

/// Renders the views numbered `frames` (0-based) of those `--turntable N` or `--views FILE`
/// in `flags` make, each as the command renders it in the whole run (framed alike).
pub fn render_frames(
    loaded: &Loaded,
    flags: &[String],
    want: Want,
    frames: &[usize],
) -> Result<Vec<Made>> {
    let a = parse_for(loaded, flags)?;
    refuse_command_only(&a, false)?;
    let mut opts = options(&a, want)?;
    let (cameras, framed) = a.cameras(&loaded.scene, false)?;
    frames
        .iter()
        .map(|&k| match cameras.get(k) {
            Some(camera) => {
                opts.outputs.picture.frame = framed[k];
                made(&loaded.scene, camera, &opts)
            }
            None => bail!("view {} of {}: no such view", k + 1, cameras.len()),
        })
        .collect()
}

/// The file the command writes view `k` (0-based) of `total` to, for an output named `path`.
pub fn frame_path(path: &Path, k: usize, total: usize) -> PathBuf {
    numbered(path, k + 1, total)
}

/// The flags parsed, with the hierarchy the scene was prepared for.
fn parse_for(loaded: &Loaded, flags: &[String]) -> Result<RenderArgs> {
    if flags.iter().any(|f| f.starts_with("--hierarchy")) {
        bail!("`hierarchy` is chosen when the scene is loaded: give it to load()");
    }
    let mut flags = flags.to_vec();
    flags.extend(loaded.hierarchy.iter().map(|h| format!("--hierarchy={h}")));
    Ok(parse(&loaded.path, &flags)?.0)
}

/// The render options of `a`, making the outputs `want` asks for.
fn options(a: &RenderArgs, want: Want) -> Result<RenderOptions> {
    let mut opts = a.options()?;
    opts.outputs.json = want.json;
    opts.outputs.svg = want.svg;
    opts.outputs.png = want.png;
    Ok(opts)
}

/// One render's outputs, made on one of rayon's threads as the command makes them
/// ([`crate::pool`]).
fn made(scene: &Scene, camera: &Camera, opts: &RenderOptions) -> Result<Made> {
    crate::pool::on_pool(|| {
        let r = kepler_hsr::render(scene, camera, opts, &Progress::default())?;
        Ok(Made {
            json: r.json,
            svg: r.svg,
            png: r.png,
            warnings: r.warnings.iter().map(ToString::to_string).collect(),
        })
    })
}

/// `kepler render PATH FLAGS...` parsed by the command's own definitions.
fn parse(path: &Path, flags: &[String]) -> Result<(RenderArgs, LoadOptions)> {
    let mut argv = vec![
        "kepler".into(),
        "render".into(),
        path.as_os_str().to_owned(),
    ];
    argv.extend(flags.iter().map(Into::into));
    let cli = match Cli::try_parse_from(argv) {
        Ok(cli) => cli,
        Err(e) => bail!("{}", first_line(&e.render().to_string())),
    };
    let load = cli.load_options();
    match cli.command {
        Command::Render(a) => Ok((a, load)),
        _ => unreachable!("the argv names the render command"),
    }
}

/// The command's flags that name files or print, which an embedding program does itself.
/// With `one_view`, `--views` and `--turntable` are refused too.
fn refuse_command_only(a: &RenderArgs, one_view: bool) -> Result<()> {
    for (given, name) in [
        (a.json.is_some(), "json"),
        (a.svg.is_some(), "svg"),
        (a.png.is_some(), "png"),
        (one_view && a.views.is_some(), "views"),
        (one_view && a.turntable.is_some(), "turntable"),
        (a.stats, "stats"),
        (a.styles.is_some(), "styles"),
        (a.shard.is_some(), "shard"),
        (a.sheet.is_some(), "sheet"),
    ] {
        if given {
            bail!("`{name}` is a flag of the command only: ask the result for its outputs");
        }
    }
    Ok(())
}

/// The first line of a clap message, without its `error: ` prefix.
fn first_line(message: &str) -> String {
    let line = message.lines().next().unwrap_or_default();
    line.strip_prefix("error: ").unwrap_or(line).to_owned()
}
