//! Numbers checked where they can degenerate: a view whose screen coordinates leave the range
//! the exact stages compute in (a field of view of 1e-150 degrees magnifies the scene 1e152
//! times, and areas then overflow) is an error, not a picture of NaNs.

use crate::error::{Error, Result};

use super::screen::ScreenFaces;

/// Largest screen coordinate accepted: products of two (areas) stay far from overflow.
pub const SCREEN_LIMIT: f64 = 1e30;

/// An error when a projected point is not finite or beyond [`SCREEN_LIMIT`].
pub fn check_screen(screen: &ScreenFaces) -> Result<()> {
    let mut worst = 0.0f64;
    for p in &screen.points {
        for &c in p {
            if !c.is_finite() {
                worst = f64::INFINITY;
            } else {
                worst = worst.max(c.abs());
            }
        }
    }
    if worst <= SCREEN_LIMIT {
        return Ok(());
    }
    let size = if worst.is_finite() {
        format!("{worst:.1e}")
    } else {
        "infinity".into()
    };
    Err(Error::Usage(format!(
        "the view magnifies the scene to screen coordinates of {size}, beyond the {SCREEN_LIMIT:e} kepler computes with: the field of view is too narrow for the scene"
    )))
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
            let r = render(&scene, &cam, &RenderOptions::default());
            assert_eq!(r.is_ok(), ok, "{fov}");
            if let Err(e) = r {
                assert!(e.to_string().contains("field of view is too narrow"), "{e}");
            }
        }
    }
}
