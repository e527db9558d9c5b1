//! Checked access to a KDL node's arguments, properties and children, with positioned errors.

use super::kdl::{Entry as KdlEntry, Node as KdlNode, Value as KdlValue};
use super::source::Source;
use crate::error::{Error, Location, Result};

/// Largest accepted |number| in a scene file (the cleanup stage's coordinate limit).
pub(super) const MAX_NUMBER: f64 = crate::geom::MAX_COORD;

/// A KDL node together with the source it came from, for checked access.
#[derive(Clone, Copy)]
pub(super) struct Node<'a> {
    /// The source text (for positions).
    pub src: &'a Source,
    /// The node.
    pub node: &'a KdlNode,
}

impl<'a> Node<'a> {
    /// Wraps `node` of `src`.
    pub(super) fn new(src: &'a Source, node: &'a KdlNode) -> Self {
        Node { src, node }
    }

    /// The node's name.
    pub(super) fn name(&self) -> &'a str {
        &self.node.name.value
    }

    /// The node's position.
    pub(super) fn loc(&self) -> Location {
        self.src.node_loc(self.node)
    }

    /// A parse error at the node.
    pub(super) fn parse_err(&self, msg: impl Into<String>) -> Error {
        Error::parse(self.loc(), msg)
    }

    /// An invalid-input error at the node.
    pub(super) fn invalid(&self, msg: impl Into<String>) -> Error {
        Error::invalid(self.loc(), msg)
    }

    /// The positional arguments, in order.
    pub(super) fn args(&self) -> Vec<&'a KdlEntry> {
        self.node
            .entries
            .iter()
            .filter(|e| e.name.is_none())
            .collect()
    }

    /// The property `key`, if given.
    pub(super) fn prop(&self, key: &str) -> Option<&'a KdlEntry> {
        self.node
            .entries
            .iter()
            .find(|e| e.name.as_ref().is_some_and(|n| n.value == key))
    }

    /// Checks that every property is one of `allowed` and given once, and that no type
    /// annotation is used.
    pub(super) fn check_props(&self, allowed: &[&str]) -> Result<()> {
        if self.node.ty.is_some() {
            return Err(self.parse_err("type annotations are not used in scene files"));
        }
        let mut seen: Vec<&str> = Vec::new();
        for e in &self.node.entries {
            if e.ty.is_some() {
                return Err(Error::parse(
                    self.src.entry_loc(e),
                    "type annotations are not used in scene files",
                ));
            }
            let Some(key) = e.name.as_ref().map(|n| n.value.as_str()) else {
                continue;
            };
            if !allowed.contains(&key) {
                let expected = if allowed.is_empty() {
                    "it takes no properties".to_string()
                } else {
                    format!("expected {}", quoted_list(allowed))
                };
                return Err(Error::parse(
                    self.src.entry_loc(e),
                    format!("unknown property `{key}` of `{}`: {expected}", self.name()),
                ));
            }
            if seen.contains(&key) {
                return Err(Error::parse(
                    self.src.entry_loc(e),
                    format!("property `{key}` given twice"),
                ));
            }
            seen.push(key);
        }
        Ok(())
    }

    /// Checks the argument count against `counts` (the accepted counts); `what` describes them.
    pub(super) fn check_count(&self, counts: &[usize], what: &str) -> Result<Vec<&'a KdlEntry>> {
        let args = self.args();
        if counts.contains(&args.len()) {
            return Ok(args);
        }
        let accepted = counts
            .iter()
            .map(|c| c.to_string())
            .collect::<Vec<_>>()
            .join(" or ");
        let msg = format!(
            "`{}` takes {accepted} {what}, found {}",
            self.name(),
            args.len()
        );
        // Point at the first surplus argument, else at the node.
        let max = counts.iter().copied().max().unwrap_or(0);
        match args.get(max) {
            Some(extra) => Err(Error::parse(self.src.entry_loc(extra), msg)),
            None => Err(self.parse_err(msg)),
        }
    }

    /// Exactly `n` numeric arguments (any of `counts`), checked finite and not huge.
    pub(super) fn numbers(&self, counts: &[usize], what: &str) -> Result<Vec<f64>> {
        self.check_count(counts, what)?
            .into_iter()
            .map(|e| number(self.src, e))
            .collect()
    }

    /// Exactly one string argument.
    pub(super) fn one_string(&self, what: &str) -> Result<&'a str> {
        let args = self.check_count(&[1], what)?;
        string(self.src, args[0])
    }

    /// The string property `key`, if given.
    pub(super) fn string_prop(&self, key: &str) -> Result<Option<&'a str>> {
        self.prop(key).map(|e| string(self.src, e)).transpose()
    }

    /// The number property `key`, if given.
    pub(super) fn number_prop(&self, key: &str) -> Result<Option<f64>> {
        self.prop(key).map(|e| number(self.src, e)).transpose()
    }

    /// The children, or an error when the node has no `{ }` block.
    pub(super) fn children(&self) -> Result<Vec<Node<'a>>> {
        match &self.node.children {
            Some(nodes) => Ok(nodes.iter().map(|n| Node::new(self.src, n)).collect()),
            None => Err(self.parse_err(format!("`{}` needs a {{ ... }} block", self.name()))),
        }
    }

    /// The children if there is a block, else none.
    pub(super) fn children_or_none(&self) -> Vec<Node<'a>> {
        self.node.children.as_ref().map_or_else(Vec::new, |nodes| {
            nodes.iter().map(|n| Node::new(self.src, n)).collect()
        })
    }

    /// An error when the node has a non-empty `{ }` block.
    pub(super) fn no_children(&self) -> Result<()> {
        match self.node.children.as_ref().and_then(|d| d.first()) {
            Some(first) => Err(Error::parse(
                self.src.node_loc(first),
                format!("`{}` takes no child nodes", self.name()),
            )),
            None => Ok(()),
        }
    }
}

