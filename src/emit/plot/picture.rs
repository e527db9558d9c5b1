//! The picture both SVG and PNG draw, on a page in millimetres: fills, and layers of strokes
//! in the order a plotter draws them, each stroke with a pen. [`super::picture()`] builds it.

use crate::geom::poly2::{polyline_length, Pt2, Ring};
use crate::geom::{Rect, V3};

use super::color::Rgb;
use super::dedup::DedupStats;
use super::hatch::HatchOptions;
use super::page::PageSize;
use crate::emit::lines::edges::EdgeKind;

/// A pen: what a kind of line is drawn with. Pens in priority order: where two lines
/// coincide, the one with the earlier pen is kept.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Pen {
    /// Silhouettes and borders.
    Outline,
    /// Creases and plain polygon edges.
    Edges,
    /// Intersection curves.
    Intersection,
    /// Texture markings on faces.
    Mark,
    /// Hatching.
    Hatch,
    /// Hidden lines, as dashes.
    Hidden,
    /// Outlines of section faces and cut edges (heavy, layer 7 with the section hatching).
    Section,
    /// The section faces' 45° hatching (layer 7).
    SectionHatch,
}

impl Pen {
    /// Every pen, in layer order.
    pub const ALL: [Pen; 8] = [
        Pen::Outline,
        Pen::Edges,
        Pen::Intersection,
        Pen::Mark,
        Pen::Hatch,
        Pen::Hidden,
        Pen::Section,
        Pen::SectionHatch,
    ];

    /// The pen of a visible line kind.
    pub fn of(kind: EdgeKind) -> Pen {
        match kind {
            EdgeKind::Silhouette | EdgeKind::Border => Pen::Outline,
            EdgeKind::Intersection => Pen::Intersection,
            EdgeKind::Crease | EdgeKind::Plain => Pen::Edges,
            EdgeKind::Section => Pen::Section,
        }
    }

    /// Layer number of the pen with `--layers pen` (fixed, whichever pens are present).
    pub fn number(self) -> u32 {
        match self {
            Pen::Outline => 1,
            Pen::Edges => 2,
            Pen::Intersection => 3,
            Pen::Mark => 4,
            Pen::Hatch => 5,
            Pen::Hidden => 6,
            Pen::Section | Pen::SectionHatch => 7,
        }
    }

    /// Name (layer label and SVG class).
    pub fn name(self) -> &'static str {
        match self {
            Pen::Outline => "outline",
            Pen::Edges => "edges",
            Pen::Intersection => "intersections",
            Pen::Mark => "marks",
            Pen::Hatch => "hatching",
            Pen::Hidden => "hidden",
            Pen::Section => "section",
            Pen::SectionHatch => "section-hatching",
        }
    }

    /// Stroke width as a fraction of the outline pen's (`--pen`).
    pub fn width_factor(self) -> f64 {
        match self {
            Pen::Outline | Pen::Section => 1.0,
            Pen::Edges | Pen::Intersection => 0.6,
            Pen::Mark | Pen::Hatch | Pen::Hidden | Pen::SectionHatch => 0.5,
        }
    }

    /// Grey level of the ink (0 black).
    pub fn grey(self) -> u8 {
        match self {
            Pen::Hidden => 140,
            Pen::Mark => 70,
            _ => 0,
        }
    }
}

/// How the strokes are grouped into layers (`--layers`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum LayerMode {
    /// One layer per pen, numbered by [`Pen::number`].
    #[default]
    Pen,
    /// One layer per top-level object, numbered in object order.
    Object,
    /// Everything in one group (not a layer).
    None,
}

