//! SVG output of a [`Picture`]: a page in millimetres (width and height in mm, a viewBox in
//! mm), one Inkscape layer per picture layer (`inkscape:groupmode="layer"`, label "N name",
//! which plotter tools such as vpype and the AxiDraw extension read as layer N), no
//! background unless one is asked for. The `svg` crate builds the document; path data is
//! written here with shortest round-trip f64 numbers (the crate's own path data rounds to f32).

use rayon::prelude::*;
use svg::node::element::{Group, Path, Rectangle};
use svg::Document;

use crate::count::Count;
use crate::geom::poly2::Pt2;

use super::json::num;
#[cfg(test)]
use crate::emit::plot::picture::Pen;
use crate::emit::plot::picture::{LayerMode, Picture, Run};
use crate::scene::flatten::write_num;

/// The Inkscape namespace (layers).
const INKSCAPE: &str = "http://www.inkscape.org/namespaces/inkscape";

/// The SVG document of a picture.
///
/// Each fill's rings and each run's strokes go to `done` as their paths are made.
pub(crate) fn to_svg(pic: &Picture, done: Count) -> String {
    let (w, h) = (pic.page.width, pic.page.height);
    let mut doc = Document::new()
        .set("xmlns:inkscape", INKSCAPE)
        .set("width", format!("{}mm", num(w)))
        .set("height", format!("{}mm", num(h)))
        .set("viewBox", format!("0 0 {} {}", num(w), num(h)));
    if let Some(bg) = pic.background {
        doc = doc.add(
            Rectangle::new()
                .set("id", "background")
                .set("width", num(w))
                .set("height", num(h))
                .set("fill", bg.hex()),
        );
    }
    if !pic.fills.is_empty() {
        // Numbered after every line layer, so plotter tools never merge it into one; drawn
        // first, under the lines. A thin stroke in each face's own grey closes seams.
        let number = pic.layers.iter().map(|l| l.number).max().unwrap_or(0) + 1;
        let mut g = layer(number, "fill")
            .set("stroke-width", num(0.05))
            .set("stroke-linejoin", "round");
        for f in &pic.fills {
            let mut d = String::new();
            for r in &f.rings {
                polyline(&mut d, r, true);
            }
            let grey = crate::emit::plot::color::Rgb::grey(f.grey).hex();
            g = g.add(
                Path::new()
                    .set("d", d)
                    .set("fill", grey.clone())
                    .set("stroke", grey)
                    .set("fill-rule", "evenodd"),
            );
            done.add(f.rings.len());
        }
        doc = doc.add(g);
    }
    for l in &pic.layers {
        let mut g = match pic.mode {
            LayerMode::None => Group::new().set("id", "drawing"),
            _ => layer(l.number, &l.name),
        }
        .set("fill", "none")
        .set("stroke-linecap", "round")
        .set("stroke-linejoin", "round");
        let one_pen = l
            .runs
            .windows(2)
            .all(|w| w[0].pen == w[1].pen && w[0].width_mm == w[1].width_mm);
        if let (true, Some(r)) = (one_pen, l.runs.first()) {
            // One pen: its colour and width on the layer, where plotter tools look for them.
            g = pen_style(g, r, pic);
        }
        for r in &l.runs {
            let mut p = Path::new()
                .set("class", r.pen.name())
                .set("d", path_data(&r.lines));
            if !one_pen {
                p = pen_style(p, r, pic);
            }
            g = g.add(p);
            done.add(r.lines.len());
        }
        doc = doc.add(g);
    }
    let mut s = doc.to_string();
    s.push('\n');
    s
}

/// An Inkscape layer group labelled "N name".
fn layer(number: u32, name: &str) -> Group {
    Group::new()
        .set("id", format!("layer{number}"))
        .set("inkscape:groupmode", "layer")
        .set(
            "inkscape:label",
            format!("{number} {}", crate::scene::names::printable(name)),
        )
}

/// Sets a pen's stroke colour and width (mm) on an element.
fn pen_style<T: svg::Node>(mut e: T, run: &Run, pic: &Picture) -> T {
    e.assign(
        "stroke",
        crate::emit::plot::color::Rgb::grey(run.pen.grey()).hex(),
    );
    e.assign("stroke-width", num(pic.run_width(run)));
    e
}

/// Polylines a task of [`path_data`] writes.
const PATH_TASK: usize = 2048;

