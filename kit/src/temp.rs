//! Scratch folders for tests: one per test and process, so parallel runs never share files.

use std::path::PathBuf;

/// A fresh, empty folder `kepler-{suite}-{pid}-{name}` under the system's temporary folder.
pub fn temp_dir(suite: &str, name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("kepler-{suite}-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("a writable temporary folder");
    d
}
