//! The shared models lookup and the skips that cannot pass silently.
//!
//! The models live in `$KEPLER_MODELS`, else in `shared/models` beside the checkout. A test that
//! needs one and cannot find it skips: it writes a skip line straight to the process's stderr
//! (past cargo's capture, so every `cargo test` shows it) and to its captured stdout (so a
//! failing run's report carries it). With `KEPLER_REQUIRE_MODELS=1`, as CI sets it, the test
//! fails instead, naming the path it looked for: a mistyped name cannot pass as a skip.

use std::io::Write as _;
use std::path::PathBuf;

/// The variable naming the models folder.
pub const MODELS_ENV: &str = "KEPLER_MODELS";

/// The variable that turns a missing model from a skip into a failure.
pub const REQUIRE_MODELS_ENV: &str = "KEPLER_REQUIRE_MODELS";

/// The folder the shared models are looked for in (it may not exist).
fn models_path() -> PathBuf {
    std::env::var_os(MODELS_ENV)
        .map(PathBuf::from)
        .unwrap_or_else(|| {
            PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../../shared/models"))
        })
}

/// Whether the variable `var` is set to anything but empty or "0".
pub fn require(var: &str) -> bool {
    std::env::var_os(var).is_some_and(|v| !v.is_empty() && v != "0")
}

/// Skips what `what` names because of `why`; fails instead when `require_var` is set.
pub fn skip(require_var: &str, what: &str, why: &str) {
    assert!(
        !require(require_var),
        "{what}: {why} ({require_var} is set)"
    );
    let line = format!("SKIPPED {what}: {why} (set {require_var}=1 to fail instead)");
    println!("{line}");
    let _ = writeln!(std::io::stderr().lock(), "{line}");
}

/// The shared models folder, or None after a skip line when it is absent.
pub fn models_dir() -> Option<PathBuf> {
    let dir = models_path();
    if dir.is_dir() {
        return Some(dir);
    }
    let why = format!("no models folder at {} (set {MODELS_ENV})", dir.display());
    skip(REQUIRE_MODELS_ENV, "the shared models", &why);
    None
}

/// The shared model `name` (e.g. "ogre.obj"), or None after a skip line naming the path
/// looked for.
pub fn model(name: &str) -> Option<PathBuf> {
    let path = models_dir()?.join(name);
    if path.is_file() {
        return Some(path);
    }
    let why = format!("no file at {}", path.display());
    skip(REQUIRE_MODELS_ENV, name, &why);
    None
}
