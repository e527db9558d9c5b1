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

/// The visible regions of the faces of one grey, flat shaded.
#[derive(Debug, Clone, PartialEq)]
pub struct Fill {
    /// Rings of the visible regions (even-odd fill; the regions are disjoint).
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
    /// Fills, one per grey, under everything.
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

/// Flat-shaded visible regions, one fill per grey holding the regions of every face of that
/// grey. Visible regions are disjoint, so the even-odd fill of their union is each of them;
/// drawn as one path, the triangles of one flat surface meet without the light anti-aliasing
/// seam that two separately filled, half-covered edge pixels blend to.
fn fills(view: &View, vis: &Visibility) -> Vec<Fill> {
    let m = &view.camera.matrix;
    let row = |r: usize| V3::new(m[(r, 0)], m[(r, 1)], m[(r, 2)]).normalize();
    let (u, v) = (row(0), row(1));
    let w = u.cross(&v);
    let light = (u * -0.4 + v * 0.6 + w).normalize();
    let mut by_grey: BTreeMap<u8, Vec<Ring>> = BTreeMap::new();
    for (f, fv) in vis.iter().filter(|(_, fv)| !fv.visible.is_empty()) {
        let n = world_normal(view, f);
        let n = if n.dot(&w) < 0.0 { -n } else { n };
        let shade = n.try_normalize(0.0).map_or(0.0, |n| n.dot(&light).max(0.0));
        let grey = (110.0 + 140.0 * shade).round().clamp(0.0, 255.0) as u8;
        by_grey
            .entry(grey)
            .or_default()
            .extend(fv.visible.iter().flatten().cloned());
    }
    by_grey
        .into_iter()
        .map(|(grey, rings)| Fill { rings, grey })
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
    fn faces_of_one_grey_fill_as_one_path() {
        use crate::scene::testing::unit_square_scene;
        use crate::view::Camera;
        use crate::{render, RenderOptions};
        // The unit square as two triangles, seen from the front: one grey, one fill.
        let scene = unit_square_scene(vec![vec![0, 1, 2], vec![0, 2, 3]]);
        let cam = Camera::orthographic(V3::new(0.1, 0.2, -1.), V3::y()).unwrap();
        let r = render(&scene, &cam, &RenderOptions::default()).unwrap();
        let pic = r.picture(&crate::PictureOptions {
            size: 100,
            fill: true,
        });
        assert_eq!(pic.fills.len(), 1);
        assert_eq!(pic.fills[0].rings.len(), 2);
    }

    #[test]
    fn pens_by_kind() {
        assert_eq!(Pen::of(EdgeKind::Silhouette), Pen::Heavy);
        assert_eq!(Pen::of(EdgeKind::Crease), Pen::Light);
        assert!(Pen::Heavy.width() > Pen::Light.width());
        assert!(Pen::Hidden.dash().is_some());
    }
}
