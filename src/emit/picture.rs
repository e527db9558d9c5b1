//! The picture both SVG and PNG draw: a frame, flat-shaded fills, and per-object layers of
//! polylines with a pen per line kind.

use std::collections::BTreeMap;

use crate::geom::poly2::{bounds, Pt2, Ring};
use crate::geom::V3;
use crate::view::{Camera, View};
use crate::visibility::Visibility;

use super::edges::EdgeKind;
use super::lines::{Drawing, Stroke};

/// Relative margin around the drawing.
const MARGIN: f64 = 0.05;

/// A pen: how a kind of line is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Pen {
    /// Hidden lines: thin, dashed, grey (drawn first, under the rest).
    Hidden,
    /// Texture markings on faces.
    Mark,
    /// Creases, plain edges and intersection curves.
    Light,
    /// Silhouettes and borders.
    Heavy,
}

impl Pen {
    /// The pen of a visible line kind.
    pub fn of(kind: EdgeKind) -> Pen {
        match kind {
            EdgeKind::Silhouette | EdgeKind::Border => Pen::Heavy,
            _ => Pen::Light,
        }
    }

    /// Name (SVG class).
    pub fn name(self) -> &'static str {
        match self {
            Pen::Hidden => "hidden",
            Pen::Mark => "mark",
            Pen::Light => "light",
            Pen::Heavy => "heavy",
        }
    }

    /// Line width as a fraction of the drawing's size.
    pub fn width(self) -> f64 {
        match self {
            Pen::Heavy => 0.003,
            Pen::Light => 0.0015,
            Pen::Hidden | Pen::Mark => 0.001,
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

    /// Dash and gap lengths as fractions of the drawing's size, for dashed pens.
    pub fn dash(self) -> Option<[f64; 2]> {
        (self == Pen::Hidden).then_some([0.008, 0.005])
    }
}

/// One face's visible region, flat shaded.
#[derive(Debug, Clone, PartialEq)]
pub struct Fill {
    /// Rings of the visible region (even-odd fill).
    pub rings: Vec<Ring>,
    /// Grey level.
    pub grey: u8,
}

/// The lines of one object.
#[derive(Debug, Clone, PartialEq)]
pub struct Layer {
    /// The object's path.
    pub name: String,
    /// Polylines by pen, pens in drawing order.
    pub pens: Vec<(Pen, Vec<Vec<Pt2>>)>,
}

/// Everything to draw, in screen space (y up).
#[derive(Debug, Clone, PartialEq)]
pub struct Picture {
    /// Framed rectangle [xmin, ymin, xmax, ymax], margin included.
    pub frame: [f64; 4],
    /// Size of the drawing (the larger side without margin): line widths scale with it.
    pub unit: f64,
    /// Fills, under everything.
    pub fills: Vec<Fill>,
    /// Line layers, one per object that has lines, in object order.
    pub layers: Vec<Layer>,
}

/// Builds the picture of a view: `marks` are texture markings, `fill` adds shaded faces.
pub fn picture(
    view: &View,
    vis: &Visibility,
    drawing: &Drawing,
    marks: &[Stroke],
    fill: bool,
) -> Picture {
    let fills = if fill { fills(view, vis) } else { Vec::new() };
    let mut by_leaf: BTreeMap<u32, BTreeMap<Pen, Vec<Vec<Pt2>>>> = BTreeMap::new();
    let mut add = |s: &Stroke, pen: Pen| {
        by_leaf
            .entry(s.leaf)
            .or_default()
            .entry(pen)
            .or_default()
            .push(s.pts.clone());
    };
    drawing.hidden.iter().for_each(|s| add(s, Pen::Hidden));
    marks.iter().for_each(|s| add(s, Pen::Mark));
    drawing.visible.iter().for_each(|s| add(s, Pen::of(s.kind)));
    let layers: Vec<Layer> = by_leaf
        .into_iter()
        .map(|(leaf, pens)| Layer {
            name: drawing
                .leaf_paths
                .get(leaf as usize)
                .cloned()
                .unwrap_or_default(),
            pens: pens.into_iter().collect(),
        })
        .collect();
    let pts = layers
        .iter()
        .flat_map(|l| l.pens.iter().flat_map(|p| p.1.iter().flatten()))
        .chain(fills.iter().flat_map(|f| f.rings.iter().flatten()));
    let (frame, unit) = frame(field_of_view(&view.camera, bounds(pts)));
    Picture {
        frame,
        unit,
        fills,
        layers,
    }
}

/// Widest screen aspect a perspective picture keeps (x from -A to A, y from -1 to 1).
const MAX_ASPECT: f64 = 1.6;

/// Drawing bounds limited, for a perspective camera, to its field of view: the projection
/// puts the edges of the vertical field of view at y = ±1, and a ground plane clipped near the
/// eye would otherwise stretch the frame far beyond what the camera sees.
fn field_of_view(camera: &Camera, b: [f64; 4]) -> [f64; 4] {
    if camera.projection != crate::view::Projection::Perspective {
        return b;
    }
    let fov = [-MAX_ASPECT, -1.0, MAX_ASPECT, 1.0];
    let c = [
        b[0].max(fov[0]),
        b[1].max(fov[1]),
        b[2].min(fov[2]),
        b[3].min(fov[3]),
    ];
    if c[0] < c[2] && c[1] < c[3] {
        c
    } else {
        b
    }
}

/// Pixels per screen unit of a picture `size` pixels along its longer side whose drawing
/// has screen bounds `b` [xmin, ymin, xmax, ymax]: the mapping SVG and PNG use.
pub fn pixels_per_unit(camera: &Camera, b: [f64; 4], size: u32) -> f64 {
    let ([x0, y0, x1, y1], _) = frame(field_of_view(camera, b));
    f64::from(size.max(1)) / (x1 - x0).max(y1 - y0)
}

/// The framed rectangle (5% margin) and unit of drawing bounds.
fn frame(b: [f64; 4]) -> ([f64; 4], f64) {
    if !(b[0] <= b[2] && b[1] <= b[3]) {
        return ([0.0, 0.0, 1.0, 1.0], 1.0);
    }
    let size = (b[2] - b[0]).max(b[3] - b[1]);
    let unit = if size > 0.0 { size } else { 1.0 };
    let m = MARGIN * unit;
    ([b[0] - m, b[1] - m, b[2] + m, b[3] + m], unit)
}

/// Flat-shaded visible regions, one per face with something visible.
fn fills(view: &View, vis: &Visibility) -> Vec<Fill> {
    let m = &view.camera.matrix;
    let row = |r: usize| V3::new(m[(r, 0)], m[(r, 1)], m[(r, 2)]).normalize();
    let (u, v) = (row(0), row(1));
    let w = u.cross(&v);
    let light = (u * -0.4 + v * 0.6 + w).normalize();
    vis.iter()
        .filter(|(_, fv)| !fv.visible.is_empty())
        .map(|(f, fv)| {
            let n = world_normal(view, f);
            let n = if n.dot(&w) < 0.0 { -n } else { n };
            let shade = n.try_normalize(0.0).map_or(0.0, |n| n.dot(&light).max(0.0));
            Fill {
                rings: fv.visible.iter().flatten().cloned().collect(),
                grey: (110.0 + 140.0 * shade).round().clamp(0.0, 255.0) as u8,
            }
        })
        .collect()
}

/// Newell normal of face `f`'s world points.
fn world_normal(view: &View, f: usize) -> V3 {
    let r = view.screen.piece_range(f as u32..f as u32 + 1);
    if r.len() != 1 {
        // A warped face: the sum of its pieces' normals.
        return r
            .map(|p| piece_normal(view.screen.world_pts(p as usize)))
            .sum();
    }
    piece_normal(view.screen.world_pts(r.start as usize))
}

/// Newell normal of a polygon.
fn piece_normal(p: &[crate::geom::P3]) -> V3 {
    crate::scene::cleanup::FaceShape::of(p).normal
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frame_has_margin_and_survives_empty() {
        let (f, u) = frame([0., 0., 10., 5.]);
        assert_eq!(u, 10.0);
        assert_eq!(f, [-0.5, -0.5, 10.5, 5.5]);
        let (f, u) = frame(bounds(std::iter::empty()));
        assert_eq!((f, u), ([0., 0., 1., 1.], 1.0));
    }

    #[test]
    fn pens_by_kind() {
        assert_eq!(Pen::of(EdgeKind::Silhouette), Pen::Heavy);
        assert_eq!(Pen::of(EdgeKind::Crease), Pen::Light);
        assert!(Pen::Heavy.width() > Pen::Light.width());
        assert!(Pen::Hidden.dash().is_some());
    }
}
