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
    let text = std::fs::read_to_string(path).map_err(|e| anyhow!("{}: {e}", path.display()))?;
    parse_views(&text, path)
}

fn parse_views(text: &str, path: &Path) -> Result<Vec<CameraArgs>> {
    let mut out = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let line = line.split('#').next().unwrap_or("").trim();
        if line.is_empty() {
            continue;
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
    fn numbered_names() {
        assert_eq!(
            numbered(Path::new("out/a.svg"), 1, 12),
            PathBuf::from("out/a-001.svg")
        );
        assert_eq!(numbered(Path::new("a"), 7, 1000), PathBuf::from("a-0007"));
    }
}
