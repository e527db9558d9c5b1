//! `kepler tribox`: hierarchical tribox substitutes of a mesh at each level (OBJ and SVG) and
//! the paper's Table 1; also the `--lod` flags of `kepler render` and `query --interfere`.

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use anyhow::{bail, Result};
use clap::Args;
use kepler_hsr::geom::PolyMesh;
use kepler_hsr::scene::cleanup::{cleanup, Origin};
use kepler_hsr::scene::{Mesh, Object, Scene};
use kepler_hsr::tribox::hull::hull_volume;
use kepler_hsr::tribox::{Hierarchy, HierarchyOptions};
use kepler_hsr::view::{LodOptions, LodStats};
use kepler_hsr::{
    render, EdgeOptions, EdgeSet, LineOptions, Outputs, PictureOptions, RenderOptions,
};

use super::{load_only, out, write, CameraArgs};

/// `--lod` flags of `kepler render`.
#[derive(Args, Debug, Clone, Default)]
pub(crate) struct LodArgs {
    /// Draw every object whose projected size is under PX pixels as its tribox (a
    /// level-of-detail substitute that takes part in visibility like any object).
    #[arg(long, value_name = "PX", allow_negative_numbers = true)]
    pub(crate) lod: Option<f64>,
    /// With --lod: draw small meshes as hierarchical triboxes at the shallowest cut whose
    /// error is at most PX pixels, instead of one tribox.
    #[arg(
        long,
        value_name = "PX",
        requires = "lod",
        allow_negative_numbers = true
    )]
    pub(crate) lod_error: Option<f64>,
}

/// One line on what `--lod` did, for `--stats`.
pub(crate) fn lod_report(s: &LodStats) -> String {
    format!(
        "lod: {} objects replaced by {} triboxes; faces modelled {} of {} in the scene ({:.1}%)",
        s.objects_replaced,
        s.triboxes,
        s.faces_modelled,
        s.faces_in_scene,
        100.0 * s.faces_modelled as f64 / (s.faces_in_scene.max(1)) as f64,
    )
}

impl LodArgs {
    /// The substitution the flags ask for, for a picture `size` pixels wide (None without
    /// `--lod`).
    pub(crate) fn options(&self, size: u32) -> Result<Option<LodOptions>> {
        let Some(px) = self.lod else { return Ok(None) };
        if !(px.is_finite() && px >= 0.0) {
            bail!("--lod {px}: expected a number of pixels, 0 or more");
        }
        let mut opts = LodOptions::new(px, size);
        if let Some(e) = self.lod_error {
            if !(e.is_finite() && e > 0.0) {
                bail!("--lod-error {e}: expected a positive number of pixels");
            }
            opts.error_px = Some(e);
        }
        Ok(Some(opts))
    }
}

/// Arguments of `kepler tribox`.
#[derive(Args, Debug)]
pub(crate) struct TriboxArgs {
    /// Mesh (.obj, .stl, .ply) or scene file (.kdl): each object gets its own hierarchy.
    pub(crate) scene: PathBuf,
    /// Number of levels of detail (level 0 is one tribox per object).
    #[arg(long, default_value_t = 4, value_parser = clap::value_parser!(u32).range(1..=16))]
    pub(crate) levels: u32,
    /// Write the substitute of each level here, as NAME-L<k>.obj and NAME-L<k>.svg.
    #[arg(short, long, value_name = "DIR")]
    pub(crate) out: Option<PathBuf>,
    /// Simplification tolerance of each tribox, as a fraction of the object's CBOX diagonal.
    #[arg(long, default_value_t = 0.01, allow_negative_numbers = true)]
    pub(crate) tol: f64,
    /// Least relative area reduction of a split (the stop rule).
    #[arg(long, default_value_t = 0.02, allow_negative_numbers = true)]
    pub(crate) min_gain: f64,
    /// Skip the convex-hull volumes.
    #[arg(long)]
    pub(crate) no_hull: bool,
    /// Pixels along the longer side of the SVGs.
    #[arg(long, default_value_t = 600)]
    pub(crate) size: u32,
    #[command(flatten)]
    pub(crate) camera: CameraArgs,
    /// Do not print warnings.
    #[arg(long, short)]
    pub(crate) quiet: bool,
}

/// One object placed in the world with its hierarchy.
struct Part {
    path: String,
    faces: usize,
    diagonal: f64,
    cbox_volume: f64,
    hull_volume: f64,
    hierarchy: Hierarchy,
}

