//! A scene file's text with its name: reading (UTF-8 checked), KDL parsing, byte offset → line:col.

use std::path::{Path, PathBuf};

use kdl::{KdlDocument, KdlEntry, KdlNode};

use crate::error::{Error, Location, Result};

/// The text of one scene file, with the start offset of every line for positions.
#[derive(Debug, Clone)]
pub(super) struct Source {
    /// The file's name as shown in messages (as given, or joined from an include).
    pub path: PathBuf,
    /// The whole text.
    pub text: String,
    line_starts: Vec<usize>,
}

impl Source {
    /// A source from text already in memory.
    pub(super) fn new(path: &Path, text: String) -> Self {
        let mut line_starts = vec![0];
        line_starts.extend(text.match_indices('\n').map(|(i, _)| i + 1));
        Source {
            path: path.to_path_buf(),
            text,
            line_starts,
        }
    }

    /// Reads `path`; `at` is where the file was asked for (an include node), if anywhere.
    /// Text that is not UTF-8 is a parse error at the first bad byte.
    pub(super) fn read(path: &Path, at: Option<&Location>) -> Result<Self> {
        let bytes = std::fs::read(path).map_err(|e| {
            let loc = at.cloned().unwrap_or_else(|| Location::file(path));
            let msg = format!("cannot read {}: {e}", path.display());
            Error::Io(loc, std::io::Error::new(e.kind(), msg))
        })?;
        match String::from_utf8(bytes) {
            Ok(text) => Ok(Source::new(path, text)),
            Err(e) => {
                let valid = e.utf8_error().valid_up_to();
                let bytes = e.into_bytes();
                let prefix = String::from_utf8_lossy(&bytes[..valid]).into_owned();
                let src = Source::new(path, prefix);
                Err(Error::parse(
                    src.loc(valid),
                    "the file is not UTF-8 text (a scene file is KDL text)",
                ))
            }
        }
    }

    /// The 1-based line and column (in characters) of byte `offset`.
    pub(super) fn line_col(&self, offset: usize) -> (usize, usize) {
        let offset = offset.min(self.text.len());
        let line = self.line_starts.partition_point(|&s| s <= offset);
        let start = self.line_starts[line.saturating_sub(1)];
        let col = self
            .text
            .get(start..offset)
            .map_or(offset - start, |s| s.chars().count());
        (line.max(1), col + 1)
    }

    /// The location of byte `offset`.
    pub(super) fn loc(&self, offset: usize) -> Location {
        let (line, col) = self.line_col(offset);
        Location::line(&self.path, line, col)
    }

    /// The location of a node (its name, or its type annotation).
    pub(super) fn node_loc(&self, node: &KdlNode) -> Location {
        self.loc(node.span().offset())
    }

    /// The location of an argument or property (a property's key).
    pub(super) fn entry_loc(&self, entry: &KdlEntry) -> Location {
        self.loc(entry.span().offset())
    }

    /// Parses the text as a KDL v2 document; a syntax error names the first diagnostic's
    /// position. Blocks nested deeper than [`MAX_DEPTH`] are refused before parsing.
    pub(super) fn parse(&self) -> Result<KdlDocument> {
        if let Some(at) = too_deep(self.text.as_bytes(), MAX_DEPTH) {
            return Err(Error::parse(
                self.loc(at),
                format!("blocks are nested more than {MAX_DEPTH} deep"),
            ));
        }
        KdlDocument::parse_v2(&self.text).map_err(|e| {
            let Some(d) = e.diagnostics.first() else {
                return Error::parse(self.loc(0), "KDL syntax error");
            };
            let mut msg = format!(
                "KDL syntax error: {}",
                d.message.as_deref().unwrap_or("unexpected input")
            );
            if let Some(help) = &d.help {
                msg.push_str(" (");
                msg.push_str(help);
                msg.push(')');
            }
            Error::parse(self.loc(d.span.offset()), msg)
        })
    }
}

/// The deepest `{ }` nesting accepted (the KDL parser recurses once per level).
pub(super) const MAX_DEPTH: usize = 64;

/// The offset of the first `{` nested deeper than `max`, if any. Braces in comments and
/// strings do not count (a rough scan of KDL's comment and string forms).
fn too_deep(b: &[u8], max: usize) -> Option<usize> {
    let mut depth = 0usize;
    let mut i = 0;
    while i < b.len() {
        match (b[i], b.get(i + 1).copied()) {
            (b'/', Some(b'/')) => i = skip_to(b, i, b"\n"),
            (b'/', Some(b'*')) => i = skip_block_comment(b, i),
            (b'"', _) if b[i..].starts_with(b"\"\"\"") => i = skip_to(b, i + 3, b"\"\"\""),
            (b'"', _) => i = skip_quoted(b, i + 1),
            (b'#', Some(b'#' | b'"')) => i = skip_raw(b, i),
            (b'{', _) => {
                depth += 1;
                if depth > max {
                    return Some(i);
                }
                i += 1;
            }
            (b'}', _) => {
                depth = depth.saturating_sub(1);
                i += 1;
            }
            _ => i += 1,
        }
    }
    None
}

