//! Small SVG charts: lines and markers on linear or logarithmic axes, written with the `svg`
//! crate as the library's own SVG writer is.

use svg::node::element::{Circle, Line, Polyline, Rectangle, Text};
use svg::node::Value;
use svg::{Document, Node};

/// How a series is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Style {
    /// A polyline through the points, with a marker on each.
    LineMarkers,
    /// Markers only.
    Markers,
    /// A dashed polyline without markers (reference lines).
    Dashed,
}

/// One named set of points.
#[derive(Debug, Clone)]
pub struct Series {
    /// Legend text.
    pub label: String,
    /// Stroke and fill colour (any SVG colour).
    pub colour: String,
    /// Data points (x, y); points a log axis cannot show (<= 0, non-finite) are left out.
    pub points: Vec<(f64, f64)>,
    /// Optional text next to each point (same length as `points`, or empty).
    pub labels: Vec<String>,
    /// How it is drawn.
    pub style: Style,
}

impl Series {
    /// A series without point labels.
    pub fn new(label: &str, colour: &str, style: Style, points: Vec<(f64, f64)>) -> Series {
        Series {
            label: label.to_string(),
            colour: colour.to_string(),
            points,
            labels: Vec::new(),
            style,
        }
    }
}

/// A chart: title, axes and series (and free-text notes under the title).
#[derive(Debug, Clone, Default)]
pub struct Chart {
    /// Title at the top.
    pub title: String,
    /// Lines of small text under the title.
    pub notes: Vec<String>,
    /// Horizontal axis label.
    pub x_label: String,
    /// Vertical axis label.
    pub y_label: String,
    /// Logarithmic horizontal axis.
    pub log_x: bool,
    /// Logarithmic vertical axis.
    pub log_y: bool,
    /// The data.
    pub series: Vec<Series>,
}

/// Canvas size and margins (left, right, top, bottom).
const W: f64 = 760.0;
const H: f64 = 500.0;
const ML: f64 = 80.0;
const MR: f64 = 210.0;
const MB: f64 = 56.0;

/// One axis: data value to plot coordinate, and its ticks.
#[derive(Debug, Clone, Copy)]
struct Axis {
    log: bool,
    lo: f64,
    hi: f64,
    from: f64,
    to: f64,
}

impl Axis {
    /// An axis over the given values (in data units), mapped onto [from, to].
    fn over(values: &[f64], log: bool, from: f64, to: f64) -> Axis {
        let t: Vec<f64> = values.iter().map(|&v| tr(v, log)).collect();
        let mut lo = t.iter().cloned().fold(f64::INFINITY, f64::min);
        let mut hi = t.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
        if !(lo.is_finite() && hi.is_finite() && lo <= hi) {
            (lo, hi) = (0.0, 1.0);
        }
        if log {
            (lo, hi) = (lo.floor(), hi.ceil());
        } else {
            let pad = 0.05 * (hi - lo).max(1e-12);
            (lo, hi) = (lo - pad, hi + pad);
        }
        if hi - lo < 1e-12 {
            hi = lo + 1.0;
        }
        Axis {
            log,
            lo,
            hi,
            from,
            to,
        }
    }

    /// Plot coordinate of a data value.
    fn at(&self, v: f64) -> f64 {
        self.from + (tr(v, self.log) - self.lo) / (self.hi - self.lo) * (self.to - self.from)
    }

    /// Tick values (data units) with their labels: decades on a log axis (with 2 and 5 when
    /// it spans fewer than three), about six round numbers on a linear one.
    fn ticks(&self) -> Vec<(f64, String)> {
        if self.log {
            let decades = (self.hi - self.lo).round() as i32;
            let mut out = Vec::new();
            for e in self.lo as i32..=self.hi as i32 {
                let steps: &[f64] = if decades < 3 { &[1., 2., 5.] } else { &[1.] };
                for &m in steps {
                    let v = m * 10f64.powi(e);
                    if v.log10() <= self.hi + 1e-9 {
                        out.push((v, number(v)));
                    }
                }
            }
            return out;
        }
        let span = self.hi - self.lo;
        let raw = span / 6.0;
        let mag = 10f64.powf(raw.log10().floor());
        let step = [1., 2., 5., 10.]
            .iter()
            .map(|m| m * mag)
            .find(|s| *s >= raw)
            .unwrap_or(10. * mag);
        let mut v = (self.lo / step).ceil() * step;
        let mut out = Vec::new();
        while v <= self.hi + 1e-9 * span {
            out.push((v, number(v)));
            v += step;
        }
        out
    }
}

/// A value on the axis scale (log10 for a log axis).
fn tr(v: f64, log: bool) -> f64 {
    if log {
        v.log10()
    } else {
        v
    }
}

