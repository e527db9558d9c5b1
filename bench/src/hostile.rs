//! `kepler-bench --hostile`: the valid but hostile inputs of issue 16, timed — 65536-gons in
//! a group and in the example scenes (rendered), a 20-deep instancing
//! tree, long comments, many one-line objects. Each timed run is a fresh child process that loads, prepares and (where the case
//! says) renders to JSON; the table gives medians. The time bound of each case (1 s for the
//! 65536-gon scenes) is checked here, by the benchmark, never by a timed test.

use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::{Duration, Instant};

use anyhow::{bail, Context, Result};
use kepler_hsr::{Camera, CameraRequest, LoadOptions, Outputs, RenderOptions};

/// One hostile case: a scene text and what to run on it.
#[derive(Debug, Clone)]
pub struct HostileCase {
    /// Short name (the scene file is `NAME.kdl` in the output directory).
    pub name: &'static str,
    /// The scene file's text.
    pub text: String,
    /// Render to JSON after loading and preparing (else what `kepler info` does).
    pub render: bool,
    /// The whole-run median this case should stay under.
    pub bound: Duration,
}

/// The scene of `n` prototypes, each placing the one before twice: 6 * 2^n faces.
pub fn instancing_tree(n: usize) -> String {
    let mut s = String::from("prototype \"p0\" { box 0 0 0 1 1 1 }\n");
    for i in 1..=n {
        s += &format!(
            "prototype \"p{i}\" {{\n    instance \"a\" of=\"p{}\"\n    instance \"b\" of=\"p{}\" {{ translate {} 0 0 }}\n}}\n",
            i - 1,
            i - 1,
            2.0f64.powi(i as i32)
        );
    }
    s + &format!("object \"tree\" {{ instance \"t\" of=\"p{n}\" }}\n")
}

/// The cases, from the example scenes in `scenes`.
pub fn cases(scenes: &Path) -> Result<Vec<HostileCase>> {
    let read = |name: &str| {
        std::fs::read_to_string(scenes.join(name))
            .with_context(|| format!("{}", scenes.join(name).display()))
    };
    let assembly = read("assembly.kdl")?;
    let polyhedra = read("polyhedra.kdl")?;
    let swap = |text: &str, from: &str, to: &str| -> Result<String> {
        if !text.contains(from) {
            bail!("the example scene has no `{from}` to replace");
        }
        Ok(text.replacen(from, to, 1))
    };
    let second = Duration::from_secs(1);
    let mut comments = String::from("// 50 MB of comments, then one box\n");
    let line = format!("// {}\n", "x".repeat(97));
    let block = format!("/* {} */\n", "y".repeat(96));
    while comments.len() < 50_000_000 {
        comments += &line;
        comments += &block;
    }
    comments += "object \"a\" { box 0 0 0 1 1 1 }\n";
    let objects: String = (0..200_000)
        .map(|i| format!("object \"o{i}\" {{ box {i} 0 0 {} 1 1 }}\n", i as f64 + 0.5))
        .collect();
    Ok(vec![
        HostileCase {
            name: "group-box-prism65536",
            text: "object \"g\" {\n    object \"box\" { box -2 -2 -2 2 2 2 }\n    object \"p\" { prism 65536; translate 5 0 0 }\n}\n".into(),
            render: true,
            bound: second,
        },
        // Rendered: a long occluder is cut to each face's window (view::ring_index).
        HostileCase {
            name: "assembly-prism65536",
            text: swap(&assembly, "prism 8", "prism 65536")?,
            render: true,
            bound: second,
        },
        HostileCase {
            name: "polyhedra-antiprism65536",
            text: swap(&polyhedra, "antiprism 8;", "antiprism 65536;")?,
            render: true,
            bound: second,
        },
        HostileCase {
            name: "instancing-20-deep-info",
            text: instancing_tree(20),
            render: false,
            bound: Duration::from_secs(5),
        },
        HostileCase {
            name: "instancing-40-deep-refused",
            text: instancing_tree(40),
            render: false,
            bound: Duration::from_millis(100),
        },
        HostileCase {
            name: "comments-50MB-info",
            text: comments,
            render: false,
            bound: Duration::from_secs(2),
        },
        HostileCase {
            name: "objects-200k-info",
            text: objects,
            render: false,
            bound: Duration::from_secs(10),
        },
    ])
}