/// Runs `kepler tribox`.
pub(crate) fn run(a: TriboxArgs, opts: &kepler_hsr::LoadOptions) -> Result<ExitCode> {
    if !(a.tol.is_finite() && a.tol >= 0.0 && a.min_gain.is_finite() && a.min_gain < 1.0) {
        bail!("--tol must be 0 or more and --min-gain below 1");
    }
    let scene = load_only(&a.scene, a.quiet, opts)?;
    let opts = HierarchyOptions {
        max_depth: a.levels as usize - 1,
        min_gain: a.min_gain,
    };
    let t = Instant::now();
    let parts: Vec<Part> = scene
        .leaves()
        .iter()
        .filter_map(|l| {
            let m = world_mesh(l.mesh, &l.transform)?;
            let cbox = kepler_hsr::geom::Box3::from_points(m.vertices.iter());
            let s = cbox.size();
            Some(Part {
                path: l.path.clone(),
                faces: m.faces.len(),
                diagonal: (s[0] * s[0] + s[1] * s[1] + s[2] * s[2]).sqrt(),
                cbox_volume: cbox.volume(),
                hull_volume: if a.no_hull {
                    f64::NAN
                } else {
                    hull_volume(&m.vertices)
                },
                hierarchy: Hierarchy::build(&m, &opts),
            })
        })
        .collect();
    let build = t.elapsed();
    let name = a
        .scene
        .file_stem()
        .map_or("scene".into(), |s| s.to_string_lossy().into_owned());
    let n: usize = parts.iter().map(|p| p.faces).sum();
    let cbox: f64 = parts.iter().map(|p| p.cbox_volume).sum();
    let hull: f64 = parts.iter().map(|p| p.hull_volume).sum();
    let diag = parts.iter().map(|p| p.diagonal).fold(0.0, f64::max);
    let (mut adds_min, mut adds_max) = (u32::MAX, 0);
    let mut rows = vec![
        format!("{name}: {} objects, N = {n} faces, CBOX volume {}, convex hull volume {}, hierarchies built in {:.1} ms", parts.len(), g(cbox), g(hull), build.as_secs_f64() * 1e3),
        String::new(),
        "| level | N | M | triboxes | N/M | error | error/diag | volume | /CBOX | /hull |".into(),
        "|---|---|---|---|---|---|---|---|---|---|".into(),
    ];
    if let Some(dir) = &a.out {
        std::fs::create_dir_all(dir).map_err(|e| anyhow::anyhow!("{}: {e}", dir.display()))?;
    }
    for level in 0..a.levels as usize {
        let mut lod = Vec::new();
        let (mut m, mut count, mut err, mut vol) = (0, 0, 0.0f64, 0.0);
        for p in &parts {
            let cut = p.hierarchy.cut(level);
            let tol = a.tol * p.diagonal;
            for &node in &cut {
                let t = p.hierarchy.nodes[node].tribox.simplified(tol);
                let b = t.boundary();
                adds_min = adds_min.min(b.ops.additions);
                adds_max = adds_max.max(b.ops.additions);
                vol += b.volume();
                let mesh = b.mesh();
                m += mesh.faces.len();
                lod.push((format!("{}#{}", p.path, node), mesh));
            }
            count += cut.len();
            err = err.max(p.hierarchy.cut_error(&cut));
        }
        rows.push(format!(
            "| {level} | {n} | {m} | {count} | {:.2} | {} | {} | {} | {} | {} |",
            n as f64 / m.max(1) as f64,
            g(err),
            ratio(err, diag, 4),
            g(vol),
            ratio(vol, cbox, 3),
            ratio(vol, hull, 3)
        ));
        if let Some(dir) = &a.out {
            let stem = dir.join(format!("{name}-L{level}"));
            write(&stem.with_extension("obj"), to_obj(&lod))?;
            write(&stem.with_extension("svg"), render_svg(&lod, &scene, &a)?)?;
        }
    }
    rows.push(String::new());
    rows.push(format!(
        "boundary evaluation: {adds_min}..{adds_max} additions per tribox (paper: at most 112), 24 shifts, at most 24 tests"
    ));
    out(&rows.join("\n"));
    Ok(ExitCode::SUCCESS)
}

/// a / b with `digits` decimals, "-" when b is 0 or unknown.
fn ratio(a: f64, b: f64, digits: usize) -> String {
    if b > 0.0 {
        format!("{:.*}", digits, a / b)
    } else {
        "-".into()
    }
}

