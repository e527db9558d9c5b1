//! The town benchmark: a wall in front of N detailed buildings (instances of a few
//! prototypes), timed stage by stage with inboxes on and off, with the buildings in city
//! blocks (a hierarchy, as the paper assumes) and flat under the root. Writes out/town-bench.csv and
//! out/town-bench.svg. Run with `cargo bench --bench town` (optionally `-- 10,30` for the Ns).

use std::fmt::Write as _;
use std::sync::Arc;
use std::time::Instant;

use kepler::geom::{M4, P3, V3};
use kepler::prepare::compute_inboxes;
use kepler::scene::cleanup::{cleanup, Origin};
use kepler::scene::{Mesh, Object, Scene};
use kepler::view::{Camera, Cull, View};
use kepler::visibility::{solve, PassOptions};

/// Spacing of the building grid.
const PITCH: f64 = 16.0;

fn cuboid(lo: [f64; 3], hi: [f64; 3]) -> Mesh {
    let raw =
        kepler::primitives::cuboid(P3::new(lo[0], lo[1], lo[2]), P3::new(hi[0], hi[1], hi[2]));
    let origin = Origin {
        file: std::path::Path::new("town"),
        face_pos: &[],
    };
    cleanup(&raw, &origin, &mut Vec::new()).expect("a cuboid is clean")
}

/// A building: a body of w × w × h with a window ledge per floor and bay on all 4 facades.
fn building(name: &str, w: f64, h: f64, bays: usize, floors: usize) -> Object {
    let mut parts = vec![Object::from_mesh("body", cuboid([0., 0., 0.], [w, w, h]))];
    let bay = w / bays as f64;
    let floor = h / floors as f64;
    for f in 0..floors {
        let z = f as f64 * floor + 0.3 * floor;
        for b in 0..bays {
            let s = b as f64 * bay + 0.2 * bay;
            let e = s + 0.6 * bay;
            let boxes = [
                ([s, -0.4, z], [e, 0., z + 0.2 * floor]),
                ([s, w, z], [e, w + 0.4, z + 0.2 * floor]),
                ([-0.4, s, z], [0., e, z + 0.2 * floor]),
                ([w, s, z], [w + 0.4, e, z + 0.2 * floor]),
            ];
            for (k, (lo, hi)) in boxes.into_iter().enumerate() {
                parts.push(Object::from_mesh(format!("l{f}_{b}_{k}"), cuboid(lo, hi)));
            }
        }
    }
    Object::group(name, parts)
}

/// The town of `n` buildings on a grid under a wall (the camera looks down, slightly tilted:
/// a steep tilt gives the wide wall a depth range that reaches the roofs, and an INBOX hides
/// only what lies behind its farthest corner).
/// How the buildings are organised under the root.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Layout {
    /// All N buildings directly under the root, beside the wall.
    Flat,
    /// Buildings in city blocks of BLOCK x BLOCK grid cells, blocks in districts of
    /// DISTRICT x DISTRICT blocks, as a modeller would group them.
    Blocks,
}

/// Grid cells per side of a city block.
const BLOCK: usize = 8;
/// Blocks per side of a district.
const DISTRICT: usize = 4;

/// Objects grouped by cell, one group per cell (in cell order), keyed by the cell.
fn group_cells(
    items: impl Iterator<Item = ((usize, usize), Object)>,
    prefix: &str,
) -> impl Iterator<Item = ((usize, usize), Object)> {
    let mut cells: std::collections::BTreeMap<(usize, usize), Vec<Object>> = Default::default();
    for (cell, o) in items {
        cells.entry(cell).or_default().push(o);
    }
    let prefix = prefix.to_string();
    cells
        .into_iter()
        .map(move |((i, j), os)| ((i, j), Object::group(format!("{prefix}{i}_{j}"), os)))
}