/// How the SVG and PNG pictures look.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PictureOptions {
    /// Without a page: the picture's longer side in CSS pixels (1/96 in) for the SVG and
    /// pixels for the PNG. With a page: the PNG's longer side, unless `dpi` is given.
    pub size: u32,
    /// PNG resolution in dots per inch of the page (instead of `size`).
    pub dpi: Option<f64>,
    /// A physical page (the drawing fitted inside the margin and centred); none: a page of
    /// the drawing's own shape.
    pub page: Option<PageSize>,
    /// Margin in mm (default: 10 mm on a page, 5% of the drawing without one).
    pub margin_mm: Option<f64>,
    /// Width of the outline pen in mm; the other pens are fractions of it.
    pub pen_mm: f64,
    /// How strokes are grouped into layers.
    pub layers: LayerMode,
    /// A background colour (SVG: a rectangle under everything; PNG: default white).
    pub background: Option<Rgb>,
    /// Hidden lines' dash and gap lengths in mm.
    pub dash_mm: [f64; 2],
    /// Stroke ends closer than this (mm) are joined into one stroke; 0 joins exact ends only.
    pub join_mm: f64,
    /// Simplify strokes to within this distance (mm; 0 keeps every point).
    pub simplify_mm: f64,
    /// Flat-shaded visible faces under the lines (not plottable: for the screen).
    pub fill: bool,
    /// Hatch the visible faces.
    pub hatch: Option<HatchOptions>,
    /// Direction toward the light for fills and hatching (world coordinates); default from
    /// the upper left, in front of the picture.
    pub light: Option<V3>,
    /// Frame this screen rectangle instead of the drawing's bounds (the same frame for every
    /// view of a turntable).
    pub frame: Option<Rect>,
    /// Spacing in mm of the 45° hatching of section faces (`--section-hatch`).
    pub section_hatch_mm: f64,
}

impl Default for PictureOptions {
    fn default() -> Self {
        PictureOptions {
            size: 1024,
            dpi: None,
            page: None,
            margin_mm: None,
            pen_mm: 0.5,
            layers: LayerMode::Pen,
            background: None,
            dash_mm: [2.0, 1.0],
            join_mm: 0.05,
            simplify_mm: 0.0,
            fill: false,
            hatch: None,
            light: None,
            frame: None,
            section_hatch_mm: 2.0,
        }
    }
}

/// The visible regions of the faces of one grey on the page, flat shaded.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Fill {
    /// Rings of the visible regions (even-odd fill; the regions are disjoint), in mm.
    pub rings: Vec<Ring>,
    /// Grey level.
    pub grey: u8,
}

/// Consecutive strokes of one layer drawn with one pen.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Run {
    /// The pen.
    pub pen: Pen,
    /// A stroke width in mm instead of the pen's (an object's style weight).
    pub width_mm: Option<f64>,
    /// Polylines in mm, in drawing order and direction.
    pub lines: Vec<Vec<Pt2>>,
}

/// A layer: what a plotter draws in one go.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Layer {
    /// Layer number (the digits of its Inkscape label).
    pub number: u32,
    /// Name: the pen's or the top-level object's.
    pub name: String,
    /// Strokes in drawing order, in runs of one pen.
    pub runs: Vec<Run>,
}

impl Layer {
    /// Every stroke of the layer in drawing order.
    pub(crate) fn lines(&self) -> impl Iterator<Item = &Vec<Pt2>> {
        self.runs.iter().flat_map(|r| r.lines.iter())
    }

    /// What a plotter does for this layer.
    pub(crate) fn summary(&self) -> LayerSummary {
        let lines: Vec<&Vec<Pt2>> = self.lines().collect();
        let travel = super::tour::travel(&lines);
        LayerSummary {
            number: self.number,
            name: self.name.clone(),
            strokes: lines.len(),
            drawn_mm: lines
                .iter()
                .map(|l| polyline_length(l))
                .fold(0.0, |s, d| s + d),
            travel_mm: travel,
        }
    }
}

