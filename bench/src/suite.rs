//! The fixed benchmark suite: generated scenes and shared meshes, their views, and one timed
//! run of the full pipeline (load, prepare, view, visibility, emit JSON and SVG).

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{Context, Result};
use kepler_hsr::plot::PictureOptions;
use kepler_hsr::stats::Stage;
use kepler_hsr::{render, Camera, CameraRequest, Outputs, RenderOptions, Scene, V3};

use crate::generate;

/// Where a case's scene comes from.
#[derive(Debug, Clone, PartialEq)]
pub enum Source {
    /// [`generate::field`] of at least this many faces.
    Field(usize),
    /// [`generate::terrain`] of at least this many faces.
    Terrain(usize),
    /// A mesh file.
    Model(PathBuf),
}

/// One scene of the suite.
#[derive(Debug, Clone, PartialEq)]
pub struct Case {
    /// Unique name (e.g. `field-10k`, `stanford-bunny`).
    pub name: String,
    /// Family for the charts: `field`, `terrain` or `model`.
    pub family: &'static str,
    /// Where it comes from.
    pub source: Source,
}

impl Case {
    /// The load stage: reads the mesh file, or generates the scene.
    pub fn load(&self) -> Result<Scene> {
        Ok(match &self.source {
            Source::Field(n) => generate::field(*n, 1),
            Source::Terrain(n) => generate::terrain(*n),
            Source::Model(p) => kepler_hsr::load_scene(
                p,
                &kepler_hsr::LoadOptions::default(),
                &mut Vec::new(),
                &kepler_hsr::Progress::default(),
            )
            .with_context(|| format!("{}", p.display()))?,
        })
    }
}

/// The views every case is measured from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ViewKind {
    /// kepler's default three-quarter orthographic view.
    ThreeQuarter,
    /// Orthographic, looking along −z.
    Front,
    /// Perspective from the right, above and in front, 40° field of view.
    Perspective,
}

impl ViewKind {
    /// Every view, in table order.
    pub const ALL: [ViewKind; 3] = [
        ViewKind::ThreeQuarter,
        ViewKind::Front,
        ViewKind::Perspective,
    ];

    /// Name in tables and CSV.
    pub fn name(self) -> &'static str {
        match self {
            ViewKind::ThreeQuarter => "three-quarter",
            ViewKind::Front => "front",
            ViewKind::Perspective => "perspective",
        }
    }

    /// The view of that name.
    pub fn by_name(s: &str) -> Option<ViewKind> {
        ViewKind::ALL.into_iter().find(|v| v.name() == s)
    }

    /// The camera of this view for a scene.
    pub fn camera(self, scene: &Scene) -> Result<Camera> {
        Ok(match self {
            ViewKind::ThreeQuarter => Camera::three_quarter(),
            ViewKind::Front => Camera::orthographic(V3::new(0., 0., -1.), V3::y())?,
            ViewKind::Perspective => {
                let b = scene.cbox();
                let c = b.center();
                let r = (b.hi - b.lo).norm();
                let request = CameraRequest {
                    eye: Some(c + V3::new(0.6, 0.4, 1.0) * r),
                    target: Some(c),
                    fov_deg: Some(40.0),
                    ..CameraRequest::default()
                };
                Camera::for_scene(scene, &request)?
            }
        })
    }
}

/// The shared meshes the suite uses where present, smallest first.
pub const MODELS: [&str; 13] = [
    "ico3.obj",
    "suzanne.obj",
    "spot.obj",
    "cow.obj",
    "teapot.obj",
    "rocker-arm.obj",
    "fandisk.obj",
    "ico5.obj",
    "grid100.obj",
    "beetle.obj",
    "ogre.obj",
    "stanford-bunny.obj",
    "nefertiti.obj",
];

/// The meshes of the quick suite (the two with targets).
pub const QUICK_MODELS: [&str; 2] = ["stanford-bunny.obj", "nefertiti.obj"];

/// A face count as a short name: 100, 3k, 100k.
pub fn size_name(n: usize) -> String {
    if n >= 1000 && n.is_multiple_of(1000) {
        format!("{}k", n / 1000)
    } else {
        n.to_string()
    }
}