/// A number argument: an integer or a float, finite and at most [`MAX_NUMBER`] in magnitude.
pub(super) fn number(src: &Source, e: &KdlEntry) -> Result<f64> {
    let x = match &e.value {
        KdlValue::Integer(i) => *i as f64,
        KdlValue::Float(f) => *f,
        other => {
            return Err(Error::parse(
                src.entry_loc(e),
                format!("expected a number, found {}", describe(other)),
            ))
        }
    };
    let literal = src.literal(e);
    if !x.is_finite() {
        let why = if literal.starts_with('#') {
            "is not finite"
        } else {
            "is out of range: it overflows a 64-bit float"
        };
        return Err(Error::invalid(
            src.entry_loc(e),
            format!("number {literal} {why}"),
        ));
    }
    if x.abs() > MAX_NUMBER {
        return Err(Error::invalid(
            src.entry_loc(e),
            format!("number {literal} is too large (the limit is {MAX_NUMBER:e})"),
        ));
    }
    Ok(x)
}

/// An integer argument.
pub(super) fn integer(src: &Source, e: &KdlEntry) -> Result<i128> {
    match &e.value {
        KdlValue::Integer(i) => Ok(*i),
        other => Err(Error::parse(
            src.entry_loc(e),
            format!("expected an integer, found {}", describe(other)),
        )),
    }
}

/// A string argument.
pub(super) fn string<'a>(src: &Source, e: &'a KdlEntry) -> Result<&'a str> {
    match &e.value {
        KdlValue::String(s) => Ok(s),
        other => Err(Error::parse(
            src.entry_loc(e),
            format!("expected a string, found {}", describe(other)),
        )),
    }
}

/// A boolean argument (`#true` / `#false`).
pub(super) fn boolean(src: &Source, e: &KdlEntry) -> Result<bool> {
    match &e.value {
        KdlValue::Bool(b) => Ok(*b),
        other => Err(Error::parse(
            src.entry_loc(e),
            format!("expected #true or #false, found {}", describe(other)),
        )),
    }
}

