//! Plotter flags of `kepler render`: page, margin, pens, layers, dashes, joining, hatching.

use anyhow::{bail, Result};
use clap::{Args, ValueEnum};
use kepler_hsr::plot::{HatchOptions, LayerMode, PageSize, PictureOptions, Rgb};

use super::camera_args::parse_vec3;

/// How the drawing goes onto paper.
#[derive(Args, Debug, Clone)]
pub(crate) struct PlotArgs {
    /// Page size: a3, a4, a5, a6, letter (portrait; --landscape turns it) or WIDTHxHEIGHTmm
    /// (e.g. 200x150mm). The drawing is fitted
    /// inside the margin and centred; without a page, the page is the drawing's own shape,
    /// --size CSS pixels (1/96 in) along its longer side.
    #[arg(long, value_name = "PAGE")]
    pub(crate) page: Option<String>,
    /// Turn the page so that its longer side is horizontal.
    #[arg(long, requires = "page")]
    pub(crate) landscape: bool,
    /// Margin around the drawing in mm (default 10 on a page, 5% of the drawing without).
    #[arg(long, value_name = "MM")]
    pub(crate) margin: Option<f64>,
    /// Width of the outline pen in mm (edges and intersections 0.6 of it, markings,
    /// hatching and hidden lines 0.5); independent of --size.
    #[arg(long, value_name = "MM", default_value_t = 0.5)]
    pub(crate) pen: f64,
    /// PNG resolution in dots per inch of the page (instead of --size).
    #[arg(long, value_name = "DPI")]
    pub(crate) dpi: Option<f64>,
    /// Layers of the SVG: one per pen (1 outline, 2 edges, 3 intersections, 4 marks,
    /// 5 hatching, 6 hidden, 7 section), one per top-level object, or none.
    #[arg(long, value_enum, value_name = "BY", default_value = "pen")]
    pub(crate) layers: LayersArg,
    /// Background colour (#rrggbb, #rgb, white, ivory, ...): a rectangle under the SVG,
    /// the PNG's ground (default white). The SVG has none unless asked.
    #[arg(long, value_name = "COLOR")]
    pub(crate) background: Option<String>,
    /// Hidden lines' dash and gap in mm: each dash is a stroke of its own.
    #[arg(long, value_name = "MM,MM", default_value = "2,1")]
    pub(crate) dash: String,
    /// Join stroke ends closer than this (mm) into one stroke; 0 joins exactly equal ends
    /// only.
    #[arg(long = "join", value_name = "MM", default_value_t = 0.05)]
    pub(crate) join: f64,
    /// Simplify strokes to within this distance (mm; 0 keeps every point).
    #[arg(long, value_name = "MM", default_value_t = 0.0)]
    pub(crate) simplify: f64,
    /// Hatch visible faces by their shading (five tones, cross-hatched where darkest),
    /// clipped exactly to each face's visible region.
    #[arg(long)]
    pub(crate) hatch: bool,
    /// Distance between the densest hatch lines, in mm.
    #[arg(long, value_name = "MM", default_value_t = 1.0)]
    pub(crate) hatch_spacing: f64,
    /// Angle of the hatch lines in degrees (default: across the light's direction).
    #[arg(long, value_name = "DEG", allow_hyphen_values = true)]
    pub(crate) hatch_angle: Option<f64>,
    /// Direction toward the light (X,Y,Z, world); default from the upper left, in front.
    #[arg(long, value_name = "X,Y,Z", allow_hyphen_values = true)]
    pub(crate) light: Option<String>,
    /// Hatch, with outlines only around hatched regions: the boundaries of the hatched tone
    /// regions replace creases and plain edges (silhouettes and intersections stay).
    #[arg(long)]
    pub(crate) hatch_outline: bool,
    /// Distance in mm between the 45° hatch lines of section faces (--section), drawn on
    /// layer 7 with the faces' heavy outlines.
    #[arg(long, value_name = "MM", default_value_t = 2.0)]
    pub(crate) section_hatch: f64,
}

/// `--layers` values.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum LayersArg {
    /// One layer per pen.
    Pen,
    /// One layer per top-level object.
    Object,
    /// No layers.
    None,
}

impl PlotArgs {
    /// The picture options the flags ask for (`size` from --size, `fill` from --fill).
    pub(crate) fn options(&self, size: u32, fill: bool) -> Result<PictureOptions> {
        let page = self
            .page
            .as_deref()
            .map(PageSize::parse)
            .transpose()?
            .map(|p| if self.landscape { p.landscape() } else { p });
        let dash: Vec<&str> = self.dash.split(',').map(str::trim).collect();
        let mm = |s: &str| s.parse::<f64>().ok().filter(|v| v.is_finite() && *v > 0.0);
        let dash_mm = match dash.as_slice() {
            [a, b] => match (mm(a), mm(b)) {
                (Some(a), Some(b)) => [a, b],
                _ => bail!(
                    "--dash {}: expected two lengths in mm > 0, DASH,GAP",
                    self.dash
                ),
            },
            _ => bail!("--dash {}: expected two lengths in mm, DASH,GAP", self.dash),
        };
        let hatch = (self.hatch || self.hatch_outline).then_some(HatchOptions {
            spacing_mm: self.hatch_spacing,
            angle_deg: self.hatch_angle,
            outline: self.hatch_outline,
        });
        if self.light.is_some() && hatch.is_none() && !fill {
            bail!("--light shades --hatch or --fill: give one of them");
        }
        let light = self
            .light
            .as_deref()
            .map(|s| parse_vec3(s, "light"))
            .transpose()?;
        Ok(PictureOptions {
            size,
            dpi: self.dpi,
            page,
            margin_mm: self.margin,
            pen_mm: self.pen,
            layers: match self.layers {
                LayersArg::Pen => LayerMode::Pen,
                LayersArg::Object => LayerMode::Object,
                LayersArg::None => LayerMode::None,
            },
            background: self.background.as_deref().map(Rgb::parse).transpose()?,
            dash_mm,
            join_mm: self.join,
            simplify_mm: self.simplify,
            fill,
            hatch,
            light,
            frame: None,
            section_hatch_mm: self.section_hatch,
        })
    }
}
