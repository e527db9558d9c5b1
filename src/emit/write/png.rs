//! PNG output of a [`Picture`]: the same page as the SVG, rasterised anti-aliased with
//! tiny-skia and encoded with the `image` crate. Pixels: `size` along the page's longer
//! side, or the page at `dpi`.

use tiny_skia::{
    Color, FillRule, LineCap, LineJoin, Paint, PathBuilder, Pixmap, Stroke, Transform,
};

use crate::count::Count;
use crate::geom::poly2::Pt2;
use crate::Error;

use crate::emit::plot::color::Rgb;
use crate::emit::plot::picture::Picture;

/// Largest PNG side in pixels.
const MAX_SIDE: f64 = 32768.0;

/// Pixels per mm of a picture drawn `size` pixels along its longer side, or at `dpi`.
pub(crate) fn pixels_per_mm(pic: &Picture, size: u32, dpi: Option<f64>) -> f64 {
    match dpi {
        Some(d) => d / 25.4,
        None => f64::from(size.max(1)) / pic.page.longer_side(),
    }
}

/// Pixel size (width, height), each >= 1.
pub(crate) fn pixel_size(pic: &Picture, px_per_mm: f64) -> (u32, u32) {
    let px = |v: f64| (v * px_per_mm).round().clamp(1.0, MAX_SIDE) as u32;
    (px(pic.page.width), px(pic.page.height))
}

/// The PNG bytes of a picture.
///
/// Each fill's rings and each run's strokes go to `done` as they are painted.
pub(crate) fn to_png(
    pic: &Picture,
    size: u32,
    dpi: Option<f64>,
    done: Count,
) -> Result<Vec<u8>, Error> {
    let pixmap = rasterise(pic, pixels_per_mm(pic, size, dpi), done)?;
    let (w, h) = (pixmap.width(), pixmap.height());
    // Opaque background: premultiplied RGBA equals straight RGBA.
    let img = image::RgbaImage::from_raw(w, h, pixmap.take())
        .ok_or_else(|| Error::Usage("PNG buffer has the wrong size".into()))?;
    let mut out = std::io::Cursor::new(Vec::new());
    img.write_to(&mut out, image::ImageFormat::Png)
        .map_err(|e| Error::Usage(format!("PNG encoding failed: {e}")))?;
    Ok(out.into_inner())
}

