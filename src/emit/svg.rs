//! SVG output of a [`Picture`]: the `svg` crate builds the document, path data is written
//! here with shortest round-trip f64 numbers (the crate's own path data rounds to f32).
//!
//! Screen y grows up and SVG y grows down, so every y is written negated. One `<g>` per
//! object (a layer for plotter tools), one path per object and pen.

use std::fmt::Write as _;

use svg::node::element::{Group, Path, Rectangle};
use svg::Document;

use crate::geom::poly2::Pt2;
use crate::geom::Rect;

use super::json::num;
use super::picture::{Pen, Picture};

/// The SVG document of a picture, `size` pixels along its longer side.
pub fn to_svg(pic: &Picture, size: u32) -> String {
    let Rect {
        xmin: x0,
        ymin: y0,
        xmax: x1,
        ymax: y1,
    } = pic.frame.rect;
    let (w, h) = (x1 - x0, y1 - y0);
    let px = f64::from(size.max(1)) / w.max(h);
    let view_box = format!("{} {} {} {}", num(x0), num(-y1), num(w), num(h));
    let mut doc = Document::new()
        .set("viewBox", view_box)
        .set("width", num((w * px).round().max(1.0)))
        .set("height", num((h * px).round().max(1.0)))
        .add(
            Rectangle::new()
                .set("x", num(x0))
                .set("y", num(-y1))
                .set("width", num(w))
                .set("height", num(h))
                .set("fill", "white"),
        );
    if !pic.fills.is_empty() {
        // A thin stroke in each face's own grey closes anti-aliasing seams between faces.
        let mut g = Group::new()
            .set("id", "fill")
            .set("stroke-width", num(0.0003 * pic.frame.unit))
            .set("stroke-linejoin", "round");
        for f in &pic.fills {
            let mut d = String::new();
            for r in &f.rings {
                polyline(&mut d, r, true);
            }
            g = g.add(
                Path::new()
                    .set("d", d)
                    .set("fill", grey(f.grey))
                    .set("stroke", grey(f.grey))
                    .set("fill-rule", "evenodd"),
            );
        }
        doc = doc.add(g);
    }
    let mut ids = Vec::new();
    for layer in &pic.layers {
        let id = unique_id(&layer.name, &mut ids);
        let mut g = Group::new()
            .set("id", id)
            .set("fill", "none")
            .set("stroke-linecap", "round")
            .set("stroke-linejoin", "round");
        for (pen, lines) in &layer.pens {
            g = g.add(pen_path(*pen, lines, pic.frame.unit));
        }
        doc = doc.add(g);
    }
    let mut s = doc.to_string();
    s.push('\n');
    s
}

/// One path for all polylines of a pen.
fn pen_path(pen: Pen, lines: &[Vec<Pt2>], unit: f64) -> Path {
    let mut d = String::new();
    for l in lines {
        polyline(&mut d, l, false);
    }
    let mut p = Path::new()
        .set("class", pen.name())
        .set("d", d)
        .set("stroke", grey(pen.grey()))
        .set("stroke-width", num(pen.width() * unit));
    if let Some([a, b]) = pen.dash() {
        p = p.set(
            "stroke-dasharray",
            format!("{} {}", num(a * unit), num(b * unit)),
        );
    }
    p
}

/// Appends "Mx,y Lx,y ..." (y negated), closed with Z when `close`.
fn polyline(d: &mut String, pts: &[Pt2], close: bool) {
    for (i, p) in pts.iter().enumerate() {
        let _ = write!(
            d,
            "{}{},{}",
            if i == 0 { "M" } else { "L" },
            num(p[0]),
            num(-p[1])
        );
    }
    if close && !pts.is_empty() {
        d.push('Z');
    }
}

/// "#rrggbb" of a grey level.
fn grey(g: u8) -> String {
    format!("#{g:02x}{g:02x}{g:02x}")
}

/// An XML id from an object path: letters, digits, '-', '_' and '.' kept, others '_';
/// prefixed so it starts with a letter, suffixed with a counter when already taken.
fn unique_id(name: &str, taken: &mut Vec<String>) -> String {
    let clean: String = name
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || "-_.".contains(c) {
                c
            } else {
                '_'
            }
        })
        .collect();
    let base = format!("obj_{clean}");
    let mut id = base.clone();
    let mut k = 1;
    while taken.contains(&id) {
        k += 1;
        id = format!("{base}_{k}");
    }
    taken.push(id.clone());
    id
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::emit::picture::{Fill, Layer};
    use crate::view::Frame;

    fn pic() -> Picture {
        Picture {
            frame: Frame {
                rect: Rect::new(-0.5, -0.5, 10.5, 5.5),
                unit: 10.0,
            },
            fills: vec![Fill {
                rings: vec![vec![[0., 0.], [1., 0.], [0., 1.]]],
                grey: 200,
            }],
            layers: vec![Layer {
                name: "house/roof".into(),
                pens: vec![(Pen::Heavy, vec![vec![[0.1, 0.2], [1.0 / 3.0, 5.0]]])],
            }],
        }
    }

    #[test]
    fn document_shape() {
        let s = to_svg(&pic(), 1100);
        assert!(s.starts_with("<svg"), "{s}");
        assert!(s.contains(r#"viewBox="-0.5 -5.5 11 6""#), "{s}");
        assert!(s.contains(r#"width="1100""#));
        assert!(s.contains(r#"id="obj_house_roof""#));
        assert!(s.contains("M0.1,-0.2L0.3333333333333333,-5"), "{s}");
        assert!(s.contains(r##"fill="#c8c8c8""##));
        assert_eq!(s.matches("<path").count(), 2);
    }

    #[test]
    fn ids_are_unique() {
        let mut t = Vec::new();
        assert_eq!(unique_id("a b", &mut t), "obj_a_b");
        assert_eq!(unique_id("a/b", &mut t), "obj_a_b_2");
    }
}