fn town(n: usize, layout: Layout) -> Scene {
    let protos = [
        Arc::new(building("tower", 10., 40., 5, 10)),
        Arc::new(building("block", 12., 20., 6, 5)),
        Arc::new(building("house", 8., 10., 4, 3)),
    ];
    let side = (n as f64).sqrt().ceil() as usize;
    let extent = side as f64 * PITCH;
    let buildings = (0..n).map(|k| {
        let (i, j) = (k % side, k / side);
        let m: M4 =
            nalgebra::Translation3::new(i as f64 * PITCH, j as f64 * PITCH, 0.).to_homogeneous();
        (
            (i / BLOCK, j / BLOCK),
            Object::instance(format!("b{k}"), protos[k % 3].clone(), m),
        )
    });
    let mut objs = vec![Object::from_mesh(
        "wall",
        cuboid([-20., -20., 100.], [extent + 20., extent + 20., 102.]),
    )];
    match layout {
        Layout::Flat => objs.extend(buildings.map(|b| b.1)),
        Layout::Blocks => {
            let blocks = group_cells(buildings, "block");
            let districts = blocks.map(|((i, j), b)| ((i / DISTRICT, j / DISTRICT), b));
            objs.extend(group_cells(districts, "district").map(|d| d.1));
        }
    }
    Scene::new(Object::group("", objs), "town".into())
}

fn camera() -> Camera {
    Camera::orthographic(V3::new(0.02, 0.03, -1.), V3::y()).expect("valid camera")
}

