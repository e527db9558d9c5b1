//! The golden visible-polygon sets, byte for byte.
//!
//! Every scene in scenes/ re-renders to its golden (tests/golden/NAME.json) through `kepler
//! check` (the set made in memory) and through `kepler render --json` (the set written to its
//! file as it is made). Regenerate those with `kepler check scenes/NAME.kdl --golden
//! tests/golden/NAME.json --update`.
//!
//! The data-driven cases, in the manner of iOverlay's fixtures: each `tests/golden/NAME.case`
//! names its input (`input: PATH` from the checkout's root, or `model: FILE` of the shared
//! models) and the flags of `kepler render` (`args: ...`, camera and drawing), and
//! `tests/golden/NAME.json` is the JSON it must write. A case needing a missing model skips
//! loudly (fails with `KEPLER_REQUIRE_MODELS=1`). After an intended change of output, regenerate
//! every expected file and review the diff:
//!
//! ```text
//! KEPLER_UPDATE_GOLDENS=1 KEPLER_MODELS=/path/to/models cargo test -p kepler-hsr-cli --test end_to_end goldens
//! ```

use std::path::{Path, PathBuf};
use std::process::Command;

use serde_json::Value;

use super::common::root;

#[test]
fn every_scene_matches_its_golden() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let mut checked = 0;
    for entry in std::fs::read_dir(root.join("scenes")).unwrap() {
        let scene = entry.unwrap().path();
        if scene.extension().and_then(|e| e.to_str()) != Some("kdl") {
            continue;
        }
        let name = scene.file_stem().unwrap().to_str().unwrap().to_string();
        let golden = root.join("tests/golden").join(format!("{name}.json"));
        assert!(
            golden.exists(),
            "scene {name} has no golden at {}",
            golden.display()
        );
        let out = Command::new(env!("CARGO_BIN_EXE_kepler"))
            .arg("check")
            .arg(&scene)
            .arg("--golden")
            .arg(&golden)
            .arg("-q")
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{name}: {}{}",
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr)
        );
        let written =
            std::env::temp_dir().join(format!("kepler-golden-{}-{name}.json", std::process::id()));
        let out = Command::new(env!("CARGO_BIN_EXE_kepler"))
            .arg("render")
            .arg(&scene)
            .arg("--json")
            .arg(&written)
            .arg("-q")
            .output()
            .unwrap();
        assert!(out.status.success(), "{name}: {out:?}");
        let same = std::fs::read(&written).unwrap() == std::fs::read(&golden).unwrap();
        let _ = std::fs::remove_file(&written);
        assert!(
            same,
            "{name}: `kepler render --json` differs from its golden"
        );
        checked += 1;
    }
    assert!(checked >= 3, "only {checked} scenes");
}

/// A golden case: its input, the flags it renders with, and its expected JSON.
struct Case {
    name: String,
    input: Option<PathBuf>,
    args: Vec<String>,
    expected: PathBuf,
}

/// Reads `tests/golden/NAME.case`; its input is None when it names a missing shared model.
fn read_case(path: &Path) -> Case {
    let name = path.file_stem().unwrap().to_str().unwrap().to_string();
    let text = std::fs::read_to_string(path).unwrap();
    let (mut input, mut args, mut keys) = (None, Vec::new(), 0);
    for line in text
        .lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
    {
        let (key, value) = line
            .split_once(':')
            .unwrap_or_else(|| panic!("{}: `{line}` is not `key: value`", path.display()));
        let value = value.trim();
        match key {
            "input" => input = Some(root().join(value)),
            "model" => input = kepler_testkit::model(value),
            "args" => args = value.split_whitespace().map(String::from).collect(),
            _ => panic!("{}: unknown key `{key}`", path.display()),
        }
        keys += 1;
    }
    assert_eq!(
        keys,
        2,
        "{}: wants an input (or model) and args",
        path.display()
    );
    if let Some(p) = &input {
        assert!(p.is_file(), "{name}: no input at {}", p.display());
    }
    let expected = path.with_extension("json");
    Case {
        name,
        input,
        args,
        expected,
    }
}

