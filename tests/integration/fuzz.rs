//! The fuzzing target: a mutation loop over every fixture (example scenes, good and bad mesh
//! and scene files) that loads, prepares and renders each mutant, asserting that nothing
//! panics, that every load error names the mutated file, and that every result is finite JSON.
//!
//! The normal test suite runs it for a few seconds (`KEPLER_FUZZ_SECS`, default 3); CI runs
//! the ignored `fuzz_for_a_minute` (`cargo test --test integration fuzz -- --ignored`). Mutants are
//! deterministic by case number; a failing one is written to `target/fuzz-found/` and belongs,
//! with its expected message, in `tests/fixtures/bad/`.

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use kepler_hsr::lines::LineOptions;
use kepler_hsr::RenderOptions;
use kepler_hsr::{load_scene, render, Camera, CameraRequest, LoadOptions, Outputs};
use kepler_testkit::Rng;

/// Faces above which a mutant is loaded and prepared but not rendered (a mutant that turns
/// `prism 8` into `prism 99999999` is refused by the face limit; this keeps the rest quick).
const RENDER_FACES: usize = 20_000;

/// Byte strings a mutation inserts or writes over: the tokens that reach odd corners.
const TOKENS: &[&[u8]] = &[
    b"{",
    b"}",
    b"/-",
    b"/*",
    b"*/",
    b"//",
    b"\"",
    b"\\",
    b";",
    b"=",
    b"#true",
    b"true",
    b"#nan",
    b"1e400",
    b"-1e308",
    b"1e-320",
    b"0",
    b"-0",
    b"-",
    b".",
    b"99999999",
    b"\r",
    b"\n",
    b"\r\n",
    b"\0",
    b"\xff\xfe",
    b"\xef\xbb\xbf",
    b"include \"fuzz.kdl\"\n",
    b"instance \"i\" of=\"p\"\n",
    b"prototype \"p\" { box 0 0 0 1 1 1 }\n",
    b"prism 3",
    b"inbox 0 0 0 1 1 1\n",
    b"f 1 2 3\n",
    b"v 1e12 0 0\n",
    b"facet normal 0 0 1\n",
    b"vertex 0 0 0\n",
    b"element vertex 4000000000\n",
    b"property list uchar int vertex_indices\n",
    b"end_header\n",
    b"solid ",
    b"endsolid",
    b"camera { eye 0 0 0; target 0 0 0 }\n",
    b"fov 1e-300",
    b"scale 0 1 1",
    b"matrix",
    // PLY and STL seeds reach their readers' corners too (issue 32).
    b"format binary_little_endian 1.0\n",
    b"format binary_big_endian 1.0\n",
    b"element face 4294967295\n",
    b"property list uint uint vertex_indices\n",
    b"property double x\n",
    b"comment ",
    b"outer loop\n",
    b"endloop\n",
    b"endfacet\n",
    b"\xff\xff\xff\x7f",
    b"o \x1b[2J\n",
    b"f 1 2 1 2 3\n",
    b"f 1 2 3 1 2 3 1 2 3\n",
    b"include \"/dev/zero.kdl\"\n",
    // glTF and 3MF seeds (issue 34).
    b"\"children\":[0],",
    b"\"mesh\":0,",
    b"\"count\":4294967295,",
    b"\"byteStride\":252,",
    b"\"mode\":5,",
    b"\"uri\":\"../x.bin\",",
    b"\"matrix\":[0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,1],",
    b"<component objectid=\"2\"/>",
    b" transform=\"0 0 0 0 0 0 0 0 0 0 0 0\"",
    b"<triangle v1=\"0\" v2=\"1\" v3=\"99\"/>",
];

/// The directory of bad fixtures.
fn bad_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/bad")
}

/// Every fixture: the example scenes and good meshes first, then the bad files.
fn fixtures() -> Vec<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = Vec::new();
    for dir in [
        "scenes",
        "tests/fixtures/meshes",
        "tests/fixtures/scenes",
        "tests/fixtures/bad",
    ] {
        let mut here = Vec::new();
        for e in std::fs::read_dir(root.join(dir)).unwrap() {
            let p = e.unwrap().path();
            let ext = p.extension().and_then(|e| e.to_str()).unwrap_or("");
            if p.is_file() && ["kdl", "obj", "stl", "ply", "gltf", "glb", "3mf"].contains(&ext) {
                here.push(p);
            }
        }
        here.sort();
        files.extend(here);
    }
    assert!(files.len() > 50, "only {} fixtures", files.len());
    files
}