/// The suite: generated fields and terrains of the given sizes, then the named meshes found
/// in `models` (absent ones are listed in the second result, to report as skipped).
pub fn cases(sizes: &[usize], models: &Path, names: &[&str]) -> (Vec<Case>, Vec<String>) {
    let mut out = Vec::new();
    for &n in sizes {
        out.push(Case {
            name: format!("field-{}", size_name(n)),
            family: "field",
            source: Source::Field(n),
        });
    }
    for &n in sizes {
        out.push(Case {
            name: format!("terrain-{}", size_name(n)),
            family: "terrain",
            source: Source::Terrain(n),
        });
    }
    let mut missing = Vec::new();
    for name in names {
        let path = models.join(name);
        if path.is_file() {
            out.push(Case {
                name: name.trim_end_matches(".obj").to_string(),
                family: "model",
                source: Source::Model(path),
            });
        } else {
            missing.push(path.display().to_string());
        }
    }
    (out, missing)
}

/// The stages of one run, in order.
pub const STAGES: [&str; 5] = ["load", "prepare", "view", "visibility", "emit"];

/// One run's stage times (ms) and the scene's face count.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Run {
    /// Milliseconds per stage, in [`STAGES`] order.
    pub ms: [f64; 5],
    /// Faces of the scene.
    pub faces: usize,
}

/// Milliseconds since `t`.
pub fn ms_since(t: Instant) -> f64 {
    t.elapsed().as_secs_f64() * 1e3
}

/// The options of `kepler render --json F --svg G` (default size 1024).
pub fn render_options() -> RenderOptions {
    RenderOptions {
        outputs: Outputs {
            json: true,
            svg: true,
            picture: PictureOptions::default(),
            ..Outputs::default()
        },
        ..RenderOptions::default()
    }
}

/// One full, timed run of a case from a view: exactly what `kepler render --json F --svg G`
/// does (load, prepare, then [`render`]), outputs kept in memory. Stages of the render are
/// grouped as the tables show them: view = cull + view, emit = lines + emit.
pub fn run(case: &Case, view: ViewKind) -> Result<Run> {
    let mut ms = [0.0; 5];
    let t = Instant::now();
    let mut scene = case.load()?;
    ms[0] = ms_since(t);
    let t = Instant::now();
    kepler_hsr::prepare(
        &mut scene,
        &kepler_hsr::PrepareOptions::default(),
        &kepler_hsr::Progress::default(),
    );
    ms[1] = ms_since(t);
    let r = render(
        &scene,
        &view.camera(&scene)?,
        &render_options(),
        &kepler_hsr::Progress::default(),
    )?;
    let st = |stages: &[Stage]| {
        stages
            .iter()
            .map(|&s| r.stats.time(s).as_secs_f64() * 1e3)
            .sum()
    };
    ms[2] = st(&[Stage::Lod, Stage::Prepare, Stage::Cull, Stage::View]);
    ms[3] = st(&[Stage::Visibility]);
    ms[4] = st(&[Stage::Lines, Stage::Emit]);
    std::hint::black_box((
        r.json.as_ref().map(String::len),
        r.svg.as_ref().map(String::len),
    ));
    Ok(Run {
        ms,
        faces: scene.face_count(),
    })
}

/// This process's peak resident set size (VmHWM) in KB, where /proc says it.
pub fn peak_kb() -> Option<u64> {
    let s = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = s.lines().find(|l| l.starts_with("VmHWM:"))?;
    line.split_whitespace().nth(1)?.parse().ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn suite_names_and_missing_models() {
        let (c, missing) = cases(&[100, 1000], Path::new("/nonexistent"), &["a.obj"]);
        let names: Vec<&str> = c.iter().map(|c| c.name.as_str()).collect();
        assert_eq!(
            names,
            ["field-100", "field-1k", "terrain-100", "terrain-1k"]
        );
        assert_eq!(missing, ["/nonexistent/a.obj"]);
        assert_eq!(size_name(30000), "30k");
    }

    #[test]
    fn a_run_measures_every_stage() {
        let case = Case {
            name: "t".into(),
            family: "field",
            source: Source::Field(50),
        };
        let r = run(&case, ViewKind::Perspective).unwrap();
        assert!(r.faces >= 50);
        assert!(r.ms.iter().all(|&t| t >= 0.0));
        assert!(peak_kb().is_some_and(|k| k > 0) || !Path::new("/proc/self/status").exists());
    }
}