/// Every case of tests/golden/, sorted by name.
fn cases() -> Vec<PathBuf> {
    let mut cases: Vec<PathBuf> = std::fs::read_dir(root().join("tests/golden"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().and_then(|e| e.to_str()) == Some("case"))
        .collect();
    cases.sort();
    cases
}

/// The JSON `kepler render` writes for the case.
fn render(case: &Case, input: &Path) -> Vec<u8> {
    let out = std::env::temp_dir().join(format!(
        "kepler-case-{}-{}.json",
        std::process::id(),
        case.name
    ));
    let run = Command::new(env!("CARGO_BIN_EXE_kepler"))
        .arg("render")
        .arg(input)
        .args(&case.args)
        .arg("--json")
        .arg(&out)
        .arg("-q")
        .output()
        .unwrap();
    assert!(run.status.success(), "{}: {run:?}", case.name);
    let bytes = std::fs::read(&out).unwrap();
    let _ = std::fs::remove_file(&out);
    bytes
}

/// Where two JSON texts first differ: the first face (by position) or the first other key.
fn first_difference(got: &[u8], want: &[u8]) -> String {
    let (Ok(got), Ok(want)) = (
        serde_json::from_slice::<Value>(got),
        serde_json::from_slice::<Value>(want),
    ) else {
        return "one of them is not JSON".into();
    };
    let faces = |v: &Value| v["faces"].as_array().cloned().unwrap_or_default();
    let (gf, wf) = (faces(&got), faces(&want));
    if let Some(k) = (0..gf.len().max(wf.len())).find(|&k| gf.get(k) != wf.get(k)) {
        return format!(
            "face #{k} differs:\n  got  {}\n  want {}",
            gf.get(k).map_or("(none)".into(), Value::to_string),
            wf.get(k).map_or("(none)".into(), Value::to_string)
        );
    }
    let keys = got
        .as_object()
        .into_iter()
        .chain(want.as_object())
        .flat_map(|o| o.keys());
    match keys
        .into_iter()
        .find(|k| got.get(k.as_str()) != want.get(k.as_str()))
    {
        Some(k) => format!("the faces agree; `{k}` differs"),
        None => "the values agree; only the bytes (number spelling, layout) differ".into(),
    }
}

#[test]
fn every_golden_case_renders_its_json_byte_for_byte() {
    let update = kepler_testkit::require("KEPLER_UPDATE_GOLDENS");
    let (mut checked, mut failed) = (0, Vec::new());
    for path in cases() {
        let case = read_case(&path);
        let Some(input) = &case.input else { continue };
        let got = render(&case, input);
        if update {
            std::fs::write(&case.expected, &got).unwrap();
        }
        let want = std::fs::read(&case.expected).unwrap_or_else(|e| {
            panic!(
                "{}: {e} (regenerate with KEPLER_UPDATE_GOLDENS=1)",
                case.expected.display()
            )
        });
        if got != want {
            failed.push(format!("{}: {}", case.name, first_difference(&got, &want)));
        }
        checked += 1;
    }
    assert!(
        failed.is_empty(),
        "{} of {checked} cases differ from their golden JSON:\n{}",
        failed.len(),
        failed.join("\n")
    );
    assert!(
        checked >= 11,
        "only {checked} cases ran (scene cases need no models)"
    );
}

/// Every scene of scenes/ and docs/example/ has a case, so a new scene cannot go unchecked.
#[test]
fn every_scene_has_a_golden_case() {
    let inputs: Vec<String> = cases()
        .iter()
        .filter_map(|p| std::fs::read_to_string(p).ok())
        .flat_map(|t| {
            t.lines()
                .filter_map(|l| l.strip_prefix("input:").map(|v| v.trim().to_string()))
                .collect::<Vec<_>>()
        })
        .collect();
    for dir in ["scenes", "docs/example"] {
        for entry in std::fs::read_dir(root().join(dir)).unwrap() {
            let name = entry.unwrap().file_name().into_string().unwrap();
            if name.ends_with(".kdl") {
                let path = format!("{dir}/{name}");
                assert!(
                    inputs.contains(&path),
                    "{path} has no case in tests/golden/"
                );
            }
        }
    }
}
