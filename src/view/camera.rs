//! Cameras: the 4x4 matrix M taking world points to the paper's standard view (viewer at z = +inf).

use crate::error::{Error, Result};
use crate::geom::{M4, P3, V3};
use crate::scene::{CameraSpec, Scene};

/// Field of view of a perspective camera asked for by an eye point alone, degrees.
pub const DEFAULT_FOV_DEG: f64 = 40.0;

/// What a caller asks of the camera (the command line's `--dir`, `--eye`, `--target`,
/// `--fov`, `--ortho`, `--up`); what it leaves unset comes from the scene's camera block, then
/// from the three-quarter view. See [`Camera::for_scene`].
#[derive(Debug, Clone, Default, PartialEq)]
pub struct CameraRequest {
    /// Orthographic, looking along this vector.
    pub dir: Option<V3>,
    /// Perspective from this eye point.
    pub eye: Option<P3>,
    /// With `eye`: the point looked at (default: the centre of the scene's CBOX).
    pub target: Option<P3>,
    /// With `eye`: vertical field of view in degrees (default [`DEFAULT_FOV_DEG`]).
    pub fov_deg: Option<f64>,
    /// With `eye`: orthographic along `target - eye` instead of perspective.
    pub ortho: bool,
    /// Up vector (default +Y).
    pub up: Option<V3>,
}

/// Kind of projection.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Projection {
    /// Parallel projection: w' = 1.
    Orthographic,
    /// Central projection from an eye point; faces are clipped at the near plane before the divide.
    Perspective,
}

/// A camera: world point p maps to (x'/w', y'/w', z'/w') with (x', y', z', w') = M p.
/// Screen x grows right, y grows up, depth z grows toward the viewer.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Camera {
    /// World to screen, homogeneous.
    pub matrix: M4,
    /// Orthographic or perspective.
    pub projection: Projection,
    /// Perspective only: the near plane, as the least allowed w' (distance along the view axis).
    pub near: f64,
    /// Perspective only: the eye point. A face whose plane passes exactly through it is seen
    /// exactly edge-on.
    pub eye: Option<P3>,
}

/// The orthonormal frame (u, v, w) of a view direction: w = -dir, u = up x w, v = w x u.
fn frame(dir: &V3, up: &V3) -> Result<(V3, V3, V3)> {
    let d = dir.norm();
    if !(d > 0.0 && d.is_finite()) {
        return Err(Error::Usage(format!(
            "view direction {:?} has no length",
            dir.as_slice()
        )));
    }
    let w = -dir / d;
    let u = up.cross(&w);
    let ul = u.norm();
    // Written so that a NaN length also fails.
    if ul.is_nan() || ul <= 1e-12 * up.norm() {
        return Err(Error::Usage(format!(
            "up vector {:?} is parallel to the view direction",
            up.as_slice()
        )));
    }
    let u = u / ul;
    Ok((u, w.cross(&u), w))
}

impl Camera {
    /// Orthographic camera looking along `dir` (DESIGN's `--dir` frame): screen x = p.u,
    /// y = p.v, depth z = p.w.
    pub fn orthographic(dir: V3, up: V3) -> Result<Camera> {
        let (u, v, w) = frame(&dir, &up)?;
        #[rustfmt::skip]
        let matrix = M4::new(
            u.x, u.y, u.z, 0.0,
            v.x, v.y, v.z, 0.0,
            w.x, w.y, w.z, 0.0,
            0.0, 0.0, 0.0, 1.0,
        );
        Ok(Camera {
            matrix,
            projection: Projection::Orthographic,
            near: 0.0,
            eye: None,
        })
    }

    /// Perspective camera at `eye` looking at `target` with vertical field of view `fov_deg`.
    /// Screen x = f·(p−eye)·u / d, y = f·(p−eye)·v / d, depth z = 1/d, where d is the distance
    /// along the view axis and f = 1/tan(fov/2). The near plane is at d = `near`.
    pub fn perspective(eye: P3, target: P3, up: V3, fov_deg: f64, near: f64) -> Result<Camera> {
        if !(fov_deg > 0.0 && fov_deg < 180.0) {
            return Err(Error::Usage(format!(
                "field of view {fov_deg} is not between 0 and 180 degrees"
            )));
        }
        let (u, v, w) = frame(&(target - eye), &up)?;
        let f = 1.0 / (fov_deg.to_radians() / 2.0).tan();
        let e = eye.coords;
        #[rustfmt::skip]
        let matrix = M4::new(
            f * u.x, f * u.y, f * u.z, -f * u.dot(&e),
            f * v.x, f * v.y, f * v.z, -f * v.dot(&e),
            0.0, 0.0, 0.0, 1.0,
            -w.x, -w.y, -w.z, w.dot(&e),
        );
        Ok(Camera {
            matrix,
            projection: Projection::Perspective,
            near,
            eye: Some(eye),
        })
    }

    /// The camera a scene file states (perspective: near plane from the eye-target distance).
    pub fn from_spec(spec: &CameraSpec) -> Result<Camera> {
        match *spec {
            CameraSpec::Orthographic { dir, up } => Camera::orthographic(dir, up),
            CameraSpec::Perspective {
                eye,
                target,
                up,
                fov_deg,
            } => Camera::perspective(eye, target, up, fov_deg, default_near(&eye, &target)),
        }
    }