/// "Mx,y Lx,y ..." of every polyline: [`PATH_TASK`] polylines a task, in parallel, joined in
/// order (the same text for any number of threads).
fn path_data(lines: &[Vec<Pt2>]) -> String {
    let part = |lines: &[Vec<Pt2>]| {
        let mut d = String::new();
        for l in lines {
            polyline(&mut d, l, false);
        }
        d
    };
    if lines.len() <= PATH_TASK {
        return part(lines);
    }
    let parts: Vec<String> = lines.par_chunks(PATH_TASK).map(part).collect();
    let mut d = String::with_capacity(parts.iter().map(String::len).sum());
    parts.iter().for_each(|p| d.push_str(p));
    d
}

/// Appends "Mx,y Lx,y ...", closed with Z when `close`.
fn polyline(d: &mut String, pts: &[Pt2], close: bool) {
    for (i, p) in pts.iter().enumerate() {
        d.push(if i == 0 { 'M' } else { 'L' });
        write_num(d, p[0]);
        d.push(',');
        write_num(d, p[1]);
    }
    if close && !pts.is_empty() {
        d.push('Z');
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::emit::plot::color::Rgb;
    use crate::emit::plot::page::PageSize;
    use crate::emit::plot::picture::{Fill, Layer, PlotStats, Run};

    fn pic(mode: LayerMode) -> Picture {
        Picture {
            page: PageSize::A4,
            pen_mm: 0.5,
            background: None,
            fills: vec![],
            layers: vec![
                Layer {
                    number: 1,
                    name: "outline".into(),
                    runs: vec![Run {
                        pen: Pen::Outline,
                        width_mm: None,
                        lines: vec![vec![[10.0, 20.0], [1.0 / 3.0, 50.0]]],
                    }],
                },
                Layer {
                    number: 6,
                    name: "hidden".into(),
                    runs: vec![Run {
                        pen: Pen::Hidden,
                        width_mm: None,
                        lines: vec![vec![[1.0, 1.0], [2.0, 1.0]], vec![[3.0, 1.0], [4.0, 1.0]]],
                    }],
                },
            ],
            mode,
            stats: PlotStats::default(),
        }
    }

    #[test]
    fn a4_page_in_mm_with_inkscape_layers_and_no_background() {
        let s = to_svg(&pic(LayerMode::Pen), Count::NONE);
        assert!(s.starts_with("<svg"), "{s}");
        assert!(s.contains(r#"width="210mm""#) && s.contains(r#"height="297mm""#));
        assert!(s.contains(r#"viewBox="0 0 210 297""#), "{s}");
        assert!(s.contains(r#"xmlns:inkscape="http://www.inkscape.org/namespaces/inkscape""#));
        assert!(s.contains(r#"inkscape:groupmode="layer""#));
        assert!(s.contains(r#"inkscape:label="1 outline""#));
        assert!(s.contains(r#"inkscape:label="6 hidden""#));
        assert!(s.contains("M10,20L0.3333333333333333,50"), "{s}");
        assert!(s.contains("M1,1L2,1M3,1L4,1"), "{s}");
        assert!(s.contains(r#"stroke-width="0.5""#) && s.contains(r#"stroke-width="0.25""#));
        assert!(!s.contains("<rect"));
        assert_eq!(s.matches("<path").count(), 2);
    }

    #[test]
    fn background_and_fills_only_when_asked() {
        let mut p = pic(LayerMode::None);
        p.background = Some(Rgb::parse("ivory").unwrap());
        p.fills = vec![Fill {
            rings: vec![vec![[0., 0.], [1., 0.], [0., 1.]]],
            grey: 200,
        }];
        let s = to_svg(&p, Count::NONE);
        assert!(s.contains(r##"fill="#fffff0""##));
        assert!(s.contains(r#"inkscape:label="7 fill""#), "{s}");
        assert!(s.contains(r##"fill="#c8c8c8""##));
        assert!(s.contains(r#"id="drawing""#));
    }

    #[test]
    fn many_polylines_are_written_in_order_in_parallel() {
        // More polylines than a task takes, on a pool of two threads: the same text as one
        // after the other, every polyline in place.
        let lines: Vec<Vec<Pt2>> = (0..2 * PATH_TASK + 7)
            .map(|k| {
                let x = k as f64 / 3.0;
                vec![[x, 1.0], [x + 0.5, -2.25], [x, 1e-9]]
            })
            .collect();
        let mut want = String::new();
        lines.iter().for_each(|l| polyline(&mut want, l, false));
        let pool = crate::chunked::pool(2);
        assert_eq!(pool.install(|| path_data(&lines)), want);
        assert_eq!(path_data(&lines[..3]), want[..want.find("M1,").unwrap()]);
        assert_eq!(want.matches('M').count(), lines.len());
    }
}
