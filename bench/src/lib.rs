//! `kepler-bench`: kepler's benchmark harness — stage times, peak memory, time against accuracy
//! (against a z-buffer and a ray sampler), time against size and against hidden complexity —
//! written as CSV and SVG charts, with a table on standard output.

pub mod accuracy;
pub mod chart;
pub mod coverage;
pub mod generate;
pub mod hostile;
pub mod rays;
pub mod report;
pub mod suite;
pub mod town;
pub mod trees;
pub mod zbuffer;

use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Duration;

use anyhow::{Context, Result};
use clap::Args;

use accuracy::{Method, Reference};
use kepler_cli::bar::Bar;
use suite::{Case, Run, Source, ViewKind};

/// Arguments of `kepler-bench`.
#[derive(Args, Debug)]
pub struct BenchArgs {
    /// A short suite: 3 sizes, one view, 3 runs, two meshes, fewer baseline points.
    #[arg(long)]
    pub quick: bool,
    /// Directory of the shared meshes (default: $KEPLER_MODELS, else ../shared/models next to
    /// the source tree); absent meshes are skipped with a message.
    #[arg(long, value_name = "DIR")]
    pub models: Option<PathBuf>,
    /// Where the CSV files and charts go.
    #[arg(long, value_name = "DIR", default_value = "out/bench")]
    pub out: PathBuf,
    /// Timed runs per measurement, after one warm-up run (default 7; 3 with --quick).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=1000))]
    pub runs: Option<u32>,
    /// Leave out scenes with more faces than this.
    #[arg(long, value_name = "N")]
    pub max_faces: Option<usize>,
    /// Town sizes (buildings) for the hidden-complexity chart (default 10,30,100,300,1000;
    /// 10,30,100 with --quick).
    #[arg(long, value_name = "N,...", value_delimiter = ',')]
    pub town: Option<Vec<usize>>,
    /// Only paper 002's tables (object trees: preprocessing, and interference in boxes of
    /// moving instances over this many steps), written to OUT/trees.md.
    #[arg(long, value_name = "STEPS")]
    pub trees: Option<usize>,
    /// Time the hostile inputs of issue 16 instead (65536-gons, a 20-deep instancing tree,
    /// long comments, many objects): a table of medians, `hostile.csv`, and exit 1 when a
    /// case is over its time bound.
    #[arg(long)]
    pub hostile: bool,
    /// Internal: one hostile run of this scene file in this process.
    #[arg(long, hide = true, value_name = "F")]
    pub hostile_child: Option<PathBuf>,
    /// Internal: with --hostile-child, render too.
    #[arg(long, hide = true)]
    pub hostile_render: bool,
    /// Internal: run one case once in this process and print its peak memory and stage
    /// times (every timed run is such a fresh process).
    #[arg(long, hide = true, value_name = "CASE/VIEW")]
    pub child: Option<String>,
    /// Only write the generated terrain of at least FACES triangles as an OBJ file (the
    /// issues' 10M-face terrain: `--terrain-obj 10000000 T.obj`).
    #[arg(long, num_args = 2, value_names = ["FACES", "FILE"])]
    pub terrain_obj: Option<Vec<String>>,
}

/// What one `kepler-bench` run measures.
#[derive(Debug, Clone)]
pub struct Plan {
    /// Generated scene sizes (faces).
    pub sizes: Vec<usize>,
    /// Views of every case.
    pub views: Vec<ViewKind>,
    /// Timed runs per measurement.
    pub runs: usize,
    /// Shared meshes to use where present.
    pub models: Vec<&'static str>,
    /// z-buffer resolutions.
    pub zbuffer: Vec<u32>,
    /// Ray-sampling steps (per picture side).
    pub rays: Vec<u32>,
    /// `--lod` pixel sizes.
    pub lod: Vec<u32>,
    /// Cases of the time-against-accuracy chart (by name, where present).
    pub accuracy: Vec<String>,
    /// Town sizes.
    pub town: Vec<usize>,
    /// Largest scene.
    pub max_faces: usize,
}

