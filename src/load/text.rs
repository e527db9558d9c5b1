//! Text helpers for the text mesh formats: UTF-8 checking with a location, and words with their line and column.

use std::path::Path;

use crate::error::{Error, Location, Pos, Result};

/// `bytes` as text, or a parse error at the line and column of the first byte that is not
/// text: the first byte that is not UTF-8, or the first NUL byte (valid UTF-8, but no text
/// format here has one; UTF-16 text is full of them), whichever comes first.
/// `first_line` is the 1-based line number of the first byte of `bytes`.
pub(crate) fn decode<'a>(path: &Path, bytes: &'a [u8], first_line: usize) -> Result<&'a str> {
    let utf8 = std::str::from_utf8(bytes);
    let bad = utf8.as_ref().err().map(|e| e.valid_up_to());
    let nul = bytes.iter().position(|&b| b == 0);
    let (at, msg) = match (nul, bad) {
        (None, None) => return Ok(utf8.unwrap_or_default()),
        (Some(n), b) if b.is_none_or(|b| n < b) => {
            let msg = if looks_like_utf16(bytes) {
                "NUL bytes: not UTF-8 text (UTF-16 text has a NUL in every other byte)".to_string()
            } else {
                "a NUL byte: not a text file?".to_string()
            };
            (n, msg)
        }
        (_, b) => {
            let b = b.unwrap_or_default();
            let byte = bytes.get(b).copied().unwrap_or(0);
            (
                b,
                format!("invalid UTF-8 (byte 0x{byte:02X}): not a text file?"),
            )
        }
    };
    let before = bytes.get(..at).unwrap_or_default();
    let line = first_line + before.iter().filter(|&&b| b == b'\n').count();
    let start = before
        .iter()
        .rposition(|&b| b == b'\n')
        .map_or(0, |i| i + 1);
    let col = String::from_utf8_lossy(&before[start..]).chars().count() + 1;
    Err(Error::parse(Location::line(path, line, col), msg))
}

/// Whether `bytes` look like UTF-16 text: at least a third of them NUL, nine in ten of those
/// at even offsets or nine in ten at odd ones (every other byte of mostly-ASCII UTF-16).
pub(crate) fn looks_like_utf16(bytes: &[u8]) -> bool {
    let nuls = bytes.iter().filter(|&&b| b == 0).count();
    let even = bytes.iter().step_by(2).filter(|&&b| b == 0).count();
    let one_side = even.max(nuls - even);
    nuls * 3 > bytes.len() && one_side * 10 >= nuls * 9
}

/// The 1-based column (in characters) of byte `offset` of `line`.
fn column(line: &str, offset: usize) -> usize {
    line.get(..offset).map_or(offset, |s| s.chars().count()) + 1
}

/// A whitespace-separated word of a text, with the line it is on.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Word<'a> {
    /// The word itself.
    pub text: &'a str,
    /// The whole line holding it (for the column).
    line_text: &'a str,
    /// 1-based line number.
    line: usize,
    /// Byte offset of the word in its line.
    offset: usize,
}

impl Word<'_> {
    /// The word's 1-based line number.
    pub(super) fn line(&self) -> usize {
        self.line
    }

    /// The word's line and column.
    pub(super) fn pos(&self) -> Pos {
        Pos::Line {
            line: self.line,
            col: column(self.line_text, self.offset),
        }
    }

    /// Where the word is, in `path`.
    pub(super) fn loc(&self, path: &Path) -> Location {
        Location {
            file: path.to_path_buf(),
            pos: self.pos(),
        }
    }
}

/// The lines of a text, ended by LF, CR LF or a lone CR (old Mac files).
#[derive(Clone)]
struct Lines<'a> {
    rest: Option<&'a str>,
}

impl<'a> Iterator for Lines<'a> {
    type Item = &'a str;