/// Draws the picture into a new pixmap at `k` pixels per mm.
///
/// Each fill's rings and each run's strokes go to `done` once drawn.
pub(crate) fn rasterise(pic: &Picture, k: f64, done: Count) -> Result<Pixmap, Error> {
    let (w, h) = pixel_size(pic, k);
    let mut pm =
        Pixmap::new(w, h).ok_or_else(|| Error::Usage(format!("cannot make a {w}x{h} picture")))?;
    let [r, g, b] = pic.background.unwrap_or(Rgb::WHITE).0;
    pm.fill(Color::from_rgba8(r, g, b, 255));
    let to_px = |p: &Pt2| (p[0] * k, p[1] * k);
    for f in &pic.fills {
        let mut pb = PathBuilder::new();
        for r in &f.rings {
            add_polyline(&mut pb, r.iter().map(to_px), true);
        }
        if let Some(path) = pb.finish() {
            let paint = paint(f.grey);
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
        done.add(f.rings.len());
    }
    for layer in &pic.layers {
        for run in &layer.runs {
            let mut pb = PathBuilder::new();
            for l in &run.lines {
                add_polyline(&mut pb, l.iter().map(to_px), false);
            }
            if let Some(path) = pb.finish() {
                let stroke = Stroke {
                    width: ((pic.run_width(run) * k) as f32).max(0.5),
                    line_cap: LineCap::Round,
                    line_join: LineJoin::Round,
                    ..Stroke::default()
                };
                let grey = paint(run.pen.grey());
                pm.stroke_path(&path, &grey, &stroke, Transform::identity(), None);
            }
            done.add(run.lines.len());
        }
    }
    Ok(pm)
}

/// Anti-aliased paint of a grey level.
fn paint(g: u8) -> Paint<'static> {
    let mut paint = Paint::default();
    paint.set_color_rgba8(g, g, g, 255);
    paint.anti_alias = true;
    paint
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
    use crate::emit::plot::page::PageSize;
    use crate::emit::plot::picture::{Fill, Layer, LayerMode, Pen, PlotStats, Run};

    fn pic() -> Picture {
        Picture {
            page: PageSize {
                width: 110.0,
                height: 60.0,
            },
            pen_mm: 1.0,
            background: None,
            fills: vec![Fill {
                rings: vec![vec![[5., 5.], [105., 5.], [105., 55.], [5., 55.]]],
                grey: 200,
            }],
            layers: vec![Layer {
                number: 1,
                name: "outline".into(),
                runs: vec![Run {
                    pen: Pen::Outline,
                    width_mm: None,
                    lines: vec![vec![[5., 55.], [105., 5.]]],
                }],
            }],
            mode: LayerMode::Pen,
            stats: PlotStats::default(),
        }
    }

    #[test]
    fn page_picture_has_requested_size_and_ink() {
        let pic = pic();
        assert_eq!(pixel_size(&pic, pixels_per_mm(&pic, 110, None)), (110, 60));
        assert_eq!(
            pixel_size(&pic, pixels_per_mm(&pic, 1, Some(254.0))),
            (1100, 600)
        );
        let pm = rasterise(&pic, 1.0, Count::NONE).unwrap();
        let px = |x: u32, y: u32| pm.pixel(x, y).unwrap().red();
        assert_eq!(px(1, 1), 255, "margin is white");
        assert_eq!(px(20, 50), 200, "fill");
        let ink = (28..33).map(|y| px(55, y)).min().unwrap();
        assert!(ink < 150, "line through the centre: {ink}");
        let bytes = to_png(&pic, 110, None, Count::NONE).unwrap();
        assert_eq!(&bytes[1..4], b"PNG");
    }

    #[test]
    fn line_width_in_mm_is_the_same_at_any_resolution() {
        // A 1 mm pen is 1 px at 1 px/mm and 4 px at 4 px/mm: ink across the line scales.
        let pic = pic();
        let across = |k: f64| {
            let pm = rasterise(&pic, k, Count::NONE).unwrap();
            let x = (55.0 * k) as u32;
            (0..pm.height())
                .filter(|&y| pm.pixel(x, y).unwrap().red() < 100)
                .count() as f64
                / k
        };
        let (a, b) = (across(2.0), across(8.0));
        assert!((a - b).abs() < 0.75, "{a} mm vs {b} mm");
    }

    #[test]
    fn triangles_of_one_surface_fill_without_seams() {
        // A dark rectangle made of two triangles (a flat face of a triangle mesh), diagonal
        // at odd angles to the pixels, in one fill as `plot` groups them; every pixel well
        // inside must be the fill grey (two fills drawn one after the other leave a light
        // seam along the diagonal: grey 58 here).
        let (a, b, c, d) = ([0.5, 0.5], [10.5, 0.5], [10.5, 7.5], [0.5, 7.5]);
        let mut pic = pic();
        pic.page = PageSize {
            width: 11.0,
            height: 8.0,
        };
        pic.fills = vec![Fill {
            rings: vec![vec![a, b, c], vec![a, c, d]],
            grey: 40,
        }];
        pic.layers.clear();
        let pm = rasterise(&pic, 30.3, Count::NONE).unwrap();
        let (w, h) = (pm.width(), pm.height());
        let lightest = (h / 10..h * 9 / 10)
            .flat_map(|y| (w / 10..w * 9 / 10).map(move |x| (x, y)))
            .map(|(x, y)| pm.pixel(x, y).unwrap().red())
            .max()
            .unwrap();
        assert!(lightest <= 44, "seam: grey {lightest} inside a fill of 40");
    }
}
