//! Output files written as one transaction: a failed or interrupted run leaves every old
//! output as it was and no temporary behind. Every file the commands write goes through
//! [`OutputFiles`] ([`write`] for one file made whole).
//!
//! - Before anything is computed, [`OutputFiles::new`] refuses two outputs on one path and an
//!   output that is an input (symlinks and `..` resolved, hard links by inode), and proves
//!   each output's directory writable by creating and removing a temporary there.
//! - Each output is written to a temporary beside it (same directory, so the same file
//!   system), made when its first bytes are (an abort before that leaves nothing), created
//!   exclusively (`create_new`: a file or symlink planted at its name is
//!   never written through; another name is tried), and closed when written.
//! - Only when every output of the run is written does [`OutputFiles::commit`] put them in place,
//!   each by a rename, each with the mode of the file it replaces.
//! - An error drops the transaction, which removes its temporaries; SIGINT, SIGTERM and SIGHUP
//!   reach a watcher thread (signal-hook: libc and nothing else) that removes them and exits
//!   with 128 + the signal. SIGKILL and an abort cannot be caught: their temporary (hidden,
//!   `.NAME.kepler-PID-N.tmp`) stays until the next run that puts NAME in place removes the
//!   temporaries of NAME whose process is gone ([`remove_stale`]; Linux, where `/proc` says so).
//! - A path that exists and is not a regular file (`/dev/null`, `/dev/stdout`, a pipe) cannot be
//!   replaced: it is written directly.

use std::ffi::OsString;
use std::fs::{File, OpenOptions};
use std::io::{BufWriter, ErrorKind, Write};
use std::os::unix::fs::MetadataExt;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, PoisonError};

use anyhow::{anyhow, bail, Result};

/// Writes `bytes` to `path`, naming it in the error, as a transaction of one file.
pub(crate) fn write(path: &Path, bytes: impl AsRef<[u8]>) -> Result<()> {
    write_from(&[], path, bytes)
}

/// [`write`], refusing a `path` that is one of `inputs`.
pub(crate) fn write_from(inputs: &[&Path], path: &Path, bytes: impl AsRef<[u8]>) -> Result<()> {
    let mut outs = OutputFiles::new(inputs, &[path])?;
    outs.write(path, bytes.as_ref())?;
    outs.commit()
}

/// Temporaries not yet renamed, shared with the signal watcher.
type Pending = Arc<Mutex<Vec<PathBuf>>>;

/// The outputs of one run: written to temporaries, put in place together.
pub(crate) struct OutputFiles {
    pending: Pending,
    /// Written and closed: (temporary, target), in the order written.
    done: Vec<(PathBuf, PathBuf)>,
    watcher: Option<signal_hook::iterator::Handle>,
}

impl OutputFiles {
    /// A transaction for `outputs`, refusing two on one path, one that is an input, and one
    /// whose directory cannot be written (found now, before a long render).
    pub(crate) fn new(inputs: &[&Path], outputs: &[&Path]) -> Result<OutputFiles> {
        check_paths(inputs, outputs)?;
        let pending: Pending = Arc::default();
        let watcher = watch_signals(&pending);
        let outs = OutputFiles {
            pending,
            done: Vec::new(),
            watcher,
        };
        for p in outputs {
            if !is_device(p) {
                // Made and listed under the lock, so that a signal's watcher sees it.
                let mut pending = lock(&outs.pending);
                let (tmp, file) = temporary_beside(p)?;
                pending.push(tmp.clone());
                drop(pending);
                drop(file);
                std::fs::remove_file(&tmp).map_err(|e| anyhow!("{}: {e}", p.display()))?;
                lock(&outs.pending).retain(|t| t != &tmp);
            }
        }
        Ok(outs)
    }

    /// Output `path`: a device is opened now; a file's temporary beside it is created when
    /// the first bytes are written (a render that dies before its output is made, even by an
    /// abort no handler sees, leaves no empty temporary).
    pub(crate) fn create(&mut self, path: &Path) -> Result<Staged> {
        let mut f = Staged {
            path: path.to_path_buf(),
            tmp: None,
            file: None,
            pending: None,
        };
        if is_device(path) {
            let file = OpenOptions::new()
                .write(true)
                .open(path)
                .map_err(|e| f.named(e))?;
            f.file = Some(BufWriter::with_capacity(1 << 16, file));
        } else {
            f.pending = Some(self.pending.clone());
        }
        Ok(f)
    }

