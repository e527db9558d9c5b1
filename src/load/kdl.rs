//! A KDL v2 reader for scene files: the document as nodes with byte offsets, read in one pass
//! in time and memory linear in the text, recursing only into `{ }` blocks and at most
//! [`MAX_DEPTH`] deep (comments and slashdashes are skipped without recursion).
//!
//! It follows the KDL 2.0.0 grammar (<https://kdl.dev/spec>): identifier, quoted, raw and
//! multi-line strings with their escapes; decimal, hex, octal and binary numbers; `#true`,
//! `#false`, `#null`, `#inf`, `#-inf`, `#nan`; type annotations; `//` and nested `/* */`
//! comments; `/-` slashdash on nodes, entries and blocks; `\` line continuations. A syntax
//! error names its byte offset and says what was expected; constructs of KDL v1 (bare
//! `true`, `r"raw"` strings) get a hint.

/// The deepest `{ }` nesting accepted: the reader recurses once per level.
pub(super) const MAX_DEPTH: usize = 64;

/// A syntax error: where and what.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct SyntaxError {
    /// Byte offset in the text.
    pub at: usize,
    /// What is wrong (without the "KDL syntax error" prefix).
    pub msg: String,
}

/// A value of an argument or property.
#[derive(Debug, Clone, PartialEq)]
pub(super) enum Value {
    /// A string (identifier, quoted or raw).
    String(String),
    /// An integer literal that fits in i128.
    Integer(i128),
    /// A decimal literal with a fraction or exponent, a keyword number, or an integer too
    /// large for i128.
    Float(f64),
    /// `#true` or `#false`.
    Bool(bool),
    /// `#null`.
    Null,
}

/// A string with the offset of its first byte.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Ident {
    /// The string's value.
    pub value: String,
    /// Byte offset of the literal.
    pub at: usize,
}

/// An argument (`name` None) or a property of a node.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Entry {
    /// The property's key.
    pub name: Option<Ident>,
    /// The value's type annotation.
    pub ty: Option<Ident>,
    /// The value.
    pub value: Value,
    /// Byte offset of the entry (its key, else its annotation, else its value).
    pub at: usize,
    /// Byte range of the value's literal, as written.
    pub literal: (usize, usize),
}

/// A node: annotation, name, entries and an optional block of children.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Node {
    /// The node's type annotation.
    pub ty: Option<Ident>,
    /// The node's name (its offset is the node's).
    pub name: Ident,
    /// Arguments and properties, in order.
    pub entries: Vec<Entry>,
    /// The `{ }` block, if any.
    pub children: Option<Vec<Node>>,
}

/// Reads a KDL v2 document.
pub(super) fn parse(text: &str) -> Result<Vec<Node>, SyntaxError> {
    let mut r = Reader {
        s: text,
        i: 0,
        depth: 0,
    };
    if text.starts_with('\u{feff}') {
        r.i = 3;
    }
    let nodes = r.nodes(true)?;
    Ok(nodes)
}

/// The reader's position in the text.
struct Reader<'a> {
    s: &'a str,
    i: usize,
    depth: usize,
}

type Res<T> = Result<T, SyntaxError>;

/// Characters that end an identifier besides spaces and newlines.
const SYNTAX: &str = "\\/(){};[]\"#=";

/// True for KDL's unicode-space (whitespace that is not a newline).
fn is_space(c: char) -> bool {
    matches!(
        c,
        '\t' | ' ' | '\u{a0}' | '\u{1680}' | '\u{2000}'
            ..='\u{200a}' | '\u{202f}' | '\u{205f}' | '\u{3000}'
    )
}

/// True for a newline character (CR LF counts once: see [`Reader::newline`]).
fn is_newline(c: char) -> bool {
    matches!(
        c,
        '\n' | '\r' | '\u{85}' | '\u{b}' | '\u{c}' | '\u{2028}' | '\u{2029}'
    )
}

/// Code points KDL forbids anywhere in a document.
fn is_disallowed(c: char) -> bool {
    matches!(c, '\u{0}'..='\u{8}' | '\u{e}'..='\u{1f}' | '\u{7f}' | '\u{200e}' | '\u{200f}' | '\u{202a}'..='\u{202e}' | '\u{2066}'..='\u{2069}' | '\u{feff}')
}

/// True for a character that may appear in an identifier string.
fn is_ident_char(c: char) -> bool {
    !is_space(c) && !is_newline(c) && !SYNTAX.contains(c) && !is_disallowed(c)
}