/// The child: loads, prepares and (with `render`) renders the scene at `path` once, then
/// prints `load prepare render` in ms (a refused scene: its error on standard error, and
/// the load time).
pub fn child(path: &Path, render: bool) -> Result<ExitCode> {
    let t = Instant::now();
    let loaded = kepler_hsr::load_scene(
        path,
        &LoadOptions::default(),
        &mut Vec::new(),
        &kepler_hsr::Progress::default(),
    );
    let load = t.elapsed();
    let ms = |d: Duration| d.as_secs_f64() * 1e3;
    let mut scene = match loaded {
        Ok(s) => s,
        Err(e) => {
            eprintln!("refused: {e}");
            let _ = writeln!(std::io::stdout().lock(), "{:.3} 0 0", ms(load));
            return Ok(ExitCode::SUCCESS);
        }
    };
    let t = Instant::now();
    kepler_hsr::prepare(
        &mut scene,
        &kepler_hsr::PrepareOptions::default(),
        &kepler_hsr::Progress::default(),
    );
    let prepare = t.elapsed();
    let mut rendered = Duration::ZERO;
    if render {
        let t = Instant::now();
        let camera = Camera::for_scene(&scene, &CameraRequest::default())?;
        let opts = RenderOptions {
            outputs: Outputs {
                json: true,
                ..Default::default()
            },
            ..Default::default()
        };
        let r = kepler_hsr::render(&scene, &camera, &opts, &kepler_hsr::Progress::default())?;
        std::hint::black_box(r.json);
        rendered = t.elapsed();
    }
    let _ = writeln!(
        std::io::stdout().lock(),
        "{:.3} {:.3} {:.3}",
        ms(load),
        ms(prepare),
        ms(rendered)
    );
    Ok(ExitCode::SUCCESS)
}

/// One timed row: medians in ms of load, prepare, render, and whole.
#[derive(Debug, Clone)]
pub struct HostileRow {
    /// The case.
    pub name: &'static str,
    /// Median stage times and their sum (ms).
    pub ms: [f64; 4],
    /// The bound (ms).
    pub bound_ms: f64,
}

/// Median of `v` (not empty).
fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// Runs every case `runs` times (after a warm-up) in fresh processes; writes the scenes and
/// `hostile.csv` into `out`, prints the table, and fails if a median is over its bound.
pub fn run(scenes: &Path, out: &Path, runs: usize) -> Result<ExitCode> {
    let dir = out.join("hostile");
    std::fs::create_dir_all(&dir).with_context(|| format!("{}", dir.display()))?;
    let exe = std::env::current_exe().context("finding kepler-bench itself")?;
    let mut rows = Vec::new();
    for case in cases(scenes)? {
        let path: PathBuf = dir.join(format!("{}.kdl", case.name));
        std::fs::write(&path, &case.text).with_context(|| format!("{}", path.display()))?;
        let mut times: Vec<[f64; 3]> = Vec::new();
        for i in 0..=runs {
            let mut cmd = std::process::Command::new(&exe);
            cmd.arg("--hostile-child").arg(&path);
            if case.render {
                cmd.arg("--hostile-render");
            }
            let o = cmd.output().context("starting a child run")?;
            let text = String::from_utf8_lossy(&o.stdout);
            let w: Vec<f64> = text
                .split_whitespace()
                .filter_map(|w| w.parse().ok())
                .collect();
            if !o.status.success() || w.len() != 3 {
                bail!(
                    "{}: the child failed: {}",
                    case.name,
                    String::from_utf8_lossy(&o.stderr)
                );
            }
            if i > 0 {
                times.push([w[0], w[1], w[2]]);
            }
        }
        let col = |k: usize| median(times.iter().map(|t| t[k]).collect());
        let whole = median(times.iter().map(|t| t.iter().sum()).collect());
        rows.push(HostileRow {
            name: case.name,
            ms: [col(0), col(1), col(2), whole],
            bound_ms: case.bound.as_secs_f64() * 1e3,
        });
    }
    let mut csv = String::from("case,load_ms,prepare_ms,render_ms,total_ms,bound_ms\n");
    println!(
        "{:<28} {:>10} {:>10} {:>10} {:>10} {:>8}",
        "case", "load ms", "prepare ms", "render ms", "total ms", "bound"
    );
    let mut over = Vec::new();
    for r in &rows {
        let [l, p, d, t] = r.ms;
        csv += &format!("{},{l:.3},{p:.3},{d:.3},{t:.3},{:.0}\n", r.name, r.bound_ms);
        let ok = if t <= r.bound_ms { "ok" } else { "OVER" };
        println!(
            "{:<28} {l:>10.1} {p:>10.1} {d:>10.1} {t:>10.1} {:>5.0} {ok}",
            r.name, r.bound_ms
        );
        if t > r.bound_ms {
            over.push(r.name);
        }
    }
    let csv_path = out.join("hostile.csv");
    std::fs::write(&csv_path, csv).with_context(|| format!("{}", csv_path.display()))?;
    if !over.is_empty() {
        bail!("over their time bound: {}", over.join(", "));
    }
    Ok(ExitCode::SUCCESS)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn instancing_tree_has_six_times_two_to_the_n_faces() {
        let dir = std::env::temp_dir().join(format!("kepler-hostile-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("tree.kdl");
        std::fs::write(&path, instancing_tree(5)).unwrap();
        let s = kepler_hsr::load_scene(
            &path,
            &kepler_hsr::LoadOptions::default(),
            &mut Vec::new(),
            &kepler_hsr::Progress::default(),
        )
        .unwrap();
        assert_eq!(s.face_count(), 6 * 32);
    }

    #[test]
    fn the_cases_are_made_from_the_example_scenes() {
        let scenes = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes");
        let c = cases(&scenes).unwrap();
        assert!(c[1].text.contains("prism 65536") && c[2].text.contains("antiprism 65536;"));
    }
}