/// The offset just past the first `end` at or after `from` (or the end of the text).
fn skip_to(b: &[u8], from: usize, end: &[u8]) -> usize {
    b.get(from..)
        .and_then(|rest| rest.windows(end.len()).position(|w| w == end))
        .map_or(b.len(), |k| from + k + end.len())
}

/// Past a `/* ... */` comment (they nest in KDL) starting at `i`.
fn skip_block_comment(b: &[u8], mut i: usize) -> usize {
    let mut nest = 0usize;
    while i < b.len() {
        if b[i..].starts_with(b"/*") {
            nest += 1;
            i += 2;
        } else if b[i..].starts_with(b"*/") {
            nest -= 1;
            i += 2;
            if nest == 0 {
                return i;
            }
        } else {
            i += 1;
        }
    }
    b.len()
}

/// Past a quoted string whose body starts at `i` (ends at an unescaped quote or a newline).
fn skip_quoted(b: &[u8], mut i: usize) -> usize {
    while i < b.len() {
        match b[i] {
            b'\\' => i += 2,
            b'"' | b'\n' => return i + 1,
            _ => i += 1,
        }
    }
    b.len()
}

/// Past a raw string `#"..."#` (any number of `#`) starting at `i`.
fn skip_raw(b: &[u8], i: usize) -> usize {
    let hashes = b[i..].iter().take_while(|&&c| c == b'#').count();
    let open = i + hashes;
    if b.get(open) != Some(&b'"') {
        return open;
    }
    let mut end = vec![b'"'];
    end.extend(std::iter::repeat_n(b'#', hashes));
    skip_to(b, open + 1, &end)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn src(text: &str) -> Source {
        Source::new(Path::new("s.kdl"), text.to_string())
    }

    #[test]
    fn offsets_become_lines_and_char_columns() {
        let s = src("ab\néü x\n\nz");
        assert_eq!(s.line_col(0), (1, 1));
        assert_eq!(s.line_col(2), (1, 3));
        assert_eq!(s.line_col(3), (2, 1));
        // 'x' is after two 2-byte characters and a space: byte 8, column 4.
        assert_eq!(s.line_col(8), (2, 4));
        assert_eq!(s.line_col(10), (3, 1));
        assert_eq!(s.line_col(11), (4, 1));
        assert_eq!(s.line_col(999), (4, 2));
        assert_eq!(s.loc(3).to_string(), "s.kdl:2:1");
    }

    #[test]
    fn syntax_error_has_position() {
        let e = src("a 1\nb 1.\n").parse().unwrap_err().to_string();
        assert!(e.starts_with("s.kdl:2:3: KDL syntax error"), "{e}");
    }

    #[test]
    fn deep_nesting_is_refused_before_parsing() {
        let deep = "a {\n".repeat(5000) + &"}\n".repeat(5000);
        let e = src(&deep).parse().unwrap_err().to_string();
        assert_eq!(e, "s.kdl:65:3: blocks are nested more than 64 deep");
        // Braces in comments and strings do not count.
        let braces = "{".repeat(100);
        for text in [
            format!("a \"{braces}\""),
            format!("a #\"{braces}\"#"),
            format!("a ##\"x\"#{braces}\"##"),
            format!("// {braces}\na"),
            format!("/* /* */ {braces} */ a"),
            format!("a \"\"\"\n{braces}\n\"\"\""),
        ] {
            assert!(src(&text).parse().is_ok(), "{text}");
        }
        assert!(too_deep(b"a { b { c } }", 2).is_none());
        assert_eq!(too_deep(b"a { b { c { } } }", 2), Some(10));
    }

    #[test]
    fn node_positions() {
        let s = src("// c\n  /* x */ foo 1 k=2\n");
        let doc = s.parse().unwrap();
        let n = &doc.nodes()[0];
        assert_eq!(s.node_loc(n).to_string(), "s.kdl:2:11");
        assert_eq!(s.entry_loc(&n.entries()[1]).to_string(), "s.kdl:2:17");
    }

    #[test]
    fn non_utf8_is_a_parse_error_at_the_byte() {
        let dir = std::env::temp_dir().join(format!("kepler-src-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let p = dir.join("bad.kdl");
        std::fs::write(&p, b"a 1\nbc \xff\xfe").unwrap();
        let e = Source::read(&p, None).unwrap_err().to_string();
        assert!(
            e.ends_with("bad.kdl:2:4: the file is not UTF-8 text (a scene file is KDL text)"),
            "{e}"
        );
        let _ = std::fs::remove_dir_all(&dir);
    }
}