impl Reader<'_> {
    fn err<T>(&self, at: usize, msg: impl Into<String>) -> Res<T> {
        Err(SyntaxError {
            at,
            msg: msg.into(),
        })
    }

    fn peek(&self) -> Option<char> {
        self.s[self.i..].chars().next()
    }

    fn peek2(&self) -> Option<char> {
        let mut c = self.s[self.i..].chars();
        c.next();
        c.next()
    }

    fn rest(&self) -> &str {
        &self.s[self.i..]
    }

    fn bump(&mut self) -> Option<char> {
        let c = self.peek()?;
        self.i += c.len_utf8();
        Some(c)
    }

    /// Consumes one newline (CR LF as one); false when there is none here.
    fn newline(&mut self) -> bool {
        match self.peek() {
            Some('\r') => {
                self.i += 1;
                if self.peek() == Some('\n') {
                    self.i += 1;
                }
                true
            }
            Some(c) if is_newline(c) => {
                self.i += c.len_utf8();
                true
            }
            _ => false,
        }
    }

    /// Skips a `/* */` comment (nested ones included, counted without recursion).
    fn block_comment(&mut self) -> Res<()> {
        let start = self.i;
        self.i += 2;
        let mut nest = 1usize;
        let b = self.s.as_bytes();
        while self.i < b.len() {
            if b[self.i] == b'/' && b.get(self.i + 1) == Some(&b'*') {
                nest += 1;
                self.i += 2;
            } else if b[self.i] == b'*' && b.get(self.i + 1) == Some(&b'/') {
                nest -= 1;
                self.i += 2;
                if nest == 0 {
                    return Ok(());
                }
            } else {
                self.i += 1;
            }
        }
        self.err(start, "unterminated /* comment: it needs a closing */")
    }

    /// Skips a `//` comment up to (not past) the end of its line.
    fn line_comment(&mut self) {
        while let Some(c) = self.peek() {
            if is_newline(c) {
                return;
            }
            self.i += c.len_utf8();
        }
    }

    /// Skips whitespace and block comments; true when any was skipped.
    fn ws(&mut self) -> Res<bool> {
        let start = self.i;
        loop {
            match self.peek() {
                Some(c) if is_space(c) => self.i += c.len_utf8(),
                Some('/') if self.peek2() == Some('*') => self.block_comment()?,
                _ => return Ok(self.i > start),
            }
        }
    }

    /// node-space: whitespace, block comments and `\` line continuations; true when any.
    fn node_space(&mut self) -> Res<bool> {
        let start = self.i;
        loop {
            self.ws()?;
            if self.peek() != Some('\\') {
                break;
            }
            let at = self.i;
            self.i += 1;
            self.ws()?;
            if self.rest().starts_with("//") {
                self.line_comment();
            }
            if !self.newline() && self.peek().is_some() {
                return self.err(at, "a `\\` line continuation must end its line");
            }
        }
        Ok(self.i > start)
    }

    /// line-space: node-space, newlines and `//` comments.
    fn line_space(&mut self) -> Res<()> {
        loop {
            let moved = self.node_space()?;
            if self.rest().starts_with("//") {
                self.line_comment();
                continue;
            }
            if self.newline() {
                continue;
            }
            if !moved {
                return Ok(());
            }
        }
    }

    /// Consumes `/-` and the line-space after it; false when there is none here.
    fn slashdash(&mut self) -> Res<bool> {
        if !self.rest().starts_with("/-") {
            return Ok(false);
        }
        self.i += 2;
        self.line_space()?;
        if self.rest().starts_with("/-") {
            return self.err(
                self.i,
                "`/-` must be followed by what it comments out, not another `/-`",
            );
        }
        Ok(true)
    }

    /// Nodes up to the end of the text (`top`) or of a block (its `}` is left unread).
    fn nodes(&mut self, top: bool) -> Res<Vec<Node>> {
        let mut out = Vec::new();
        loop {
            self.line_space()?;
            match self.peek() {
                None if top => return Ok(out),
                None => {
                    return self.err(
                        self.i,
                        "unexpected end of the file: a `{` block is not closed with `}`",
                    )
                }
                Some('}') if top => return self.err(self.i, "unexpected `}`: no block is open"),
                Some('}') => return Ok(out),
                _ => {}
            }
            let dashed = self.slashdash()?;
            if dashed && matches!(self.peek(), None | Some('}')) {
                return self.err(self.i, "`/-` must be followed by the node it comments out");
            }
            let node = self.node()?;
            if !dashed {
                out.push(node);
            }
        }
    }

    /// One node and its terminator.
    fn node(&mut self) -> Res<Node> {
        let ty = self.type_annotation()?;
        let at = self.i;
        let name = match self.string()? {
            Some(value) => Ident { value, at },
            None => return self.unexpected("a node name"),
        };
        let mut node = Node {
            ty,
            name,
            entries: Vec::new(),
            children: None,
        };
        // Entries come first; after a block (even a commented-out one) only blocks follow.
        let mut after_block = false;
        loop {
            let spaced = self.node_space()?;
            match self.peek() {
                None | Some('}') => return Ok(node),
                Some(';') => {
                    self.i += 1;
                    return Ok(node);
                }
                Some(c) if is_newline(c) => {
                    self.newline();
                    return Ok(node);
                }
                Some('/') if self.peek2() == Some('/') => {
                    self.line_comment();
                    self.newline();
                    return Ok(node);
                }
                Some('/') if self.peek2() == Some('-') => {
                    self.slashdash()?;
                    if self.peek() == Some('{') {
                        self.block()?;
                        after_block = true;
                    } else if after_block {
                        return self.unexpected(
                            "a `{ }` block after `/-` (only blocks may follow a block)",
                        );
                    } else {
                        self.entry()?;
                    }
                }
                Some('{') => {
                    if node.children.is_some() {
                        return self.err(self.i, "a node has at most one `{ }` block");
                    }
                    node.children = Some(self.block()?);
                    after_block = true;
                }
                _ if after_block => {
                    return self.unexpected("the end of the node after its `{ }` block")
                }
                _ if !spaced => return self.unexpected("a space before the next argument"),
                _ => node.entries.push(self.entry()?),
            }
        }
    }

    /// A `{ ... }` block, at most [`MAX_DEPTH`] deep.
    fn block(&mut self) -> Res<Vec<Node>> {
        let at = self.i;
        self.depth += 1;
        if self.depth > MAX_DEPTH {
            return self.err(at, format!("blocks are nested more than {MAX_DEPTH} deep"));
        }
        self.i += 1;
        let nodes = self.nodes(false)?;
        self.i += 1; // the `}` nodes() stopped at
        self.depth -= 1;
        Ok(nodes)
    }

    /// A type annotation `(ty)` and the space after it, if one starts here.
    fn type_annotation(&mut self) -> Res<Option<Ident>> {
        if self.peek() != Some('(') {
            return Ok(None);
        }
        let t = self.annotation()?;
        self.node_space()?;
        Ok(Some(t))
    }

    /// `(type)`.
    fn annotation(&mut self) -> Res<Ident> {
        self.i += 1;
        self.node_space()?;
        let at = self.i;
        let Some(value) = self.string()? else {
            return self.unexpected("a type name");
        };
        self.node_space()?;
        if self.peek() != Some(')') {
            return self.unexpected("`)` closing the type annotation");
        }
        self.i += 1;
        Ok(Ident { value, at })
    }

    /// An argument or a property.
    fn entry(&mut self) -> Res<Entry> {
        let at = self.i;
        if self.peek() == Some('(') {
            let ty = Some(self.annotation()?);
            self.node_space()?;
            let (value, literal) = self.value()?;
            return Ok(Entry {
                name: None,
                ty,
                value,
                at,
                literal,
            });
        }
        let (value, literal) = self.value()?;
        let save = self.i;
        self.node_space()?;
        if self.peek() != Some('=') {
            self.i = save;
            return Ok(Entry {
                name: None,
                ty: None,
                value,
                at,
                literal,
            });
        }
        let Value::String(key) = value else {
            return self.err(at, "a property's key must be a string");
        };
        self.i += 1;
        self.node_space()?;
        let ty = self.type_annotation()?;
        let (value, literal) = self.value()?;
        Ok(Entry {
            name: Some(Ident { value: key, at }),
            ty,
            value,
            at,
            literal,
        })
    }

    /// A value: string, number or keyword, with the byte range of its literal.
    fn value(&mut self) -> Res<(Value, (usize, usize))> {
        let at = self.i;
        let v = match self.peek() {
            Some('#') if !matches!(self.peek2(), Some('"' | '#')) => self.keyword()?,
            Some(c) if c.is_ascii_digit() => self.number()?,
            Some('+' | '-') if self.peek2().is_some_and(|d| d.is_ascii_digit()) => self.number()?,
            _ => match self.string()? {
                Some(s) => Value::String(s),
                None => {
                    return self.unexpected("a value (a string, a number, #true, #false or #null)")
                }
            },
        };
        self.end_of_value(at)?;
        Ok((v, (at, self.i)))
    }

    /// A value must be followed by space, a newline, `;`, `}`, `=`, `)`, a comment, `\` or
    /// the end.
    fn end_of_value(&self, at: usize) -> Res<()> {
        match self.peek() {
            None => Ok(()),
            Some(c) if is_space(c) || is_newline(c) || ";{}=)\\/".contains(c) => Ok(()),
            Some(_) => {
                let word: String = self.s[at..]
                    .chars()
                    .take_while(|&c| is_ident_char(c))
                    .take(40)
                    .collect();
                let mut msg = format!("`{word}` is not a valid value");
                if word.starts_with(|c: char| c.is_ascii_digit() || c == '-' || c == '+') {
                    msg.push_str(" (a number, or a string that needs quotes)");
                }
                self.err(at, msg)
            }
        }
    }

    /// `#true`, `#false`, `#null`, `#inf`, `#-inf`, `#nan`.
    fn keyword(&mut self) -> Res<Value> {
        let at = self.i;
        self.i += 1;
        let word: String = self
            .rest()
            .chars()
            .take_while(|&c| is_ident_char(c))
            .collect();
        let v = match word.as_str() {
            "true" => Value::Bool(true),
            "false" => Value::Bool(false),
            "null" => Value::Null,
            "inf" => Value::Float(f64::INFINITY),
            "-inf" => Value::Float(f64::NEG_INFINITY),
            "nan" => Value::Float(f64::NAN),
            _ => {
                return self.err(
                    at,
                    format!(
                    "unknown keyword `#{word}`: expected #true, #false, #null, #inf, #-inf or #nan"
                ),
                )
            }
        };
        self.i += word.len();
        Ok(v)
    }

    /// A number literal (at a digit, or a sign before one).
    fn number(&mut self) -> Res<Value> {
        let at = self.i;
        let b = self.s.as_bytes();
        let mut j = self.i;
        let negative = b[j] == b'-';
        if matches!(b[j], b'+' | b'-') {
            j += 1;
        }
        let radix = match (b[j], b.get(j + 1)) {
            (b'0', Some(b'x')) => 16,
            (b'0', Some(b'o')) => 8,
            (b'0', Some(b'b')) => 2,
            _ => 10,
        };
        if radix != 10 {
            j += 2;
            let digits_start = j;
            while j < b.len() && (b[j] == b'_' || (b[j] as char).is_digit(radix)) {
                j += 1;
            }
            if j == digits_start || b[digits_start] == b'_' {
                return self.err(at, "a number needs a digit after its 0x, 0o or 0b");
            }
            self.i = j;
            let digits: String = self.s[digits_start..j]
                .chars()
                .filter(|&c| c != '_')
                .collect();
            return Ok(match i128::from_str_radix(&digits, radix) {
                Ok(v) => Value::Integer(if negative { -v } else { v }),
                Err(_) => {
                    let v = digits.chars().fold(0.0f64, |a, c| {
                        a * f64::from(radix) + f64::from(c.to_digit(radix).unwrap_or(0))
                    });
                    Value::Float(if negative { -v } else { v })
                }
            });
        }
        let digits = |j: &mut usize| {
            let s = *j;
            while *j < b.len() && (b[*j].is_ascii_digit() || b[*j] == b'_') {
                *j += 1;
            }
            *j > s && b[s] != b'_'
        };
        digits(&mut j);
        let mut float = false;
        if j < b.len() && b[j] == b'.' {
            j += 1;
            float = true;
            if !digits(&mut j) {
                return self.err(at, "a number's fraction needs a digit after the `.`");
            }
        }
        if j < b.len() && matches!(b[j], b'e' | b'E') {
            j += 1;
            float = true;
            if j < b.len() && matches!(b[j], b'+' | b'-') {
                j += 1;
            }
            if !digits(&mut j) {
                return self.err(at, "a number's exponent needs a digit after the `e`");
            }
        }
        self.i = j;
        let clean: String = self.s[at..j].chars().filter(|&c| c != '_').collect();
        let clean = clean.strip_prefix('+').unwrap_or(&clean);
        if !float {
            if let Ok(v) = clean.parse::<i128>() {
                return Ok(Value::Integer(v));
            }
        }
        match clean.parse::<f64>() {
            Ok(v) => Ok(Value::Float(v)),
            Err(_) => self.err(at, "invalid number"),
        }
    }

    /// A string (identifier, quoted, raw or multi-line), or None when none starts here.
    fn string(&mut self) -> Res<Option<String>> {
        match self.peek() {
            Some('"') => self.quoted().map(Some),
            Some('#') if matches!(self.peek2(), Some('"' | '#')) => self.raw().map(Some),
            Some(c) if is_ident_char(c) => self.identifier().map(Some),
            _ => Ok(None),
        }
    }

    /// A bare identifier string.
    fn identifier(&mut self) -> Res<String> {
        let at = self.i;
        let word: String = self
            .rest()
            .chars()
            .take_while(|&c| is_ident_char(c))
            .collect();
        // One sign, then no digit; a `.` (after the sign, if any) not followed by a digit.
        let body = word.strip_prefix(['+', '-']).unwrap_or(&word);
        let after_dot = body.strip_prefix('.').unwrap_or("x");
        let digit = |s: &str| s.starts_with(|c: char| c.is_ascii_digit());
        if digit(body) || digit(after_dot) {
            return self.err(
                at,
                format!("`{word}` is neither a number nor a string: quote it if it is a string"),
            );
        }
        match word.as_str() {
            "true" | "false" | "null" => {
                return self.err(
                    at,
                    format!(
                    "bare `{word}` is KDL v1; scene files are KDL v2, where it is written #{word}"
                ),
                )
            }
            "inf" | "-inf" | "nan" => {
                return self.err(
                    at,
                    format!(
                        "bare `{word}` is not allowed: write #{word} (or quote it for a string)"
                    ),
                )
            }
            _ => {}
        }
        self.i += word.len();
        if word == "r" && matches!(self.peek(), Some('"' | '#')) {
            return self.err(
                at,
                "`r\"...\"` is a KDL v1 raw string; in KDL v2 it is written #\"...\"#",
            );
        }
        Ok(word)
    }

    /// A `"..."` or `"""` multi-line string, escapes resolved.
    fn quoted(&mut self) -> Res<String> {
        let at = self.i;
        if self.rest().starts_with("\"\"\"") {
            self.i += 3;
            let body_at = self.i;
            let body = self.multi_line_body(at, "\"\"\"")?;
            return dedent(&body, true).map_err(|(off, msg)| SyntaxError {
                at: body_at + off,
                msg,
            });
        }
        self.i += 1;
        let start = self.i;
        loop {
            match self.peek() {
                None => return self.err(at, "unterminated string: it needs a closing \""),
                Some('"') => break,
                Some('\\') => {
                    self.i += 1;
                    if self.bump().is_none() {
                        return self.err(at, "unterminated string: it needs a closing \"");
                    }
                }
                Some(c) if is_newline(c) => {
                    return self.err(at, "a quoted string ends on its line: close it with \", or use \"\"\" for a multi-line string")
                }
                Some(c) if is_disallowed(c) => return self.disallowed(c),
                Some(c) => self.i += c.len_utf8(),
            }
        }
        let raw = &self.s[start..self.i];
        self.i += 1;
        unescape(raw).map_err(|(off, msg)| SyntaxError {
            at: start + off,
            msg,
        })
    }

    /// A raw string `#"..."#` (any number of `#`), or raw multi-line `#"""..."""#`.
    fn raw(&mut self) -> Res<String> {
        let at = self.i;
        let hashes = self.rest().bytes().take_while(|&c| c == b'#').count();
        self.i += hashes;
        if self.peek() != Some('"') {
            return self.err(
                at,
                "a raw string is #\"...\"# (with as many # on each side)",
            );
        }
        let fence: String = "#".repeat(hashes);
        if self.rest().starts_with("\"\"\"") {
            self.i += 3;
            let body_at = self.i;
            let body = self.multi_line_body(at, &format!("\"\"\"{fence}"))?;
            return dedent(&body, false).map_err(|(off, msg)| SyntaxError {
                at: body_at + off,
                msg,
            });
        }
        self.i += 1;
        let close = format!("\"{fence}");
        let Some(k) = self.rest().find(&close) else {
            return self.err(
                at,
                format!("unterminated raw string: it needs a closing {close}"),
            );
        };
        let body = &self.rest()[..k];
        if let Some(c) = body.chars().find(|&c| is_newline(c) || is_disallowed(c)) {
            return if is_newline(c) {
                self.err(
                    at,
                    "a raw string ends on its line: use #\"\"\" for a multi-line one",
                )
            } else {
                self.disallowed(c)
            };
        }
        let body = body.to_string();
        self.i += k + close.len();
        Ok(body)
    }

    /// The text of a multi-line string up to `close` (which is consumed), after the opening
    /// quotes; it must start with a newline.
    fn multi_line_body(&mut self, at: usize, close: &str) -> Res<String> {
        if !self.newline() {
            return self.err(
                at,
                "a multi-line string starts with a newline after its opening quotes",
            );
        }
        let start = self.i;
        // Escaped quotes cannot end a non-raw multi-line string: skip `\` + char.
        let escapes = close.starts_with("\"\"\"") && !close.ends_with('#');
        let b = self.s.as_bytes();
        let mut j = start;
        while j < b.len() {
            if escapes && b[j] == b'\\' {
                j += 2;
                continue;
            }
            if self.s[j..].starts_with(close) {
                let body = self.s[start..j].to_string();
                self.i = j + close.len();
                return Ok(body);
            }
            j += 1;
        }
        self.err(
            at,
            format!("unterminated multi-line string: it needs a closing {close}"),
        )
    }

    fn disallowed<T>(&self, c: char) -> Res<T> {
        self.err(
            self.i,
            format!(
                "the character U+{:04X} is not allowed in KDL text",
                c as u32
            ),
        )
    }

    /// An error at the current position naming what was `expected` and what is here.
    fn unexpected<T>(&self, expected: &str) -> Res<T> {
        let found = match self.peek() {
            None => "the end of the file".to_string(),
            Some(c) if is_newline(c) => "the end of the line".to_string(),
            Some(c) if is_disallowed(c) => {
                format!("the character U+{:04X}, which KDL does not allow", c as u32)
            }
            Some(c) => format!("`{c}`"),
        };
        self.err(self.i, format!("expected {expected}, found {found}"))
    }
}