impl Plan {
    /// The plan the arguments ask for.
    pub fn of(a: &BenchArgs) -> Plan {
        let mut p = if a.quick {
            Plan {
                sizes: vec![100, 1000, 10000],
                views: vec![ViewKind::ThreeQuarter],
                runs: 3,
                models: suite::QUICK_MODELS.to_vec(),
                zbuffer: vec![256, 1024, 4096],
                rays: vec![64, 512],
                lod: vec![16, 64],
                accuracy: vec!["stanford-bunny".into(), "field-1k".into()],
                town: vec![10, 30, 100],
                max_faces: usize::MAX,
            }
        } else {
            Plan {
                sizes: vec![100, 300, 1000, 3000, 10000, 30000, 100000],
                views: ViewKind::ALL.to_vec(),
                runs: 7,
                models: suite::MODELS.to_vec(),
                zbuffer: vec![256, 512, 1024, 2048, 4096, 8192],
                rays: vec![64, 256, 1024, 4096],
                lod: vec![8, 16, 32, 64, 128],
                accuracy: vec!["stanford-bunny".into(), "field-10k".into()],
                town: town::TOWN_NS.to_vec(),
                max_faces: usize::MAX,
            }
        };
        if let Some(r) = a.runs {
            p.runs = r as usize;
        }
        if let Some(t) = &a.town {
            p.town = t.clone();
        }
        if let Some(m) = a.max_faces {
            p.max_faces = m;
            p.sizes.retain(|&s| s <= m);
        }
        p
    }
}

/// The models directory: the flag, else $KEPLER_MODELS, else ../shared/models.
fn models_dir(a: &BenchArgs) -> PathBuf {
    a.models.clone().unwrap_or_else(|| {
        std::env::var_os("KEPLER_MODELS")
            .map(PathBuf::from)
            .unwrap_or_else(|| {
                PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../shared/models"))
            })
    })
}

/// The case of a name (as [`suite::cases`] names them).
fn case_by_name(name: &str, models: &Path) -> Option<Case> {
    let size = |s: &str| -> Option<usize> {
        match s.strip_suffix('k') {
            Some(k) => k.parse::<usize>().ok().map(|k| k * 1000),
            None => s.parse().ok(),
        }
    };
    if let Some(n) = name.strip_prefix("field-").and_then(size) {
        return Some(Case {
            name: name.into(),
            family: "field",
            source: Source::Field(n),
        });
    }
    if let Some(n) = name.strip_prefix("terrain-").and_then(size) {
        return Some(Case {
            name: name.into(),
            family: "terrain",
            source: Source::Terrain(n),
        });
    }
    let path = models.join(format!("{name}.obj"));
    path.is_file().then(|| Case {
        name: name.into(),
        family: "model",
        source: Source::Model(path),
    })
}

/// The child process: one run of one case, then `peak_kb base_kb faces ms…` (the stage
/// times of [`suite::STAGES`]) on standard output.
fn child(spec: &str, models: &Path) -> Result<ExitCode> {
    let base = suite::peak_kb().unwrap_or(0);
    let (name, view) = spec.rsplit_once('/').context("--child expects CASE/VIEW")?;
    let case = case_by_name(name, models).with_context(|| format!("no case {name}"))?;
    let view = ViewKind::by_name(view).with_context(|| format!("no view {view}"))?;
    let r = suite::run(&case, view)?;
    let peak = suite::peak_kb().unwrap_or(0);
    let ms: Vec<String> = r.ms.iter().map(|m| format!("{m:.6}")).collect();
    // A closed pipe is not an error.
    let _ = writeln!(
        std::io::stdout().lock(),
        "{peak} {base} {} {}",
        r.faces,
        ms.join(" ")
    );
    Ok(ExitCode::SUCCESS)
}

/// One run of a case and view in a fresh process (this program with `--child`): its stage
/// times, and its peak memory and memory at start (KB) where /proc tells them.
fn child_run(case: &Case, view: ViewKind, models: &Path) -> Result<(Run, Option<(u64, u64)>)> {
    let exe = std::env::current_exe().context("finding kepler-bench itself")?;
    let out = std::process::Command::new(exe)
        .args(["--child", &format!("{}/{}", case.name, view.name())])
        .arg("--models")
        .arg(models)
        .stderr(std::process::Stdio::inherit())
        .output()
        .context("starting a child run")?;
    let text = String::from_utf8_lossy(&out.stdout);
    let words: Vec<f64> = text
        .split_whitespace()
        .filter_map(|w| w.parse().ok())
        .collect();
    if !out.status.success() || words.len() != 3 + suite::STAGES.len() {
        anyhow::bail!("child run of {}/{} failed: {text}", case.name, view.name());
    }
    let run = Run {
        ms: std::array::from_fn(|k| words[3 + k]),
        faces: words[2] as usize,
    };
    let (peak, base) = (words[0] as u64, words[1] as u64);
    Ok((run, (peak > 0).then_some((peak, base))))
}

/// Median and least of some numbers (0, 0 for none).
pub fn median_min(v: &[f64]) -> (f64, f64) {
    let mut s = v.to_vec();
    s.sort_by(f64::total_cmp);
    match s.len() {
        0 => (0.0, 0.0),
        n => (s[n / 2], s[0]),
    }
}