    /// Writes a whole output at once: [`OutputFiles::create`], the bytes, [`OutputFiles::finish`].
    pub(crate) fn write(&mut self, path: &Path, bytes: &[u8]) -> Result<()> {
        let mut f = self.create(path)?;
        f.write_all(bytes).map_err(|e| f.named(e))?;
        self.finish(f)
    }

    /// Closes a written output; it is put in place by [`OutputFiles::commit`].
    pub(crate) fn finish(&mut self, mut f: Staged) -> Result<()> {
        let flushed = f.opened().and_then(|w| w.flush());
        flushed.map_err(|e| f.named(e))?;
        f.file = None;
        if let Some(tmp) = f.tmp.take() {
            self.done.push((tmp, f.path.clone()));
        }
        Ok(())
    }

    /// Puts every finished output in place (keeping the mode of the file it replaces).
    /// A failure removes the temporaries not yet renamed.
    pub(crate) fn commit(mut self) -> Result<()> {
        for (tmp, path) in std::mem::take(&mut self.done) {
            if let Ok(m) = std::fs::metadata(&path) {
                if m.is_file() {
                    std::fs::set_permissions(&tmp, m.permissions())
                        .map_err(|e| anyhow!("{}: {e}", path.display()))?;
                }
            }
            std::fs::rename(&tmp, &path).map_err(|e| anyhow!("{}: {e}", path.display()))?;
            lock(&self.pending).retain(|p| p != &tmp);
            remove_stale(&path);
        }
        Ok(())
    }
}

/// Removes the temporaries of `path` that killed runs left beside it: regular files named
/// `.NAME.kepler-PID-N.tmp` whose PID is neither this process nor a live one. Only where
/// `/proc` lists processes (a PID reused since is taken as alive: the file stays).
fn remove_stale(path: &Path) {
    let (Some(name), Some(dir)) = (path.file_name(), path.parent()) else {
        return;
    };
    if !Path::new("/proc/self").exists() {
        return;
    }
    let dir = if dir.as_os_str().is_empty() {
        Path::new(".")
    } else {
        dir
    };
    let prefix = format!(".{}.kepler-", name.to_string_lossy());
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for e in entries.flatten() {
        let file = e.file_name();
        let Some(pid) = file
            .to_str()
            .and_then(|f| f.strip_prefix(&prefix))
            .and_then(|rest| rest.strip_suffix(".tmp"))
            .and_then(|rest| rest.split_once('-'))
            .filter(|(_, n)| !n.is_empty() && n.bytes().all(|b| b.is_ascii_digit()))
            .and_then(|(pid, _)| pid.parse::<u32>().ok())
        else {
            continue;
        };
        let gone = pid != std::process::id() && !Path::new(&format!("/proc/{pid}")).exists();
        let plain = e.file_type().is_ok_and(|t| t.is_file());
        if gone && plain {
            let _ = std::fs::remove_file(e.path());
        }
    }
}

impl Drop for OutputFiles {
    /// What was not committed leaves nothing behind.
    fn drop(&mut self) {
        if let Some(h) = self.watcher.take() {
            h.close();
        }
        remove_all(&self.pending);
    }
}

/// Removes every pending temporary.
fn remove_all(pending: &Pending) {
    for p in lock(pending).drain(..) {
        let _ = std::fs::remove_file(p);
    }
}

fn lock(p: &Pending) -> std::sync::MutexGuard<'_, Vec<PathBuf>> {
    p.lock().unwrap_or_else(PoisonError::into_inner)
}

/// A thread that, on SIGINT, SIGTERM or SIGHUP, removes the pending temporaries and exits
/// with 128 + the signal (None where signals cannot be watched: the run goes on unwatched).
fn watch_signals(pending: &Pending) -> Option<signal_hook::iterator::Handle> {
    use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};
    let mut signals = signal_hook::iterator::Signals::new([SIGINT, SIGTERM, SIGHUP]).ok()?;
    let handle = signals.handle();
    let pending = pending.clone();
    std::thread::Builder::new()
        .name("signals".into())
        .spawn(move || {
            if let Some(sig) = signals.forever().next() {
                // The lock is held to the exit: no temporary is made after the removal.
                let mut listed = lock(&pending);
                for p in listed.drain(..) {
                    let _ = std::fs::remove_file(p);
                }
                std::process::exit(128 + sig);
            }
        })
        .ok()?;
    Some(handle)
}