/// Resolves the escapes of a quoted string's body; errors give the offset in `raw`.
fn unescape(raw: &str) -> Result<String, (usize, String)> {
    let mut out = String::with_capacity(raw.len());
    let mut it = raw.char_indices().peekable();
    while let Some((k, c)) = it.next() {
        if c != '\\' {
            out.push(c);
            continue;
        }
        let Some((_, e)) = it.next() else {
            return Err((k, "a `\\` escape at the end of a string".into()));
        };
        match e {
            'n' => out.push('\n'),
            'r' => out.push('\r'),
            't' => out.push('\t'),
            '\\' => out.push('\\'),
            '"' => out.push('"'),
            'b' => out.push('\u{8}'),
            'f' => out.push('\u{c}'),
            's' => out.push(' '),
            'u' => {
                if it.next().map(|x| x.1) != Some('{') {
                    return Err((k, "a \\u escape is written \\u{HEX}".into()));
                }
                let mut hex = String::new();
                loop {
                    match it.next() {
                        Some((_, '}')) => break,
                        Some((_, h)) if h.is_ascii_hexdigit() && hex.len() < 6 => hex.push(h),
                        _ => {
                            return Err((
                                k,
                                "a \\u escape is written \\u{HEX} with 1 to 6 hex digits".into(),
                            ))
                        }
                    }
                }
                let ch = u32::from_str_radix(&hex, 16)
                    .ok()
                    .and_then(char::from_u32)
                    .ok_or((k, format!("\\u{{{hex}}} is not a Unicode scalar value")))?;
                out.push(ch);
            }
            w if is_space(w) || is_newline(w) => {
                while it
                    .peek()
                    .is_some_and(|&(_, c)| is_space(c) || is_newline(c))
                {
                    it.next();
                }
            }
            other => return Err((k, format!("unknown escape `\\{other}`"))),
        }
    }
    Ok(out)
}

