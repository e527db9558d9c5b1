//! Reading input files: regular files only (a directory or a device such as `/dev/zero` is
//! an error, not a hang), errors reported where the file was asked for.

use std::path::Path;

use crate::error::{Error, Location, Result};

/// The bytes of the regular file at `path`. `at` is the node that asked for it (an include
/// or `mesh` node), where a missing or unreadable file is reported; else the file itself.
pub(crate) fn read_file(path: &Path, at: Option<&Location>) -> Result<Vec<u8>> {
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
    std::fs::read(path).map_err(|e| fail(format!("cannot read {}: {e}", path.display()), e.kind()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn directories_and_devices_are_refused_at_the_asking_node() {
        let at = Location::line(Path::new("s.kdl"), 3, 5);
        let e = read_file(Path::new("."), Some(&at))
            .unwrap_err()
            .to_string();
        assert_eq!(e, "s.kdl:3:5: cannot read .: it is a directory, not a file");
        if Path::new("/dev/zero").exists() {
            let e = read_file(Path::new("/dev/zero"), None)
                .unwrap_err()
                .to_string();
            assert!(
                e.ends_with("it is not a regular file (a device, pipe or socket)"),
                "{e}"
            );
        }
        let e = read_file(Path::new("/no/such.kdl"), None)
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("/no/such.kdl: cannot read /no/such.kdl: "),
            "{e}"
        );
    }
}
