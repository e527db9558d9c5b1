//! Where the files a scene refers to (includes and meshes) may be: `--include-root DIR`
//! confines them under one directory, symlinks and `..` resolved first.
//!
//! The rules, documented in docs/scene-format.md: a path is relative to the file that names it
//! (or absolute); an include is a `.kdl` file, a mesh an `.obj`, `.stl` or `.ply` file, each a
//! regular file of bounded size; includes nest at most [`MAX_INCLUDE_DEPTH`] deep; with a root,
//! a file whose real path (every symlink followed) is not under the root is refused before it
//! is opened. Errors about a refused file name it and never quote its content.

use std::path::{Path, PathBuf};

use crate::error::{Error, Location, Result};

/// The deepest chain of includes followed (the top file is depth 0): bounds the loader's
/// recursion long before the stack would run out (5,000 nested includes overflowed it).
pub(crate) const MAX_INCLUDE_DEPTH: usize = 64;

/// The canonical form of the root directory `dir`, or the error naming it.
pub(crate) fn canonical_root(dir: &Path) -> Result<PathBuf> {
    let c = std::fs::canonicalize(dir).map_err(|e| {
        let msg = format!("--include-root {}: {e}", dir.display());
        Error::Usage(msg)
    })?;
    if !c.is_dir() {
        return Err(Error::Usage(format!(
            "--include-root {}: not a directory",
            dir.display()
        )));
    }
    Ok(c)
}

/// An error at `at` when `canonical` (the real path of `shown`) is not under `root`.
pub(crate) fn check_under(
    root: Option<&Path>,
    shown: &Path,
    canonical: &Path,
    at: &Location,
) -> Result<()> {
    match root {
        Some(r) if !canonical.starts_with(r) => Err(Error::invalid(
            at.clone(),
            format!(
                "{} is outside the include root {} (--include-root): its real path is {}",
                shown.display(),
                r.display(),
                canonical.display()
            ),
        )),
        _ => Ok(()),
    }
}

/// An error at `at` unless `path` names a scene file (`.kdl`, any case): an include of any
/// other file would read it as KDL and could quote it in a message.
pub(crate) fn check_scene_name(path: &Path, at: &Location) -> Result<()> {
    let kdl = path
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("kdl"));
    if kdl {
        Ok(())
    } else {
        Err(Error::invalid(
            at.clone(),
            format!(
                "include {}: an included file must be a scene file (.kdl)",
                path.display()
            ),
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paths_outside_the_root_are_refused() {
        let at = Location::line(Path::new("s.kdl"), 2, 1);
        let root = Path::new("/srv/scenes");
        assert!(check_under(
            Some(root),
            Path::new("a.kdl"),
            Path::new("/srv/scenes/a.kdl"),
            &at
        )
        .is_ok());
        assert!(check_under(None, Path::new("x"), Path::new("/etc/x"), &at).is_ok());
        let e = check_under(
            Some(root),
            Path::new("../x.kdl"),
            Path::new("/srv/x.kdl"),
            &at,
        )
        .unwrap_err()
        .to_string();
        assert_eq!(
            e,
            "s.kdl:2:1: ../x.kdl is outside the include root /srv/scenes (--include-root): its real path is /srv/x.kdl"
        );
        // A sibling whose name starts with the root's is not under it.
        assert!(check_under(
            Some(root),
            Path::new("x"),
            Path::new("/srv/scenes2/x.kdl"),
            &at
        )
        .is_err());
    }

    #[test]
    fn only_scene_files_are_included() {
        let at = Location::line(Path::new("s.kdl"), 1, 1);
        assert!(check_scene_name(Path::new("a/b.KDL"), &at).is_ok());
        for p in ["/etc/passwd", "x.obj", "kdl", "a.kdl.txt"] {
            let e = check_scene_name(Path::new(p), &at).unwrap_err().to_string();
            assert!(e.contains("must be a scene file (.kdl)"), "{e}");
        }
        assert!(canonical_root(Path::new("/no/such/dir")).is_err());
        assert!(canonical_root(Path::new("Cargo.toml")).is_err());
    }
}
