//! Camera flags shared by render and query: `--dir`, `--eye/--target/--fov/--ortho`, `--up`.

use anyhow::{bail, Result};
use clap::{Args, ValueEnum};
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
    /// Up vector X,Y,Z, or auto. Default: +Y with --dir or --eye (the OBJ/glTF convention),
    /// else the scene camera's up, else (no camera anywhere) auto: of ±X, ±Y, ±Z, the
    /// direction the mesh stands on, its base being the hull of the vertices within 1% of
    /// its extent from its lowest point; the base must cover at least a quarter of the
    /// mesh's shadow along that axis, the largest share wins (a near tie goes to the axis
    /// whose extent stands out: a slab's thin one, a tower's long one), and +Y is kept when
    /// no base does. `kepler info` shows the choice.
    #[arg(long, value_name = "X,Y,Z|auto", allow_hyphen_values = true)]
    pub(crate) up: Option<String>,
    /// A named orthographic view relative to the up in force, framed like the default view:
    /// front (from +Z when +Y is up), back, left (from -X), right (from +X), top, bottom, or
    /// iso (from +1,+1,+1). It is a camera of its own: no --dir, --eye, --target, --fov or
    /// --ortho with it.
    #[arg(long, value_enum, value_name = "VIEW",
          conflicts_with_all = ["dir", "eye", "target", "fov", "ortho"])]
    pub(crate) view: Option<ViewArg>,
}

/// `--view` values.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum ViewArg {
    /// Looking at the front (along -Z when +Y is up).
    Front,
    /// Looking at the back.
    Back,
    /// From the left (-X when +Y is up).
    Left,
    /// From the right (+X when +Y is up).
    Right,
    /// From above, the front at the bottom of the picture.
    Top,
    /// From below, the front at the top of the picture.
    Bottom,
    /// Isometric, from the right, in front and above.
    Iso,
}

impl ViewArg {
    fn name(self) -> &'static str {
        match self {
            ViewArg::Front => "front",
            ViewArg::Back => "back",
            ViewArg::Left => "left",
            ViewArg::Right => "right",
            ViewArg::Top => "top",
            ViewArg::Bottom => "bottom",
            ViewArg::Iso => "iso",
        }
    }
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
            up: self.given_up(scene)?,
        };
        if let Some(view) = self.view {
            return Ok(Camera::named_view(view.name(), req.up_in_force(scene))?);
        }
        Ok(Camera::for_scene(scene, &req)?)
    }

    /// The `--up` given (`auto` resolved for `scene`), if any.
    fn given_up(&self, scene: &Scene) -> Result<Option<V3>> {
        match self.up.as_deref() {
            None => Ok(None),
            Some(s) if s.trim().eq_ignore_ascii_case("auto") => Ok(Some(scene.auto_up())),
            Some(s) => parse_vec3(s, "up").map(Some),
        }
    }

    /// The vertical axis of a turntable: `--up` (auto resolved), else the scene camera's up,
    /// else +Y with --dir or --eye, else the scene's auto up.
    pub(crate) fn axis(&self, scene: &Scene) -> Result<V3> {
        Ok(match self.given_up(scene)? {
            Some(up) => up,
            None => match scene.camera_up() {
                Some(up) => up,
                None if self.dir.is_some() || self.eye.is_some() => V3::y(),
                None => scene.auto_up(),
            },
        })
    }

    /// True when any camera flag is given.
    pub(crate) fn any(&self) -> bool {
        self.dir.is_some()
            || self.eye.is_some()
            || self.target.is_some()
            || self.up.is_some()
            || self.ortho
            || self.view.is_some()
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
                if flag == "up" && s.trim().eq_ignore_ascii_case("auto") {
                    continue;
                }
                parse_vec3(s, flag)?;
            }
        }
        Ok(())
    }
}
