//! The `camera` node of scene files: perspective (`eye`, `target`, `fov`) or orthographic (`dir`, or `ortho`).

use super::args::{boolean, Node};
use crate::error::Result;
use crate::geom::{P3, V3};
use crate::scene::{CameraSpec, DEFAULT_FOV_DEG};

/// The nodes a `camera` block may hold.
const CAMERA_NODES: [&str; 6] = ["eye", "target", "up", "fov", "ortho", "dir"];

/// The camera block's settings, each with its node.
#[derive(Default)]
struct Settings<'a> {
    eye: Option<(V3, Node<'a>)>,
    target: Option<(V3, Node<'a>)>,
    up: Option<(V3, Node<'a>)>,
    dir: Option<(V3, Node<'a>)>,
    fov: Option<(f64, Node<'a>)>,
    ortho: bool,
}

/// Parses a `camera { ... }` node.
pub(super) fn parse_camera(n: &Node) -> Result<CameraSpec> {
    n.check_props(&[])?;
    if !n.args().is_empty() {
        return Err(n.parse_err("`camera` takes no arguments, only a { ... } block"));
    }
    let s = settings(n)?;
    let up = s.up.as_ref().map_or(V3::y(), |u| u.0);
    if let Some((dir, dn)) = &s.dir {
        if let Some(other) = [&s.eye, &s.target].into_iter().flatten().next() {
            return Err(other.1.parse_err(
                "a camera has either `dir` (orthographic) or `eye` and `target`, not both",
            ));
        }
        if let Some((_, f)) = &s.fov {
            return Err(f.parse_err("`fov` needs a perspective camera (`eye` and `target`)"));
        }
        check_up(n, dir, dn, &s.up)?;
        return Ok(CameraSpec::Orthographic { dir: *dir, up });
    }
    let (Some((eye, _)), Some((target, tn))) = (&s.eye, &s.target) else {
        return Err(n.parse_err(
            "the camera needs `eye` and `target` (perspective), or `dir` (orthographic)",
        ));
    };
    let dir = target - eye;
    check_up(n, &dir, tn, &s.up)?;
    if s.ortho {
        return Ok(CameraSpec::Orthographic { dir, up });
    }
    let fov_deg = s.fov.as_ref().map_or(DEFAULT_FOV_DEG, |f| f.0);
    Ok(CameraSpec::Perspective {
        eye: P3::from(*eye),
        target: P3::from(*target),
        up,
        fov_deg,
    })
}

/// Reads the block's nodes, each at most once.
fn settings<'a>(n: &Node<'a>) -> Result<Settings<'a>> {
    let mut s = Settings::default();
    let mut seen: Vec<Node> = Vec::new();
    for c in n.children()? {
        c.check_props(&[])?;
        c.no_children()?;
        if let Some(first) = seen.iter().find(|p| p.name() == c.name()) {
            return Err(c.parse_err(format!(
                "`{}` given twice in the camera (first at {})",
                c.name(),
                first.loc()
            )));
        }
        seen.push(c);
        let vec3 = |c: &Node<'a>| -> Result<(V3, Node<'a>)> {
            let v = c.numbers(&[3], "numbers (X Y Z)")?;
            Ok((V3::new(v[0], v[1], v[2]), *c))
        };
        match c.name() {
            "eye" => s.eye = Some(vec3(&c)?),
            "target" => s.target = Some(vec3(&c)?),
            "up" => s.up = Some(vec3(&c)?),
            "dir" => s.dir = Some(vec3(&c)?),
            "fov" => s.fov = Some((fov(&c)?, c)),
            "ortho" => s.ortho = ortho(&c)?,
            other => {
                return Err(c.parse_err(format!(
                    "unknown camera setting `{other}`: expected {}",
                    super::args::quoted_list(&CAMERA_NODES)
                )))
            }
        }
    }
    Ok(s)
}

fn fov(c: &Node) -> Result<f64> {
    let f = c.numbers(&[1], "number (degrees)")?[0];
    if !(f > 0.0 && f < 180.0) {
        return Err(c.invalid(format!(
            "the field of view must be between 0 and 180 degrees, not {f}"
        )));
    }
    Ok(f)
}

/// `ortho` alone, or `ortho #true` / `ortho #false`.
fn ortho(c: &Node) -> Result<bool> {
    match c
        .check_count(&[0, 1], "argument (#true or #false)")?
        .first()
    {
        None => Ok(true),
        Some(e) => boolean(c.src, e),
    }
}

/// The viewing direction must be nonzero and the up vector nonzero and not along it.
fn check_up(n: &Node, dir: &V3, dn: &Node, up: &Option<(V3, Node)>) -> Result<()> {
    if dir.norm() == 0.0 {
        return Err(dn.invalid("the viewing direction is zero (eye and target coincide?)"));
    }
    let (u, at) = up.as_ref().map_or((V3::y(), n), |(u, un)| (*u, un));
    if u.norm() == 0.0 {
        return Err(at.invalid("the up vector is zero"));
    }
    if u.cross(dir).norm() <= 1e-9 * u.norm() * dir.norm() {
        let which = if up.is_some() { "" } else { " (default 0 1 0)" };
        return Err(at.invalid(format!(
            "the up vector{which} is parallel to the viewing direction: give `up` across it"
        )));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use super::super::source::Source;
    use super::*;

    fn cam(text: &str) -> Result<CameraSpec> {
        let src = Source::new(Path::new("c.kdl"), text.to_string());
        let doc = src.parse().unwrap();
        parse_camera(&Node::new(&src, &doc[0]))
    }

    #[test]
    fn perspective_and_orthographic() {
        assert_eq!(
            cam("camera { eye 8 6 10; target 0 0 0; up 0 1 0; fov 35 }").unwrap(),
            CameraSpec::Perspective {
                eye: P3::new(8., 6., 10.),
                target: P3::origin(),
                up: V3::y(),
                fov_deg: 35.0
            }
        );
        assert_eq!(
            cam("camera { eye 1 2 3; target 1 2 0 }").unwrap(),
            CameraSpec::Perspective {
                eye: P3::new(1., 2., 3.),
                target: P3::new(1., 2., 0.),
                up: V3::y(),
                fov_deg: DEFAULT_FOV_DEG
            }
        );
        assert_eq!(
            cam("camera { eye 1 2 3; target 1 2 0; ortho #true }").unwrap(),
            CameraSpec::Orthographic {
                dir: V3::new(0., 0., -3.),
                up: V3::y()
            }
        );
        assert_eq!(
            cam("camera { dir -1 -0.8 -1.2; up 0 0 1 }").unwrap(),
            CameraSpec::Orthographic {
                dir: V3::new(-1., -0.8, -1.2),
                up: V3::z()
            }
        );
    }

    #[test]
    fn bad_cameras() {
        let err = |t: &str| cam(t).unwrap_err().to_string();
        assert!(err("camera { eye 1 2 3 }").contains("needs `eye` and `target`"));
        assert!(err("camera { dir 0 -1 0 }").contains("parallel"));
        assert!(err("camera { dir 0 0 0 }").contains("zero"));
        assert!(err("camera { eye 0 0 0; target 0 0 0 }").contains("zero"));
        assert!(err("camera { dir 1 0 0; eye 0 0 0 }").contains("not both"));
        assert!(err("camera { eye 0 0 1; target 0 0 0; fov 180 }").contains("between 0 and 180"));
        assert_eq!(
            err("camera {\n  dir 1 0 0\n  dir 1 0 0\n}"),
            "c.kdl:3:3: `dir` given twice in the camera (first at c.kdl:2:3)"
        );
        assert!(err("camera { zoom 2 }").starts_with("c.kdl:1:10: unknown camera setting `zoom`"));
        assert!(err("camera 1 { dir 1 0 0 }").contains("takes no arguments"));
    }
}
