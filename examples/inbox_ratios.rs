//! Prints INBOX/CBOX volume ratios and prepare times for the shared closed meshes, when present.
//! Usage: `cargo run --release --example inbox_ratios [MODEL_DIR]` (default /work/shared/models).

use std::time::Instant;

use kepler_hsr::{Box3, Object};

/// The first object below `o` (or `o` itself) that holds a mesh.
fn first_mesh_object(o: &Object) -> Option<&Object> {
    if o.mesh().is_some() {
        return Some(o);
    }
    o.subobjects().iter().find_map(first_mesh_object)
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
        let mut scene = match kepler_hsr::load_scene(
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
        let t = Instant::now();
        kepler_hsr::prepare(
            &mut scene,
            &kepler_hsr::PrepareOptions::default(),
            &kepler_hsr::Progress::default(),
        );
        let ms = t.elapsed().as_secs_f64() * 1e3;
        let Some(object) = first_mesh_object(&scene.root) else {
            println!("{name}: no mesh");
            continue;
        };
        let (mesh, inbox) = (object.mesh().expect("a mesh object"), object.inbox);
        let cbox = Box3::from_points(mesh.vertices.iter());
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