/// An output file being written (to its temporary, or directly to a device).
pub(crate) struct Staged {
    path: PathBuf,
    /// The temporary file, once created and until finished (None for a device).
    tmp: Option<PathBuf>,
    file: Option<BufWriter<File>>,
    /// The transaction's pending temporaries, where this one's is listed (None for a device).
    pending: Option<Pending>,
}

impl Staged {
    /// The file, its temporary created (and listed as pending) on first use.
    fn opened(&mut self) -> std::io::Result<&mut BufWriter<File>> {
        if self.file.is_none() {
            // The temporary is made and listed under the pending list's lock: a signal's
            // watcher, which removes the listed ones under that lock, either sees it or
            // ends the process before it is made (made first and listed after, a signal
            // between the two left it behind).
            let mut pending = self.pending.as_ref().map(lock);
            let (tmp, file) =
                temporary_beside(&self.path).map_err(|e| std::io::Error::other(e.to_string()))?;
            if let Some(p) = &mut pending {
                p.push(tmp.clone());
            }
            drop(pending);
            self.tmp = Some(tmp);
            self.file = Some(BufWriter::with_capacity(1 << 16, file));
        }
        Ok(self.file.as_mut().expect("opened above"))
    }

    /// `e` as an error of this output, named by its path.
    pub(crate) fn named(&self, e: impl std::fmt::Display) -> anyhow::Error {
        anyhow!("{}: {e}", self.path.display())
    }
}

impl Write for Staged {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        self.opened()?.write(buf)
    }

    fn flush(&mut self) -> std::io::Result<()> {
        match &mut self.file {
            Some(f) => f.flush(),
            None => Ok(()),
        }
    }
}

/// True for a path that exists and is not a regular file or directory: written directly.
fn is_device(path: &Path) -> bool {
    std::fs::metadata(path).is_ok_and(|m| !m.is_file() && !m.is_dir())
}

/// A new hidden temporary beside `path`, created exclusively: `.NAME.kepler-PID-N.tmp`, the
/// first N whose name is free.
fn temporary_beside(path: &Path) -> Result<(PathBuf, File)> {
    let name = path
        .file_name()
        .ok_or_else(|| anyhow!("{}: not a file name", path.display()))?;
    for n in 0..1000 {
        let mut tmp = OsString::from(".");
        tmp.push(name);
        tmp.push(format!(".kepler-{}-{n}.tmp", std::process::id()));
        let tmp = path.with_file_name(tmp);
        match OpenOptions::new().write(true).create_new(true).open(&tmp) {
            Ok(f) => return Ok((tmp, f)),
            Err(e) if e.kind() == ErrorKind::AlreadyExists => continue,
            Err(e) => bail!("{}: cannot write there: {e}", path.display()),
        }
    }
    bail!("{}: no free temporary name beside it", path.display())
}

/// A path's real path and, where it exists, its (device, inode).
type Identity = (PathBuf, Option<(u64, u64)>);

/// What a path is, for comparing: its real path (symlinks and `..` resolved; for a file not
/// there yet, its directory's real path and its name) and, where it exists, its inode.
fn identity(path: &Path) -> Identity {
    let inode = std::fs::metadata(path).ok().map(|m| (m.dev(), m.ino()));
    let real = std::fs::canonicalize(path).unwrap_or_else(|_| {
        let dir = match path.parent() {
            Some(d) if !d.as_os_str().is_empty() => d,
            _ => Path::new("."),
        };
        let dir = std::fs::canonicalize(dir).unwrap_or_else(|_| dir.to_path_buf());
        dir.join(path.file_name().unwrap_or_default())
    });
    (real, inode)
}