/// Whether a point can be shown on the chart's axes.
fn shown(c: &Chart, p: &(f64, f64)) -> bool {
    let ok = |v: f64, log: bool| v.is_finite() && (!log || v > 0.0);
    ok(p.0, c.log_x) && ok(p.1, c.log_y)
}

/// A tick label: short, no trailing zeros, powers of ten beyond 1e5 and below 1e-3 as 1e±k.
pub fn number(v: f64) -> String {
    let a = v.abs();
    if v == 0.0 {
        return "0".into();
    }
    if !(1e-3..1e6).contains(&a) {
        let e = a.log10().floor() as i32;
        let m = v / 10f64.powi(e);
        if (m - m.round()).abs() < 1e-9 {
            return format!("{}e{e}", m.round());
        }
        return format!("{m:.1}e{e}");
    }
    let s = format!("{v:.3}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    s.to_string()
}

/// A plot coordinate as SVG text: two decimals, as the charts have always been written.
fn c2(v: f64) -> String {
    format!("{v:.2}")
}

/// A text element at (x, y).
fn text(x: impl Into<Value>, y: impl Into<Value>, content: &str) -> Text {
    Text::new(content).set("x", x).set("y", y)
}

/// The dash pattern of a series' lines, where it has one.
fn dashed<T: Node>(mut e: T, style: Style) -> T {
    if style == Style::Dashed {
        e.assign("stroke-dasharray", "6 4");
    }
    e
}

/// The chart as a standalone SVG document.
pub fn to_svg(c: &Chart) -> String {
    let top = 48.0 + 14.0 * c.notes.len() as f64;
    let pts: Vec<(f64, f64)> = c
        .series
        .iter()
        .flat_map(|s| s.points.iter().copied())
        .filter(|p| shown(c, p))
        .collect();
    let xs: Vec<f64> = pts.iter().map(|p| p.0).collect();
    let ys: Vec<f64> = pts.iter().map(|p| p.1).collect();
    let ax = Axis::over(&xs, c.log_x, ML, W - MR);
    let ay = Axis::over(&ys, c.log_y, H - MB, top);
    let mut doc = Document::new()
        .set("width", W)
        .set("height", H)
        .set("viewBox", format!("0 0 {W} {H}"))
        .set("font-family", "sans-serif")
        .set("font-size", 12)
        .add(
            Rectangle::new()
                .set("width", "100%")
                .set("height", "100%")
                .set("fill", "white"),
        )
        .add(
            text((ML + W - MR) / 2.0, 22, &c.title)
                .set("text-anchor", "middle")
                .set("font-size", 15),
        );
    for (k, n) in c.notes.iter().enumerate() {
        doc = doc.add(
            text(ML, 40.0 + 14.0 * k as f64, n)
                .set("font-size", 11)
                .set("fill", "#555"),
        );
    }
    doc = labels(grid(doc, &ax, &ay, top), c, top);
    for (k, se) in c.series.iter().enumerate() {
        doc = legend(series(doc, c, se, &ax, &ay), se, top + 20.0 * k as f64);
    }
    format!("{doc}\n")
}

/// Grid lines and tick labels of both axes, and the plot frame.
fn grid(mut doc: Document, ax: &Axis, ay: &Axis, top: f64) -> Document {
    let rule = |x1: Value, y1: Value, x2: Value, y2: Value| {
        Line::new()
            .set("x1", x1)
            .set("y1", y1)
            .set("x2", x2)
            .set("y2", y2)
            .set("stroke", "#e4e4e4")
    };
    for (v, t) in ax.ticks() {
        let x = c2(ax.at(v));
        doc = doc
            .add(rule(
                x.clone().into(),
                top.into(),
                x.clone().into(),
                (H - MB).into(),
            ))
            .add(text(x, H - MB + 16.0, &t).set("text-anchor", "middle"));
    }
    for (v, t) in ay.ticks() {
        let y = ay.at(v);
        doc = doc
            .add(rule(ML.into(), c2(y).into(), (W - MR).into(), c2(y).into()))
            .add(text(ML - 6.0, c2(y + 4.0), &t).set("text-anchor", "end"));
    }
    doc.add(
        Rectangle::new()
            .set("x", ML)
            .set("y", top)
            .set("width", W - MR - ML)
            .set("height", H - MB - top)
            .set("fill", "none")
            .set("stroke", "black"),
    )
}

/// Axis labels.
fn labels(doc: Document, c: &Chart, top: f64) -> Document {
    let log = |l: bool| if l { " (log)" } else { "" };
    let cy = (top + H - MB) / 2.0;
    doc.add(
        text(
            (ML + W - MR) / 2.0,
            H - 14.0,
            &format!("{}{}", c.x_label, log(c.log_x)),
        )
        .set("text-anchor", "middle"),
    )
    .add(
        text(18, cy, &format!("{}{}", c.y_label, log(c.log_y)))
            .set("text-anchor", "middle")
            .set("transform", format!("rotate(-90 18 {cy})")),
    )
}

/// One series: its polyline and markers (and point labels).
fn series(mut doc: Document, c: &Chart, se: &Series, ax: &Axis, ay: &Axis) -> Document {
    let pts: Vec<(f64, f64, usize)> = se
        .points
        .iter()
        .enumerate()
        .filter(|(_, p)| shown(c, p))
        .map(|(k, p)| (ax.at(p.0), ay.at(p.1), k))
        .collect();
    let col = se.colour.as_str();
    if se.style != Style::Markers && pts.len() > 1 {
        let line: Vec<String> = pts
            .iter()
            .map(|p| format!("{},{}", c2(p.0), c2(p.1)))
            .collect();
        let polyline = Polyline::new()
            .set("fill", "none")
            .set("stroke", col)
            .set("stroke-width", 1.8)
            .set("points", line.join(" "));
        doc = doc.add(dashed(polyline, se.style));
    }
    if se.style == Style::Dashed {
        return doc;
    }
    for &(x, y, k) in &pts {
        doc = doc.add(
            Circle::new()
                .set("cx", c2(x))
                .set("cy", c2(y))
                .set("r", 3.5)
                .set("fill", col),
        );
        if let Some(t) = se.labels.get(k).filter(|t| !t.is_empty()) {
            doc = doc.add(
                text(c2(x + 5.0), c2(y - 5.0), t)
                    .set("font-size", 10)
                    .set("fill", col),
            );
        }
    }
    doc
}

/// One legend entry at height `y`, right of the plot.
fn legend(doc: Document, se: &Series, y: f64) -> Document {
    let x = W - MR + 12.0;
    let line = Line::new()
        .set("x1", x)
        .set("y1", y)
        .set("x2", x + 18.0)
        .set("y2", y)
        .set("stroke", se.colour.as_str())
        .set("stroke-width", 2);
    doc.add(dashed(line, se.style))
        .add(text(x + 24.0, y + 4.0, &se.label).set("font-size", 11))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn chart() -> Chart {
        Chart {
            title: "t <&>".into(),
            notes: vec!["note".into()],
            x_label: "faces".into(),
            y_label: "ms".into(),
            log_x: true,
            log_y: true,
            series: vec![
                Series::new(
                    "a",
                    "#123456",
                    Style::LineMarkers,
                    vec![(100., 1.), (1000., 10.), (10000., 100.), (0.0, 5.0)],
                ),
                Series::new(
                    "ref",
                    "grey",
                    Style::Dashed,
                    vec![(100., 2.), (10000., 200.)],
                ),
            ],
        }
    }

    /// Counts of opening and closing tags match, every element is closed.
    fn well_formed(svg: &str) -> bool {
        let opens = svg.matches('<').count();
        let closes = svg.matches('>').count();
        let self_closed = svg.matches("/>").count();
        let end_tags = svg.matches("</").count();
        let start_tags = opens - end_tags;
        opens == closes && start_tags - self_closed == end_tags
    }

    #[test]
    fn svg_is_well_formed_and_escaped() {
        let svg = to_svg(&chart());
        assert!(svg.starts_with("<svg "));
        assert!(svg.contains(" xmlns=\"http://www.w3.org/2000/svg\""));
        assert!(svg.trim_end().ends_with("</svg>"));
        assert!(well_formed(&svg));
        assert!(svg.contains("t &lt;&amp;&gt;"));
        assert!(svg.contains("stroke-dasharray"));
    }

    #[test]
    fn log_axes_put_decades_equally_apart() {
        let ax = Axis::over(&[100., 100000.], true, 0.0, 300.0);
        let ticks: Vec<f64> = ax.ticks().iter().map(|t| t.0).collect();
        assert_eq!(ticks, vec![100., 1000., 10000., 100000.]);
        let (a, b, c) = (ax.at(100.), ax.at(1000.), ax.at(10000.));
        assert!((b - a - (c - b)).abs() < 1e-9);
        assert_eq!((a, ax.at(100000.)), (0.0, 300.0));
        // Fewer than three decades: 1, 2 and 5 of each.
        let short = Axis::over(&[100., 1000.], true, 0.0, 300.0);
        assert_eq!(short.ticks().len(), 4);
        // A point a log axis cannot show (x = 0) is left out: three markers of series a.
        let svg = to_svg(&chart());
        assert_eq!(svg.matches("<circle").count(), 3);
        // The svg crate puts a text element's content on a line of its own.
        assert!(svg.lines().any(|l| l == "1e4" || l == "10000"), "{svg}");
    }

    #[test]
    fn tick_labels_are_short() {
        assert_eq!(number(1000.0), "1000");
        assert_eq!(number(0.5), "0.5");
        assert_eq!(number(1e-6), "1e-6");
        assert_eq!(number(1e6), "1e6");
    }
}