/// A number with six decimals, "-" when unknown.
fn g(x: f64) -> String {
    if x.is_nan() {
        "-".into()
    } else {
        format!("{x:.6}")
    }
}

/// A leaf's mesh in world coordinates (None when nothing survives cleanup).
fn world_mesh(mesh: &Mesh, xf: &kepler_hsr::geom::M4) -> Option<Mesh> {
    let raw = PolyMesh::new(
        mesh.vertices
            .iter()
            .map(|v| xf.transform_point(v))
            .collect(),
        mesh.faces.iter().map(|f| f.vertices.clone()).collect(),
    );
    clean(&raw)
}

fn clean(raw: &PolyMesh) -> Option<Mesh> {
    let origin = Origin {
        file: std::path::Path::new("tribox"),
        face_pos: &[],
    };
    cleanup(raw, &origin, &mut Vec::new(), Default::default())
        .ok()
        .filter(|m| !m.faces.is_empty())
}

/// One `o` group per tribox.
fn to_obj(parts: &[(String, PolyMesh)]) -> String {
    use std::fmt::Write as _;
    let mut s = String::from("# kepler tribox substitutes\n");
    let mut base = 1;
    for (name, m) in parts {
        let _ = writeln!(s, "o {name}");
        for v in &m.vertices {
            let _ = writeln!(
                s,
                "v {} {} {}",
                kepler_hsr::scene::flatten::num(v.x),
                kepler_hsr::scene::flatten::num(v.y),
                kepler_hsr::scene::flatten::num(v.z)
            );
        }
        for f in &m.faces {
            let idx: Vec<String> = f.iter().map(|&i| (i as usize + base).to_string()).collect();
            let _ = writeln!(s, "f {}", idx.join(" "));
        }
        base += m.vertices.len();
    }
    s
}

/// The substitutes drawn by kepler itself: exact hidden lines, every edge.
fn render_svg(parts: &[(String, PolyMesh)], original: &Scene, a: &TriboxArgs) -> Result<String> {
    let objs: Vec<Object> = parts
        .iter()
        .filter_map(|(name, m)| clean(m).map(|m| Object::from_mesh(name.clone(), m)))
        .collect();
    let mut scene = Scene::new(Object::group("", objs), original.source.clone());
    scene.camera = original.camera.clone();
    let camera = a.camera.camera(&scene)?;
    kepler_hsr::prepare(
        &mut scene,
        &kepler_hsr::PrepareOptions::default(),
        &kepler_hsr::Progress::default(),
    );
    let opts = RenderOptions {
        lines: LineOptions {
            edges: EdgeOptions {
                set: EdgeSet::All,
                crease_deg: 30.0,
            },
            hidden: false,
        },
        outputs: Outputs {
            svg: true,
            picture: PictureOptions {
                size: a.size,
                fill: true,
                ..PictureOptions::default()
            },
            ..Outputs::default()
        },
        ..RenderOptions::default()
    };
    Ok(
        render(&scene, &camera, &opts, &kepler_hsr::Progress::default())?
            .svg
            .unwrap_or_default(),
    )
}

/// `kepler query --interfere`: the pairs of objects whose triboxes meet, each with whether
/// their faces really intersect, then a summary line (with `stats`, the work done too).
pub(crate) fn interfere_report(
    scene: &Scene,
    method: kepler_hsr::tribox::interfere::Method,
    stats: bool,
) -> String {
    let t = Instant::now();
    let r = kepler_hsr::tribox::interfere::interfere_with(scene, method);
    let time = t.elapsed();
    let mut lines: Vec<String> = r
        .tribox_meet
        .iter()
        .map(|&(i, j, hit)| {
            format!(
                "{}\t{}\t{}",
                r.objects[i],
                r.objects[j],
                if hit { "INTERSECT" } else { "APART" }
            )
        })
        .collect();
    let hits = r.tribox_meet.iter().filter(|p| p.2).count();
    lines.push(format!(
        "objects {}, pairs {}, CBOXes meet {}, triboxes meet {}, faces intersect {}",
        r.objects.len(),
        r.pairs,
        r.cbox_meet,
        r.tribox_meet.len(),
        hits,
    ));
    if stats {
        lines.push(format!(
            "method {:?}: {} BV nodes traversed, {} exact triangle tests, {:.3} ms",
            method,
            r.bv_tests,
            r.triangle_tests,
            time.as_secs_f64() * 1e3
        ));
    }
    lines.join("\n")
}
