//! The `section` node of scene files: a plane that cuts the scene, removing the side its
//! normal points to (`section { point X Y Z; normal X Y Z }`, as `--section` does).

use super::args::Node;
use crate::error::Result;
use crate::geom::{P3, V3};

/// Parses a `section { point X Y Z; normal X Y Z }` node.
pub(super) fn parse_section(n: &Node) -> Result<(P3, V3)> {
    n.check_props(&[])?;
    if !n.args().is_empty() {
        return Err(n.parse_err(
            "`section` takes no arguments, only a { point X Y Z; normal X Y Z } block",
        ));
    }
    let mut point: Option<(V3, Node)> = None;
    let mut normal: Option<(V3, Node)> = None;
    for c in n.children()? {
        c.check_props(&[])?;
        c.no_children()?;
        let slot = match c.name() {
            "point" => &mut point,
            "normal" => &mut normal,
            other => {
                return Err(c.parse_err(format!(
                    "unknown section setting `{other}`: expected `point` or `normal`"
                )))
            }
        };
        if let Some((_, first)) = slot {
            return Err(c.parse_err(format!(
                "`{}` given twice in the section (first at {})",
                c.name(),
                first.loc()
            )));
        }
        let v = c.numbers(&[3], "numbers (X Y Z)")?;
        *slot = Some((V3::new(v[0], v[1], v[2]), c));
    }
    let (Some((p, _)), Some((nv, nn))) = (point, normal) else {
        return Err(n.parse_err("the section needs `point X Y Z` and `normal X Y Z`"));
    };
    if nv.iter().all(|&x| x == 0.0) {
        return Err(nn.invalid("the section's normal is zero"));
    }
    Ok((P3::from(p), nv))
}
