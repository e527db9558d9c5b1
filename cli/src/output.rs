//! Output files written atomically: a failed or interrupted run never leaves a truncated file
//! in place of a good one. Every file the commands write goes through [`write`].

use std::ffi::OsString;
use std::path::{Path, PathBuf};

use anyhow::{anyhow, Result};

/// Writes `bytes` to `path`, naming it in the error. A regular file (or a new one) is written
/// to a temporary file beside it (same directory, so the same file system), which then
/// replaces it by a rename; a path that exists and is not a regular file (`/dev/stdout`, a
/// pipe) is written directly, as it cannot be replaced.
pub(crate) fn write(path: &PathBuf, bytes: impl AsRef<[u8]>) -> Result<()> {
    let named = |e: std::io::Error| anyhow!("{}: {e}", path.display());
    let special = std::fs::metadata(path).is_ok_and(|m| !m.is_file() && !m.is_dir());
    if special {
        return std::fs::write(path, bytes).map_err(named);
    }
    let tmp = temporary_beside(path)?;
    let done = std::fs::write(&tmp, bytes).and_then(|()| std::fs::rename(&tmp, path));
    done.map_err(|e| {
        let _ = std::fs::remove_file(&tmp);
        named(e)
    })
}

/// A hidden temporary name beside `path`, unique to this process: `.NAME.kepler-PID.tmp`.
fn temporary_beside(path: &Path) -> Result<PathBuf> {
    let name = path
        .file_name()
        .ok_or_else(|| anyhow!("{}: not a file name", path.display()))?;
    let mut tmp = OsString::from(".");
    tmp.push(name);
    tmp.push(format!(".kepler-{}.tmp", std::process::id()));
    Ok(path.with_file_name(tmp))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dir(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("kepler-out-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    #[test]
    fn replaces_the_file_and_leaves_no_temporary() {
        let d = dir("replace");
        let f = d.join("a.json");
        std::fs::write(&f, "old").unwrap();
        write(&f, "new").unwrap();
        assert_eq!(std::fs::read_to_string(&f).unwrap(), "new");
        let names: Vec<_> = std::fs::read_dir(&d)
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert_eq!(names, vec![OsString::from("a.json")]);
    }

    #[test]
    fn a_failed_write_keeps_the_old_file_and_names_the_path() {
        let d = dir("fail");
        // A directory in the way: the rename fails, nothing is left behind.
        let f = d.join("out.svg");
        std::fs::create_dir(&f).unwrap();
        std::fs::write(f.join("keep"), "x").unwrap();
        let e = write(&f, "new").unwrap_err().to_string();
        assert!(e.starts_with(&f.display().to_string()), "{e}");
        assert_eq!(std::fs::read_dir(&d).unwrap().count(), 1);
        // A missing directory: named too.
        let e = write(&d.join("no/such.json"), "x").unwrap_err().to_string();
        assert!(e.contains("no/such.json"), "{e}");
    }

    #[test]
    fn devices_are_written_directly() {
        write(&PathBuf::from("/dev/null"), "x").unwrap();
    }
}
