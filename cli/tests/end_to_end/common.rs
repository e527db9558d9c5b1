//! What the modules share: the built command, the checkout's root, paths as text.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// Runs the built `kepler` with `args`, whatever its exit status.
pub(crate) fn kepler(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_kepler"))
        .args(args)
        .output()
        .unwrap()
}

/// The checkout's root.
pub(crate) fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// A path as a command-line argument.
pub(crate) fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}