/// The timings of one case from one view.
#[derive(Debug, Clone)]
pub struct CaseRow {
    /// The case.
    pub case: Case,
    /// The view.
    pub view: ViewKind,
    /// Faces.
    pub faces: usize,
    /// The timed runs.
    pub runs: Vec<Run>,
    /// Peak memory and memory at start of the child process, KB.
    pub memory: Option<(u64, u64)>,
}

impl CaseRow {
    /// Median milliseconds of each stage.
    pub fn stage_medians(&self) -> [f64; 5] {
        std::array::from_fn(|s| {
            median_min(&self.runs.iter().map(|r| r.ms[s]).collect::<Vec<_>>()).0
        })
    }

    /// Median and least total milliseconds (totals of whole runs).
    pub fn total(&self) -> (f64, f64) {
        median_min(
            &self
                .runs
                .iter()
                .map(|r| r.ms.iter().sum())
                .collect::<Vec<_>>(),
        )
    }
}

/// One point of the time-against-accuracy chart.
#[derive(Debug, Clone)]
pub struct AccuracyRow {
    /// Case name.
    pub subject: String,
    /// Its faces.
    pub faces: usize,
    /// The method.
    pub method: Method,
    /// Median and least milliseconds.
    pub ms: (f64, f64),
    /// Its error against kepler's exact result.
    pub error: accuracy::Error,
    /// Exact only: the independent union check (relative residual).
    pub check: Option<f64>,
    /// The exact reference: visible area and visible line length, and drawn line length.
    pub reference: (f64, f64, f64),
}

/// Counts the jobs of a plan, for the progress bar.
fn job_count(p: &Plan, cases: usize, subjects: usize) -> usize {
    cases * p.views.len()
        + subjects * (2 + p.zbuffer.len() + p.rays.len() + p.lod.len())
        + 2 * p.town.len()
}

/// `--terrain-obj FACES FILE`: the generated terrain written as an OBJ.
fn terrain_obj(faces: &str, path: &Path) -> Result<ExitCode> {
    let faces: usize = faces
        .parse()
        .with_context(|| format!("--terrain-obj: {faces:?} is not a face count"))?;
    let file = std::fs::File::create(path).with_context(|| format!("{}", path.display()))?;
    let mut w = std::io::BufWriter::new(file);
    let n = generate::write_terrain_obj(faces, &mut w)
        .and_then(|n| w.flush().map(|()| n))
        .with_context(|| format!("{}", path.display()))?;
    eprintln!("{}: terrain of {n} faces", path.display());
    Ok(ExitCode::SUCCESS)
}

/// Runs `kepler-bench`.
pub fn run(a: BenchArgs) -> Result<ExitCode> {
    let models = models_dir(&a);
    if let Some(spec) = &a.child {
        return child(spec, &models);
    }
    if let Some(args) = &a.terrain_obj {
        return terrain_obj(&args[0], Path::new(&args[1]));
    }
    if let Some(steps) = a.trees {
        std::fs::create_dir_all(&a.out).with_context(|| format!("{}", a.out.display()))?;
        let doc = trees::run_tables(&models, &a.out, steps, &suite::MODELS)?;
        println!("{doc}");
        return Ok(ExitCode::SUCCESS);
    }
    if let Some(path) = &a.hostile_child {
        return hostile::child(path, a.hostile_render);
    }
    if a.hostile {
        let scenes = PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes"));
        let runs = a.runs.map_or(if a.quick { 3 } else { 5 }, |r| r as usize);
        return hostile::run(&scenes, &a.out, runs);
    }
    let plan = Plan::of(&a);
    std::fs::create_dir_all(&a.out).with_context(|| format!("{}", a.out.display()))?;
    let (cases, missing) = suite::cases(&plan.sizes, &models, &plan.models);
    for m in &missing {
        eprintln!("bench: {m} not found, skipped");
    }
    let subjects: Vec<&String> = plan
        .accuracy
        .iter()
        .filter(|s| cases.iter().any(|c| &c.name == *s))
        .collect();
    let mut bar = Bar::new(
        "bench",
        job_count(&plan, cases.len(), subjects.len()),
        Duration::ZERO,
    );
    let mut done = 0;
    let rows = time_cases(&plan, &cases, &models, &mut bar, &mut done)?;
    let mut acc = Vec::new();
    for s in subjects {
        let case = cases.iter().find(|c| &c.name == s).expect("filtered above");
        if rows.iter().any(|r| &r.case == case) {
            acc.extend(time_accuracy(&plan, case, &mut bar, &mut done)?);
        }
    }
    let mut town_rows = Vec::new();
    for &n in &plan.town {
        for (layout, inbox, _, _) in town::SERIES {
            bar.update(done, &format!("town N={n} {layout:?} inbox={inbox}"));
            town_rows.push(town::measure(n, layout, inbox, plan.runs.min(5)));
            done += 1;
        }
    }
    bar.finish();
    report::write_all(&a.out, &rows, &acc, &town_rows, &missing)?;
    Ok(ExitCode::SUCCESS)
}

