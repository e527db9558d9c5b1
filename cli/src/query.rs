//! `kepler query`: INCLUDE (point in scene), VISP (point visibility), VISOBJ (what A does to B).

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{bail, Result};
use clap::Args;
use kepler_hsr::query::{
    include, visobj, visp, Inclusion, InterfereMethod as Method, PointVisibility, Verdict,
};
use kepler_hsr::{HierarchyKind, View, P3};

use super::camera_args::parse_vec3;
use super::{load_with, out, CameraArgs};

/// Arguments of `kepler query`.
#[derive(Args, Debug)]
pub(crate) struct QueryArgs {
    /// Scene file (.kdl), mesh (.obj, .stl, .ply) or modeller's scene (.gltf, .glb, .3mf).
    pub(crate) scene: PathBuf,
    /// INCLUDE: is the point X,Y,Z inside the scene's solids? Prints IN or OUT.
    #[arg(long, value_name = "X,Y,Z", allow_hyphen_values = true)]
    pub(crate) include: Option<String>,
    /// VISP: is the point X,Y,Z visible from the camera? Prints VISIBLE or HIDDEN.
    #[arg(long, value_name = "X,Y,Z", allow_hyphen_values = true)]
    pub(crate) visp: Option<String>,
    /// VISOBJ: what object A does to object B (paths as in `kepler info`). Prints VISIBLE, HIDDEN or MIXED.
    #[arg(long, num_args = 2, value_names = ["A", "B"])]
    pub(crate) visobj: Option<Vec<String>>,
    /// The pairs of objects whose triboxes meet, each INTERSECT (faces really meet, touching
    /// included) or APART, then a summary.
    #[arg(long)]
    pub(crate) interfere: bool,
    /// With --interfere: compare faces without trees (every pair of leaf triangles near the
    /// other object), for checking.
    #[arg(long, requires = "interfere")]
    pub(crate) brute: bool,
    /// With --interfere: print the work done (BV nodes traversed, triangle tests).
    #[arg(long)]
    pub(crate) stats: bool,
    #[command(flatten)]
    pub(crate) hierarchy: super::hierarchy_arg::HierarchyArgs,
    #[command(flatten)]
    pub(crate) camera: CameraArgs,
    /// Do not print warnings.
    #[arg(long, short)]
    pub(crate) quiet: bool,
}

/// Runs `kepler query`.
pub(crate) fn run(a: QueryArgs, opts: &kepler_hsr::LoadOptions) -> Result<ExitCode> {
    let scene = load_with(&a.scene, a.quiet, opts, &a.hierarchy.prepare())?;
    let asked = a.include.is_some() as u8
        + a.visp.is_some() as u8
        + a.visobj.is_some() as u8
        + a.interfere as u8;
    if asked != 1 {
        bail!("give exactly one of --include, --visp, --visobj, --interfere");
    }
    if a.interfere {
        let method = if a.brute {
            Method::Brute
        } else {
            Method::Tree(a.hierarchy.kind().unwrap_or(HierarchyKind::Simplify))
        };
        out(&super::tribox::interfere_report(&scene, method, a.stats));
        return Ok(ExitCode::SUCCESS);
    }
    if let Some(p) = &a.include {
        let p = P3::from(parse_vec3(p, "include")?);
        let r = include(&scene, &p);
        out(if r == Inclusion::In { "IN" } else { "OUT" });
        return Ok(ExitCode::SUCCESS);
    }
    let view = View::new(&scene, a.camera.camera(&scene)?);
    if let Some(p) = &a.visp {
        let p = P3::from(parse_vec3(p, "visp")?);
        let r = visp(&view, &p);
        out(if r == PointVisibility::Visible {
            "VISIBLE"
        } else {
            "HIDDEN"
        });
    }
    if let Some(ab) = &a.visobj {
        let r = visobj(&view, &ab[0], &ab[1])?;
        out(match r {
            Verdict::Visible => "VISIBLE",
            Verdict::Hidden => "HIDDEN",
            Verdict::Mixed => "MIXED",
        });
    }
    Ok(ExitCode::SUCCESS)
}
