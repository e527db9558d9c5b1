//! Camera flags shared by render and query: `--dir`, `--eye/--target/--fov/--ortho`, `--up`.

use anyhow::{bail, Result};
use clap::Args;
use kepler_hsr::{Camera, CameraRequest, Scene, P3, V3};

/// Camera flags; they override the scene's camera.
#[derive(Args, Debug, Clone, Default)]
pub(crate) struct CameraArgs {
    /// Orthographic view looking along this vector (X,Y,Z).
    #[arg(long, value_name = "X,Y,Z", allow_hyphen_values = true)]
    pub(crate) dir: Option<String>,
    /// Perspective eye point (X,Y,Z).
    #[arg(long, value_name = "X,Y,Z", allow_hyphen_values = true)]
    pub(crate) eye: Option<String>,
    /// Point looked at (X,Y,Z); default the centre of the scene.
    #[arg(long, value_name = "X,Y,Z", allow_hyphen_values = true)]
    pub(crate) target: Option<String>,
    /// Vertical field of view in degrees (perspective): with --eye (default 45, as in scene
    /// files), or alone to change the scene's perspective camera.
    #[arg(long, value_name = "DEG", allow_negative_numbers = true)]
    pub(crate) fov: Option<f64>,
    /// Orthographic along target - eye: with --eye/--target, or alone to make the scene's
    /// perspective camera orthographic.
    #[arg(long)]
    pub(crate) ortho: bool,
    /// Up vector (X,Y,Z); default +Y.
    #[arg(long, value_name = "X,Y,Z", allow_hyphen_values = true)]
    pub(crate) up: Option<String>,
}

/// Parses "X,Y,Z".
pub(crate) fn parse_vec3(s: &str, flag: &str) -> Result<V3> {
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
    /// The camera the flags ask for (see [`Camera::for_scene`]: flags first, then the
    /// scene's camera block, then the three-quarter view).
    pub(crate) fn camera(&self, scene: &Scene) -> Result<Camera> {
        self.check()?;
        let vec =
            |s: &Option<String>, flag: &str| s.as_deref().map(|s| parse_vec3(s, flag)).transpose();
        let req = CameraRequest {
            dir: vec(&self.dir, "dir")?,
            eye: vec(&self.eye, "eye")?.map(P3::from),
            target: vec(&self.target, "target")?.map(P3::from),
            fov_deg: self.fov,
            ortho: self.ortho,
            up: vec(&self.up, "up")?,
        };
        Ok(Camera::for_scene(scene, &req)?)
    }

    /// The checks of the flags alone, before any scene is loaded: combinations that cannot
    /// apply and values out of range.
    pub(crate) fn check(&self) -> Result<()> {
        if self.target.is_some() && self.eye.is_none() {
            bail!("--target needs --eye");
        }
        if self.dir.is_some() && (self.eye.is_some() || self.ortho || self.fov.is_some()) {
            bail!("--dir is an orthographic view of its own: it takes no --eye, --target, --fov or --ortho");
        }
        if let Some(fov) = self.fov {
            if !(fov > 0.0 && fov < 180.0) {
                bail!("--fov {fov}: expected degrees between 0 and 180 (both excluded)");
            }
        }
        for (s, flag) in [
            (&self.dir, "dir"),
            (&self.eye, "eye"),
            (&self.target, "target"),
            (&self.up, "up"),
        ] {
            if let Some(s) = s {
                parse_vec3(s, flag)?;
            }
        }
        Ok(())
    }
}
