//! Several views in one run: a views file (one view a line, written with the camera flags of
//! the command line) and numbered output names.
//!
//! ```text
//! # front, side and a perspective view
//! --dir 0,0,-1
//! --dir -1,0,0 --up 0,1,0
//! --eye 8,6,10 --target 0,0,0 --fov 35
//! ```

use std::path::{Path, PathBuf};

use anyhow::{anyhow, Result};
use clap::Parser;

use super::CameraArgs;

/// One line of a views file.
#[derive(Parser, Debug)]
#[command(no_binary_name = true, disable_help_flag = true)]
struct ViewLine {
    #[command(flatten)]
    camera: CameraArgs,
}

/// The views of a views file, in order: blank lines and `#` comments are skipped; an error
/// names the file and line.
pub(crate) fn read_views(path: &Path) -> Result<Vec<CameraArgs>> {
    let text = read_bounded(path)?;
    parse_views(&text, path)
}

/// The most views a views file may hold: as many as `--turntable` renders.
pub(crate) const MAX_VIEWS: usize = 10_000;

/// The largest views file read: 4 MiB, 400 bytes for each of [`MAX_VIEWS`] lines.
const MAX_VIEWS_BYTES: u64 = 4 << 20;

/// The text of a views file: a regular file (not `/dev/zero`, a pipe or a directory) of at most
/// [`MAX_VIEWS_BYTES`], read no further than that.
fn read_bounded(path: &Path) -> Result<String> {
    use std::io::Read;
    let fail = |e: &dyn std::fmt::Display| anyhow!("{}: {e}", path.display());
    let meta = std::fs::metadata(path).map_err(|e| fail(&e))?;
    if !meta.is_file() {
        return Err(fail(&"a views file must be a regular file"));
    }
    let mut bytes = Vec::new();
    std::fs::File::open(path)
        .map_err(|e| fail(&e))?
        .take(MAX_VIEWS_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| fail(&e))?;
    if bytes.len() as u64 > MAX_VIEWS_BYTES {
        return Err(fail(&format!(
            "more than {MAX_VIEWS_BYTES} bytes: not a views file"
        )));
    }
    String::from_utf8(bytes).map_err(|_| fail(&"not UTF-8 text: not a views file"))
}

fn parse_views(text: &str, path: &Path) -> Result<Vec<CameraArgs>> {
    let mut out = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let line = line.split('#').next().unwrap_or("").trim();
        if line.is_empty() {
            continue;
        }
        if !line.starts_with("--") {
            // Not quoted: a file that is not a views file may hold anything, a secret too.
            return Err(anyhow!(
                "{}:{}: not a line of camera flags (a view is written --dir X,Y,Z or --eye ...)",
                path.display(),
                i + 1
            ));
        }
        if out.len() == MAX_VIEWS {
            return Err(anyhow!(
                "{}:{}: more than {MAX_VIEWS} views (the most a run renders, as with --turntable)",
                path.display(),
                i + 1
            ));
        }
        let v = ViewLine::try_parse_from(line.split_whitespace()).map_err(|e| {
            let msg = e.to_string();
            let first = msg
                .lines()
                .next()
                .unwrap_or("")
                .trim_start_matches("error: ");
            anyhow!("{}:{}: {first}", path.display(), i + 1)
        })?;
        out.push(v.camera);
    }
    if out.is_empty() {
        return Err(anyhow!(
            "{}: no views (one line of camera flags per view)",
            path.display()
        ));
    }
    Ok(out)
}

/// `path` with view number `k` (1-based) of `n` before its extension, zero-padded to at
/// least three digits: `out/a.svg` → `out/a-001.svg`.
pub(crate) fn numbered(path: &Path, k: usize, n: usize) -> PathBuf {
    let width = n.to_string().len().max(3);
    let stem = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    let name = match path.extension() {
        Some(ext) => format!("{stem}-{k:0width$}.{}", ext.to_string_lossy()),
        None => format!("{stem}-{k:0width$}"),
    };
    path.with_file_name(name)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn views_file_lines_and_errors() {
        let p = Path::new("v.txt");
        let v = parse_views(
            "# views\n--dir 0,0,-1\n\n--eye 1,2,3 --target 0,0,0 # persp\n",
            p,
        )
        .unwrap();
        assert_eq!(v.len(), 2);
        assert_eq!(v[0].dir.as_deref(), Some("0,0,-1"));
        assert_eq!(v[1].eye.as_deref(), Some("1,2,3"));
        let e = parse_views("--dir 1,0,0\n--bogus 3\n", p)
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("v.txt:2:"), "{e}");
        assert!(parse_views("# nothing\n", p).is_err());
    }

    #[test]
    fn views_files_are_bounded_and_never_quoted() {
        let p = Path::new("v.txt");
        let e = parse_views("--dir 1,0,0\nroot:x:0:0:secret\n", p)
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("v.txt:2: not a line of camera flags"), "{e}");
        assert!(!e.contains("secret"), "{e}");
        let many = "--dir 1,0,0\n".repeat(MAX_VIEWS + 1);
        let e = parse_views(&many, p).unwrap_err().to_string();
        assert!(e.starts_with("v.txt:10001: more than 10000 views"), "{e}");
        assert_eq!(parse_views(&many[12..], p).unwrap().len(), MAX_VIEWS);
        if Path::new("/dev/zero").exists() {
            let e = read_bounded(Path::new("/dev/zero"))
                .unwrap_err()
                .to_string();
            assert!(e.contains("must be a regular file"), "{e}");
        }
        assert!(read_bounded(Path::new(".")).is_err());
    }

    #[test]
    fn numbered_names() {
        assert_eq!(
            numbered(Path::new("out/a.svg"), 1, 12),
            PathBuf::from("out/a-001.svg")
        );
        assert_eq!(numbered(Path::new("a"), 7, 1000), PathBuf::from("a-0007"));
    }
}
