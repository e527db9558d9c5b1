//! Renders a mesh (or scene file) to an SVG line drawing with hidden lines removed exactly.
//!
//! ```sh
//! cargo run --release --example mesh_to_svg -- MODEL.obj out.svg
//! ```

use std::error::Error;
use std::path::PathBuf;

use kepler_hsr::{load_scene, prepare, render, Camera, CameraRequest, Outputs, RenderOptions};

fn main() -> Result<(), Box<dyn Error>> {
    let mut args = std::env::args_os().skip(1).map(PathBuf::from);
    let (Some(input), Some(output)) = (args.next(), args.next()) else {
        return Err("usage: mesh_to_svg MODEL.obj OUT.svg".into());
    };
    let mut warnings = Vec::new();
    let mut scene = load_scene(
        &input,
        &kepler_hsr::LoadOptions::default(),
        &mut warnings,
        &kepler_hsr::Progress::default(),
    )?;
    for w in &warnings {
        eprintln!("{w}");
    }
    prepare(
        &mut scene,
        &kepler_hsr::PrepareOptions::default(),
        &kepler_hsr::Progress::default(),
    );
    let camera = Camera::for_scene(&scene, &CameraRequest::default())?;
    let outputs = Outputs {
        svg: true,
        ..Outputs::default()
    };
    let opts = RenderOptions {
        outputs,
        ..RenderOptions::default()
    };
    let rendered = render(&scene, &camera, &opts, &kepler_hsr::Progress::default())?;
    std::fs::write(&output, rendered.svg.unwrap_or_default())?;
    eprintln!(
        "{}: {} faces, {:.1} ms",
        output.display(),
        scene.face_count(),
        rendered.stats.total().as_secs_f64() * 1e3
    );
    Ok(())
}