/// A multi-line string's value: its last line (blank) is the indent every other line must
/// start with (blank lines may be empty), removed with the first and last newlines; escapes
/// resolved unless raw. Errors give the offset in `body`.
fn dedent(body: &str, escapes: bool) -> Result<String, (usize, String)> {
    let lines: Vec<&str> = split_lines(body);
    let (last, rest) = lines.split_last().unwrap_or((&"", &[]));
    if !last.chars().all(is_space) {
        return Err((
            body.len() - last.len(),
            "the closing quotes of a multi-line string must be alone on their line".into(),
        ));
    }
    let mut out = Vec::with_capacity(rest.len());
    let mut off = 0;
    for l in rest {
        if l.chars().all(is_space) {
            out.push("");
        } else if let Some(s) = l.strip_prefix(last) {
            out.push(s);
        } else {
            return Err((
                off,
                "a line of a multi-line string does not start with the closing line's indentation"
                    .into(),
            ));
        }
        off += l.len() + 1;
    }
    let joined = out.join("\n");
    if escapes {
        unescape(&joined)
    } else {
        Ok(joined)
    }
}

/// The lines of a text (split at any newline; CR LF once).
fn split_lines(s: &str) -> Vec<&str> {
    let mut out = Vec::new();
    let mut start = 0;
    let mut it = s.char_indices().peekable();
    while let Some((k, c)) = it.next() {
        if is_newline(c) {
            out.push(&s[start..k]);
            let mut end = k + c.len_utf8();
            if c == '\r' && it.peek().map(|x| x.1) == Some('\n') {
                it.next();
                end += 1;
            }
            start = end;
        }
    }
    out.push(&s[start..]);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// At most the first 60 characters of a test input, for messages.
    fn short(text: &str) -> String {
        text.chars().take(60).collect()
    }

    fn doc(text: &str) -> Vec<Node> {
        parse(text).unwrap_or_else(|e| panic!("{:?}: {e:?}", short(text)))
    }

    fn err(text: &str) -> SyntaxError {
        match parse(text) {
            Ok(_) => panic!("{:?} was read", short(text)),
            Err(e) => e,
        }
    }

    fn args(n: &Node) -> Vec<Value> {
        n.entries.iter().map(|e| e.value.clone()).collect()
    }

    #[test]
    fn nodes_entries_and_blocks() {
        let d = doc("a 1 -2.5 \"s\" k=v x=#true { b; c 0x1F 0o17 0b101 1_000 }\nd #null #inf");
        assert_eq!(d.len(), 2);
        assert_eq!(d[0].name.value, "a");
        use Value::*;
        assert_eq!(
            args(&d[0]),
            [
                Integer(1),
                Float(-2.5),
                String("s".into()),
                String("v".into()),
                Bool(true)
            ]
        );
        assert_eq!(d[0].entries[3].name.as_ref().unwrap().value, "k");
        assert_eq!(d[0].entries[3].at, 13);
        let c = d[0].children.as_ref().unwrap();
        assert_eq!(c.len(), 2);
        assert_eq!(
            args(&c[1]),
            [Integer(31), Integer(15), Integer(5), Integer(1000)]
        );
        assert_eq!(args(&d[1])[0], Null);
        assert_eq!(args(&d[1])[1], Float(f64::INFINITY));
        assert_eq!(d[1].name.at, 56);
    }

    #[test]
    fn strings_of_every_kind() {
        let d = doc("n \"a\\tb\\u{e9}\\s\" #\"raw \\n\"# ##\"q\"#\"## \"x\\\n   y\"");
        let v: Vec<String> = d[0]
            .entries
            .iter()
            .map(|e| match &e.value {
                Value::String(s) => s.clone(),
                other => panic!("{other:?}"),
            })
            .collect();
        assert_eq!(v, ["a\tb\u{e9} ", "raw \\n", "q\"#", "xy"]);
        let d = doc("n \"\"\"\n    one\n      two\n\n    three\n    \"\"\"");
        assert_eq!(args(&d[0])[0], Value::String("one\n  two\n\nthree".into()));
        let d = doc("n #\"\"\"\n  a\\n\n  \"\"\"#");
        assert_eq!(args(&d[0])[0], Value::String("a\\n".into()));
    }

    #[test]
    fn comments_slashdash_and_continuations() {
        let d = doc("// c\n/* a /* nested */ b */ a /-1 2 \\ // cont\n  3 /- { x } /-{ y }\n/- b 1 { c }\nc");
        assert!(err("a /-{ x } 2").msg.contains("after its `{ }` block"));
        assert!(err("a /-{ x } /- 2").msg.contains("only blocks may follow"));
        assert!(err("a { x } y").msg.contains("after its `{ }` block"));
        assert_eq!(d.len(), 2);
        assert_eq!(args(&d[0]), [Value::Integer(2), Value::Integer(3)]);
        assert!(d[0].children.is_none());
        assert_eq!(d[1].name.value, "c");
        let d = doc("a { b }; c {\n}\n");
        assert_eq!(d.len(), 2);
    }

    #[test]
    fn deep_input_is_refused_or_read_without_recursion() {
        let deep = "a {\n".repeat(5000) + &"}\n".repeat(5000);
        let e = err(&deep);
        assert_eq!(e.msg, "blocks are nested more than 64 deep");
        assert_eq!(e.at, 64 * 4 + 2);
        // Nested comments and slashdash chains cost no stack.
        let comments = "/*".repeat(100_000) + &"*/".repeat(100_000) + "\na";
        assert_eq!(doc(&comments).len(), 1);
        let dashes = "a ".to_string() + &"/- ".repeat(100_000) + "1 2";
        assert!(err(&dashes).msg.contains("not another `/-`"));
        let dashes = "/- ".repeat(100_000) + "a";
        assert!(err(&dashes).msg.contains("not another `/-`"));
    }

    #[test]
    fn errors_name_their_place_and_hint_at_v1() {
        let cases = [
            ("a 1.", 2, "fraction"),
            ("a true", 2, "KDL v1"),
            ("a r\"x\"", 2, "KDL v1 raw string"),
            ("a \"x", 2, "unterminated string"),
            ("a /* x", 2, "unterminated /*"),
            ("a {", 3, "not closed"),
            ("}", 0, "no block is open"),
            ("a 1x", 2, "not a valid value"),
            ("a #yes", 2, "unknown keyword"),
            ("a 1 { } 2", 8, "after its `{ }` block"),
            ("a \"\\q\"", 3, "unknown escape"),
            ("a b=", 4, "expected a value"),
            ("a \u{1} b", 2, "U+0001"),
            ("(t", 2, "`)`"),
            ("a 12abc", 2, "not a valid value"),
        ];
        for (text, at, want) in cases {
            let e = err(text);
            assert!(e.msg.contains(want), "{text:?}: {e:?}");
            assert_eq!(e.at, at, "{text:?}: {e:?}");
        }
    }

    #[test]
    fn big_numbers_keep_their_literal() {
        let d = doc("a 1e400 123456789012345678901234567890123456789012");
        assert_eq!(d[0].entries[0].value, Value::Float(f64::INFINITY));
        let (s, e) = d[0].entries[0].literal;
        assert_eq!(&"a 1e400 x"[s..e], "1e400");
        assert!(matches!(d[0].entries[1].value, Value::Float(v) if v > 1e40));
    }

    /// The document as one line per node (depth, name, entries), for comparisons.
    fn outline(nodes: &[Node], depth: usize, out: &mut Vec<String>) {
        for n in nodes {
            let entries: Vec<String> = n
                .entries
                .iter()
                .map(|e| {
                    let key = e
                        .name
                        .as_ref()
                        .map_or(String::new(), |k| format!("{}=", k.value));
                    format!("{key}{:?}", e.value)
                })
                .collect();
            out.push(format!("{depth} {} {}", n.name.value, entries.join(" ")));
            if let Some(c) = &n.children {
                outline(c, depth + 1, out);
            }
        }
    }

    /// The same outline from the `kdl` crate's parser.
    fn kdl_outline(doc: &::kdl::KdlDocument, depth: usize, out: &mut Vec<String>) {
        for n in doc.nodes() {
            let entries: Vec<String> = n
                .entries()
                .iter()
                .map(|e| {
                    let key = e
                        .name()
                        .map_or(String::new(), |k| format!("{}=", k.value()));
                    let v = match e.value() {
                        ::kdl::KdlValue::String(s) => Value::String(s.clone()),
                        ::kdl::KdlValue::Integer(i) => Value::Integer(*i),
                        ::kdl::KdlValue::Float(f) => Value::Float(*f),
                        ::kdl::KdlValue::Bool(b) => Value::Bool(*b),
                        ::kdl::KdlValue::Null => Value::Null,
                    };
                    format!("{key}{v:?}")
                })
                .collect();
            out.push(format!(
                "{depth} {} {}",
                n.name().value(),
                entries.join(" ")
            ));
            if let Some(c) = n.children() {
                kdl_outline(c, depth + 1, out);
            }
        }
    }

    #[test]
    fn reads_as_the_kdl_crate_does() {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
        let mut texts: Vec<String> = [
            "scenes/assembly.kdl",
            "scenes/polyhedra.kdl",
            "scenes/town.kdl",
        ]
        .iter()
        .map(|f| std::fs::read_to_string(dir.join(f)).unwrap())
        .collect();
        texts.extend(
            [
                "a 1 -2.5 +3 1e3 1.5E-2 0x1f -0o17 0b1_01 1_000 #true #false #null \"s\" b k=v \"q k\"=1",
                "// c\n/* a /* b */ */ n /-1 2 \\ // more\n 3 /-{ x }\n/- m\nm2;m3 { }",
                "n #\"raw\"# ##\"q\"#\"## \"e\\t\\u{263a}\\s\" .x -y +z -.w",
                "n \"\"\"\n  a\n    b\n  \"\"\"",
                "n { a { b { c 1; d 2 } }; e }\nf",
                "\u{feff}n 1\r\nm 2\rk 3",
            ]
            .map(String::from),
        );
        for text in &texts {
            let (mut ours, mut theirs) = (Vec::new(), Vec::new());
            outline(&doc(text), 0, &mut ours);
            let d = ::kdl::KdlDocument::parse_v2(text)
                .unwrap_or_else(|e| panic!("{:?}: {e}", short(text)));
            kdl_outline(&d, 0, &mut theirs);
            assert_eq!(ours, theirs, "{:?}", short(text));
        }
    }

    #[test]
    fn reading_is_linear() {
        // 20 MB of comments, 100k small nodes: both read in well under a second in release
        // builds; here only that they are read.
        let text = "// a comment line\n".repeat(100_000)
            + &"object \"o\" { box 0 0 0 1 1 1 }\n".repeat(50_000);
        assert_eq!(doc(&text).len(), 50_000);
    }
}
