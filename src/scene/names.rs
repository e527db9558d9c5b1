//! Object names made safe to print: control characters (a newline, an escape sequence that
//! clears a terminal, a byte XML forbids) written as visible escapes, for the terminal, OBJ and
//! XML alike (JSON escapes its own).

use std::borrow::Cow;
use std::fmt::Write as _;

/// True for a character no output may carry raw in a name: C0 and C1 controls, DEL, the line
/// and paragraph separators, and the bidirectional overrides that reorder a terminal's text.
fn unsafe_char(c: char) -> bool {
    c.is_control()
        || matches!(c, '\u{2028}' | '\u{2029}' | '\u{202A}'..='\u{202E}' | '\u{2066}'..='\u{2069}')
}

/// `name` with every unsafe character written as `\n`, `\r`, `\t` or `\u{XX}` (and `\` as
/// `\\` only where an escape is written, so names without controls are unchanged).
pub(crate) fn printable(name: &str) -> Cow<'_, str> {
    if !name.chars().any(unsafe_char) {
        return Cow::Borrowed(name);
    }
    let mut s = String::with_capacity(name.len() + 8);
    for c in name.chars() {
        match c {
            '\n' => s.push_str("\\n"),
            '\r' => s.push_str("\\r"),
            '\t' => s.push_str("\\t"),
            '\\' => s.push_str("\\\\"),
            c if unsafe_char(c) => {
                let _ = write!(s, "\\u{{{:x}}}", u32::from(c));
            }
            c => s.push(c),
        }
    }
    Cow::Owned(s)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn controls_become_visible_escapes() {
        assert_eq!(printable("house/roof"), "house/roof");
        assert_eq!(printable("a\\b"), "a\\b");
        assert_eq!(printable("a\nv 1 2 3\nf 1"), "a\\nv 1 2 3\\nf 1");
        assert_eq!(printable("x\u{1b}[2Jy\\"), "x\\u{1b}[2Jy\\\\");
        assert_eq!(
            printable("\u{0}\u{7f}\u{85}\u{202e}"),
            "\\u{0}\\u{7f}\\u{85}\\u{202e}"
        );
        assert_eq!(printable("tab\there\r"), "tab\\there\\r");
        // Nothing unsafe is left, and other Unicode is kept.
        let p = printable("é\u{1}日本");
        assert_eq!(p, "é\\u{1}日本");
        assert!(!p.chars().any(unsafe_char));
    }
}