/// Strokes, drawn length and pen-up travel of one layer (as vpype's `stat` counts: travel
/// from each stroke's end to the next one's start, not from or back to the home position).
#[derive(Debug, Clone, PartialEq)]
pub struct LayerSummary {
    /// Layer number.
    pub number: u32,
    /// Layer name.
    pub name: String,
    /// Strokes (the pen goes down once per stroke and is lifted `strokes - 1` times between
    /// them).
    pub strokes: usize,
    /// Pen-down length in mm.
    pub drawn_mm: f64,
    /// Pen-up travel in mm.
    pub travel_mm: f64,
}

/// What building the picture did, for `--stats`.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct PlotStats {
    /// Per layer.
    pub layers: Vec<LayerSummary>,
    /// Repeated and overlapping collinear pieces removed.
    pub duplicates: DedupStats,
    /// Line length (mm) outside the page's drawing area, clipped away.
    pub clipped_mm: f64,
}

/// Everything to draw, on a page in millimetres (y down).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Picture {
    /// The page.
    pub page: PageSize,
    /// Width of the outline pen in mm.
    pub pen_mm: f64,
    /// Background colour, when asked for.
    pub background: Option<Rgb>,
    /// Fills, under everything.
    pub fills: Vec<Fill>,
    /// Layers, in number order.
    pub layers: Vec<Layer>,
    /// How the layers were made.
    pub mode: LayerMode,
    /// What building it did.
    pub stats: PlotStats,
}

impl Picture {
    /// Stroke width of a pen in mm.
    /// The stroke width of a run in mm: its own, or its pen's.
    pub(crate) fn run_width(&self, run: &Run) -> f64 {
        run.width_mm.unwrap_or_else(|| self.width(run.pen))
    }

    pub(crate) fn width(&self, pen: Pen) -> f64 {
        self.pen_mm * pen.width_factor()
    }

    /// Polylines drawn: the fills' rings and the layers' strokes.
    pub(crate) fn polylines(&self) -> usize {
        let rings: usize = self.fills.iter().map(|f| f.rings.len()).sum();
        let strokes: usize = self
            .layers
            .iter()
            .flat_map(|l| &l.runs)
            .map(|r| r.lines.len())
            .sum();
        rings + strokes
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pens_by_kind_and_layer_numbers() {
        assert_eq!(Pen::of(EdgeKind::Silhouette), Pen::Outline);
        assert_eq!(Pen::of(EdgeKind::Crease), Pen::Edges);
        assert_eq!(Pen::of(EdgeKind::Intersection), Pen::Intersection);
        let nums: Vec<u32> = Pen::ALL.iter().map(|p| p.number()).collect();
        assert_eq!(nums, vec![1, 2, 3, 4, 5, 6, 7, 7]);
        assert!(Pen::Outline.width_factor() > Pen::Edges.width_factor());
    }

    #[test]
    fn layer_summary_counts_travel_between_strokes() {
        let l = Layer {
            number: 1,
            name: "outline".into(),
            runs: vec![Run {
                pen: Pen::Outline,
                width_mm: None,
                lines: vec![vec![[0., 0.], [3., 0.]], vec![[3., 4.], [3., 5.]]],
            }],
        };
        let s = l.summary();
        assert_eq!((s.strokes, s.drawn_mm, s.travel_mm), (2, 4.0, 4.0));
        // One stroke travels +0 (printed "0.0", not "-0.0"); an empty layer draws +0.
        let one = Layer {
            runs: vec![Run {
                pen: Pen::Outline,
                width_mm: None,
                lines: vec![vec![[0., 0.], [3., 0.]]],
            }],
            ..l.clone()
        };
        let s = one.summary();
        assert!(s.travel_mm == 0.0 && s.travel_mm.is_sign_positive());
        assert_eq!(format!("{:.1}", s.travel_mm), "0.0");
        let none = Layer {
            runs: Vec::new(),
            ..l
        };
        let s = none.summary();
        assert!(s.drawn_mm.is_sign_positive() && s.travel_mm.is_sign_positive());
    }
}
