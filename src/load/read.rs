//! Reading input files: regular files only (a directory or a device such as `/dev/zero` is
//! an error, not a hang), errors reported where the file was asked for.

use std::io::Read;
use std::path::Path;

use crate::count::Count;
use crate::error::{Error, Location, Result};

/// Bytes read between two adds to the progress.
const READ_CHUNK: u64 = 1 << 22;

/// The bytes of the regular file at `path`, counted in `done` as they are read (once per
/// chunk). `at` is the node that asked for it (an include or `mesh` node), where a missing
/// or unreadable file is reported; else the file itself.
pub(crate) fn read_file(path: &Path, at: Option<&Location>, done: Count) -> Result<Vec<u8>> {
    let len = check_regular(path, at)?;
    let file = std::fs::File::open(path).map_err(|e| failure(path, at, e))?;
    let mut bytes = Vec::with_capacity(len as usize);
    // In chunks until the end, wherever that is (the file may have changed size).
    loop {
        let n = (&file)
            .take(READ_CHUNK)
            .read_to_end(&mut bytes)
            .map_err(|e| failure(path, at, e))?;
        if n == 0 {
            return Ok(bytes);
        }
        done.add(n);
    }
}

/// The size in bytes of the regular file at `path` (errors as [`read_file`]'s).
pub(crate) fn file_len(path: &Path, at: Option<&Location>) -> Result<usize> {
    check_regular(path, at).map(|len| len as usize)
}

/// The error for a file that cannot be read.
fn failure(path: &Path, at: Option<&Location>, e: std::io::Error) -> Error {
    let loc = at.cloned().unwrap_or_else(|| Location::file(path));
    let what = format!("cannot read {}: {e}", path.display());
    Error::Io(loc, std::io::Error::new(e.kind(), what))
}

/// The size of the regular file at `path`, or the error for a missing file, a directory or
/// a device, reported at `at` (else the file itself).
fn check_regular(path: &Path, at: Option<&Location>) -> Result<u64> {
    let fail = |what: String, kind: std::io::ErrorKind| {
        let loc = at.cloned().unwrap_or_else(|| Location::file(path));
        Error::Io(loc, std::io::Error::new(kind, what))
    };
    let meta = std::fs::metadata(path)
        .map_err(|e| fail(format!("cannot read {}: {e}", path.display()), e.kind()))?;
    if meta.is_dir() {
        return Err(fail(
            format!(
                "cannot read {}: it is a directory, not a file",
                path.display()
            ),
            std::io::ErrorKind::InvalidInput,
        ));
    }
    if !meta.is_file() {
        return Err(fail(
            format!(
                "cannot read {}: it is not a regular file (a device, pipe or socket)",
                path.display()
            ),
            std::io::ErrorKind::InvalidInput,
        ));
    }
    Ok(meta.len())
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::{AtomicUsize, Ordering};

    #[test]
    fn directories_and_devices_are_refused_at_the_asking_node() {
        let at = Location::line(Path::new("s.kdl"), 3, 5);
        let e = read_file(Path::new("."), Some(&at), Count::NONE)
            .unwrap_err()
            .to_string();
        assert_eq!(e, "s.kdl:3:5: cannot read .: it is a directory, not a file");
        if Path::new("/dev/zero").exists() {
            let e = read_file(Path::new("/dev/zero"), None, Count::NONE)
                .unwrap_err()
                .to_string();
            assert!(
                e.ends_with("it is not a regular file (a device, pipe or socket)"),
                "{e}"
            );
        }
        let e = read_file(Path::new("/no/such.kdl"), None, Count::NONE)
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("/no/such.kdl: cannot read /no/such.kdl: "),
            "{e}"
        );
    }

    #[test]
    fn a_read_counts_its_bytes() {
        let path = Path::new("scenes/town.kdl");
        let p = AtomicUsize::new(0);
        let bytes = read_file(path, None, Count::to(&p)).unwrap();
        assert_eq!(bytes, std::fs::read(path).unwrap());
        assert_eq!(p.load(Ordering::Relaxed), bytes.len());
        assert_eq!(file_len(path, None).unwrap(), bytes.len());
        let e = read_file(Path::new("."), None, Count::to(&p)).unwrap_err();
        assert!(
            e.to_string().ends_with("it is a directory, not a file"),
            "{e}"
        );
    }
}