    /// The camera a request asks for, for `scene`: `dir` first, then `eye` (with `target`,
    /// `fov_deg`, `ortho`), then the scene's own camera (with `up` overriding its up vector),
    /// then the three-quarter view.
    pub fn for_scene(scene: &Scene, req: &CameraRequest) -> Result<Camera> {
        let up = req.up.unwrap_or(V3::y());
        if let Some(dir) = req.dir {
            return Camera::orthographic(dir, up);
        }
        if let Some(eye) = req.eye {
            let target = req.target.unwrap_or_else(|| scene.cbox().center());
            let spec = if req.ortho {
                CameraSpec::Orthographic {
                    dir: target - eye,
                    up,
                }
            } else {
                CameraSpec::Perspective {
                    eye,
                    target,
                    up,
                    fov_deg: req.fov_deg.unwrap_or(DEFAULT_FOV_DEG),
                }
            };
            return Camera::from_spec(&spec);
        }
        if req.target.is_some() {
            return Err(Error::Usage("a camera target needs an eye point".into()));
        }
        match (&scene.camera, req.up) {
            (None, _) => Ok(Camera::three_quarter()),
            (Some(spec), None) => Camera::from_spec(spec),
            (Some(CameraSpec::Orthographic { dir, .. }), Some(up)) => {
                Camera::orthographic(*dir, up)
            }
            (
                Some(CameraSpec::Perspective {
                    eye,
                    target,
                    fov_deg,
                    ..
                }),
                Some(up),
            ) => Camera::from_spec(&CameraSpec::Perspective {
                eye: *eye,
                target: *target,
                up,
                fov_deg: *fov_deg,
            }),
        }
    }

    /// A pleasant three-quarter orthographic view (from the right, above and in front; +Y up).
    pub fn three_quarter() -> Camera {
        let dir = V3::new(-0.55, -0.5, -0.75);
        Camera::orthographic(dir, V3::y()).expect("fixed frame is valid")
    }

    /// Homogeneous image (x', y', z', w') of a world point.
    pub fn clip_coords(&self, p: &P3) -> [f64; 4] {
        let h = self.matrix * p.to_homogeneous();
        [h.x, h.y, h.z, h.w]
    }

    /// Screen point of a world point in front of the near plane.
    pub fn project(&self, p: &P3) -> [f64; 3] {
        let [x, y, z, w] = self.clip_coords(p);
        if self.projection == Projection::Orthographic {
            [x, y, z]
        } else {
            [x / w, y / w, z / w]
        }
    }

    /// True when a world point lies in front of the near plane (always, for orthographic).
    pub fn in_front(&self, p: &P3) -> bool {
        self.projection == Projection::Orthographic || self.clip_coords(p)[3] >= self.near
    }

    /// The world point whose screen image is (x, y, z) (inverse of [`Camera::project`]).
    pub fn unproject(&self, s: [f64; 3]) -> P3 {
        let inv = self.matrix.try_inverse().unwrap_or_else(M4::identity);
        let h = inv * nalgebra::Vector4::new(s[0], s[1], s[2], 1.0);
        P3::new(h.x / h.w, h.y / h.w, h.z / h.w)
    }
}

/// Near plane for a perspective view: 1/1000 of the distance from the eye to the target.
fn default_near(eye: &P3, target: &P3) -> f64 {
    let dist = (target - eye).norm();
    (dist * 1e-3).max(1e-9)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ortho_dir_frame_matches_design() {
        let c = Camera::orthographic(V3::new(0., 0., -1.), V3::y()).unwrap();
        // Looking down -z with +y up: screen = world, depth z toward the viewer.
        assert_eq!(c.project(&P3::new(1., 2., 3.)), [1., 2., 3.]);
        let c = Camera::orthographic(V3::new(-1., 0., 0.), V3::y()).unwrap();
        // w = +x, u = y x w = -z, v = w x u = y.
        assert_eq!(c.project(&P3::new(1., 2., 3.)), [-3., 2., 1.]);
    }

    #[test]
    fn perspective_depth_grows_toward_viewer() {
        let c =
            Camera::perspective(P3::new(0., 0., 10.), P3::origin(), V3::y(), 90.0, 0.01).unwrap();
        let near = c.project(&P3::new(0., 0., 5.));
        let far = c.project(&P3::new(0., 0., -5.));
        assert!(near[2] > far[2]);
        let p = c.project(&P3::new(1., 1., 0.));
        assert!(
            (p[0] - 0.1).abs() < 1e-15 && (p[1] - 0.1).abs() < 1e-15 && (p[2] - 0.1).abs() < 1e-15
        );
        let q = c.unproject(p);
        assert!((q - P3::new(1., 1., 0.)).norm() < 1e-12);
        assert!(!c.in_front(&P3::new(0., 0., 11.)));
    }

    #[test]
    fn degenerate_cameras_are_errors() {
        assert!(Camera::orthographic(V3::zeros(), V3::y()).is_err());
        assert!(Camera::orthographic(V3::y(), V3::y()).is_err());
        assert!(Camera::perspective(P3::origin(), P3::origin(), V3::y(), 40.0, 0.1).is_err());
        assert!(
            Camera::perspective(P3::origin(), P3::new(0., 0., -1.), V3::y(), 180.0, 0.1).is_err()
        );
    }
}
