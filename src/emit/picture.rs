//! The picture both SVG and PNG draw: a frame, flat-shaded fills, and per-object layers of
//! polylines with a pen per line kind.

use std::collections::BTreeMap;

use crate::geom::poly2::{Pt2, Ring};
use crate::geom::{newell, Rect, V3};
use crate::scene::FaceId;
use crate::view::{Frame, View};
use crate::visibility::Visibility;

use super::edges::EdgeKind;
use super::lines::{Drawing, Stroke};

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
    /// The framed part of the screen plane; line widths scale with its unit.
    pub frame: Frame,
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
    Picture {
        frame: Frame::of(&view.camera, Rect::of_points(pts)),
        fills,
        layers,
    }
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

/// Newell normal of face `f`'s world points (for a warped face, the sum of its pieces').
fn world_normal(view: &View, f: FaceId) -> V3 {
    view.screen
        .pieces_of(f)
        .map(|p| newell(view.screen.world_pts(p)))
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pens_by_kind() {
        assert_eq!(Pen::of(EdgeKind::Silhouette), Pen::Heavy);
        assert_eq!(Pen::of(EdgeKind::Crease), Pen::Light);
        assert!(Pen::Heavy.width() > Pen::Light.width());
        assert!(Pen::Hidden.dash().is_some());
    }
}
