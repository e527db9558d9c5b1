//! Every scene in scenes/ re-renders to its golden visible-polygon set (tests/golden/*.json),
//! through `kepler check` (the set made in memory) and byte for byte through `kepler render
//! --json` (the set written to its file as it is made). Regenerate after an intended change with
//! `kepler check scenes/NAME.kdl --golden tests/golden/NAME.json --update`.

use std::path::Path;
use std::process::Command;

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
