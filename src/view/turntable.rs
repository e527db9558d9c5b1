//! Turntables: a camera carried round the scene about a vertical axis through its centre,
//! N views a full turn apart, and one frame that holds the scene in every one of them.
//!
//! View k sees the world turned by −360°·k/N about the axis: its matrix is M·T(c)·R(−θ)·T(−c)
//! for the base camera's M (a perspective eye turns with it). The scene's bounding cylinder
//! about the axis is the same set in every view, so the screen bounds of a polygon
//! circumscribing it, taken once with the base camera, frame every view alike: the scene
//! keeps its place and size from picture to picture.

use crate::error::{Error, Result};
use crate::geom::{Rect, M4, P3, V3};
use crate::scene::Scene;

use super::camera::{Camera, Projection};

/// Sides of the polygon circumscribing the bounding cylinder's circles.
const SIDES: usize = 64;

/// The axis of a turntable: through the scene's CBOX centre along `up` (normalised).
fn axis(scene: &Scene, up: V3) -> Result<(P3, V3)> {
    let up = up
        .try_normalize(0.0)
        .ok_or_else(|| Error::Usage("turntable axis (the up vector) has no length".into()))?;
    Ok((scene.cbox().center(), up))
}

/// `n` cameras a full turn apart about the vertical axis through the scene's centre, the
/// first being `base`.
pub(crate) fn turntable(scene: &Scene, base: &Camera, up: V3, n: usize) -> Result<Vec<Camera>> {
    if n == 0 {
        return Err(Error::Usage("a turntable needs at least one view".into()));
    }
    let (c, up) = axis(scene, up)?;
    Ok((0..n)
        .map(|k| {
            let theta = std::f64::consts::TAU * k as f64 / n as f64;
            turned(base, c, up, theta)
        })
        .collect())
}

/// The camera carried by `theta` radians about the axis through `c` along unit `up`.
fn turned(base: &Camera, c: P3, up: V3, theta: f64) -> Camera {
    if theta == 0.0 {
        return *base;
    }
    let rot = nalgebra::Rotation3::from_axis_angle(&nalgebra::Unit::new_unchecked(up), theta);
    let world = nalgebra::Translation3::from(c.coords).to_homogeneous()
        * rot.inverse().to_homogeneous()
        * nalgebra::Translation3::from(-c.coords).to_homogeneous();
    let matrix: M4 = base.matrix * world;
    Camera {
        matrix,
        projection: base.projection,
        near: base.near,
        eye: base.eye.map(|e| c + rot * (e - c)),
    }
}

/// The screen rectangle that holds the scene in every view of a turntable about `up` from
/// `base`; None when the bounding cylinder is not wholly in front of a perspective eye.
pub(crate) fn turntable_frame(scene: &Scene, base: &Camera, up: V3) -> Option<Rect> {
    let (c, up) = axis(scene, up).ok()?;
    let b = scene.cbox();
    if b.lo.x > b.hi.x || b.lo.x.is_nan() {
        return None;
    }
    // Radius and height range of the cylinder about the axis.
    let corners = (0..8).map(|k| {
        P3::new(
            if k & 1 == 0 { b.lo.x } else { b.hi.x },
            if k & 2 == 0 { b.lo.y } else { b.hi.y },
            if k & 4 == 0 { b.lo.z } else { b.hi.z },
        )
    });
    let (mut r, mut h0, mut h1) = (0.0f64, f64::INFINITY, f64::NEG_INFINITY);
    for p in corners {
        let d = p - c;
        let h = d.dot(&up);
        r = r.max((d - up * h).norm());
        h0 = h0.min(h);
        h1 = h1.max(h);
    }
    // A polygon circumscribing the circle of radius r.
    let e1 = up
        .cross(&V3::x())
        .try_normalize(1e-9)
        .unwrap_or_else(|| up.cross(&V3::z()).normalize());
    let e2 = up.cross(&e1);
    let rr = r / (std::f64::consts::PI / SIDES as f64).cos();
    let mut rect = Rect::EMPTY;
    for k in 0..SIDES {
        let a = std::f64::consts::TAU * k as f64 / SIDES as f64;
        let radial = (e1 * a.cos() + e2 * a.sin()) * rr;
        for h in [h0, h1] {
            let p = c + radial + up * h;
            if !base.in_front(&p) {
                return None;
            }
            let s = base.project(&p);
            rect.add([s[0], s[1]]);
        }
    }
    if base.projection == Projection::Perspective && rect.is_empty() {
        return None;
    }
    (!rect.is_empty()).then_some(rect)
}

