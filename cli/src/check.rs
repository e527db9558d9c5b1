//! `kepler check`: re-render a scene and compare its visible-polygon set with a golden file,
//! and/or (`--exact`) with the independent exact answer (`kepler_hsr::exact`: rationals, no
//! boolean engine, no tolerance in any decision; slow, for small scenes): each face's
//! symmetric difference must stay within 1e-9 of its projected area plus rounding.
//!
//! The camera is chosen exactly as `kepler render` chooses it (flags, then the scene's camera,
//! then the three-quarter view); a golden made with other camera flags differs everywhere, and
//! a note says so when the matrices differ. Each face's change is the area of the symmetric
//! difference of the two visible regions (i_overlay Xor on a fixed i64 grid), relative to the
//! larger of the face's projected area, its two visible areas and 1e-12 of the scene's visible
//! area. A face present on one side only is always a change.

use std::collections::BTreeMap;
use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{anyhow, Result};
use clap::Args;
use kepler_hsr::geom::boolean::xor_area;
use kepler_hsr::geom::poly2::{multipolygon_area, MultiPolygon, Pt2};
use kepler_hsr::scene::Scene;
use kepler_hsr::{render, Camera, FaceId, Outputs, RenderOptions, View, Visibility};
use serde_json::Value;

use super::{load, out, write, CameraArgs};

/// Arguments of `kepler check`.
#[derive(Args, Debug)]
pub(crate) struct CheckArgs {
    /// Scene file (.kdl) or mesh (.obj, .stl, .ply).
    pub(crate) scene: PathBuf,
    /// The golden kepler-visible/1 file.
    #[arg(long, value_name = "F.json", required_unless_present = "exact")]
    pub(crate) golden: Option<PathBuf>,
    /// Check every face against the independent exact answer (slow: small scenes).
    #[arg(long)]
    pub(crate) exact: bool,
    /// Largest allowed change of a face's visible region, relative to its area.
    #[arg(
        long,
        value_name = "T",
        default_value_t = 1e-9,
        allow_negative_numbers = true
    )]
    pub(crate) tol: f64,
    /// Write the golden from this render instead of comparing.
    #[arg(long)]
    pub(crate) update: bool,
    #[command(flatten)]
    pub(crate) camera: CameraArgs,
    /// Do not print warnings.
    #[arg(long, short)]
    pub(crate) quiet: bool,
}

/// One face of a golden file.
#[derive(Debug, Clone, PartialEq)]
struct GoldenFace {
    object: String,
    visible: MultiPolygon,
}

/// Runs `kepler check`.
pub(crate) fn run(a: CheckArgs, opts: &kepler_hsr::LoadOptions) -> Result<ExitCode> {
    if !(a.tol >= 0.0 && a.tol.is_finite()) {
        anyhow::bail!("--tol {}: expected a finite number >= 0", a.tol);
    }
    let scene = load(&a.scene, a.quiet, opts)?;
    let camera = a.camera.camera(&scene)?;
    let opts = RenderOptions {
        outputs: Outputs {
            json: true,
            ..Outputs::default()
        },
        ..RenderOptions::default()
    };
    let r = render(&scene, &camera, &opts, &kepler_hsr::Progress::default())?;
    let mut failed = false;
    if a.exact {
        failed |= !exact(&scene, &camera, &r.visibility, &r.view);
    }
    let Some(golden_path) = &a.golden else {
        return Ok(if failed {
            ExitCode::from(1)
        } else {
            ExitCode::SUCCESS
        });
    };
    let (view, vis) = (&r.view, &r.visibility);
    let json = r.json.clone().unwrap_or_default();
    if a.update {
        write(golden_path, &json)?;
        out(&format!("wrote {}", golden_path.display()));
        return Ok(ExitCode::SUCCESS);
    }
    let text = std::fs::read_to_string(golden_path)
        .map_err(|e| anyhow!("{}: {e}", golden_path.display()))?;
    let (golden, matrix) =
        parse_golden(&text).map_err(|e| anyhow!("{}: {e}", golden_path.display()))?;
    let (current, _) = parse_golden(&json).map_err(|e| anyhow!("internal JSON: {e}"))?;
    if matrix != current_matrix(view) {
        out("note: the camera differs from the golden's");
    }
    let scene_area: f64 = vis.total_area();
    let ids: std::collections::BTreeSet<u64> =
        golden.keys().chain(current.keys()).copied().collect();
    let mut changed = 0;
    for id in ids {
        let projected = vis.face(FaceId(id as u32)).projected_area;
        let line = match (golden.get(&id), current.get(&id)) {
            (Some(g), Some(c)) => {
                let diff = xor_area(&g.visible, &c.visible);
                let area = projected
                    .max(multipolygon_area(&g.visible).abs())
                    .max(multipolygon_area(&c.visible).abs())
                    .max(1e-12 * scene_area);
                let rel = if area > 0.0 { diff / area } else { diff };
                (rel > a.tol)
                    .then(|| format!("face {id} ({}): changed by {rel:.3e} of its area", c.object))
            }
            (Some(g), None) => Some(format!("face {id} ({}): no longer visible", g.object)),
            (None, Some(c)) => Some(format!("face {id} ({}): newly visible", c.object)),
            (None, None) => None,
        };
        if let Some(l) = line {
            changed += 1;
            out(&l);
        }
    }
    if changed > 0 {
        out(&format!("{changed} faces changed"));
        Ok(ExitCode::from(1))
    } else if failed {
        Ok(ExitCode::from(1))
    } else {
        out("ok");
        Ok(ExitCode::SUCCESS)
    }
}