    fn next(&mut self) -> Option<&'a str> {
        let rest = self.rest?;
        match rest.find(['\n', '\r']) {
            None => {
                self.rest = None;
                Some(rest)
            }
            Some(k) => {
                let skip = if rest[k..].starts_with("\r\n") { 2 } else { 1 };
                self.rest = Some(&rest[k + skip..]);
                Some(&rest[..k])
            }
        }
    }
}

/// The words of a text, line by line, with optional `\` line continuation and end-of-line comments.
#[derive(Clone)]
pub(crate) struct Words<'a> {
    lines: Lines<'a>,
    /// Length of the whole text in bytes.
    len: usize,
    line_text: &'a str,
    line: usize,
    pos: usize,
    /// The current physical line ended in `\` and continues on the next.
    cont: bool,
    /// Whether a trailing `\` joins a line to the next.
    continuation: bool,
    /// A word starting with this byte starts a comment running to the end of the line.
    comment: Option<u8>,
}

impl<'a> Words<'a> {
    /// The words of `text`, whose first line is line `first_line`.
    pub(super) fn new(text: &'a str, first_line: usize) -> Self {
        Words {
            lines: Lines { rest: Some(text) },
            len: text.len(),
            line_text: "",
            line: first_line.saturating_sub(1),
            pos: 0,
            cont: false,
            continuation: false,
            comment: None,
        }
    }

    /// Lets a line ending in `\` continue on the next line.
    pub(super) fn with_continuation(mut self) -> Self {
        self.continuation = true;
        self
    }

    /// Makes a word starting with `c` start a comment to the end of the line.
    pub(super) fn with_comment(mut self, c: u8) -> Self {
        self.comment = Some(c);
        self
    }

    /// The current physical line's number (after the last, the number of lines read and
    /// the first line's, less one).
    pub(super) fn line(&self) -> usize {
        self.line
    }

    /// Bytes of the text up to the end of the current physical line (a position to count
    /// progress by).
    pub(super) fn consumed(&self) -> usize {
        self.len - self.lines.rest.map_or(0, str::len)
    }

    /// Moves to the next physical line; false at the end of the text.
    fn advance(&mut self) -> bool {
        let Some(l) = self.lines.next() else {
            self.pos = self.line_text.len();
            self.cont = false;
            return false;
        };
        self.line += 1;
        self.line_text = l;
        self.pos = 0;
        self.cont = false;
        if self.continuation {
            let t = l.trim_end();
            if let Some(s) = t.strip_suffix('\\') {
                self.line_text = s;
                self.cont = true;
            }
        }
        true
    }

    /// Moves to the start of the next logical line, skipping what is left of the current one;
    /// false at the end of the text.
    pub(super) fn next_line(&mut self) -> bool {
        while self.cont {
            self.advance();
        }
        self.advance()
    }

