//! Render benchmark: median time of a full render to JSON (load, view, visibility, emit) of
//! the shared meshes, from several views. Run: `cargo bench --bench render`.
//! Models are read from ../shared/models or $KEPLER_MODELS; absent models are skipped.

use std::path::PathBuf;
use std::time::{Duration, Instant};

use kepler::emit::to_json;
use kepler::geom::V3;
use kepler::view::{Camera, View};
use kepler::visibility::{solve, PassOptions};

fn models_dir() -> PathBuf {
    std::env::var_os("KEPLER_MODELS")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../shared/models")))
}

/// How a benchmark view makes its camera from the scene.
type CameraFor = Box<dyn Fn(&kepler::scene::Scene) -> Camera>;

fn median(mut v: Vec<Duration>) -> Duration {
    v.sort();
    v[v.len() / 2]
}

fn ms(d: Duration) -> f64 {
    d.as_secs_f64() * 1e3
}

fn main() {
    let runs: usize = std::env::var("KEPLER_BENCH_RUNS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(7);
    let dir = models_dir();
    println!(
        "{:<22} {:<12} {:>8} {:>9} {:>9} {:>11} {:>9} {:>10}",
        "model", "view", "faces", "load ms", "view ms", "visible ms", "emit ms", "total ms"
    );
    for name in [
        "ico5.obj",
        "stanford-bunny.obj",
        "nefertiti.obj",
        "fandisk.obj",
        "grid100.obj",
    ] {
        let path = dir.join(name);
        if !path.exists() {
            println!("{name}: skipped (not found in {})", dir.display());
            continue;
        }
        let views: Vec<(&str, CameraFor)> = vec![
            ("three-quarter", Box::new(|_| Camera::three_quarter())),
            (
                "front",
                Box::new(|_| Camera::orthographic(V3::new(0., 0., -1.), V3::y()).unwrap()),
            ),
            (
                "perspective",
                Box::new(|s: &kepler::scene::Scene| {
                    let b = s.cbox();
                    let c = b.center();
                    let r = (b.hi - b.lo).norm();
                    Camera::from_spec(&kepler::scene::CameraSpec::Perspective {
                        eye: c + V3::new(0.6, 0.4, 1.0) * r,
                        target: c,
                        up: V3::y(),
                        fov_deg: 40.0,
                    })
                    .unwrap()
                }),
            ),
        ];
        for (vname, cam) in &views {
            let mut t = [Vec::new(), Vec::new(), Vec::new(), Vec::new(), Vec::new()];
            let mut faces = 0;
            for run in 0..=runs {
                let t0 = Instant::now();
                let scene = kepler::load::load_scene(&path, &mut Vec::new()).expect("model loads");
                let t1 = Instant::now();
                let view = View::new(&scene, cam(&scene));
                let t2 = Instant::now();
                let vis = solve(&view, PassOptions::default());
                let t3 = Instant::now();
                let json = to_json(&view, &vis, None);
                let t4 = Instant::now();
                std::hint::black_box(json.len());
                faces = scene.face_count();
                if run > 0 {
                    t[0].push(t1 - t0);
                    t[1].push(t2 - t1);
                    t[2].push(t3 - t2);
                    t[3].push(t4 - t3);
                    t[4].push(t4 - t0);
                }
            }
            let [a, b, c, d, e] = t.map(median);
            println!(
                "{name:<22} {vname:<12} {faces:>8} {:>9.1} {:>9.1} {:>11.1} {:>9.1} {:>10.1}",
                ms(a),
                ms(b),
                ms(c),
                ms(d),
                ms(e)
            );
        }
    }
}
