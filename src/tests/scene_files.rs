//! Scene files: every example in `scenes/` loads cleanly, every `scene_*` fixture in
//! `tests/fixtures/bad/` is refused with an error at the line its `// expect-line: N` names,
//! and no damaged input makes the loader panic.

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::{Path, PathBuf};
use std::sync::Arc;

use crate::load::load_scene;
use crate::scene::{Content, Object};

fn crate_dir(sub: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(sub)
}

/// The files in `dir` whose names start with `prefix` and end with `suffix`, sorted.
fn files(dir: &Path, prefix: &str, suffix: &str) -> Vec<PathBuf> {
    let mut out: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.expect("directory entry").path())
        .filter(|p| {
            let name = p.file_name().and_then(|n| n.to_str()).unwrap_or("");
            name.starts_with(prefix) && name.ends_with(suffix)
        })
        .collect();
    out.sort();
    out
}

#[test]
fn every_example_scene_loads_without_warnings() {
    let scenes = files(&crate_dir("scenes"), "", ".kdl");
    assert!(scenes.len() >= 3, "only {} scenes", scenes.len());
    for path in scenes {
        let mut warnings = Vec::new();
        let scene = load_scene(
            &path,
            &crate::LoadOptions::default(),
            &mut warnings,
            &crate::Progress::default(),
        )
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        assert!(warnings.is_empty(), "{}: {warnings:?}", path.display());
        assert!(scene.face_count() > 0, "{}", path.display());
        assert!(scene.camera.is_some(), "{}: no camera", path.display());
        assert!(scene.cbox().has_interior());
    }
}

/// The prototype of an instance.
fn prototype(o: &Object) -> &Arc<Object> {
    match &o.content {
        Content::Instance(i) => &i.prototype,
        _ => panic!("{} is not an instance", o.name),
    }
}

fn child<'a>(o: &'a Object, name: &str) -> &'a Object {
    o.subobjects()
        .iter()
        .find(|s| s.name == name)
        .unwrap_or_else(|| panic!("{} has no {name}", o.name))
}

#[test]
fn town_places_one_house_many_times() {
    let mut warnings = Vec::new();
    let town = load_scene(
        &crate_dir("scenes/town.kdl"),
        &crate::LoadOptions::default(),
        &mut warnings,
        &crate::Progress::default(),
    )
    .unwrap();
    let right = child(&town.root, "right");
    let left = child(&town.root, "left");
    let house = prototype(child(right, "house1"));
    for (side, name) in [(right, "house2"), (left, "house1"), (left, "house4")] {
        assert!(Arc::ptr_eq(house, prototype(child(side, name))));
    }
    // The house's INBOX (its core) holds most of its CBOX, and placements carry it along.
    let inbox = house.inbox.expect("the house has an inbox");
    assert!(inbox.volume() > 0.6 * house.cbox.volume());
    let placed = child(right, "house1");
    let placed_inbox = placed.inbox.expect("a quarter turn keeps the inbox");
    assert!((placed_inbox.volume() - inbox.volume()).abs() < 1e-9);
    assert!(placed.cbox.contains_box(&placed_inbox));
    // The clock dial carries its markings.
    let dial = child(child(&town.root, "tower"), "dial");
    let texture = dial.faces()[0].texture.as_ref().expect("dial markings");
    assert_eq!((texture.polygons.len(), texture.lines.len()), (1, 14));
}

#[test]
fn polyhedra_shows_all_eighteen_solids() {
    let mut warnings = Vec::new();
    let scene = load_scene(
        &crate_dir("scenes/polyhedra.kdl"),
        &crate::LoadOptions::default(),
        &mut warnings,
        &crate::Progress::default(),
    )
    .unwrap();
    let names: Vec<String> = scene
        .leaves()
        .iter()
        .map(|l| l.path.rsplit('/').next().unwrap_or("").to_string())
        .collect();
    for solid in crate::primitives::names() {
        assert!(names.iter().any(|n| n == solid), "{solid} missing");
    }
    for leaf in scene.leaves() {
        assert!(leaf.mesh.closed, "{} is not closed", leaf.path);
    }
}

/// The line named by the fixture's `// expect-line: N` comment.
fn expected_line(path: &Path) -> usize {
    let bytes = std::fs::read(path).expect("fixture readable");
    let text = String::from_utf8_lossy(&bytes);
    let rest = text
        .split("expect-line:")
        .nth(1)
        .unwrap_or_else(|| panic!("{}: no `// expect-line: N` comment", path.display()));
    let digits: String = rest
        .trim_start()
        .chars()
        .take_while(char::is_ascii_digit)
        .collect();
    digits.parse().expect("a line number")
}

#[test]
fn every_bad_scene_is_refused_at_its_line() {
    let fixtures = files(&crate_dir("tests/fixtures/bad"), "scene_", ".kdl");
    assert!(fixtures.len() >= 20, "only {} fixtures", fixtures.len());
    for path in fixtures {
        let line = expected_line(&path);
        let result = catch_unwind(|| {
            load_scene(
                &path,
                &crate::LoadOptions::default(),
                &mut Vec::new(),
                &crate::Progress::default(),
            )
        });
        let Ok(result) = result else {
            panic!("{}: the loader panicked", path.display())
        };
        let Err(e) = result else {
            panic!("{}: loaded without error", path.display())
        };
        let msg = e.to_string();
        let prefix = format!("{}:{line}:", path.display());
        assert!(
            msg.starts_with(&prefix),
            "expected {prefix}COL: ...\n got {msg}"
        );
        let col = &msg[prefix.len()..];
        let digits = col.chars().take_while(char::is_ascii_digit).count();
        assert!(
            digits > 0 && col[digits..].starts_with(": "),
            "no column: {msg}"
        );
    }
}

/// Loads `text` as a scene file at `path`; must not panic.
fn load_text(path: &Path, text: &[u8]) {
    std::fs::write(path, text).expect("temporary file");
    let r = catch_unwind(AssertUnwindSafe(|| {
        load_scene(
            path,
            &crate::LoadOptions::default(),
            &mut Vec::new(),
            &crate::Progress::default(),
        )
    }));
    assert!(
        r.is_ok(),
        "the loader panicked on:\n{}",
        String::from_utf8_lossy(text)
    );
}

#[test]
fn damaged_scenes_never_panic() {
    let dir = std::env::temp_dir().join(format!("kepler-scene-fuzz-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("damaged.kdl");
    let text = std::fs::read(crate_dir("scenes/assembly.kdl")).unwrap();
    // Every prefix ending at a line break.
    for (i, _) in text.iter().enumerate().filter(|(_, &b)| b == b'\n') {
        load_text(&path, &text[..i]);
    }
    // Deterministic byte mutations (xorshift).
    let mut rng = kepler_testkit::Rng::new(0x2545_f491_4f6c_dd1d);
    let mut next = || rng.next_u64();
    let replacements = b"0-9.#{}\";=/ \n\xffe";
    for _ in 0..300 {
        let mut t = text.clone();
        for _ in 0..3 {
            let at = (next() % t.len() as u64) as usize;
            t[at] = replacements[(next() % replacements.len() as u64) as usize];
        }
        load_text(&path, &t);
    }
    let _ = std::fs::remove_dir_all(&dir);
}
