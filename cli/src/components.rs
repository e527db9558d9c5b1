//! `kepler info MESH --components F.svg`: the components of each mesh's object tree coloured
//! one per leaf component over the exact visible regions (like paper 002's Figure 4).

use anyhow::Result;
use kepler_hsr::plot::Rect;
use kepler_hsr::{render, Camera, RenderOptions, Scene, V3};
use svg::node::element::path::Data;
use svg::node::element::{Path, Rectangle};
use svg::Document;

/// The SVG picture, `size` pixels along its longer side.
pub(crate) fn components_svg(scene: &Scene, camera: &Camera, size: u32) -> Result<String> {
    let progress = kepler_hsr::Progress::default();
    let r = render(scene, camera, &RenderOptions::default(), &progress)?;
    // The leaf component of every face in global order (None: no tree).
    let colour_of = scene.face_components();
    let mut bounds = Rect::EMPTY;
    for (_, f) in r.visibility.iter() {
        bounds = bounds.union(&Rect::of_points(f.visible().iter().flatten().flatten()));
    }
    if bounds.is_empty() {
        bounds = Rect::new(0., 0., 1., 1.);
    }
    let side = bounds.longer_side().max(f64::MIN_POSITIVE);
    let px = f64::from(size.max(1)) / side;
    let (x, y, w, h) = (bounds.xmin, -bounds.ymax, bounds.width(), bounds.height());
    let mut doc = Document::new()
        .set("viewBox", (x, y, w, h))
        .set("width", (w * px).round().max(1.0))
        .set("height", (h * px).round().max(1.0))
        .add(
            Rectangle::new()
                .set("x", x)
                .set("y", y)
                .set("width", w)
                .set("height", h)
                .set("fill", "white"),
        );
    let light = V3::new(0.3, 0.5, 1.0).normalize();
    for (id, f) in r.visibility.iter() {
        if f.is_empty() {
            continue;
        }
        let n = r.view.face_normal(id);
        let shade = 0.45 + 0.55 * n.try_normalize(0.0).map_or(0.0, |n| n.dot(&light).abs());
        let rgb = colour(colour_of.get(id.index()).copied().flatten(), shade);
        let mut d = Data::new();
        for ring in f.visible().iter().flatten() {
            for (k, p) in ring.iter().enumerate() {
                let p = (p[0], -p[1]);
                d = if k == 0 { d.move_to(p) } else { d.line_to(p) };
            }
            d = d.close();
        }
        doc = doc.add(
            Path::new()
                .set("d", d)
                .set("fill", rgb.clone())
                .set("stroke", rgb)
                .set("stroke-width", 0.3 / px)
                .set("fill-rule", "evenodd"),
        );
    }
    Ok(format!("{doc}\n"))
}

/// A colour per component (hues by the golden ratio), darkened by `shade`; grey without one.
fn colour(component: Option<u32>, shade: f64) -> String {
    let (r, g, b) = if let Some(component) = component {
        let h = (f64::from(component) * 0.618_033_988_75).fract() * 6.0;
        let (s, v) = (0.6, 0.95);
        let c = v * s;
        let x = c * (1.0 - (h % 2.0 - 1.0).abs());
        let (r, g, b) = match h as u32 {
            0 => (c, x, 0.0),
            1 => (x, c, 0.0),
            2 => (0.0, c, x),
            3 => (0.0, x, c),
            4 => (x, 0.0, c),
            _ => (c, 0.0, x),
        };
        let m = v - c;
        (r + m, g + m, b + m)
    } else {
        (0.7, 0.7, 0.7)
    };
    let q = |x: f64| (255.0 * (x * shade).clamp(0.0, 1.0)).round() as u8;
    format!("#{:02x}{:02x}{:02x}", q(r), q(g), q(b))
}
