//! Reading input files: regular files only (a directory or a device such as `/dev/zero` is
//! an error, not a hang), of bounded size, errors reported where the file was asked for.
//!
//! A file over its kind's limit is refused before a byte is read (a sparse 64 GB file reports
//! 64 GB), and again if it grows past the limit while being read. A big mesh file, once its
//! size is known to be within the limit, is read on all threads (each reads its own fixed
//! ranges of the file into their places); otherwise nothing is reserved from the size the
//! file system reports: the buffer grows with the bytes actually read.

use std::io::Read;
use std::path::Path;

use crate::count::Count;
use crate::error::{Error, Location, Result};

/// Bytes read between two adds to the progress.
const READ_CHUNK: u64 = 1 << 22;

/// The largest scene file (and included file) read: 64 MiB of KDL text, far beyond any
/// scene written by hand or by a tool (the 10,000-object town is 1.3 MB).
pub(crate) const MAX_SCENE_BYTES: u64 = 64 << 20;

/// The largest mesh file read: 4 GiB, more than an ASCII STL (the most verbose format, about
/// 250 bytes a triangle) of the default face limit, 12 million faces, needs.
pub(crate) const MAX_MESH_BYTES: u64 = 4 << 30;

/// The most bytes reserved before they are read (the buffer then grows as bytes arrive).
const FIRST_RESERVE: u64 = 1 << 24;

/// The bytes of the mesh-sized file at `path` (at most [`MAX_MESH_BYTES`]), read as the
/// `Read` phase of the load stage in `progress`; `at` as for [`read_file`].
pub(crate) fn read_mesh_bytes(
    path: &Path,
    at: Option<&Location>,
    progress: &crate::progress::Progress,
) -> Result<Vec<u8>> {
    use crate::progress::{Phase, Stage};
    let len = file_len(path, at, MAX_MESH_BYTES)?;
    progress.enter_phase(Stage::Load, Phase::Read, len);
    read_file(path, at, MAX_MESH_BYTES, progress.count())
}

/// The bytes of the regular file at `path`, of at most `limit` bytes, counted in `done` as
/// they are read (once per chunk). `at` is the node that asked for it (an include or `mesh`
/// node), where a missing, unreadable or too large file is reported; else the file itself.
pub(crate) fn read_file(
    path: &Path,
    at: Option<&Location>,
    limit: u64,
    done: Count,
) -> Result<Vec<u8>> {
    let len = check_regular(path, at)?;
    check_size(path, at, len, limit)?;
    let file = std::fs::File::open(path).map_err(|e| failure(path, at, e))?;
    let mut bytes = read_start(&file, len, done).map_err(|e| failure(path, at, e))?;
    // In chunks until the end, wherever that is (the file may have changed size).
    loop {
        let n = (&file)
            .take(READ_CHUNK)
            .read_to_end(&mut bytes)
            .map_err(|e| failure(path, at, e))?;
        if n == 0 {
            return Ok(bytes);
        }
        check_size(path, at, bytes.len() as u64, limit)?;
        done.add(n);
    }
}

/// Files read on all threads from this size on (a smaller one is read in one pass): a
/// 4 MB mesh's read was a tenth of its load stage's time on one thread.
const PARALLEL_READ_FROM: u64 = 1 << 20;

/// Bytes one thread reads at a time when a file is read on all threads.
const PARALLEL_PART: u64 = 1 << 20;

/// The first `len` bytes of `file` read on all threads, in fixed ranges of [`PARALLEL_PART`]
/// bytes, the file's position then moved past them (counted in `done` once all are read);
/// for a small file, on one thread, or where the file is no longer that long, nothing read
/// (the reading goes on from the position, one pass to the end).
fn read_start(file: &std::fs::File, len: u64, done: Count) -> std::io::Result<Vec<u8>> {
    let empty = || Vec::with_capacity(len.min(FIRST_RESERVE) as usize);
    if len < PARALLEL_READ_FROM || rayon::current_num_threads() == 1 {
        return Ok(empty());
    }
    #[cfg(unix)]
    {
        use rayon::prelude::*;
        use std::io::{Seek, SeekFrom};
        use std::os::unix::fs::FileExt;
        // Zeroed pages from the system, first touched by the threads reading into them.
        let mut bytes = vec![0u8; len as usize];
        let read = bytes
            .par_chunks_mut(PARALLEL_PART as usize)
            .enumerate()
            .try_for_each(|(k, part)| file.read_exact_at(part, k as u64 * PARALLEL_PART));
        match read {
            Ok(()) => {
                (&*file).seek(SeekFrom::Start(len))?;
                done.add(bytes.len());
                Ok(bytes)
            }
            // Shorter than it was (it changed while read): read in one pass instead.
            Err(e) if e.kind() == std::io::ErrorKind::UnexpectedEof => Ok(empty()),
            Err(e) => Err(e),
        }
    }
    #[cfg(not(unix))]
    Ok(empty())
}

