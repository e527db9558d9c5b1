//! `kepler tribox`: hierarchical tribox substitutes of a mesh at each level (OBJ and SVG) and
//! the paper's Table 1; also the `--lod` flags of `kepler render` and `query --interfere`.

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use anyhow::{bail, Result};
use clap::Args;
use kepler_hsr::lines::{EdgeOptions, EdgeSet, LineOptions};
use kepler_hsr::plot::PictureOptions;
use kepler_hsr::query::InterfereMethod;
use kepler_hsr::stats::LodStats;
use kepler_hsr::tribox::{table, HierarchyOptions, TableOptions, TableRow};
use kepler_hsr::{render, LodOptions, Object, Outputs, RenderOptions, Scene};

use super::{load_only, out, write, CameraArgs};

/// `--lod` flags of `kepler render`.
#[derive(Args, Debug, Clone, Default)]
pub(crate) struct LodArgs {
    /// Draw every object whose projected size is under PX pixels as its tribox (a
    /// level-of-detail substitute that takes part in visibility like any object).
    #[arg(long, value_name = "PX", allow_negative_numbers = true)]
    pub(crate) lod: Option<f64>,
    /// With --lod: draw small meshes as hierarchical triboxes at the shallowest cut whose
    /// error is at most PX pixels, instead of one tribox.
    #[arg(
        long,
        value_name = "PX",
        requires = "lod",
        allow_negative_numbers = true
    )]
    pub(crate) lod_error: Option<f64>,
}

/// One line on what `--lod` did, for `--stats`.
pub(crate) fn lod_report(s: &LodStats) -> String {
    format!(
        "lod: {} objects replaced by {} triboxes; faces modelled {} of {} in the scene ({:.1}%)",
        s.objects_replaced,
        s.triboxes,
        s.faces_modelled,
        s.faces_in_scene,
        100.0 * s.faces_modelled as f64 / (s.faces_in_scene.max(1)) as f64,
    )
}

impl LodArgs {
    /// The substitution the flags ask for, for a picture `size` pixels wide (None without
    /// `--lod`).
    pub(crate) fn options(&self, size: u32) -> Result<Option<LodOptions>> {
        let Some(px) = self.lod else { return Ok(None) };
        if !(px.is_finite() && px >= 0.0) {
            bail!("--lod {px}: expected a number of pixels, 0 or more");
        }
        let mut opts = LodOptions::new(px, size);
        if let Some(e) = self.lod_error {
            if !(e.is_finite() && e > 0.0) {
                bail!("--lod-error {e}: expected a positive number of pixels");
            }
            opts.error_px = Some(e);
        }
        Ok(Some(opts))
    }
}

/// Arguments of `kepler tribox`.
#[derive(Args, Debug)]
pub(crate) struct TriboxArgs {
    /// Mesh (.obj, .stl, .ply), scene file (.kdl) or glTF/3MF scene: each object gets its own hierarchy.
    pub(crate) scene: PathBuf,
    /// Number of levels of detail (level 0 is one tribox per object).
    #[arg(long, default_value_t = 4, value_parser = clap::value_parser!(u32).range(1..=16))]
    pub(crate) levels: u32,
    /// Write the substitute of each level here, as NAME-L<k>.obj and NAME-L<k>.svg.
    #[arg(short, long, visible_alias = "output", value_name = "DIR")]
    pub(crate) out: Option<PathBuf>,
    /// Simplification tolerance of each tribox, as a fraction of the object's CBOX diagonal.
    #[arg(long, default_value_t = 0.01, allow_negative_numbers = true)]
    pub(crate) tol: f64,
    /// Least relative area reduction of a split (the stop rule).
    #[arg(long, default_value_t = 0.02, allow_negative_numbers = true)]
    pub(crate) min_gain: f64,
    /// Skip the convex-hull volumes.
    #[arg(long)]
    pub(crate) no_hull: bool,
    /// Pixels along the longer side of the SVGs.
    #[arg(long, default_value_t = 600)]
    pub(crate) size: u32,
    #[command(flatten)]
    pub(crate) camera: CameraArgs,
    /// Do not print warnings.
    #[arg(long, short)]
    pub(crate) quiet: bool,
}