/// Refuses two outputs on one path and an output that is an input (devices may repeat).
fn check_paths(inputs: &[&Path], outputs: &[&Path]) -> Result<()> {
    let same = |a: &Identity, b: &Identity| a.0 == b.0 || (a.1.is_some() && a.1 == b.1);
    let ins: Vec<_> = inputs.iter().map(|p| (p, identity(p))).collect();
    let mut seen: Vec<(&Path, Identity)> = Vec::new();
    for &out in outputs {
        if is_device(out) {
            continue;
        }
        let id = identity(out);
        if let Some((input, _)) = ins.iter().find(|(_, i)| same(i, &id)) {
            bail!(
                "{}: this output is the input {}: refusing to overwrite it",
                out.display(),
                input.display()
            );
        }
        if let Some((first, _)) = seen.iter().find(|(_, s)| same(s, &id)) {
            bail!(
                "{}: two outputs on one file (also {}): give each its own path",
                out.display(),
                first.display()
            );
        }
        seen.push((out, id));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::os::unix::fs::PermissionsExt;

    fn dir(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("kepler-out-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    fn names(d: &Path) -> Vec<OsString> {
        let mut v: Vec<_> = std::fs::read_dir(d)
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        v.sort();
        v
    }

    #[test]
    fn replaces_the_file_keeps_its_mode_and_leaves_no_temporary() {
        let d = dir("replace");
        let f = d.join("a.json");
        std::fs::write(&f, "old").unwrap();
        std::fs::set_permissions(&f, std::fs::Permissions::from_mode(0o600)).unwrap();
        write(&f, "new").unwrap();
        assert_eq!(std::fs::read_to_string(&f).unwrap(), "new");
        let mode = std::fs::metadata(&f).unwrap().permissions().mode() & 0o777;
        assert_eq!(mode, 0o600);
        assert_eq!(names(&d), vec![OsString::from("a.json")]);
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
        assert_eq!(names(&d), vec![OsString::from("out.svg")]);
        // A missing directory: named, before anything is written.
        let e = OutputFiles::new(&[], &[&d.join("no/such.json")])
            .err()
            .unwrap()
            .to_string();
        assert!(e.contains("no/such.json: cannot write there"), "{e}");
    }

    #[test]
    fn nothing_is_replaced_until_everything_is_written() {
        let d = dir("all");
        let (a, b) = (d.join("a.svg"), d.join("b.png"));
        std::fs::write(&a, "old a").unwrap();
        std::fs::write(&b, "old b").unwrap();
        let mut outs = OutputFiles::new(&[], &[&a, &b]).unwrap();
        let mut f = outs.create(&a).unwrap();
        f.write_all(b"new a").unwrap();
        outs.finish(f).unwrap();
        let mut g = outs.create(&b).unwrap();
        g.write_all(b"half").unwrap();
        // The run fails here: both old files stay, no temporary.
        drop(g);
        drop(outs);
        assert_eq!(std::fs::read_to_string(&a).unwrap(), "old a");
        assert_eq!(std::fs::read_to_string(&b).unwrap(), "old b");
        assert_eq!(names(&d).len(), 2, "{:?}", names(&d));
    }

    #[test]
    fn a_planted_temporary_name_is_never_written_through() {
        let d = dir("plant");
        let f = d.join("o.json");
        let victim = d.join("victim");
        std::fs::write(&victim, "keep").unwrap();
        let planted = d.join(format!(".o.json.kepler-{}-0.tmp", std::process::id()));
        std::os::unix::fs::symlink(&victim, &planted).unwrap();
        write(&f, "new").unwrap();
        assert_eq!(std::fs::read_to_string(&victim).unwrap(), "keep");
        assert_eq!(std::fs::read_to_string(&f).unwrap(), "new");
        assert!(!std::fs::symlink_metadata(&f).unwrap().is_symlink());
    }

    #[test]
    fn outputs_on_one_file_or_on_an_input_are_refused() {
        let d = dir("same");
        let scene = d.join("s.kdl");
        std::fs::write(&scene, "x").unwrap();
        std::os::unix::fs::symlink(&scene, d.join("link.svg")).unwrap();
        std::fs::create_dir(d.join("sub")).unwrap();
        let x = d.join("x.svg");
        let also_x = d.join("sub/../x.svg");
        let e = OutputFiles::new(&[], &[&x, &also_x])
            .err()
            .unwrap()
            .to_string();
        assert!(e.contains("two outputs on one file"), "{e}");
        for out in [scene.clone(), d.join("link.svg"), d.join("sub/../s.kdl")] {
            let e = OutputFiles::new(&[&scene], &[&out])
                .err()
                .unwrap()
                .to_string();
            assert!(e.contains("this output is the input"), "{e}");
        }
        std::fs::hard_link(&scene, d.join("hard.json")).unwrap();
        assert!(OutputFiles::new(&[&scene], &[&d.join("hard.json")]).is_err());
        // Devices may repeat.
        let null = Path::new("/dev/null");
        OutputFiles::new(&[], &[null, null]).unwrap();
    }

    #[test]
    fn devices_are_written_directly() {
        write(&PathBuf::from("/dev/null"), "x").unwrap();
    }
}