/// The size in bytes of the regular file at `path`, at most `limit` (errors as
/// [`read_file`]'s).
pub(crate) fn file_len(path: &Path, at: Option<&Location>, limit: u64) -> Result<usize> {
    let len = check_regular(path, at)?;
    check_size(path, at, len, limit)?;
    Ok(len as usize)
}

/// The error for a file of `len` bytes, over `limit`.
fn check_size(path: &Path, at: Option<&Location>, len: u64, limit: u64) -> Result<()> {
    if len <= limit {
        return Ok(());
    }
    let loc = at.cloned().unwrap_or_else(|| Location::file(path));
    let what = format!(
        "cannot read {}: it is {len} bytes, more than the limit of {limit} for this kind of file",
        path.display()
    );
    Err(Error::Io(
        loc,
        std::io::Error::new(std::io::ErrorKind::InvalidData, what),
    ))
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
        let e = read_file(Path::new("."), Some(&at), MAX_SCENE_BYTES, Count::NONE)
            .unwrap_err()
            .to_string();
        assert_eq!(e, "s.kdl:3:5: cannot read .: it is a directory, not a file");
        if Path::new("/dev/zero").exists() {
            let e = read_file(Path::new("/dev/zero"), None, MAX_SCENE_BYTES, Count::NONE)
                .unwrap_err()
                .to_string();
            assert!(
                e.ends_with("it is not a regular file (a device, pipe or socket)"),
                "{e}"
            );
        }
        let e = read_file(
            Path::new("/no/such.kdl"),
            None,
            MAX_SCENE_BYTES,
            Count::NONE,
        )
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
        let bytes = read_file(path, None, MAX_SCENE_BYTES, Count::to(&p)).unwrap();
        assert_eq!(bytes, std::fs::read(path).unwrap());
        assert_eq!(p.load(Ordering::Relaxed), bytes.len());
        assert_eq!(file_len(path, None, MAX_SCENE_BYTES).unwrap(), bytes.len());
        let e = read_file(Path::new("."), None, MAX_SCENE_BYTES, Count::to(&p)).unwrap_err();
        assert!(
            e.to_string().ends_with("it is a directory, not a file"),
            "{e}"
        );
    }

    #[test]
    fn a_big_file_read_on_several_threads_is_its_bytes() {
        let d = std::env::temp_dir().join(format!("kepler-read-big-{}", std::process::id()));
        std::fs::create_dir_all(&d).unwrap();
        let f = d.join("big.obj");
        // Not a whole number of ranges, each byte told apart from its neighbours.
        let want: Vec<u8> = (0..PARALLEL_READ_FROM as usize + 3 * READ_CHUNK as usize + 12_345)
            .map(|i| (i % 251) as u8)
            .collect();
        std::fs::write(&f, &want).unwrap();
        let p = AtomicUsize::new(0);
        let pool = crate::chunked::pool(3);
        let got = pool
            .install(|| read_file(&f, None, MAX_MESH_BYTES, Count::to(&p)))
            .unwrap();
        assert!(got == want, "the bytes read are the file's");
        assert_eq!(p.load(Ordering::Relaxed), want.len());
        let _ = std::fs::remove_dir_all(&d);
    }

    #[test]
    fn a_sparse_file_over_the_limit_is_refused_before_reading() {
        let d = std::env::temp_dir().join(format!("kepler-read-{}", std::process::id()));
        std::fs::create_dir_all(&d).unwrap();
        let f = d.join("sparse.obj");
        // A hole of 64 GB: no disk used, and nothing may be reserved from its size.
        std::fs::File::create(&f)
            .unwrap()
            .set_len(64 << 30)
            .unwrap();
        let e = read_file(&f, None, MAX_MESH_BYTES, Count::NONE)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("it is 68719476736 bytes, more than the limit of 4294967296"),
            "{e}"
        );
        let e = file_len(&f, None, MAX_MESH_BYTES).unwrap_err().to_string();
        assert!(e.contains("more than the limit"), "{e}");
        // Just over a small limit: refused; at it: read.
        std::fs::write(&f, "v 0 0 0\n").unwrap();
        assert!(read_file(&f, None, 7, Count::NONE).is_err());
        assert_eq!(read_file(&f, None, 8, Count::NONE).unwrap().len(), 8);
        let _ = std::fs::remove_dir_all(&d);
    }
}
