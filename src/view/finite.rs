//! Numbers checked where they can degenerate: a view whose screen coordinates leave the range
//! the exact stages compute in (a field of view of 1e-150 degrees magnifies the scene 1e152
//! times, and areas then overflow) is an error, not a picture of NaNs.

use rayon::prelude::*;

use crate::error::{Error, Location, Result};
use crate::scene::{CameraSpec, Scene};

use super::camera::{Camera, Projection};
use super::screen::ScreenFaces;

/// Largest screen coordinate accepted: products of two (areas) stay far from overflow.
pub(crate) const SCREEN_LIMIT: f64 = 1e30;

/// An error naming `camera` when a point projected by it is not finite or beyond
/// [`SCREEN_LIMIT`] (world coordinates are at most 1e12, so only a narrow perspective view
/// gets there).
pub(crate) fn check_screen(screen: &ScreenFaces, camera: &Camera) -> Result<()> {
    // The points corners name (a vertex behind the near plane has a point no corner names),
    // in fixed chunks on all threads: a maximum, so the same in any order.
    let size = |i: &u32| {
        let p = &screen.points[*i as usize];
        p.iter().fold(0.0f64, |w, &c| match c.is_finite() {
            true => w.max(c.abs()),
            false => f64::INFINITY,
        })
    };
    let worst = screen
        .corner_at
        .par_chunks(crate::chunked::CHUNK)
        .map(|chunk| chunk.iter().map(size).fold(0.0, f64::max))
        .reduce(|| 0.0, f64::max);
    if worst <= SCREEN_LIMIT {
        return Ok(());
    }
    let size = if worst.is_finite() {
        format!("{worst:.1e}")
    } else {
        "infinity".into()
    };
    let m = &camera.matrix;
    let camera = match camera.projection {
        Projection::Perspective => {
            // The focal factor f = 1 / tan(fov / 2) scales the first row.
            // (Scaled first: the square of a focal factor of 1e300 overflows.)
            let row = m.fixed_view::<1, 3>(0, 0);
            let a = row.amax();
            let f = a * (row / a).norm();
            let fov = 2.0 * (1.0 / f).atan().to_degrees();
            format!("the perspective camera's field of view of {fov:.3e} degrees")
        }
        Projection::Orthographic => "the orthographic camera".to_string(),
    };
    Err(Error::Usage(format!(
        "{camera} magnifies the scene to screen coordinates of {size}, beyond the {SCREEN_LIMIT:e} kepler computes with: the field of view is too narrow for the scene"
    )))
}

/// `e` (a refused view) placed where its camera came from: the scene file's camera block when
/// the view's eye is that camera's (its field of view may come from a flag), else the scene
/// file itself.
pub(crate) fn placed(e: Error, scene: &Scene, camera: &Camera) -> Error {
    let Error::Usage(msg) = e else {
        return e;
    };
    let own_eye = match &scene.camera {
        Some(CameraSpec::Perspective { eye, .. }) => Some(*eye),
        _ => None,
    };
    let (loc, whose) = match (&scene.camera_at, own_eye) {
        (Some(at), Some(eye)) if camera.eye == Some(eye) => (at.clone(), " (the scene's camera)"),
        _ => (Location::file(&scene.source), ""),
    };
    Error::invalid(loc, format!("{msg}{whose}"))
}

#[cfg(test)]
mod tests {
    use crate::geom::{P3, V3};
    use crate::scene::testing::unit_cube_scene;
    use crate::view::Camera;
    use crate::{render, RenderOptions};

    #[test]
    fn narrow_fields_of_view_are_refused_wide_ones_pass() {
        let scene = unit_cube_scene();
        let eye = P3::new(0.5, 0.5, 5.0);
        let target = P3::new(0.5, 0.5, 0.0);
        for (fov, ok) in [(40.0, true), (1e-6, true), (1e-150, false), (1e-300, false)] {
            let cam = Camera::perspective(eye, target, V3::y(), fov, 0.005).unwrap();
            let r = render(
                &scene,
                &cam,
                &RenderOptions::default(),
                &crate::Progress::default(),
            );
            assert_eq!(r.is_ok(), ok, "{fov}");
            if let Err(e) = r {
                assert!(e.to_string().contains("field of view is too narrow"), "{e}");
            }
        }
    }
}
