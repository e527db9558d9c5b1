//! The picture's frame: which part of the screen plane a drawing shows, and how many pixels
//! a screen unit is. SVG, PNG and the level-of-detail substitution all use this one mapping.

use crate::geom::{Rect, P3};
use crate::scene::Scene;

use super::camera::{Camera, Projection};

/// Relative margin around the drawing.
const MARGIN: f64 = 0.05;

/// Widest screen aspect a perspective picture keeps (x from -A to A, y from -1 to 1).
const MAX_ASPECT: f64 = 1.6;

/// The framed part of the screen plane.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Frame {
    /// Framed rectangle, margin included.
    pub rect: Rect,
    /// Size of the drawing (its longer side without the margin).
    pub unit: f64,
    /// The drawing's own rectangle (`rect` without the margin): what a page shows.
    pub content: Rect,
}

impl Frame {
    /// The frame of a drawing whose screen bounds are `b`: limited, for a perspective
    /// camera, to its field of view, then given a 5% margin. An empty drawing gets the
    /// unit square.
    pub(crate) fn of(camera: &Camera, b: Rect) -> Frame {
        Frame::around(field_of_view(camera, b))
    }

    /// The frame of drawing bounds `b` as they are, given a 5% margin (the unit square when
    /// empty).
    fn around(b: Rect) -> Frame {
        if b.is_empty() {
            let unit_square = Rect::new(0.0, 0.0, 1.0, 1.0);
            return Frame {
                rect: unit_square,
                unit: 1.0,
                content: unit_square,
            };
        }
        let size = b.longer_side();
        let unit = if size > 0.0 { size } else { 1.0 };
        Frame {
            rect: b.padded(MARGIN * unit),
            unit,
            content: b,
        }
    }

    /// The frame of a picture of `scene` whose drawing has screen bounds `b`: all of it when
    /// the scene's CBOX lies wholly in front of a perspective camera's near plane (nothing was
    /// clipped there, so the projection is bounded and the whole drawing fits the page),
    /// else as [`Frame::of`] (a scene reaching behind the eye, a ground plane say, is framed
    /// by the field of view).
    pub(crate) fn of_scene(camera: &Camera, scene: &Scene, b: Rect) -> Frame {
        if camera.projection == Projection::Perspective && !wholly_in_front(camera, scene) {
            return Frame::of(camera, b);
        }
        Frame::around(b)
    }

    /// Pixels per screen unit of a picture `size` pixels along its longer side.
    pub(crate) fn pixels_per_unit(&self, size: u32) -> f64 {
        f64::from(size.max(1)) / self.rect.longer_side()
    }
}

/// True when every corner of `scene`'s CBOX is in front of `camera`'s near plane.
fn wholly_in_front(camera: &Camera, scene: &Scene) -> bool {
    let b = scene.cbox();
    if b.lo.x > b.hi.x || b.lo.x.is_nan() {
        return true;
    }
    (0..8).all(|k| {
        camera.in_front(&P3::new(
            if k & 1 == 0 { b.lo.x } else { b.hi.x },
            if k & 2 == 0 { b.lo.y } else { b.hi.y },
            if k & 4 == 0 { b.lo.z } else { b.hi.z },
        ))
    })
}

/// Drawing bounds limited, for a perspective camera, to its field of view: the projection
/// puts the edges of the vertical field of view at y = ±1, and a ground plane clipped near the
/// eye would otherwise stretch the frame far beyond what the camera sees.
fn field_of_view(camera: &Camera, b: Rect) -> Rect {
    if camera.projection != Projection::Perspective {
        return b;
    }
    let c = b.intersection(&Rect::new(-MAX_ASPECT, -1.0, MAX_ASPECT, 1.0));
    if c.xmin < c.xmax && c.ymin < c.ymax {
        c
    } else {
        b
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::V3;

    #[test]
    fn frame_has_margin_and_survives_empty() {
        let cam = Camera::orthographic(V3::new(0., 0., -1.), V3::y()).unwrap();
        let f = Frame::of(&cam, Rect::new(0., 0., 10., 5.));
        assert_eq!(f.unit, 10.0);
        assert_eq!(f.rect, Rect::new(-0.5, -0.5, 10.5, 5.5));
        assert_eq!(f.content, Rect::new(0., 0., 10., 5.));
        assert_eq!(f.pixels_per_unit(1100), 100.0);
        let e = Frame::of(&cam, Rect::EMPTY);
        assert_eq!((e.rect, e.unit), (Rect::new(0., 0., 1., 1.), 1.0));
    }

    #[test]
    fn a_perspective_scene_wholly_in_front_is_framed_whole() {
        let scene = crate::scene::testing::unit_cube_scene();
        let wide = Rect::new(-3., -1., 3., 1.);
        let at = |eye: P3| {
            let c = Camera::perspective(eye, P3::new(0.5, 0.5, 0.), V3::y(), 45.0, 1e-3).unwrap();
            Frame::of_scene(&c, &scene, wide).content
        };
        // Outside the cube: the whole drawing, wider than the field of view.
        assert_eq!(at(P3::new(0.5, 0.5, 1.2)), wide);
        // Inside it (its CBOX reaches behind the eye): cut to the field of view.
        assert_eq!(
            at(P3::new(0.5, 0.5, 0.5)),
            Rect::new(-MAX_ASPECT, -1., MAX_ASPECT, 1.)
        );
    }
}
