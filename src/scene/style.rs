//! How an object is drawn: occlude-only (it hides, and is never drawn nor listed), its pen
//! (the layer its lines go to) and its line weight. Set on objects in scene files (a
//! `style` node, inherited by the parts below) and by object path in a style file
//! (`--styles`), which applies after, a later rule over an earlier one.

use super::{Content, Object, Scene};

/// An object's drawing style; each field unset inherits.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Style {
    /// Hides what is behind it but is never drawn: no lines, no fill, no JSON entry.
    pub occlude_only: Option<bool>,
    /// The pen (the SVG layer number) its lines are drawn with, 1 to 99.
    pub pen: Option<u32>,
    /// The stroke width of its lines in mm.
    pub weight: Option<f64>,
}

impl Style {
    /// This style with the fields `over` sets replaced.
    pub(crate) fn then(self, over: &Style) -> Style {
        Style {
            occlude_only: over.occlude_only.or(self.occlude_only),
            pen: over.pen.or(self.pen),
            weight: over.weight.or(self.weight),
        }
    }

    /// True when the object is never drawn.
    pub(crate) fn hidden(&self) -> bool {
        self.occlude_only == Some(true)
    }
}

/// True when `pattern` names the object at `path` or one above it: the pattern matches the
/// whole path or the part before a `/`; `*` matches any run of characters (`/` included),
/// `?` any one.
pub(crate) fn matches(pattern: &str, path: &str) -> bool {
    glob(pattern.as_bytes(), path.as_bytes())
        || path
            .match_indices('/')
            .any(|(i, _)| glob(pattern.as_bytes(), &path.as_bytes()[..i]))
}

/// Wildcard match of the whole of `s` (iterative, linear in practice, no recursion).
fn glob(p: &[u8], s: &[u8]) -> bool {
    let (mut i, mut j) = (0, 0);
    let mut star: Option<(usize, usize)> = None;
    while j < s.len() {
        if i < p.len() && (p[i] == b'?' || p[i] == s[j]) {
            i += 1;
            j += 1;
        } else if i < p.len() && p[i] == b'*' {
            star = Some((i, j));
            i += 1;
        } else if let Some((si, sj)) = star {
            i = si + 1;
            j = sj + 1;
            star = Some((si, sj + 1));
        } else {
            return false;
        }
    }
    p[i..].iter().all(|&c| c == b'*')
}

impl Scene {
    /// The style of every leaf, in [`Scene::leaves`] order: the styles of the objects on its
    /// path, outer first, then the style file's rules that match its path, in order. Empty
    /// when the scene has no style at all (every leaf's is the default).
    pub(crate) fn leaf_styles(&self) -> Vec<Style> {
        let mut out = Vec::new();
        if self.styles.is_empty() && !has_style(&self.root) {
            // No styles anywhere: every leaf's is the default (empty: nothing to look up).
            return out;
        }
        let mut path = Vec::new();
        walk(
            &self.root,
            Style::default(),
            &mut path,
            &mut |path, style| {
                let p = path.join("/");
                let s = self
                    .styles
                    .iter()
                    .filter(|(pat, _)| matches(pat, &p))
                    .fold(style, |s, (_, r)| s.then(r));
                out.push(s);
            },
        );
        out
    }

    /// Adds style rules (an object path or pattern and a style) after those it has.
    pub fn add_styles(&mut self, rules: impl IntoIterator<Item = (String, Style)>) {
        self.styles.extend(rules);
    }
}

/// True when some object below has a style of its own.
fn has_style(o: &Object) -> bool {
    o.style.is_some()
        || match &o.content {
            Content::Mesh(_) => false,
            Content::Subobjects(s) => s.iter().any(has_style),
            Content::Instance(i) => has_style(&i.prototype),
        }
}

/// Visits every leaf depth-first (the global order) with its path and inherited style.
fn walk<'a>(
    o: &'a Object,
    inherited: Style,
    path: &mut Vec<&'a str>,
    f: &mut dyn FnMut(&[&'a str], Style),
) {
    let style = o.style.as_ref().map_or(inherited, |s| inherited.then(s));
    match &o.content {
        Content::Mesh(_) => f(path, style),
        Content::Subobjects(subs) => {
            for s in subs {
                path.push(&s.name);
                walk(s, style, path, f);
                path.pop();
            }
        }
        Content::Instance(i) => walk(&i.prototype, style, path, f),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn patterns_name_objects_and_what_is_below() {
        assert!(matches("a", "a"));
        assert!(matches("a", "a/b/c"));
        assert!(matches("a/b", "a/b/c"));
        assert!(!matches("a/b", "a/bc"));
        assert!(!matches("b", "a/b"));
        assert!(matches("*/b", "a/b"));
        assert!(matches("house*", "house12/roof"));
        assert!(matches("h?", "h1"));
        assert!(!matches("h?", "h12"));
        assert!(matches("*", "anything/at/all"));
    }

    #[test]
    fn later_styles_win_field_by_field() {
        let a = Style {
            pen: Some(3),
            weight: Some(0.5),
            ..Style::default()
        };
        let b = Style {
            weight: Some(1.0),
            occlude_only: Some(true),
            ..Style::default()
        };
        let c = a.then(&b);
        assert_eq!(c.pen, Some(3));
        assert_eq!(c.weight, Some(1.0));
        assert!(c.hidden());
    }
}
