//! PNG output of a [`Picture`]: the same picture as the SVG, rasterised anti-aliased with
//! tiny-skia and encoded with the `image` crate.

use tiny_skia::{
    Color, FillRule, LineCap, LineJoin, Paint, PathBuilder, Pixmap, Stroke, StrokeDash, Transform,
};

use crate::geom::poly2::Pt2;
use crate::Error;

use super::picture::Picture;

/// Pixel size of a picture whose longer side is `size` pixels: (width, height), each >= 1.
pub fn pixel_size(pic: &Picture, size: u32) -> (u32, u32) {
    let (w, h) = (pic.frame.rect.width(), pic.frame.rect.height());
    let s = f64::from(size.max(1)) / w.max(h);
    let px = |v: f64| ((v * s).round() as u32).clamp(1, size.max(1));
    (px(w), px(h))
}

/// The PNG bytes of a picture, `size` pixels along its longer side.
pub fn to_png(pic: &Picture, size: u32) -> Result<Vec<u8>, Error> {
    let pixmap = rasterise(pic, size)?;
    let (w, h) = (pixmap.width(), pixmap.height());
    // Opaque white background: premultiplied RGBA equals straight RGBA.
    let img = image::RgbaImage::from_raw(w, h, pixmap.take())
        .ok_or_else(|| Error::Usage("PNG buffer has the wrong size".into()))?;
    let mut out = std::io::Cursor::new(Vec::new());
    img.write_to(&mut out, image::ImageFormat::Png)
        .map_err(|e| Error::Usage(format!("PNG encoding failed: {e}")))?;
    Ok(out.into_inner())
}

/// Draws the picture into a new pixmap.
pub fn rasterise(pic: &Picture, size: u32) -> Result<Pixmap, Error> {
    let (w, h) = pixel_size(pic, size);
    let mut pm =
        Pixmap::new(w, h).ok_or_else(|| Error::Usage(format!("cannot make a {w}x{h} picture")))?;
    pm.fill(Color::WHITE);
    let r = pic.frame.rect;
    let (x0, y1) = (r.xmin, r.ymax);
    let s = f64::from(w) / r.width().max(f64::MIN_POSITIVE);
    let s = s.min(f64::from(h) / r.height().max(f64::MIN_POSITIVE));
    let to_px = |p: &Pt2| ((p[0] - x0) * s, (y1 - p[1]) * s);
    for f in &pic.fills {
        let mut pb = PathBuilder::new();
        for r in &f.rings {
            add_polyline(&mut pb, r.iter().map(to_px), true);
        }
        if let Some(path) = pb.finish() {
            let mut paint = Paint::default();
            paint.set_color_rgba8(f.grey, f.grey, f.grey, 255);
            paint.anti_alias = true;
            pm.fill_path(
                &path,
                &paint,
                FillRule::EvenOdd,
                Transform::identity(),
                None,
            );
            // A hairline in the same grey closes anti-aliasing seams between faces.
            let seam = Stroke {
                width: 0.5,
                ..Stroke::default()
            };
            pm.stroke_path(&path, &paint, &seam, Transform::identity(), None);
        }
    }
    for layer in &pic.layers {
        for (pen, lines) in &layer.pens {
            let mut pb = PathBuilder::new();
            for l in lines {
                add_polyline(&mut pb, l.iter().map(to_px), false);
            }
            let Some(path) = pb.finish() else { continue };
            let mut paint = Paint::default();
            let g = pen.grey();
            paint.set_color_rgba8(g, g, g, 255);
            paint.anti_alias = true;
            let unit = pic.frame.unit * s;
            let stroke = Stroke {
                width: ((pen.width() * unit) as f32).max(0.5),
                line_cap: LineCap::Round,
                line_join: LineJoin::Round,
                dash: pen.dash().and_then(|[a, b]| {
                    StrokeDash::new(vec![(a * unit) as f32, (b * unit) as f32], 0.0)
                }),
                ..Stroke::default()
            };
            pm.stroke_path(&path, &paint, &stroke, Transform::identity(), None);
        }
    }
    Ok(pm)
}

/// Adds one polyline (closed when `close`) in pixel coordinates.
fn add_polyline(pb: &mut PathBuilder, pts: impl Iterator<Item = (f64, f64)>, close: bool) {
    let mut first = true;
    for (x, y) in pts {
        if first {
            pb.move_to(x as f32, y as f32);
            first = false;
        } else {
            pb.line_to(x as f32, y as f32);
        }
    }
    if close && !first {
        pb.close();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::emit::picture::{Fill, Layer, Pen};

    #[test]
    fn square_picture_has_requested_size_and_ink() {
        let pic = Picture {
            frame: crate::view::Frame {
                rect: crate::geom::Rect::new(-0.5, -0.5, 10.5, 5.5),
                unit: 10.0,
            },
            fills: vec![Fill {
                rings: vec![vec![[0., 0.], [10., 0.], [10., 5.], [0., 5.]]],
                grey: 200,
            }],
            layers: vec![Layer {
                name: "a".into(),
                pens: vec![(Pen::Heavy, vec![vec![[0., 0.], [10., 5.]]])],
            }],
        };
        assert_eq!(pixel_size(&pic, 110), (110, 60));
        let pm = rasterise(&pic, 110).unwrap();
        let px = |x: u32, y: u32| pm.pixel(x, y).unwrap().red();
        assert_eq!(px(1, 1), 255, "margin is white");
        assert_eq!(px(20, 50), 200, "fill");
        let ink = (28..33).map(|y| px(55, y)).min().unwrap();
        assert!(ink < 150, "line through the centre: {ink}");
        let bytes = to_png(&pic, 110).unwrap();
        assert_eq!(&bytes[1..4], b"PNG");
    }

    #[test]
    fn triangles_of_one_surface_fill_without_seams() {
        // A dark square made of two triangles (a flat face of a triangle mesh), diagonal at
        // odd angles to the pixels, in one fill as `picture` groups them; every pixel well
        // inside the square must be the fill grey (two fills drawn one after the other leave
        // a light seam along the diagonal: grey 58 here).
        let (a, b, c, d) = ([0., 0.], [10., 0.], [10., 7.], [0., 7.]);
        let pic = Picture {
            frame: crate::view::Frame {
                rect: crate::geom::Rect::new(-0.5, -0.5, 10.5, 7.5),
                unit: 10.0,
            },
            fills: vec![Fill {
                rings: vec![vec![a, b, c], vec![a, c, d]],
                grey: 40,
            }],
            layers: Vec::new(),
        };
        let pm = rasterise(&pic, 333).unwrap();
        let (w, h) = (pm.width(), pm.height());
        let lightest = (h / 10..h * 9 / 10)
            .flat_map(|y| (w / 10..w * 9 / 10).map(move |x| (x, y)))
            .map(|(x, y)| pm.pixel(x, y).unwrap().red())
            .max()
            .unwrap();
        assert!(lightest <= 44, "seam: grey {lightest} inside a fill of 40");
    }
}