/// Runs `kepler tribox`.
pub(crate) fn run(a: TriboxArgs, opts: &kepler_hsr::LoadOptions) -> Result<ExitCode> {
    if !(a.tol.is_finite() && a.tol >= 0.0 && a.min_gain.is_finite() && a.min_gain < 1.0) {
        bail!("--tol must be 0 or more and --min-gain below 1");
    }
    let scene = load_only(&a.scene, a.quiet, opts)?;
    let t = table(
        &scene,
        &TableOptions {
            hierarchy: HierarchyOptions {
                max_depth: a.levels as usize - 1,
                min_gain: a.min_gain,
            },
            levels: a.levels as usize,
            tol: a.tol,
            hull: !a.no_hull,
        },
    );
    let name = a
        .scene
        .file_stem()
        .map_or("scene".into(), |s| s.to_string_lossy().into_owned());
    let (n, cbox, hull, diag) = (t.faces, t.cbox_volume, t.hull_volume, t.diagonal);
    let mut rows = vec![
        format!("{name}: {} objects, N = {n} faces, CBOX volume {}, convex hull volume {}, hierarchies built in {:.1} ms", t.objects, g(cbox), g(hull), t.build_time.as_secs_f64() * 1e3),
        String::new(),
        "| level | N | M | triboxes | N/M | error | error/diag | volume | /CBOX | /hull |".into(),
        "|---|---|---|---|---|---|---|---|---|---|".into(),
    ];
    if let Some(dir) = &a.out {
        std::fs::create_dir_all(dir).map_err(|e| anyhow::anyhow!("{}: {e}", dir.display()))?;
    }
    for (level, r) in t.rows.iter().enumerate() {
        rows.push(format!(
            "| {level} | {n} | {} | {} | {:.2} | {} | {} | {} | {} | {} |",
            r.faces,
            r.triboxes,
            n as f64 / r.faces.max(1) as f64,
            g(r.error),
            ratio(r.error, diag, 4),
            g(r.volume),
            ratio(r.volume, cbox, 3),
            ratio(r.volume, hull, 3)
        ));
        if let Some(dir) = &a.out {
            let stem = dir.join(format!("{name}-L{level}"));
            write(&stem.with_extension("obj"), r.to_obj())?;
            write(&stem.with_extension("svg"), render_svg(r, &scene, &a)?)?;
        }
    }
    let (adds_min, adds_max) = t.additions;
    rows.push(String::new());
    rows.push(format!(
        "boundary evaluation: {adds_min}..{adds_max} additions per tribox (paper: at most 112), 24 shifts, at most 24 tests"
    ));
    out(&rows.join("\n"));
    Ok(ExitCode::SUCCESS)
}

/// a / b with `digits` decimals, "-" when b is 0 or unknown.
fn ratio(a: f64, b: f64, digits: usize) -> String {
    if b > 0.0 {
        format!("{:.*}", digits, a / b)
    } else {
        "-".into()
    }
}

/// A number with six decimals, "-" when unknown.
fn g(x: f64) -> String {
    if x.is_nan() {
        "-".into()
    } else {
        format!("{x:.6}")
    }
}

/// The substitutes drawn by kepler itself: exact hidden lines, every edge.
fn render_svg(level: &TableRow, original: &Scene, a: &TriboxArgs) -> Result<String> {
    let mut scene = original.with_root(Object::group("", level.objects()));
    let camera = a.camera.camera(&scene)?;
    kepler_hsr::prepare(
        &mut scene,
        &kepler_hsr::PrepareOptions::default(),
        &kepler_hsr::Progress::default(),
    );
    let opts = RenderOptions {
        lines: LineOptions {
            edges: EdgeOptions {
                set: EdgeSet::All,
                crease_deg: 30.0,
            },
            hidden: false,
        },
        outputs: Outputs {
            svg: true,
            picture: PictureOptions {
                size: a.size,
                fill: true,
                ..PictureOptions::default()
            },
            ..Outputs::default()
        },
        ..RenderOptions::default()
    };
    Ok(
        render(&scene, &camera, &opts, &kepler_hsr::Progress::default())?
            .svg
            .unwrap_or_default(),
    )
}

/// `kepler query --interfere`: the pairs of objects whose triboxes meet, each with whether
/// their faces really intersect, then a summary line (with `stats`, the work done too).
pub(crate) fn interfere_report(scene: &Scene, method: InterfereMethod, stats: bool) -> String {
    let t = Instant::now();
    let r = kepler_hsr::query::interfere(scene, method);
    let time = t.elapsed();
    let mut lines: Vec<String> = r
        .tribox_meet
        .iter()
        .map(|&(i, j, hit)| {
            format!(
                "{}\t{}\t{}",
                r.objects[i],
                r.objects[j],
                if hit { "INTERSECT" } else { "APART" }
            )
        })
        .collect();
    let hits = r.tribox_meet.iter().filter(|p| p.2).count();
    lines.push(format!(
        "objects {}, pairs {}, CBOXes meet {}, triboxes meet {}, faces intersect {}",
        r.objects.len(),
        r.pairs,
        r.cbox_meet,
        r.tribox_meet.len(),
        hits,
    ));
    if stats {
        lines.push(format!(
            "method {:?}: {} BV nodes traversed, {} exact triangle tests, {:.3} ms",
            method,
            r.bv_tests,
            r.triangle_tests,
            time.as_secs_f64() * 1e3
        ));
    }
    lines.join("\n")
}