/// Mutant number `case` of `text`: one to three edits (overwrite, insert, delete, duplicate,
/// truncate, splice from `other`).
fn mutate(text: &[u8], other: &[u8], case: u64) -> Vec<u8> {
    let mut rng = Rng::new(case.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1);
    let mut t = text.to_vec();
    for _ in 0..1 + rng.below(3) {
        let at = rng.below(t.len() + 1);
        match rng.below(7) {
            0 if at < t.len() => t[at] = rng.next_u64() as u8,
            1 | 2 => {
                let tok = TOKENS[rng.below(TOKENS.len())];
                t.splice(at..at, tok.iter().copied());
            }
            3 => {
                let end = (at + 1 + rng.below(64)).min(t.len());
                t.drain(at.min(end)..end);
            }
            4 => {
                let end = (at + 1 + rng.below(256)).min(t.len());
                let chunk = t[at.min(end)..end].to_vec();
                t.splice(at..at, chunk.iter().copied());
            }
            5 => t.truncate(at),
            _ => {
                let from = rng.below(other.len() + 1);
                let end = (from + rng.below(512)).min(other.len());
                t.splice(at..at, other[from..end].iter().copied());
            }
        }
    }
    t
}

/// How far a mutant got.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Outcome {
    /// Refused on loading, with an error naming the file.
    Refused,
    /// Loaded and prepared (too big to render here, or no camera).
    Loaded,
    /// Rendered to finite JSON, or refused by the render with an error.
    Rendered,
}

/// Loads, prepares and renders the file at `path`: how far it got, or the first broken
/// promise.
fn check(path: &Path) -> Result<Outcome, String> {
    let opts = LoadOptions {
        max_faces: 200_000,
        ..LoadOptions::default()
    };
    let run = || -> Result<Outcome, String> {
        let mut warnings = Vec::new();
        let mut scene =
            match load_scene(path, &opts, &mut warnings, &kepler_hsr::Progress::default()) {
                Ok(s) => s,
                Err(e) => {
                    let msg = e.to_string();
                    let named = msg.starts_with(&format!("{}:", path.display()));
                    return match named {
                        true => Ok(Outcome::Refused),
                        false => Err(format!("error does not name the file: {msg}")),
                    };
                }
            };
        kepler_hsr::prepare(
            &mut scene,
            &kepler_hsr::PrepareOptions::default(),
            &kepler_hsr::Progress::default(),
        );
        if scene.face_count() > RENDER_FACES {
            return Ok(Outcome::Loaded);
        }
        let Ok(camera) = Camera::for_scene(&scene, &CameraRequest::default()) else {
            return Ok(Outcome::Loaded);
        };
        let opts = RenderOptions {
            lines: LineOptions {
                hidden: true,
                ..Default::default()
            },
            outputs: Outputs {
                json: true,
                json_lines: true,
                svg: true,
                ..Default::default()
            },
            ..Default::default()
        };
        let Ok(r) = render(&scene, &camera, &opts, &kepler_hsr::Progress::default()) else {
            return Ok(Outcome::Rendered);
        };
        let json = r.json.unwrap_or_default();
        match serde_json::from_str::<serde_json::Value>(&json) {
            Ok(_) => Ok(Outcome::Rendered),
            Err(e) => Err(format!("the JSON does not parse (NaN or infinity?): {e}")),
        }
    };
    catch_unwind(AssertUnwindSafe(run)).unwrap_or_else(|_| Err("panicked".into()))
}

