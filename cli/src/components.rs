//! `kepler info MESH --components F.svg`: the components of each mesh's object tree coloured
//! one per leaf component over the exact visible regions (like paper 002's Figure 4).

use std::fmt::Write as _;

use anyhow::Result;
use kepler_hsr::emit::write::json::num;
use kepler_hsr::geom::{newell, Rect, V3};
use kepler_hsr::prepare::trees::leaf_trees;
use kepler_hsr::scene::Scene;
use kepler_hsr::view::Camera;
use kepler_hsr::{render, RenderOptions};

/// The SVG picture, `size` pixels along its longer side.
pub(crate) fn components_svg(scene: &Scene, camera: &Camera, size: u32) -> Result<String> {
    let r = render(
        scene,
        camera,
        &RenderOptions::default(),
        &kepler_hsr::Progress::default(),
    )?;
    // The leaf component of every face in global order (u32::MAX: no tree).
    let mut colour_of = Vec::with_capacity(scene.face_count());
    for (leaf, tree) in scene.leaves().iter().zip(leaf_trees(scene)) {
        let comp = tree.map(|t| t.components.face_component(leaf.mesh.faces.len()));
        for k in 0..leaf.mesh.faces.len() {
            colour_of.push(comp.as_ref().map_or(u32::MAX, |c| c[k]));
        }
    }
    let mut bounds = Rect::EMPTY;
    for (_, f) in r.visibility.iter() {
        bounds = bounds.union(&Rect::of_points(f.visible.iter().flatten().flatten()));
    }
    if bounds.is_empty() {
        bounds = Rect::new(0., 0., 1., 1.);
    }
    let side = bounds.longer_side().max(f64::MIN_POSITIVE);
    let px = f64::from(size.max(1)) / side;
    let mut s = String::new();
    let _ = write!(
        s,
        "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"{} {} {} {}\" width=\"{}\" height=\"{}\">\n<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"white\"/>\n",
        num(bounds.xmin),
        num(-bounds.ymax),
        num(bounds.width()),
        num(bounds.height()),
        (bounds.width() * px).round().max(1.0),
        (bounds.height() * px).round().max(1.0),
        num(bounds.xmin),
        num(-bounds.ymax),
        num(bounds.width()),
        num(bounds.height()),
    );
    let light = V3::new(0.3, 0.5, 1.0).normalize();
    for (id, f) in r.visibility.iter() {
        if f.visible.is_empty() {
            continue;
        }
        let n = newell(&r.view.screen.face_world_pts(id));
        let n = camera.matrix.fixed_view::<3, 3>(0, 0) * n;
        let shade = 0.45 + 0.55 * n.try_normalize(0.0).map_or(0.0, |n| n.dot(&light).abs());
        let rgb = colour(
            colour_of.get(id.index()).copied().unwrap_or(u32::MAX),
            shade,
        );
        let mut d = String::new();
        for ring in f.visible.iter().flatten() {
            for (k, p) in ring.iter().enumerate() {
                let _ = write!(
                    d,
                    "{}{} {}",
                    if k == 0 { "M" } else { "L" },
                    num(p[0]),
                    num(-p[1])
                );
            }
            d.push('Z');
        }
        let _ = writeln!(
            s,
            "<path d=\"{d}\" fill=\"{rgb}\" stroke=\"{rgb}\" stroke-width=\"{}\" fill-rule=\"evenodd\"/>",
            num(0.3 / px)
        );
    }
    s.push_str("</svg>\n");
    Ok(s)
}

/// A colour per component (hues by the golden ratio), darkened by `shade`; grey without one.
fn colour(component: u32, shade: f64) -> String {
    let (r, g, b) = if component == u32::MAX {
        (0.7, 0.7, 0.7)
    } else {
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
    };
    let q = |x: f64| (255.0 * (x * shade).clamp(0.0, 1.0)).round() as u8;
    format!("#{:02x}{:02x}{:02x}", q(r), q(g), q(b))
}
