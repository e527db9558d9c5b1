//! `kepler flatten`: the paper's FLATTEN, written as one OBJ.

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Result;
use clap::Args;

use super::load_only;
use super::output::write_from;

/// Arguments of `kepler flatten`.
#[derive(Args, Debug)]
pub(crate) struct FlattenArgs {
    /// Scene file (.kdl), mesh (.obj, .stl, .ply) or modeller's scene (.gltf, .glb, .3mf).
    pub(crate) scene: PathBuf,
    /// Output OBJ file.
    #[arg(
        short = 'o',
        long = "output",
        visible_alias = "out",
        value_name = "F.obj"
    )]
    pub(crate) output: PathBuf,
    /// Do not print warnings.
    #[arg(long, short)]
    pub(crate) quiet: bool,
}

/// Runs `kepler flatten`.
pub(crate) fn run(a: FlattenArgs, opts: &kepler_hsr::LoadOptions) -> Result<ExitCode> {
    // The output is checked first: an output that is the input is refused before the load.
    super::output::OutputFiles::new(&[&a.scene], &[&a.output])?;
    let scene = load_only(&a.scene, a.quiet, opts)?;
    let flat = scene.flatten();
    write_from(&[&a.scene], &a.output, flat.to_obj())?;
    Ok(ExitCode::SUCCESS)
}
