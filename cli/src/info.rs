//! `kepler info`: the object tree with face/vertex counts, CBOX, every object's INBOX
//! (computed here even where a render would skip it, or a reason why there is none), and
//! whether each mesh is a proven solid whose back faces are culled, or why not; and the up
//! axis a render without camera flags uses (the scene camera's, or `--up auto`'s choice).

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Result;
use clap::Args;
use kepler_hsr::PrepareOptions;

use super::{load_with, out};

/// Arguments of `kepler info`.
#[derive(Args, Debug)]
pub(crate) struct InfoArgs {
    /// Scene file (.kdl), mesh (.obj, .stl, .ply) or modeller's scene (.gltf, .glb, .3mf).
    pub(crate) scene: PathBuf,
    /// Print JSON instead of the tree.
    #[arg(long)]
    pub(crate) json: bool,
    /// Write a picture of each mesh's components, one colour per leaf component (SVG).
    #[arg(long, value_name = "F")]
    pub(crate) components: Option<PathBuf>,
    /// Pixels along the longer side of the --components picture.
    #[arg(long, value_name = "PX", default_value_t = 800)]
    pub(crate) size: u32,
    #[command(flatten)]
    pub(crate) camera: super::CameraArgs,
    /// Do not print warnings.
    #[arg(long, short)]
    pub(crate) quiet: bool,
}

/// Runs `kepler info`.
pub(crate) fn run(a: InfoArgs, opts: &kepler_hsr::LoadOptions) -> Result<ExitCode> {
    // The render skips INBOXes where they cannot help (one object); info always shows them.
    let prepare = PrepareOptions {
        every_inbox: true,
        ..PrepareOptions::default()
    };
    let scene = load_with(&a.scene, a.quiet, opts, &prepare)?;
    if let Some(f) = &a.components {
        let camera = a.camera.camera(&scene)?;
        super::write(
            f,
            super::components::components_svg(&scene, &camera, a.size)?,
        )?;
    }
    if a.json {
        out(&scene.describe_json());
    } else {
        out(&format!(
            "{}: {} faces, {} vertices",
            a.scene.display(),
            scene.face_count(),
            scene.root.vertex_count()
        ));
        out(&scene.describe());
    }
    Ok(ExitCode::SUCCESS)
}
