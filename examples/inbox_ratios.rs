//! Prints INBOX/CBOX volume ratios and inbox times for the shared closed meshes, when present.
//! Usage: `cargo run --release --example inbox_ratios [MODEL_DIR]` (default /work/shared/models).

use std::time::Instant;

use kepler_hsr::prepare::mesh_inbox;
use kepler_hsr::scene::Object;

fn first_mesh(o: &Object) -> Option<&kepler_hsr::scene::Mesh> {
    o.mesh()
        .or_else(|| o.subobjects().iter().find_map(first_mesh))
}

fn main() {
    let dir = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "/work/shared/models".into());
    for name in [
        "cube",
        "ico3",
        "ico5",
        "fandisk",
        "rocker-arm",
        "nefertiti",
        "spot",
        "cow",
    ] {
        let path = std::path::Path::new(&dir).join(format!("{name}.obj"));
        if !path.exists() {
            println!("{name}: absent, skipped");
            continue;
        }
        let scene = match kepler_hsr::load::load_scene(
            &path,
            &kepler_hsr::LoadOptions::default(),
            &mut Vec::new(),
            &kepler_hsr::Progress::default(),
        ) {
            Ok(s) => s,
            Err(e) => {
                println!("{name}: {e}");
                continue;
            }
        };
        let Some(mesh) = first_mesh(&scene.root) else {
            println!("{name}: no mesh");
            continue;
        };
        let t = Instant::now();
        let inbox = mesh_inbox(mesh);
        let ms = t.elapsed().as_secs_f64() * 1e3;
        let cbox = kepler_hsr::geom::Box3::from_points(mesh.vertices.iter());
        match inbox {
            Some(b) => println!(
                "{name}: {} faces, closed {}, inbox/cbox = {:.4} ({ms:.1} ms)",
                mesh.faces.len(),
                mesh.closed,
                b.volume() / cbox.volume()
            ),
            None => println!(
                "{name}: {} faces, closed {}, no inbox ({ms:.1} ms)",
                mesh.faces.len(),
                mesh.closed
            ),
        }
    }
}