/// The render against the exact answer: prints each disagreeing face and a summary; true
/// when everything agrees.
fn exact(scene: &Scene, camera: &Camera, vis: &Visibility, view: &View) -> bool {
    let rep = kepler_hsr::exact::check(scene, camera, vis, None);
    for f in rep.disagreements() {
        let object = view
            .screen
            .leaves
            .iter()
            .find(|l| l.faces().contains(&f.face))
            .map_or("", |l| l.path.as_str());
        out(&format!(
            "face {} ({object}): differs from the exact answer by {:.3e} (allowed {:.3e}); visible {} exact {}",
            f.face, f.mismatch, f.tolerance, f.claimed, f.visible
        ));
    }
    let bad = rep.disagreements().len();
    out(&format!(
        "exact: {} of {} faces agree; visible area {} (exact {}, {:.1e} of the projected area)",
        rep.faces.len() - bad,
        rep.faces.len(),
        rep.claimed(),
        rep.visible,
        (rep.claimed() - rep.visible).abs() / rep.projected.max(f64::MIN_POSITIVE)
    ));
    rep.agrees()
}

/// The camera matrix as the JSON writes it (for comparison with the golden's).
fn current_matrix(view: &View) -> Option<Vec<f64>> {
    let m = &view.camera.matrix;
    let json = format!(
        "[{}]",
        (0..16)
            .map(|k| kepler_hsr::emit::json::num(m[(k / 4, k % 4)]))
            .collect::<Vec<_>>()
            .join(",")
    );
    serde_json::from_str::<Vec<f64>>(&json).ok()
}

/// Faces by id and the flattened camera matrix of a kepler-visible/1 document.
type Golden = (BTreeMap<u64, GoldenFace>, Option<Vec<f64>>);

/// Parses a kepler-visible/1 document.
fn parse_golden(text: &str) -> Result<Golden> {
    let v: Value = serde_json::from_str(text).map_err(|e| anyhow!("not JSON: {e}"))?;
    if v.get("format").and_then(Value::as_str) != Some("kepler-visible/1") {
        anyhow::bail!("not a kepler-visible/1 file (no \"format\": \"kepler-visible/1\")");
    }
    let matrix = v
        .pointer("/camera/matrix")
        .and_then(Value::as_array)
        .map(|rows| {
            rows.iter()
                .flat_map(|r| r.as_array().cloned().unwrap_or_default())
                .filter_map(|x| x.as_f64())
                .collect()
        });
    let faces = v
        .get("faces")
        .and_then(Value::as_array)
        .ok_or_else(|| anyhow!("no \"faces\" list"))?;
    let mut out = BTreeMap::new();
    for (i, f) in faces.iter().enumerate() {
        let id = f
            .get("id")
            .and_then(Value::as_u64)
            .ok_or_else(|| anyhow!("faces[{i}]: no integer \"id\""))?;
        let object = f
            .get("object")
            .and_then(Value::as_str)
            .unwrap_or("")
            .to_string();
        let visible = multipolygon(f.get("visible"))
            .ok_or_else(|| anyhow!("faces[{i}] (id {id}): \"visible\" is not a multipolygon"))?;
        if out.insert(id, GoldenFace { object, visible }).is_some() {
            anyhow::bail!("faces[{i}]: id {id} appears twice");
        }
    }
    Ok((out, matrix))
}

/// A multipolygon from JSON: polygons of rings of [x, y] points.
fn multipolygon(v: Option<&Value>) -> Option<MultiPolygon> {
    let list = |v: &Value| v.as_array().cloned();
    list(v?)?
        .iter()
        .map(|poly| {
            list(poly)?
                .iter()
                .map(|ring| {
                    list(ring)?
                        .iter()
                        .map(|p| {
                            let p = list(p)?;
                            match p[..] {
                                [ref x, ref y] => {
                                    let q = [x.as_f64()?, y.as_f64()?];
                                    q.iter().all(|c| c.is_finite()).then_some(q)
                                }
                                _ => None,
                            }
                        })
                        .collect::<Option<Vec<Pt2>>>()
                })
                .collect::<Option<Vec<_>>>()
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn golden_parse_errors_are_clear() {
        assert!(parse_golden("{").is_err());
        let e =
            parse_golden(r#"{"format":"kepler-visible/1","faces":[{"id":0,"visible":[[[1]]]}]}"#)
                .unwrap_err();
        assert!(e.to_string().contains("faces[0]"), "{e}");
        let (f, _) = parse_golden(
            r#"{"format":"kepler-visible/1","faces":[{"id":3,"object":"a","visible":[[[[0,0],[1,0],[0,1]]]]}]}"#,
        )
        .unwrap();
        assert_eq!(f[&3].visible[0][0].len(), 3);
    }
}
