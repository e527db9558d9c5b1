//! Cameras: the 4x4 matrix M taking world points to the paper's standard view (viewer at z = +inf).

use crate::error::{Error, Result};
use crate::geom::{M4, MAX_COORD, P3, V3};
use crate::scene::flatten::num;
use crate::scene::{CameraSpec, Scene};

pub(crate) use crate::scene::DEFAULT_FOV_DEG;

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
    /// Vertical field of view in degrees, for `eye` (default 45) or alone
    /// for the scene's perspective camera.
    pub fov_deg: Option<f64>,
    /// Orthographic along `target - eye` instead of perspective: with `eye`, or alone for
    /// the scene's perspective camera.
    pub ortho: bool,
    /// Up vector (default +Y with `dir` or `eye`, the scene camera's own up, or, for a scene
    /// without a camera, [`Scene::auto_up`]).
    pub up: Option<V3>,
}

impl CameraRequest {
    /// The up in force for this request on `scene`: `up` when given, +Y with a `dir` or an
    /// `eye`, else the scene camera's up, else the scene's [`Scene::auto_up`].
    pub fn up_in_force(&self, scene: &Scene) -> V3 {
        if let Some(up) = self.up {
            return up;
        }
        if self.dir.is_some() || self.eye.is_some() {
            return V3::y();
        }
        scene.camera_up().unwrap_or_else(|| scene.auto_up())
    }
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
/// Vectors are scaled by their largest component first, so that huge or tiny ones whose
/// length overflows or underflows still have a direction.
fn frame(dir: &V3, up: &V3) -> Result<(V3, V3, V3)> {
    let Some(d) = direction(dir) else {
        return Err(Error::Usage(format!(
            "view direction {:?} has no length",
            dir.as_slice()
        )));
    };
    let w = -d;
    let parallel = || {
        Error::Usage(format!(
            "up vector {:?} is parallel to the view direction",
            up.as_slice()
        ))
    };
    // `up` as given when its length is a normal number (DESIGN's frame, bit for bit), else
    // scaled to unit length first.
    let up = if up.norm().is_normal() {
        *up
    } else {
        direction(up).ok_or_else(parallel)?
    };
    let u = up.cross(&w);
    let ul = u.norm();
    // Written so that a NaN length also fails.
    if ul.is_nan() || ul <= 1e-12 * up.norm() {
        return Err(parallel());
    }
    let u = u / ul;
    Ok((u, w.cross(&u), w))
}

/// The unit vector along `v`, if it has a finite, non-zero direction: `v / |v|` (DESIGN's
/// frame, bit for bit) when the length is a normal finite number, else `v` scaled by its
/// largest component first so that a length that overflows or underflows still gives one.
fn direction(v: &V3) -> Option<V3> {
    let n = v.norm();
    if n.is_normal() {
        return Some(v / n);
    }
    let m = v.amax();
    if !(m > 0.0 && m.is_finite()) {
        return None;
    }
    let s = v / m;
    Some(s / s.norm())
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
        if !(f.is_finite() && f > 0.0) {
            return Err(Error::Usage(format!(
                "field of view {fov_deg} degrees is too narrow to compute with"
            )));
        }
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
    pub(crate) fn from_spec(spec: &CameraSpec) -> Result<Camera> {
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

    /// The camera a request asks for, for `scene`. `dir` (orthographic) and `eye`
    /// (perspective, or orthographic with `ortho`; `target` and `fov_deg` with it) each
    /// replace the scene's camera, and cannot be combined. Without them, `fov_deg`, `ortho`
    /// and `up` change the scene's own camera (the three-quarter view when it has none).
    /// Nothing asked for is ignored: a request that cannot apply is an error.
    pub fn for_scene(scene: &Scene, req: &CameraRequest) -> Result<Camera> {
        let usage = |m: &str| Err(Error::Usage(m.into()));
        for (what, p) in [("eye", &req.eye), ("target", &req.target)] {
            if let Some(p) = p {
                check_point(what, p)?;
            }
        }
        if let Some(fov) = req.fov_deg {
            if !(fov > 0.0 && fov < 180.0) {
                return Err(Error::Usage(format!(
                    "field of view {fov} is not between 0 and 180 degrees"
                )));
            }
        }
        let up = req.up.unwrap_or(V3::y());
        if let Some(dir) = req.dir {
            if req.eye.is_some() || req.target.is_some() {
                return usage(
                    "a camera has either a direction (orthographic) or an eye and target, not both",
                );
            }
            if req.fov_deg.is_some() {
                return usage(
                    "a field of view needs a perspective camera (an eye), not a direction",
                );
            }
            return Camera::orthographic(dir, up);
        }
        if let Some(eye) = req.eye {
            let target = req.target.unwrap_or_else(|| scene.cbox().center());
            let spec = if req.ortho {
                if req.fov_deg.is_some() {
                    return usage(
                        "a field of view needs a perspective camera, not an orthographic one",
                    );
                }
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
            return usage("a camera target needs an eye point");
        }
        match &scene.camera {
            None if req.fov_deg.is_some() => usage(
                "a field of view needs a perspective camera: the scene has none (give an eye point)",
            ),
            None => {
                let up = req.up.unwrap_or_else(|| scene.auto_up());
                Camera::three_quarter_about(up)
            }
            Some(CameraSpec::Orthographic { dir, up: own }) => {
                if req.fov_deg.is_some() {
                    return usage("a field of view needs a perspective camera: the scene's camera is orthographic");
                }
                Camera::orthographic(*dir, req.up.unwrap_or(*own))
            }
            Some(CameraSpec::Perspective {
                eye,
                target,
                up: own,
                fov_deg,
            }) => {
                let up = req.up.unwrap_or(*own);
                if req.ortho {
                    if req.fov_deg.is_some() {
                        return usage("a field of view needs a perspective camera, not an orthographic one");
                    }
                    return Camera::orthographic(target - eye, up);
                }
                Camera::from_spec(&CameraSpec::Perspective {
                    eye: *eye,
                    target: *target,
                    up,
                    fov_deg: req.fov_deg.unwrap_or(*fov_deg),
                })
            }
        }
    }

    /// A pleasant three-quarter orthographic view (from the right, above and in front; +Y up).
    pub fn three_quarter() -> Camera {
        Camera::orthographic(THREE_QUARTER, V3::y()).expect("fixed frame is valid")
    }

    /// The three-quarter view turned so that `up` is up: its direction carried by the least
    /// rotation taking +Y to `up` (for +Y, exactly [`Camera::three_quarter`]; for +Z, seen
    /// from the right, in front (−Y) and above).
    pub fn three_quarter_about(up: V3) -> Result<Camera> {
        Camera::orthographic(super::up::from_y(up)(THREE_QUARTER), up)
    }

    /// A named orthographic view relative to `up`: `front` (looking along −Z when +Y is up),
    /// `back`, `left` (from −X), `right` (from +X), `top` (from above, the front at the
    /// bottom of the picture), `bottom` (from below, the front at the top), `iso` (along
    /// −1,−1,−1: from the right, in front and above). Each is carried, with its screen up, by
    /// the least rotation taking +Y to `up`.
    pub fn named_view(name: &str, up: V3) -> Result<Camera> {
        let y = V3::y();
        let (dir, screen_up) = match name {
            "front" => (V3::new(0., 0., -1.), y),
            "back" => (V3::new(0., 0., 1.), y),
            "left" => (V3::new(1., 0., 0.), y),
            "right" => (V3::new(-1., 0., 0.), y),
            "top" => (V3::new(0., -1., 0.), V3::new(0., 0., -1.)),
            "bottom" => (V3::new(0., 1., 0.), V3::new(0., 0., 1.)),
            "iso" => (V3::new(-1., -1., -1.), y),
            _ => {
                return Err(Error::Usage(format!(
                    "view {name}: expected front, back, left, right, top, bottom or iso"
                )))
            }
        };
        if up.try_normalize(0.0).is_none() {
            return Err(Error::Usage(format!(
                "up vector {:?} has no length",
                up.as_slice()
            )));
        }
        let r = super::up::from_y(up);
        Camera::orthographic(r(dir), r(screen_up))
    }

    /// Homogeneous image (x', y', z', w') of a world point: each coordinate within 1 ulp plus
    /// 1.8e-31·Σ|m_ij·p_j| of the exact value (compensated, so a large translation in M does
    /// not cancel the point's digits; docs/numerics.md).
    pub fn clip_coords(&self, p: &P3) -> [f64; 4] {
        crate::geom::accurate::mat_point(&self.matrix, p)
    }

    /// Screen point of a world point in front of the near plane: each coordinate within 1 ulp
    /// of the exact x'/w' (plus 1.8e-31·Σ|m_ij·p_j| / w').
    pub fn project(&self, p: &P3) -> [f64; 3] {
        project_dd(
            &crate::geom::accurate::mat_point_dd(&self.matrix, p),
            self.projection,
        )
    }

    /// True when a world point lies in front of the near plane (always, for orthographic).
    pub fn in_front(&self, p: &P3) -> bool {
        self.projection == Projection::Orthographic
            || crate::geom::construct::near_side(
                &self.matrix,
                p,
                &crate::geom::accurate::mat_point_dd(&self.matrix, p),
                self.near,
            ) != std::cmp::Ordering::Less
    }

    /// The world point whose screen image is (x, y, z) (inverse of [`Camera::project`]).
    pub fn unproject(&self, s: [f64; 3]) -> P3 {
        let inv = self.matrix.try_inverse().unwrap_or_else(M4::identity);
        let h = inv * nalgebra::Vector4::new(s[0], s[1], s[2], 1.0);
        P3::new(h.x / h.w, h.y / h.w, h.z / h.w)
    }
}

/// The screen point (x, y, depth) of double-double clip coordinates: divided by w' in
/// perspective (each within 1 ulp of the pairs' exact quotient), rounded once in orthographic.
pub(crate) fn project_dd(h: &[(f64, f64); 4], projection: Projection) -> [f64; 3] {
    match projection {
        Projection::Perspective => {
            std::array::from_fn(|k| crate::geom::accurate::div_dd(h[k], h[3]))
        }
        Projection::Orthographic => std::array::from_fn(|k| h[k].0 + h[k].1),
    }
}

/// An error unless every coordinate of the camera's `what` point (eye or target) is finite and
/// within [`MAX_COORD`], the limit scene coordinates have: beyond it, distances and the near
/// plane overflow (an eye at 1e160 made a near plane of infinity).
fn check_point(what: &str, p: &P3) -> Result<()> {
    match p.iter().find(|c| !(c.is_finite() && c.abs() <= MAX_COORD)) {
        None => Ok(()),
        Some(c) => Err(Error::Usage(format!(
            "camera {what} {},{},{}: coordinate {} is beyond {MAX_COORD:e}, the limit scene coordinates have",
            num(p.x),
            num(p.y),
            num(p.z),
            num(*c)
        ))),
    }
}

/// The direction of the three-quarter view.
const THREE_QUARTER: V3 = V3::new(-0.55, -0.5, -0.75);

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
    fn requests_change_the_scenes_camera_or_fail_never_ignored() {
        let mut scene = crate::scene::testing::unit_cube_scene();
        scene.camera = Some(CameraSpec::Perspective {
            eye: P3::new(0., 0., 10.),
            target: P3::origin(),
            up: V3::y(),
            fov_deg: 30.0,
        });
        let req = |f: &dyn Fn(&mut CameraRequest)| {
            let mut r = CameraRequest::default();
            f(&mut r);
            Camera::for_scene(&scene, &r)
        };
        let own = req(&|_| {}).unwrap();
        let narrow = req(&|r| r.fov_deg = Some(10.0)).unwrap();
        assert_eq!(narrow.eye, own.eye);
        assert!(narrow.matrix[(0, 0)] > 3.0 * own.matrix[(0, 0)]);
        let ortho = req(&|r| r.ortho = true).unwrap();
        assert_eq!(ortho.projection, Projection::Orthographic);
        assert_eq!(ortho.project(&P3::new(1., 2., 3.))[..2], [1., 2.]);
        let e = req(&|r| {
            r.dir = Some(V3::x());
            r.eye = Some(P3::origin());
        });
        assert!(e.unwrap_err().to_string().contains("not both"));
        assert!(req(&|r| {
            r.dir = Some(V3::z());
            r.fov_deg = Some(20.0)
        })
        .is_err());
        assert!(req(&|r| r.fov_deg = Some(-5.0)).is_err());
        // No camera in the scene: a field of view alone has nothing to apply to.
        scene.camera = None;
        let e = Camera::for_scene(
            &scene,
            &CameraRequest {
                fov_deg: Some(10.0),
                ..Default::default()
            },
        );
        assert!(e
            .unwrap_err()
            .to_string()
            .contains("needs a perspective camera"));
        // An eye alone: the one default field of view.
        let c = Camera::for_scene(
            &scene,
            &CameraRequest {
                eye: Some(P3::new(0., 0., 5.)),
                ..Default::default()
            },
        )
        .unwrap();
        let f = 1.0 / (DEFAULT_FOV_DEG.to_radians() / 2.0).tan();
        assert!((c.matrix.fixed_view::<1, 3>(0, 0).norm() - f).abs() < 1e-12);
    }

    #[test]
    fn huge_and_tiny_directions_have_a_frame() {
        for s in [1e308, 1e-308, 5e-324] {
            let c = Camera::orthographic(V3::new(s, s, s), V3::y()).unwrap();
            let d = Camera::orthographic(V3::new(1., 1., 1.), V3::y()).unwrap();
            assert!((c.matrix - d.matrix).amax() < 1e-15, "{s}");
        }
        assert!(Camera::orthographic(V3::new(f64::INFINITY, 0., 0.), V3::y()).is_err());
        assert!(
            Camera::perspective(P3::origin(), P3::new(0., 0., -1.), V3::y(), 1e-320, 0.1).is_err()
        );
    }

    #[test]
    fn eyes_and_targets_beyond_scene_coordinates_are_refused() {
        let scene = crate::scene::testing::unit_cube_scene();
        let ask = |eye: [f64; 3], target: Option<[f64; 3]>| {
            let req = CameraRequest {
                eye: Some(P3::from(eye)),
                target: target.map(P3::from),
                ..Default::default()
            };
            Camera::for_scene(&scene, &req)
        };
        let e = ask([1e160, 0., 0.], None).unwrap_err().to_string();
        assert_eq!(
            e,
            "camera eye 1e160,0,0: coordinate 1e160 is beyond 1e12, the limit scene coordinates have"
        );
        let e = ask([5., 5., 5.], Some([1e308, 0., 0.]))
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("camera target "), "{e}");
        assert!(ask([f64::NAN, 0., 0.], None).is_err());
        // At the limit: a camera with a finite near plane.
        let c = ask([1e12, 0., 0.], None).unwrap();
        assert!(c.near.is_finite() && c.near > 0.0);
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