impl Camera {
    /// `n` cameras a full turn apart about the vertical axis (`up`) through `scene`'s
    /// centre, the first being this one (see the module's description).
    pub fn turntable(&self, scene: &Scene, up: V3, n: usize) -> Result<Vec<Camera>> {
        turntable(scene, self, up, n)
    }

    /// The one frame that holds `scene` in every view of a turntable from this camera about
    /// `up` (None for an empty scene): set it as the pictures' frame so that the scene keeps
    /// its place and size from picture to picture.
    pub fn turntable_frame(&self, scene: &Scene, up: V3) -> Option<Rect> {
        turntable_frame(scene, self, up)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::testing::unit_cube_scene;

    #[test]
    fn views_turn_about_the_axis_and_share_one_frame() {
        let scene = unit_cube_scene();
        let base = Camera::orthographic(V3::new(-1., -0.5, -1.), V3::y()).unwrap();
        let cams = turntable(&scene, &base, V3::y(), 4).unwrap();
        assert_eq!(cams.len(), 4);
        assert_eq!(cams[0], base);
        let frame = turntable_frame(&scene, &base, V3::y()).unwrap();
        let b = scene.cbox();
        for cam in &cams {
            // Every corner of the scene is inside the shared frame in every view.
            for k in 0..8 {
                let p = P3::new(
                    if k & 1 == 0 { b.lo.x } else { b.hi.x },
                    if k & 2 == 0 { b.lo.y } else { b.hi.y },
                    if k & 4 == 0 { b.lo.z } else { b.hi.z },
                );
                let s = cam.project(&p);
                assert!(frame
                    .padded(1e-12)
                    .contains_rect(&Rect::new(s[0], s[1], s[0], s[1])));
            }
        }
        // A quarter turn of a cube about its vertical axis shows the same picture.
        let c = scene.cbox().center();
        let p = P3::new(b.hi.x, b.hi.y, b.hi.z);
        let q =
            c + nalgebra::Rotation3::from_axis_angle(&V3::y_axis(), -std::f64::consts::FRAC_PI_2)
                * (p - c);
        let (s1, s0) = (cams[1].project(&p), base.project(&q));
        assert!((s1[0] - s0[0]).abs() < 1e-12 && (s1[1] - s0[1]).abs() < 1e-12);
    }

    #[test]
    fn perspective_eye_turns_with_the_camera() {
        let scene = unit_cube_scene();
        let c = scene.cbox().center();
        let eye = P3::new(c.x, c.y, c.z + 10.0);
        let base = Camera::perspective(eye, c, V3::y(), 40.0, 0.01).unwrap();
        let cams = turntable(&scene, &base, V3::y(), 4).unwrap();
        let e1 = cams[1].eye.unwrap();
        assert!((e1 - P3::new(c.x + 10.0, c.y, c.z)).norm() < 1e-9, "{e1:?}");
        // The centre still projects to the middle of the picture.
        let s = cams[1].project(&c);
        assert!(s[0].abs() < 1e-12 && s[1].abs() < 1e-12);
        assert!(turntable_frame(&scene, &base, V3::y()).is_some());
        let inside =
            Camera::perspective(c, P3::new(c.x, c.y, c.z - 1.0), V3::y(), 40.0, 0.01).unwrap();
        assert!(turntable_frame(&scene, &inside, V3::y()).is_none());
    }
}