/// Times every case from every view: a warm-up, then the plan's runs, each in a fresh
/// process (so the numbers are what `kepler render` takes, whatever ran before), with the
/// largest peak memory of the runs.
fn time_cases(
    plan: &Plan,
    cases: &[Case],
    models: &Path,
    bar: &mut Bar,
    done: &mut usize,
) -> Result<Vec<CaseRow>> {
    let mut rows = Vec::new();
    for case in cases {
        for &view in &plan.views {
            let label = format!("{} {}", case.name, view.name());
            bar.update(*done, &format!("{label} warm-up"));
            let first = match child_run(case, view, models) {
                Ok((r, _)) => r,
                Err(e) => {
                    eprintln!("bench: {label}: {e:#}, skipped");
                    *done += 1;
                    continue;
                }
            };
            // Generated sizes were filtered by their target; meshes by what they hold.
            if case.family == "model" && first.faces > plan.max_faces {
                *done += 1;
                continue;
            }
            let mut runs = Vec::with_capacity(plan.runs);
            let mut memory: Option<(u64, u64)> = None;
            for k in 0..plan.runs {
                bar.update(*done, &format!("{label} run {}/{}", k + 1, plan.runs));
                let (run, mem) = child_run(case, view, models)?;
                runs.push(run);
                memory = memory.max(mem);
            }
            rows.push(CaseRow {
                case: case.clone(),
                view,
                faces: first.faces,
                runs,
                memory,
            });
            *done += 1;
        }
    }
    Ok(rows)
}

/// Times kepler and the baselines on one case (three-quarter view) and measures their errors.
fn time_accuracy(
    plan: &Plan,
    case: &Case,
    bar: &mut Bar,
    done: &mut usize,
) -> Result<Vec<AccuracyRow>> {
    bar.update(*done, &format!("{} exact reference", case.name));
    let mut scene = case.load()?;
    kepler_hsr::prepare(
        &mut scene,
        &kepler_hsr::PrepareOptions::default(),
        &kepler_hsr::Progress::default(),
    );
    let camera = ViewKind::ThreeQuarter.camera(&scene)?;
    let reference = Reference::new(&scene, camera);
    let check = accuracy::union_residual(&reference);
    let mut methods = vec![Method::Exact, Method::ExactLines];
    methods.extend(plan.zbuffer.iter().map(|&px| Method::ZBuffer(px)));
    methods.extend(plan.rays.iter().map(|&k| Method::Rays(k)));
    methods.extend(plan.lod.iter().map(|&px| Method::Lod(px)));
    let mut out = Vec::new();
    for m in methods {
        let label = format!("{} {} {}", case.name, m.name(), m.param());
        bar.update(*done, &label);
        let (_, mut last) = accuracy::run(&scene, camera, m);
        let mut ms = Vec::with_capacity(plan.runs);
        for k in 0..plan.runs {
            bar.update(*done, &format!("{label} run {}/{}", k + 1, plan.runs));
            let (t, o) = accuracy::run(&scene, camera, m);
            ms.push(t);
            last = o;
        }
        bar.update(*done, &format!("{label} error"));
        out.push(AccuracyRow {
            subject: case.name.clone(),
            faces: scene.face_count(),
            method: m,
            ms: median_min(&ms),
            error: accuracy::error(&reference, &last),
            check: (m == Method::Exact).then_some(check),
            reference: (
                reference.visible_area,
                reference.visible_length,
                reference.drawn_length,
            ),
        });
        *done += 1;
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn case_names_round_trip() {
        let m = Path::new("/nonexistent");
        let (cases, _) = suite::cases(&[100, 30000], m, &[]);
        for c in cases {
            assert_eq!(case_by_name(&c.name, m), Some(c));
        }
        assert_eq!(case_by_name("stanford-bunny", m), None);
    }

    #[test]
    fn medians_of_odd_and_even_counts() {
        assert_eq!(median_min(&[3., 1., 2.]), (2., 1.));
        assert_eq!(median_min(&[4., 1., 2., 3.]), (3., 1.));
        assert_eq!(median_min(&[]), (0., 0.));
    }
}