/// Stage times in ms of one run: build, prepare, cull, view, visibility (the pass).
fn run(n: usize, layout: Layout, use_inbox: bool) -> ([f64; 5], usize) {
    let t = Instant::now();
    let mut scene = town(n, layout);
    let build = t.elapsed().as_secs_f64() * 1e3;
    let t = Instant::now();
    if use_inbox {
        compute_inboxes(&mut scene.root);
    }
    let prepare = t.elapsed().as_secs_f64() * 1e3;
    let t = Instant::now();
    let cull = if use_inbox {
        Cull::new(&scene, &camera())
    } else {
        Cull::none(&scene)
    };
    let cull_ms = t.elapsed().as_secs_f64() * 1e3;
    let t = Instant::now();
    let view = View::from_cull(&scene, camera(), &cull);
    let view_ms = t.elapsed().as_secs_f64() * 1e3;
    let t = Instant::now();
    let vis = solve(&view, PassOptions { use_inbox });
    let vis_ms = t.elapsed().as_secs_f64() * 1e3;
    let visible = vis.iter().filter(|f| f.1.area > 0.0).count();
    ([build, prepare, cull_ms, view_ms, vis_ms], visible)
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// Median stage times over `runs` runs.
fn medians(n: usize, layout: Layout, use_inbox: bool, runs: usize) -> [f64; 5] {
    let all: Vec<[f64; 5]> = (0..runs).map(|_| run(n, layout, use_inbox).0).collect();
    std::array::from_fn(|s| median(all.iter().map(|r| r[s]).collect()))
}

/// The measured series: layout, inboxes on or off, label, colour.
const SERIES: [(Layout, bool, &str, &str); 3] = [
    (
        Layout::Blocks,
        true,
        "districts and blocks, inboxes",
        "#1f77b4",
    ),
    (Layout::Flat, true, "flat, inboxes", "#2ca02c"),
    (Layout::Blocks, false, "without inboxes", "#d62728"),
];

fn main() {
    let ns: Vec<usize> = std::env::args()
        .skip(1)
        .find(|a| !a.starts_with('-'))
        .map(|a| a.split(',').filter_map(|x| x.parse().ok()).collect())
        .unwrap_or_else(|| vec![10, 30, 100, 300, 1000]);
    let mut csv = String::from(
        "n,faces,layout,inbox,load_ms,prepare_ms,cull_ms,view_ms,pass_ms,visibility_ms,visible_faces\n",
    );
    let mut rows = Vec::new();
    for &n in &ns {
        let faces = town(n, Layout::Flat).face_count();
        for (si, &(layout, use_inbox, _, _)) in SERIES.iter().enumerate() {
            let runs = if n >= 300 { 5 } else { 9 };
            let m = medians(n, layout, use_inbox, runs);
            let visible = run(n, layout, use_inbox).1;
            // The visibility stage: the box cull (VISOBJ on CBOXes and INBOXes) and the pass.
            // Without inboxes the "cull" only lists the leaves: that is view work.
            let visibility = if use_inbox { m[2] + m[4] } else { m[4] };
            let _ = writeln!(
                csv,
                "{n},{faces},{layout:?},{use_inbox},{:.3},{:.3},{:.3},{:.3},{:.3},{visibility:.3},{visible}",
                m[0], m[1], m[2], m[3], m[4]
            );
            eprintln!(
                "N={n:5} faces={faces:7} {layout:?} inbox={use_inbox:5} load {:7.3} prepare {:7.3} cull {:7.3} view {:8.3} pass {:8.3} visibility {visibility:8.3} ms  visible faces {visible}",
                m[0], m[1], m[2], m[3], m[4]
            );
            rows.push((n, si, visibility));
        }
    }
    for (si, (_, _, label, _)) in SERIES.iter().enumerate() {
        let at = |n| rows.iter().find(|r| r.0 == n && r.1 == si).map(|r| r.2);
        if let (Some(a), Some(b)) = (at(ns[0]), at(*ns.last().unwrap_or(&ns[0]))) {
            eprintln!(
                "visibility, {label}: N={} / N={}: {:.2}x",
                ns.last().unwrap_or(&0),
                ns[0],
                b / a
            );
        }
    }
    let _ = std::fs::create_dir_all("out");
    let _ = std::fs::write("out/town-bench.csv", csv);
    let _ = std::fs::write("out/town-bench.svg", chart(&rows));
}

/// A log-log chart of visibility time against N, one line per series.
fn chart(rows: &[(usize, usize, f64)]) -> String {
    let (w, h, m) = (640.0, 420.0, 60.0);
    let lx = |n: f64| n.log10();
    let ly = |t: f64| t.max(1e-3).log10();
    let xs: Vec<f64> = rows.iter().map(|r| lx(r.0 as f64)).collect();
    let ys: Vec<f64> = rows.iter().map(|r| ly(r.2)).collect();
    let (x0, x1) = (
        xs.iter().cloned().fold(f64::INFINITY, f64::min),
        xs.iter().cloned().fold(f64::NEG_INFINITY, f64::max),
    );
    let (y0, y1) = (
        ys.iter().cloned().fold(f64::INFINITY, f64::min).floor(),
        ys.iter().cloned().fold(f64::NEG_INFINITY, f64::max).ceil(),
    );
    let px = |x: f64| m + (x - x0) / (x1 - x0).max(1e-9) * (w - 2.0 * m);
    let py = |y: f64| h - m - (y - y0) / (y1 - y0).max(1e-9) * (h - 2.0 * m);
    let mut s = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
    );
    let _ = writeln!(s, "<text x=\"{}\" y=\"20\" text-anchor=\"middle\">town benchmark: visibility stage (cull + pass) time vs N (log-log)</text>", w / 2.0);
    let _ = writeln!(
        s,
        "<line x1=\"{m}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" stroke=\"black\"/>",
        h - m,
        w - m,
        h - m
    );
    let _ = writeln!(
        s,
        "<line x1=\"{m}\" y1=\"{m}\" x2=\"{m}\" y2=\"{}\" stroke=\"black\"/>",
        h - m
    );
    for r in rows.iter().filter(|r| r.1 == 0) {
        let x = px(lx(r.0 as f64));
        let _ = writeln!(
            s,
            "<text x=\"{x}\" y=\"{}\" text-anchor=\"middle\">{}</text>",
            h - m + 18.0,
            r.0
        );
    }
    let mut e = y0 as i32;
    while e as f64 <= y1 {
        let y = py(e as f64);
        let _ = writeln!(s, "<line x1=\"{}\" y1=\"{y}\" x2=\"{}\" y2=\"{y}\" stroke=\"#ddd\"/><text x=\"{}\" y=\"{}\" text-anchor=\"end\">{} ms</text>", m, w - m, m - 6.0, y + 4.0, 10f64.powi(e));
        e += 1;
    }
    let _ = writeln!(
        s,
        "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">N (buildings)</text>",
        w / 2.0,
        h - 15.0
    );
    for (si, &(_, _, label, colour)) in SERIES.iter().enumerate() {
        let pts: Vec<String> = rows
            .iter()
            .filter(|r| r.1 == si)
            .map(|r| format!("{:.1},{:.1}", px(lx(r.0 as f64)), py(ly(r.2))))
            .collect();
        let _ = writeln!(
            s,
            "<polyline fill=\"none\" stroke=\"{colour}\" stroke-width=\"2\" points=\"{}\"/>",
            pts.join(" ")
        );
        let ly_ = 40.0 + 18.0 * si as f64;
        let _ = writeln!(
            s,
            "<text x=\"{}\" y=\"{ly_}\" fill=\"{colour}\">{label}</text>",
            m + 10.0
        );
    }
    s.push_str("</svg>\n");
    s
}
