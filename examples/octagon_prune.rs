//! What screen octagons (x, y, x+y, x−y) would prune in VISFAC2 beyond rectangles.
//!
//! `cargo run --release --example octagon_prune -- SCENE...` prints, per scene and for the
//! scene's camera (or the three-quarter view), the counters of
//! `kepler::tribox::screen::prune_counts` and the time of the two walks.

use std::time::Instant;

use kepler::view::{Camera, View};

fn main() {
    for arg in std::env::args().skip(1) {
        let mut warnings = Vec::new();
        let scene = match kepler::load::load_scene(std::path::Path::new(&arg), &mut warnings) {
            Ok(s) => s,
            Err(e) => {
                eprintln!("{arg}: {e}");
                continue;
            }
        };
        let camera = match &scene.camera {
            Some(spec) => Camera::from_spec(spec).unwrap_or_else(|_| Camera::three_quarter()),
            None => Camera::three_quarter(),
        };
        let view = View::new(&scene, camera);
        let t = Instant::now();
        let c = kepler::tribox::screen::prune_counts(&view);
        let ms = t.elapsed().as_secs_f64() * 1e3;
        println!("{arg}: {c:?} ({ms:.0} ms for both walks)");
        println!(
            "  nodes entered: rect {} -> octagon {} ({:.1}% fewer); faces past rect+depth {}: octagon apart {} ({:.2}%), of which not already rejected by the exact convex test {}; exact convex test rejects {}",
            c.nodes_rect,
            c.nodes_octagon,
            100.0 * (c.nodes_rect - c.nodes_octagon) as f64 / c.nodes_rect.max(1) as f64,
            c.faces_rect,
            c.faces_octagon_apart,
            100.0 * c.faces_octagon_apart as f64 / c.faces_rect.max(1) as f64,
            c.faces_octagon_only,
            c.faces_separated
        );
    }
}
