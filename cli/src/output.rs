//! Output files written atomically: a failed or interrupted run never leaves a truncated file
//! in place of a good one. Every file the commands write goes through [`Staged`] ([`write`]
//! for bytes made whole).

use std::ffi::OsString;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

use anyhow::{anyhow, Result};

/// Writes `bytes` to `path`, naming it in the error, through a [`Staged`] file.
pub(crate) fn write(path: &Path, bytes: impl AsRef<[u8]>) -> Result<()> {
    let mut f = Staged::create(path)?;
    f.write_all(bytes.as_ref()).map_err(|e| f.named(e))?;
    f.commit()
}

/// An output file being written. A regular file (or a new one) is written to a temporary
/// file beside it (same directory, so the same file system), which replaces it by a rename
/// on [`Staged::commit`] and is removed when dropped uncommitted; a path that exists and is
/// not a regular file (`/dev/stdout`, a pipe) is written directly, as it cannot be replaced.
pub(crate) struct Staged {
    path: PathBuf,
    /// The temporary file, until committed (None for a device).
    tmp: Option<PathBuf>,
    file: BufWriter<File>,
}

impl Staged {
    /// Opens the output `path` (its temporary beside it), naming it in the error.
    pub(crate) fn create(path: &Path) -> Result<Staged> {
        let special = std::fs::metadata(path).is_ok_and(|m| !m.is_file() && !m.is_dir());
        let tmp = (!special).then(|| temporary_beside(path)).transpose()?;
        let at = tmp.as_deref().unwrap_or(path);
        let file = File::create(at).map_err(|e| anyhow!("{}: {e}", path.display()))?;
        Ok(Staged {
            path: path.to_path_buf(),
            tmp,
            file: BufWriter::with_capacity(1 << 16, file),
        })
    }

    /// `e` as an error of this output, named by its path.
    pub(crate) fn named(&self, e: impl std::fmt::Display) -> anyhow::Error {
        anyhow!("{}: {e}", self.path.display())
    }

    /// Finishes the file: everything written out, then put in place of the old one.
    pub(crate) fn commit(mut self) -> Result<()> {
        self.file.flush().map_err(|e| self.named(e))?;
        if let Some(tmp) = self.tmp.take() {
            if let Err(e) = std::fs::rename(&tmp, &self.path) {
                let _ = std::fs::remove_file(&tmp);
                return Err(self.named(e));
            }
        }
        Ok(())
    }
}

impl Write for Staged {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        self.file.write(buf)
    }

    fn flush(&mut self) -> std::io::Result<()> {
        self.file.flush()
    }
}

impl Drop for Staged {
    /// An uncommitted file leaves nothing behind.
    fn drop(&mut self) {
        if let Some(tmp) = self.tmp.take() {
            let _ = std::fs::remove_file(tmp);
        }
    }
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
