//! README's commands and its complete scene example run as written: the example is the file
//! `docs/example/town.kdl` byte for byte, and renders without a warning.

use std::process::Command;

use super::common::root;

/// The text of the first fenced block of `lang` in README.md.
fn block(lang: &str) -> String {
    let readme = std::fs::read_to_string(root().join("README.md")).unwrap();
    let fence = format!("```{lang}\n");
    let start = readme.find(&fence).expect("README has the block") + fence.len();
    let len = readme[start..].find("```").expect("the block ends");
    readme[start..start + len].to_string()
}

#[test]
fn the_complete_example_is_a_file_that_renders_cleanly() {
    let file = root().join("docs/example/town.kdl");
    assert_eq!(block("kdl"), std::fs::read_to_string(&file).unwrap());
    let out = std::env::temp_dir().join(format!("kepler-readme-{}.svg", std::process::id()));
    let o = Command::new(env!("CARGO_BIN_EXE_kepler"))
        .arg("render")
        .arg(&file)
        .arg("--svg")
        .arg(&out)
        .args(["--layers", "object"])
        .output()
        .unwrap();
    assert!(o.status.success(), "{o:?}");
    assert!(
        o.stderr.is_empty(),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    // Both top-level objects (the included trees and the town with its mesh) are drawn.
    let svg = std::fs::read_to_string(&out).unwrap();
    assert!(svg.contains("inkscape:label=\"1 trees\""), "{svg}");
    assert!(svg.contains("inkscape:label=\"2 town\""), "{svg}");
    let _ = std::fs::remove_file(out);
}

#[test]
fn install_uses_the_lock_file() {
    let sh = block("sh");
    assert!(sh.contains("cargo install --locked --path cli"), "{sh}");
}

#[test]
fn the_first_command_writes_only_where_git_ignores() {
    let sh = block("sh");
    let first = sh.lines().next().unwrap_or_default();
    let outputs: Vec<&str> = first
        .split_whitespace()
        .skip_while(|w| !w.starts_with("--"))
        .collect::<Vec<_>>()
        .windows(2)
        .filter(|w| ["--svg", "--png", "--json"].contains(&w[0]))
        .map(|w| w[1])
        .collect();
    assert_eq!(outputs.len(), 3, "{first}");
    let ignore = std::fs::read_to_string(root().join(".gitignore")).unwrap();
    assert!(ignore.lines().any(|l| l == "/target"), "{ignore}");
    for path in outputs {
        assert!(
            path.starts_with("target/"),
            "{path} is not in the ignored target/"
        );
    }
}

#[test]
fn the_test_command_shares_the_install_profile() {
    let readme = std::fs::read_to_string(root().join("README.md")).unwrap();
    assert!(readme.contains("cargo test --workspace --locked --release"));
    let ci = std::fs::read_to_string(root().join(".ci/run")).unwrap();
    assert!(
        ci.contains("cargo test --workspace --locked --release"),
        "CI runs README's command"
    );
}
