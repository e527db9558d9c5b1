//! A scene file's text with its name: reading (UTF-8 checked), KDL parsing, byte offset → line:col.

use std::path::{Path, PathBuf};

use super::kdl::{self, Entry, Node as KdlNode};
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
        let b = text.as_bytes();
        // A line ends at LF, CR LF or a lone CR.
        line_starts.extend((0..b.len()).filter_map(|i| match b[i] {
            b'\n' => Some(i + 1),
            b'\r' if b.get(i + 1) != Some(&b'\n') => Some(i + 1),
            _ => None,
        }));
        Source {
            path: path.to_path_buf(),
            text,
            line_starts,
        }
    }

    /// Reads `path`; `at` is where the file was asked for (an include node), if anywhere.
    /// Text that is not UTF-8 is a parse error at the first bad byte; so is a NUL byte
    /// (UTF-16 text without a byte-order mark is valid UTF-8 full of them), whichever is first.
    pub(super) fn read(path: &Path, at: Option<&Location>) -> Result<Self> {
        let bytes = super::read::read_file(
            path,
            at,
            super::read::MAX_SCENE_BYTES,
            crate::count::Count::NONE,
        )?;
        let nul = bytes.iter().position(|&b| b == 0);
        let valid = std::str::from_utf8(&bytes).err().map(|e| e.valid_up_to());
        let (offset, why) = match (nul, valid) {
            (None, None) => {
                let text = String::from_utf8(bytes).unwrap_or_default();
                return Ok(Source::new(path, text));
            }
            (Some(n), v) if v.is_none_or(|v| n < v) => {
                let why = if super::text::looks_like_utf16(&bytes) {
                    ": it is full of NUL bytes, as UTF-16 text is"
                } else {
                    ": it holds a NUL byte"
                };
                (n, why)
            }
            (_, v) => {
                let bom16 = bytes.starts_with(&[0xff, 0xfe]) || bytes.starts_with(&[0xfe, 0xff]);
                let why = if bom16 {
                    ": it starts with a UTF-16 byte-order mark"
                } else {
                    ""
                };
                (v.unwrap_or_default(), why)
            }
        };
        let prefix = String::from_utf8_lossy(&bytes[..offset]).into_owned();
        Err(Error::parse(
            Source::new(path, prefix).loc(offset),
            format!("the file is not UTF-8 text{why} (a scene file is KDL text)"),
        ))
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

    /// The location of a node (its name).
    pub(super) fn node_loc(&self, node: &KdlNode) -> Location {
        self.loc(node.name.at)
    }

    /// The location of an argument or property (a property's key).
    pub(super) fn entry_loc(&self, entry: &Entry) -> Location {
        self.loc(entry.at)
    }

    /// The text of an entry's value as written (for messages about numbers).
    pub(super) fn literal(&self, entry: &Entry) -> &str {
        self.text
            .get(entry.literal.0..entry.literal.1)
            .unwrap_or("")
    }

    /// Parses the text as a KDL v2 document; a syntax error names its position. Blocks
    /// nested deeper than [`kdl::MAX_DEPTH`] are an error (the reader stops there).
    pub(super) fn parse(&self) -> Result<Vec<KdlNode>> {
        kdl::parse(&self.text)
            .map_err(|e| Error::parse(self.loc(e.at), format!("KDL syntax error: {}", e.msg)))
    }
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
        let e = src("a\rb true").parse().unwrap_err().to_string();
        assert!(
            e.starts_with("s.kdl:2:3: KDL syntax error: bare `true` is KDL v1"),
            "{e}"
        );
    }

    #[test]
    fn deep_nesting_is_refused() {
        let deep = "a {\n".repeat(5000) + &"}\n".repeat(5000);
        let e = src(&deep).parse().unwrap_err().to_string();
        assert_eq!(
            e,
            "s.kdl:65:3: KDL syntax error: blocks are nested more than 64 deep"
        );
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
    }

    #[test]
    fn node_positions() {
        let s = src("// c\n  /* x */ foo 1 k=2\n");
        let doc = s.parse().unwrap();
        let n = &doc[0];
        assert_eq!(s.node_loc(n).to_string(), "s.kdl:2:11");
        assert_eq!(s.entry_loc(&n.entries[1]).to_string(), "s.kdl:2:17");
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
        let utf16: Vec<u8> = "object \"a\" { prism 3 }"
            .bytes()
            .flat_map(|b| [b, 0])
            .collect();
        std::fs::write(&p, &utf16).unwrap();
        let e = Source::read(&p, None).unwrap_err().to_string();
        assert!(e.ends_with("bad.kdl:1:2: the file is not UTF-8 text: it is full of NUL bytes, as UTF-16 text is (a scene file is KDL text)"), "{e}");
        let _ = std::fs::remove_dir_all(&dir);
    }
}