/// A short description of a value for messages.
fn describe(v: &KdlValue) -> String {
    match v {
        KdlValue::String(s) => format!("the string {s:?}"),
        KdlValue::Integer(i) => format!("the integer {i}"),
        KdlValue::Float(f) => format!("the number {f}"),
        KdlValue::Bool(b) => format!("#{b}"),
        KdlValue::Null => "#null".into(),
    }
}

/// `a`, `b` or `c`.
pub(super) fn quoted_list(items: &[&str]) -> String {
    let q: Vec<String> = items.iter().map(|s| format!("`{s}`")).collect();
    match q.split_last() {
        None => String::new(),
        Some((last, [])) => last.clone(),
        Some((last, rest)) => format!("{} or {last}", rest.join(", ")),
    }
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use super::*;

    fn with_node<T>(text: &str, f: impl FnOnce(Node) -> T) -> T {
        let src = Source::new(Path::new("a.kdl"), text.to_string());
        let doc = src.parse().unwrap();
        f(Node::new(&src, &doc[0]))
    }

    #[test]
    fn numbers_are_checked() {
        let v = with_node("box 1 2.5 -3 0x10", |n| n.numbers(&[4], "numbers").unwrap());
        assert_eq!(v, vec![1.0, 2.5, -3.0, 16.0]);
        let e = with_node("box 1 2", |n| {
            n.numbers(&[3], "numbers (X Y Z)").unwrap_err()
        });
        assert_eq!(
            e.to_string(),
            "a.kdl:1:1: `box` takes 3 numbers (X Y Z), found 2"
        );
        let e = with_node("box 1 2 3 4", |n| {
            n.numbers(&[1, 3], "numbers").unwrap_err()
        });
        assert_eq!(
            e.to_string(),
            "a.kdl:1:11: `box` takes 1 or 3 numbers, found 4"
        );
        let e = with_node("t 1 #nan", |n| n.numbers(&[2], "n").unwrap_err());
        assert_eq!(e.to_string(), "a.kdl:1:5: number #nan is not finite");
        let e = with_node("t 1e13", |n| n.numbers(&[1], "n").unwrap_err());
        assert_eq!(
            e.to_string(),
            "a.kdl:1:3: number 1e13 is too large (the limit is 1e12)"
        );
        let e = with_node("t 1e400", |n| n.numbers(&[1], "n").unwrap_err());
        assert_eq!(
            e.to_string(),
            "a.kdl:1:3: number 1e400 is out of range: it overflows a 64-bit float"
        );
        let e = with_node("t \"x\"", |n| n.numbers(&[1], "n").unwrap_err());
        assert_eq!(
            e.to_string(),
            "a.kdl:1:3: expected a number, found the string \"x\""
        );
    }

    #[test]
    fn properties_are_checked() {
        with_node("r 90 axis=z", |n| n.check_props(&["axis"]).unwrap());
        let e = with_node("r 90 axes=z", |n| {
            n.check_props(&["axis", "ax"]).unwrap_err()
        });
        assert_eq!(
            e.to_string(),
            "a.kdl:1:6: unknown property `axes` of `r`: expected `axis` or `ax`"
        );
        let e = with_node("r a=1 a=2", |n| n.check_props(&["a"]).unwrap_err());
        assert!(e
            .to_string()
            .starts_with("a.kdl:1:7: property `a` given twice"));
        let e = with_node("(t)r 1", |n| n.check_props(&[]).unwrap_err());
        assert!(e.to_string().contains("type annotations"));
    }

    #[test]
    fn children_checks() {
        let e = with_node("box 1 {\n  x\n}", |n| n.no_children().unwrap_err());
        assert_eq!(e.to_string(), "a.kdl:2:3: `box` takes no child nodes");
        with_node("box 1 {}", |n| n.no_children().unwrap());
        let e = with_node("object \"a\"", |n| n.children().map(|_| ()).unwrap_err());
        assert!(e.to_string().contains("needs a { ... } block"));
    }

    #[test]
    fn list_words() {
        assert_eq!(quoted_list(&["a"]), "`a`");
        assert_eq!(quoted_list(&["a", "b", "c"]), "`a`, `b` or `c`");
    }
}
