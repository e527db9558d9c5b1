//! Styles in KDL: the `style` node of an object, instance or prototype block
//! (`style occlude-only=#true pen=3 weight=0.5`), and the style file of `--styles`, whose
//! nodes are `style "PATH-OR-PATTERN" pen=... weight=... occlude-only=#true`.

use std::path::Path;

use super::args::{boolean, Node};
use super::source::Source;
use crate::error::Result;
use crate::scene::style::Style;
use crate::scene::Scene;

/// The properties a `style` node may have.
const STYLE_PROPS: [&str; 3] = ["occlude-only", "pen", "weight"];

/// The style of a `style` node's properties (its arguments are the caller's).
pub(super) fn style_props(n: &Node) -> Result<Style> {
    n.check_props(&STYLE_PROPS)?;
    n.no_children()?;
    let mut s = Style::default();
    if let Some(e) = n.prop("occlude-only") {
        s.occlude_only = Some(boolean(n.src, e)?);
    }
    if let Some(p) = n.number_prop("pen")? {
        if !(p.fract() == 0.0 && (1.0..=99.0).contains(&p)) {
            return Err(n.invalid(format!("pen={p}: expected a whole number from 1 to 99")));
        }
        s.pen = Some(p as u32);
    }
    if let Some(w) = n.number_prop("weight")? {
        if !(w.is_finite() && w > 0.0 && w <= 100.0) {
            return Err(n.invalid(format!(
                "weight={w}: expected a stroke width in mm, above 0 and at most 100"
            )));
        }
        s.weight = Some(w);
    }
    Ok(s)
}

/// The `style` node of an object's block: properties only.
pub(super) fn parse_style(n: &Node) -> Result<Style> {
    if !n.args().is_empty() {
        return Err(n.parse_err(
            "`style` in a block takes properties only: occlude-only=#true, pen=N, weight=MM",
        ));
    }
    style_props(n)
}

impl Scene {
    /// Reads a style file (`--styles`): KDL nodes `style "PATH" occlude-only=#true pen=N
    /// weight=MM`, each applying to the objects whose path (or a path above theirs) the
    /// pattern matches (`*` any run of characters, `?` one), after the scene file's own
    /// styles, a later node over an earlier one. Errors name the file, line and column.
    pub fn load_styles(&mut self, path: &Path) -> Result<()> {
        let src = Source::read(path, None)?;
        let doc = src.parse()?;
        let mut rules = Vec::new();
        for kn in &doc {
            let n = Node::new(&src, kn);
            if n.name() != "style" {
                return Err(n.parse_err(format!(
                    "unknown node `{}` in a style file: expected `style \"PATH\" ...`",
                    crate::scene::names::printable(n.name())
                )));
            }
            let pattern = n
                .one_string("string (an object path or pattern)")?
                .to_string();
            rules.push((pattern, style_props(&n)?));
        }
        self.add_styles(rules);
        Ok(())
    }
}
