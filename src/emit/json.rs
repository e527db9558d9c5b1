//! The `kepler-visible/1` visible-polygon set: canonical JSON (same input, same bytes).
//!
//! Faces by id, one per line; rings start at their least point (x, then y); numbers in the
//! shortest form that reads back to the same f64, with -0 written as 0. A perspective camera
//! also carries `near` (the near plane, the least w' kept by clipping) and `eye`.

use std::fmt::Write as _;

use crate::geom::poly2::Pt2;
use crate::progress::Progress;
use crate::scene::flatten::write_num;
use crate::view::{Projection, View};
use crate::visibility::Visibility;

/// Polylines of a line drawing, in screen space.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Lines {
    /// Visible polylines.
    pub visible: Vec<Vec<Pt2>>,
    /// Hidden polylines.
    pub hidden: Vec<Vec<Pt2>>,
}

/// Shortest round-trip form of a finite number, -0 as 0.
pub fn num(x: f64) -> String {
    crate::scene::flatten::num(x)
}

fn point(s: &mut String, p: &Pt2) {
    s.push('[');
    write_num(s, p[0]);
    s.push(',');
    write_num(s, p[1]);
    s.push(']');
}

fn ring(s: &mut String, r: &[Pt2]) {
    s.push('[');
    for (i, p) in r.iter().enumerate() {
        if i > 0 {
            s.push(',');
        }
        point(s, p);
    }
    s.push(']');
}

fn list<T>(s: &mut String, items: &[T], mut each: impl FnMut(&mut String, &T)) {
    s.push('[');
    for (i, it) in items.iter().enumerate() {
        if i > 0 {
            s.push(',');
        }
        each(s, it);
    }
    s.push(']');
}

/// The JSON document for a view's visible-polygon set (faces with nothing visible left out),
/// with `lines` when given.
pub fn to_json(view: &View, vis: &Visibility, lines: Option<&Lines>) -> String {
    to_json_counted(view, vis, lines, &Progress::new())
}

/// [`to_json`], counting in `progress` the solved faces as they are written.
pub(crate) fn to_json_counted(
    view: &View,
    vis: &Visibility,
    lines: Option<&Lines>,
    progress: &Progress,
) -> String {
    let mut s = String::with_capacity(256 + vis.solved_count() * 128);
    s.push_str("{\"format\":\"kepler-visible/1\",\n\"camera\":{\"projection\":");
    s.push_str(match view.camera.projection {
        Projection::Orthographic => "\"orthographic\"",
        Projection::Perspective => "\"perspective\"",
    });
    s.push_str(",\"matrix\":[");
    for r in 0..4 {
        if r > 0 {
            s.push(',');
        }
        let row: Vec<f64> = (0..4).map(|c| view.camera.matrix[(r, c)]).collect();
        list(&mut s, &row, |s, x| s.push_str(&num(*x)));
    }
    s.push(']');
    if view.camera.projection == Projection::Perspective {
        // The near plane (least w') and the eye: the clipping reproduces from the file alone.
        let _ = write!(s, ",\"near\":{}", num(view.camera.near));
        if let Some(e) = view.camera.eye {
            s.push_str(",\"eye\":");
            list(&mut s, &[e.x, e.y, e.z], |s, x| s.push_str(&num(*x)));
        }
    }
    s.push_str("},\n\"faces\":[");
    // Each leaf's path as a JSON string, once.
    let paths: Vec<String> = view
        .screen
        .leaves
        .iter()
        .map(|l| json_string(&l.path))
        .collect();
    let mut first = true;
    for (k, (id, f)) in vis.iter().enumerate() {
        progress.tick(k);
        if f.visible.is_empty() {
            continue;
        }
        s.push_str(if first { "\n" } else { ",\n" });
        first = false;
        let leaf = view.screen.leaf_index_of_face(id);
        let _ = write!(
            s,
            "{{\"id\":{id},\"object\":{},\"area\":",
            paths[leaf as usize]
        );
        write_num(&mut s, f.area);
        s.push_str(",\"visible\":");
        list(&mut s, &f.visible, |s, poly| {
            list(s, poly, |s, r| ring(s, r))
        });
        s.push('}');
    }
    progress.tick_rest(vis.solved_count());
    s.push_str("\n]");
    if let Some(l) = lines {
        s.push_str(",\n\"lines\":{\"visible\":");
        list(&mut s, &l.visible, |s, r| ring(s, r));
        s.push_str(",\n\"hidden\":");
        list(&mut s, &l.hidden, |s, r| ring(s, r));
        s.push('}');
    }
    s.push_str("}\n");
    s
}

/// A JSON string literal.
pub fn json_string(x: &str) -> String {
    serde_json::to_string(x).unwrap_or_else(|_| "\"\"".into())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_shortest_round_trip() {
        assert_eq!(num(0.1), "0.1");
        assert_eq!(num(-0.0), "0");
        assert_eq!(num(1e-300), "1e-300");
        assert_eq!(num(2.0), "2");
        for x in [1.0 / 3.0, 12345.678e10, -7.25e-9] {
            assert_eq!(num(x).parse::<f64>().unwrap(), x);
        }
        assert_eq!(json_string("a\"b"), "\"a\\\"b\"");
    }
}
