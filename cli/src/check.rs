//! `kepler check`: re-render a scene and compare its visible-polygon set with a golden file,
//! and/or (`--exact`) with the independent exact answer (`kepler_hsr::check::exact`: rationals, no
//! boolean engine, no tolerance in any decision; slow, for small scenes): each face's
//! symmetric difference must stay within `--allowance` units of output rounding (one unit:
//! 2^-52 × the largest |screen coordinate| × the face's projected perimeter).
//!
//! The camera is chosen exactly as `kepler render` chooses it (flags, then the scene's camera,
//! then the three-quarter view); a golden made with other camera flags differs everywhere, and
//! a note says so when the matrices differ. Each face's change is the area of the symmetric
//! difference of the two visible regions (i_overlay Xor on a fixed i64 grid), relative to the
//! larger of the face's projected area, its two visible areas and 1e-12 of the larger set's
//! visible area; one rule for faces that change, appear or vanish (`kepler_hsr::check::compare`).
//! The report and the exit statuses are `kepler diff`'s (`--report json`; 0 same, 1 changed,
//! 2 usage or unreadable input).

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{anyhow, Result};
use clap::Args;
use kepler_hsr::check::{compare, VisibleSet};
use kepler_hsr::{render, Camera, FaceId, Outputs, RenderOptions, Scene, View, Visibility};

use super::diff::{check_tol, exit_2_on_error, print_report, Report, EXIT_STATUS};
use super::{load, out, write, CameraArgs};

/// Arguments of `kepler check`.
#[derive(Args, Debug)]
#[command(after_help = EXIT_STATUS)]
pub(crate) struct CheckArgs {
    /// Scene file (.kdl), mesh (.obj, .stl, .ply) or modeller's scene (.gltf, .glb, .3mf).
    pub(crate) scene: PathBuf,
    /// The golden kepler-visible/1 file.
    #[arg(long, value_name = "F.json", required_unless_present = "exact")]
    pub(crate) golden: Option<PathBuf>,
    /// Check every face against the independent exact answer (slow: small scenes).
    #[arg(long)]
    pub(crate) exact: bool,
    /// Largest allowed change of a face's visible region: the area of the symmetric
    /// difference relative to the face's projected area (or larger visible area). The same
    /// for changed, newly visible and no longer visible faces.
    #[arg(
        long,
        value_name = "T",
        default_value_t = 1e-9,
        allow_negative_numbers = true
    )]
    pub(crate) tol: f64,
    /// With --exact: the largest allowed symmetric difference of a face with the exact answer,
    /// in units of output rounding (2^-52 × the largest |screen coordinate| × the face's
    /// projected perimeter).
    #[arg(long, value_name = "UNITS", default_value_t = kepler_hsr::check::ALLOWANCE_UNITS)]
    pub(crate) allowance: f64,
    /// Write the golden from this render instead of comparing.
    #[arg(long)]
    pub(crate) update: bool,
    /// How to print the comparison: lines of text, or kepler-diff/1 JSON on standard output
    /// (then the exact checker's lines go to standard error).
    #[arg(long, value_name = "FORMAT", default_value = "text")]
    pub(crate) report: Report,
    #[command(flatten)]
    pub(crate) camera: CameraArgs,
    /// Cut the scene as `kepler render --section` does (repeatable); the exact checker
    /// checks the cut scene.
    #[arg(long, value_name = "PX,PY,PZ,NX,NY,NZ", allow_hyphen_values = true)]
    pub(crate) section: Vec<String>,
    /// Do not print warnings.
    #[arg(long, short)]
    pub(crate) quiet: bool,
}

/// Runs `kepler check`: errors are reported here and exit 2.
pub(crate) fn run(a: CheckArgs, opts: &kepler_hsr::LoadOptions) -> Result<ExitCode> {
    Ok(exit_2_on_error(check(a, opts)))
}

/// Renders and compares; the exit status.
fn check(a: CheckArgs, opts: &kepler_hsr::LoadOptions) -> Result<ExitCode> {
    check_tol(a.tol)?;
    let scene = load(&a.scene, a.quiet, opts)?;
    let camera = a.camera.camera(&scene)?;
    let opts = RenderOptions {
        outputs: Outputs {
            json: true,
            ..Outputs::default()
        },
        sections: a
            .section
            .iter()
            .map(|s| super::render::parse_section(s))
            .collect::<Result<_>>()?,
        ..RenderOptions::default()
    };
    let r = render(&scene, &camera, &opts, &kepler_hsr::Progress::default())?;
    let mut failed = false;
    if a.exact {
        let say = if a.report == Report::Json { err } else { out };
        let units = a.allowance;
        if !(units >= 0.0 && units.is_finite()) {
            return Err(anyhow!(
                "--allowance {units}: not a finite number of units >= 0"
            ));
        }
        failed |= !exact(&r.scene, &camera, &r.visibility, &r.view, units, say);
    }
    let Some(golden_path) = &a.golden else {
        return Ok(if failed {
            ExitCode::from(1)
        } else {
            ExitCode::SUCCESS
        });
    };
    let vis = &r.visibility;
    let json = r.json.clone().unwrap_or_default();
    if a.update {
        write(golden_path, &json)?;
        out(&format!("wrote {}", golden_path.display()));
        return Ok(ExitCode::SUCCESS);
    }
    let golden = VisibleSet::read(golden_path)?;
    let current =
        VisibleSet::parse(&json, "render".as_ref()).map_err(|e| anyhow!("internal JSON: {e}"))?;
    let report = compare(&golden, &current, a.tol, |id| {
        vis.face(FaceId(id as u32)).projected_area
    });
    let code = print_report(&report, a.report);
    Ok(if failed { ExitCode::from(1) } else { code })
}

/// Prints to standard error.
fn err(text: &str) {
    eprintln!("{text}");
}

/// The render against the exact answer, each face allowed `units` units of output rounding:
/// prints each disagreeing face and a summary; true when every face agrees.
fn exact(
    scene: &Scene,
    camera: &Camera,
    vis: &Visibility,
    view: &View,
    units: f64,
    out: fn(&str),
) -> bool {
    let rep = kepler_hsr::check::exact(scene, camera, vis, None);
    let bad = rep.disagreements_within(units);
    for f in &bad {
        let object = view.object_path(f.face);
        out(&format!(
            "face {} ({object}): differs from the exact answer by {:.3e}, {:.3} units of output rounding (allowed {units}); visible {} exact {}",
            f.face, f.mismatch, f.units, f.claimed, f.visible
        ));
    }
    out(&format!(
        "exact: {} of {} faces agree within {units} units of output rounding (worst {:.3}); visible area {} (exact {}, {:.1e} of the projected area)",
        rep.faces.len() - bad.len(),
        rep.faces.len(),
        rep.worst_units(),
        rep.claimed(),
        rep.visible,
        (rep.claimed() - rep.visible).abs() / rep.projected.max(f64::MIN_POSITIVE)
    ));
    bad.is_empty()
}