/// Runs mutants of every fixture in turn for `budget`; returns how many were refused,
/// loaded, and rendered.
fn fuzz(budget: Duration) -> [u64; 3] {
    let files = fixtures();
    let good = files
        .iter()
        .take_while(|f| !f.starts_with(bad_dir()))
        .count();
    let texts: Vec<Vec<u8>> = files.iter().map(|f| std::fs::read(f).unwrap()).collect();
    let dir = std::env::temp_dir().join(format!("kepler-fuzz-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let start = Instant::now();
    let mut case = 0u64;
    let mut counts = [0u64; 3];
    while start.elapsed() < budget {
        // Three mutants in four are of good files (the example scenes and good meshes,
        // which come first), so that most get past the first line; the rest of bad ones.
        let k = match case % 4 {
            0 => case as usize / 4 % files.len(),
            _ => case as usize % good,
        };
        let other = &texts[(k * 7 + 3) % texts.len()];
        let mutant = mutate(&texts[k], other, case);
        let ext = files[k].extension().unwrap().to_str().unwrap();
        let path = dir.join(format!("fuzz.{ext}"));
        std::fs::write(&path, &mutant).unwrap();
        match check(&path) {
            Ok(outcome) => counts[outcome as usize] += 1,
            Err(broken) => {
                let found = Path::new(env!("CARGO_MANIFEST_DIR")).join("target/fuzz-found");
                std::fs::create_dir_all(&found).unwrap();
                let keep = found.join(format!("case{case}.{ext}"));
                std::fs::write(&keep, &mutant).unwrap();
                panic!(
                    "mutant {case} of {}: {broken} (kept as {})",
                    files[k].display(),
                    keep.display()
                );
            }
        }
        case += 1;
    }
    let _ = std::fs::remove_dir_all(&dir);
    counts
}

/// Seconds from `KEPLER_FUZZ_SECS`, else `default`.
fn budget(default: u64) -> Duration {
    let secs = std::env::var("KEPLER_FUZZ_SECS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(default);
    Duration::from_secs(secs)
}

#[test]
fn mutated_fixtures_never_panic_and_errors_name_the_file() {
    let [refused, loaded, rendered] = fuzz(budget(3));
    println!("mutants: {refused} refused, {loaded} loaded only, {rendered} rendered");
    assert!(refused > 0 && rendered > 0);
}

#[test]
#[ignore = "a minute of fuzzing: CI runs it with --ignored"]
fn fuzz_for_a_minute() {
    let [refused, loaded, rendered] = fuzz(budget(60));
    println!("mutants: {refused} refused, {loaded} loaded only, {rendered} rendered");
}

/// Numbers a flag is given in the flag fuzz: the degenerate, the huge, the tiny.
const NUMBERS: &[f64] = &[
    0.0,
    -0.0,
    1.0,
    -1.0,
    0.5,
    1e-6,
    1e-300,
    5e-324,
    1e12,
    1.5e12,
    1e160,
    1e308,
    -1e308,
    f64::INFINITY,
    f64::NAN,
];

/// A camera request and picture options from case number `case`: every camera flag and the
/// plotter flags whose numbers size loops (dash, hatch spacing, page), from [`NUMBERS`].
fn flags(case: u64) -> (CameraRequest, kepler_hsr::plot::PictureOptions) {
    let mut rng = Rng::new(case.wrapping_mul(0x2545_f491_4f6c_dd1d) | 1);
    let mut n = || NUMBERS[rng.below(NUMBERS.len())];
    let v3 = |n: &mut dyn FnMut() -> f64| kepler_hsr::V3::new(n(), n(), n());
    let mut req = CameraRequest::default();
    match case % 4 {
        0 => req.dir = Some(v3(&mut n)),
        1 => {
            req.eye = Some(v3(&mut n).into());
            req.target = Some(v3(&mut n).into());
            req.fov_deg = Some(n() * 90.0);
        }
        2 => req.up = Some(v3(&mut n)),
        _ => req.fov_deg = Some(n()),
    }
    let mut pic = kepler_hsr::plot::PictureOptions {
        dash_mm: [n(), n()],
        ..Default::default()
    };
    if case.is_multiple_of(3) {
        pic.hatch = Some(kepler_hsr::plot::HatchOptions {
            spacing_mm: n(),
            ..Default::default()
        });
    }
    if case.is_multiple_of(5) {
        pic.page = Some(kepler_hsr::plot::PageSize {
            width: n() * 1e5,
            height: n() * 1e5,
        });
    }
    (req, pic)
}

/// The flag fuzz: a small scene rendered with random camera and plotter flags never panics,
/// and every render that succeeds writes finite JSON and an SVG with no NaN or infinity.
#[test]
fn random_flags_are_applied_or_refused_never_a_panic_or_nan() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/meshes/cube_groups.obj");
    let mut warnings = Vec::new();
    let scene = load_scene(
        &path,
        &LoadOptions::default(),
        &mut warnings,
        &kepler_hsr::Progress::default(),
    )
    .unwrap();
    let (mut ok, mut refused) = (0, 0);
    let start = Instant::now();
    for case in 0..400u64 {
        if start.elapsed() > budget(3) && ok > 0 && refused > 0 {
            break;
        }
        let (req, picture) = flags(case);
        let run = || {
            let camera = Camera::for_scene(&scene, &req).ok()?;
            let opts = RenderOptions {
                lines: LineOptions {
                    hidden: true,
                    ..Default::default()
                },
                outputs: Outputs {
                    json: true,
                    svg: true,
                    picture,
                    ..Default::default()
                },
                ..Default::default()
            };
            render(&scene, &camera, &opts, &kepler_hsr::Progress::default()).ok()
        };
        match catch_unwind(AssertUnwindSafe(run)) {
            Err(_) => panic!("flag case {case} panicked: {req:?} {picture:?}"),
            Ok(None) => refused += 1,
            Ok(Some(r)) => {
                let json = r.json.clone().unwrap_or_default();
                assert!(
                    serde_json::from_str::<serde_json::Value>(&json).is_ok(),
                    "flag case {case}: JSON does not parse: {req:?}"
                );
                let svg = r.svg.clone().unwrap_or_default();
                let bad = svg
                    .split(|c: char| !(c.is_ascii_alphanumeric() || c == '-'))
                    .any(|w| matches!(w, "NaN" | "inf" | "-inf"));
                assert!(
                    !bad,
                    "flag case {case}: SVG with NaN or inf: {req:?} {picture:?}"
                );
                ok += 1;
            }
        }
    }
    println!("flag cases: {ok} rendered, {refused} refused");
    assert!(ok > 0 && refused > 0, "{ok} {refused}");
}

#[test]
fn mutations_are_deterministic_and_change_the_text() {
    let text = b"object \"a\" { box 0 0 0 1 1 1 }\n";
    assert_eq!(mutate(text, text, 7), mutate(text, text, 7));
    let changed = (0..100).filter(|&c| mutate(text, b"x", c) != text).count();
    assert!(changed > 90, "{changed}");
}
