//! Camera flags shared by render and query: `--dir`, `--eye/--target/--fov/--ortho`, `--up`.

use anyhow::{bail, Result};
use clap::Args;
use kepler::geom::{P3, V3};
use kepler::scene::{CameraSpec, Scene};
use kepler::view::Camera;

/// Camera flags; they override the scene's camera.
#[derive(Args, Debug, Clone, Default)]
pub struct CameraArgs {
    /// Orthographic view looking along this vector (X,Y,Z).
    #[arg(long, value_name = "X,Y,Z", allow_hyphen_values = true)]
    pub dir: Option<String>,
    /// Perspective eye point (X,Y,Z).
    #[arg(long, value_name = "X,Y,Z", allow_hyphen_values = true)]
    pub eye: Option<String>,
    /// Point looked at (X,Y,Z); default the centre of the scene.
    #[arg(long, value_name = "X,Y,Z", allow_hyphen_values = true)]
    pub target: Option<String>,
    /// Vertical field of view in degrees (perspective).
    #[arg(long, default_value_t = 40.0)]
    pub fov: f64,
    /// With --eye/--target: orthographic along target - eye.
    #[arg(long)]
    pub ortho: bool,
    /// Up vector (X,Y,Z); default +Y.
    #[arg(long, value_name = "X,Y,Z", allow_hyphen_values = true)]
    pub up: Option<String>,
}

/// Parses "X,Y,Z".
pub fn parse_vec3(s: &str, flag: &str) -> Result<V3> {
    let parts: Vec<&str> = s.split(',').map(str::trim).collect();
    if parts.len() != 3 {
        bail!("--{flag} {s}: expected three numbers X,Y,Z");
    }
    let mut v = [0.0; 3];
    for (k, p) in parts.iter().enumerate() {
        v[k] = p
            .parse::<f64>()
            .map_err(|_| anyhow::anyhow!("--{flag} {s}: '{p}' is not a number"))?;
        if !v[k].is_finite() {
            bail!("--{flag} {s}: '{p}' is not finite");
        }
    }
    Ok(V3::new(v[0], v[1], v[2]))
}

impl CameraArgs {
    /// The camera: flags first, then the scene's camera block, then the three-quarter view.
    pub fn camera(&self, scene: &Scene) -> Result<Camera> {
        let up = match &self.up {
            Some(u) => Some(parse_vec3(u, "up")?),
            None => None,
        };
        let cbox = scene.cbox();
        if let Some(d) = &self.dir {
            return Ok(Camera::orthographic(
                parse_vec3(d, "dir")?,
                up.unwrap_or(V3::y()),
            )?);
        }
        if let Some(e) = &self.eye {
            let eye = P3::from(parse_vec3(e, "eye")?);
            let target = match &self.target {
                Some(t) => P3::from(parse_vec3(t, "target")?),
                None => cbox.center(),
            };
            let up = up.unwrap_or(V3::y());
            let spec = if self.ortho {
                CameraSpec::Orthographic {
                    dir: target - eye,
                    up,
                }
            } else {
                CameraSpec::Perspective {
                    eye,
                    target,
                    up,
                    fov_deg: self.fov,
                }
            };
            return Ok(Camera::from_spec(&spec)?);
        }
        if self.target.is_some() {
            bail!("--target needs --eye");
        }
        match &scene.camera {
            Some(spec) => {
                let spec = match (spec.clone(), up) {
                    (CameraSpec::Orthographic { dir, .. }, Some(up)) => {
                        CameraSpec::Orthographic { dir, up }
                    }
                    (
                        CameraSpec::Perspective {
                            eye,
                            target,
                            fov_deg,
                            ..
                        },
                        Some(up),
                    ) => CameraSpec::Perspective {
                        eye,
                        target,
                        up,
                        fov_deg,
                    },
                    (s, None) => s,
                };
                Ok(Camera::from_spec(&spec)?)
            }
            None => Ok(Camera::three_quarter()),
        }
    }
}