    /// The next word of the current logical line, or `None` at its end.
    pub(super) fn next_in_line(&mut self) -> Option<Word<'a>> {
        loop {
            let bytes = self.line_text.as_bytes();
            let mut p = self.pos;
            while p < bytes.len() && bytes[p].is_ascii_whitespace() {
                p += 1;
            }
            if p >= bytes.len() {
                self.pos = p;
                if self.cont && self.advance() {
                    continue;
                }
                return None;
            }
            if self.comment == Some(bytes[p]) {
                self.pos = bytes.len();
                self.cont = false;
                return None;
            }
            let start = p;
            while p < bytes.len() && !bytes[p].is_ascii_whitespace() {
                p += 1;
            }
            self.pos = p;
            let text = self.line_text.get(start..p).unwrap_or_default();
            return Some(Word {
                text,
                line_text: self.line_text,
                line: self.line,
                offset: start,
            });
        }
    }

    /// The next word, crossing line ends; `None` at the end of the text.
    pub(super) fn next_word(&mut self) -> Option<Word<'a>> {
        loop {
            if let Some(w) = self.next_in_line() {
                return Some(w);
            }
            if !self.next_line() {
                return None;
            }
        }
    }

    /// Whether nothing but blanks is left of the text (a scan of the rest: for error messages).
    pub(super) fn at_end(&self) -> bool {
        let rest = self.line_text.get(self.pos..).unwrap_or_default();
        rest.trim().is_empty() && self.lines.clone().all(|l| l.trim().is_empty())
    }

    /// The current line and the column just after the last word read (or the end of the text).
    pub(super) fn here(&self, path: &Path) -> Location {
        Location::line(path, self.line.max(1), column(self.line_text, self.pos))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn words_of(w: &mut Words) -> Vec<(String, Pos)> {
        let mut v = Vec::new();
        while let Some(x) = w.next_word() {
            v.push((x.text.to_string(), x.pos()));
        }
        v
    }

    #[test]
    fn load_text_words_have_line_and_char_column() {
        let mut w = Words::new("a  bc\r\n\n\téé x\n", 1);
        let v = words_of(&mut w);
        let expect = [("a", 1, 1), ("bc", 1, 4), ("éé", 3, 2), ("x", 3, 5)];
        assert_eq!(v.len(), expect.len());
        for ((t, p), (et, el, ec)) in v.iter().zip(expect) {
            assert_eq!(t, et);
            assert_eq!(*p, Pos::Line { line: el, col: ec });
        }
        assert_eq!(w.here(Path::new("f")).to_string(), "f:4:1");
        assert_eq!(w.consumed(), "a  bc\r\n\n\téé x\n".len());
    }

    #[test]
    fn load_text_continuation_and_comments() {
        let mut w = Words::new("f 1 2\\\n 3 # c\nv 4\\\n5\nx", 7)
            .with_continuation()
            .with_comment(b'#');
        assert!(w.next_line());
        let l: Vec<_> = std::iter::from_fn(|| w.next_in_line())
            .map(|x| (x.text, x.pos()))
            .collect();
        assert_eq!(l.len(), 4);
        assert_eq!(l[3], ("3", Pos::Line { line: 8, col: 2 }));
        assert!(w.next_line());
        assert_eq!(w.next_in_line().unwrap().text, "v");
        assert!(w.next_line(), "skips the continued rest of 'v 4 5'");
        assert_eq!(
            w.next_in_line().unwrap().pos(),
            Pos::Line { line: 11, col: 1 }
        );
        assert!(!w.next_line());
    }

    #[test]
    fn load_text_lines_end_at_lf_crlf_or_lone_cr() {
        let mut w = Words::new("a b\rc\r\nd\n\re", 1);
        let v = words_of(&mut w);
        let lines: Vec<(&str, usize)> = v
            .iter()
            .map(|(t, p)| match p {
                Pos::Line { line, .. } => (t.as_str(), *line),
                _ => unreachable!(),
            })
            .collect();
        assert_eq!(lines, [("a", 1), ("b", 1), ("c", 2), ("d", 3), ("e", 5)]);
    }

    #[test]
    fn load_text_decode_reports_line_and_column() {
        let utf16: Vec<u8> = "v 1 2 3\n".bytes().flat_map(|b| [b, 0]).collect();
        let e = decode(Path::new("u.obj"), &utf16, 1)
            .unwrap_err()
            .to_string();
        assert_eq!(
            e,
            "u.obj:1:2: NUL bytes: not UTF-8 text (UTF-16 text has a NUL in every other byte)"
        );
        let e = decode(Path::new("g.obj"), b"v 1 2 3\nv \xc3\xa9 \xff\n", 1).unwrap_err();
        assert!(matches!(e, Error::Parse(..)));
        assert!(
            e.to_string()
                .starts_with("g.obj:2:5: invalid UTF-8 (byte 0xFF)"),
            "{e}"
        );
        let e = decode(Path::new("h.ply"), b"\x80", 10).unwrap_err();
        assert!(e.to_string().starts_with("h.ply:10:1: "), "{e}");
    }
}
