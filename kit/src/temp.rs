//! Scratch folders for tests: one per test and process, so parallel runs never share files.

use std::path::{Path, PathBuf};

/// A fresh, empty folder `kepler-{suite}-{pid}-{name}` under the system's temporary folder.
///
/// The folders of test processes that have ended are removed first: a test's
/// folder stays for looking at until the next run, and runs do not pile up.
pub fn temp_dir(suite: &str, name: &str) -> PathBuf {
    let tmp = std::env::temp_dir();
    sweep(&tmp);
    let d = tmp.join(format!("kepler-{suite}-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("a writable temporary folder");
    d
}

/// Removes the `kepler-…-{pid}-…` folders in `tmp` whose process has ended. Only where
/// `/proc` tells which processes live (Linux); elsewhere nothing is removed.
fn sweep(tmp: &Path) {
    if !Path::new("/proc/self").exists() {
        return;
    }
    let Ok(entries) = std::fs::read_dir(tmp) else {
        return;
    };
    for e in entries.flatten() {
        let name = e.file_name();
        let Some(pid) = name.to_str().and_then(owner_pid) else {
            continue;
        };
        if !Path::new(&format!("/proc/{pid}")).exists() {
            let _ = std::fs::remove_dir_all(e.path());
        }
    }
}

/// The process id in a folder name `kepler-{suite}-{pid}-{name}`: the first part of digits
/// only after `kepler-` (suites are words), followed by a name.
fn owner_pid(folder: &str) -> Option<u32> {
    let rest = folder.strip_prefix("kepler-")?;
    let mut parts = rest.split('-');
    let pid = parts
        .by_ref()
        .find(|p| !p.is_empty() && p.bytes().all(|b| b.is_ascii_digit()))?;
    parts.next()?;
    pid.parse().ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_owner_is_read_from_the_folder_name() {
        assert_eq!(owner_pid("kepler-test-4092-json"), Some(4092));
        assert_eq!(owner_pid("kepler-e2e-import-29023-site"), Some(29023));
        assert_eq!(owner_pid("kepler-views-10092-auto-default"), Some(10092));
        // Not a test folder: no pid, no name after it, or not ours.
        assert_eq!(owner_pid("kepler-test-json"), None);
        assert_eq!(owner_pid("kepler-test-4092"), None);
        assert_eq!(owner_pid("other-test-4092-json"), None);
    }

    #[test]
    fn folders_of_ended_processes_are_swept_and_live_ones_kept() {
        if !Path::new("/proc/self").exists() {
            return;
        }
        let tmp = std::env::temp_dir().join(format!("kepler-sweep-{}-root", std::process::id()));
        let _ = std::fs::remove_dir_all(&tmp);
        std::fs::create_dir_all(&tmp).unwrap();
        // A pid above Linux's largest (2^22) never runs; this process does.
        let dead = tmp.join("kepler-test-4194305-old");
        let live = tmp.join(format!("kepler-test-{}-now", std::process::id()));
        let other = tmp.join("unrelated-4194305-folder");
        for d in [&dead, &live, &other] {
            std::fs::create_dir_all(d).unwrap();
        }
        sweep(&tmp);
        assert!(!dead.exists() && live.exists() && other.exists());
        std::fs::remove_dir_all(&tmp).unwrap();
    }
}
