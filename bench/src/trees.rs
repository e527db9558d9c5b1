//! Paper 002's tables on this machine: Table 1 (levels, components per level, preprocessing
//! time of the object trees against the median split's), Tables 2 and 3 (a box of moving
//! instances of one model, sparse, normal and dense; colliding pairs, time per step and BV
//! nodes traversed, simplify against median, every answer checked against brute force).

use std::fmt::Write as _;
use std::path::Path;
use std::time::{Duration, Instant};

use anyhow::{Context, Result};
use kepler_hsr::tribox::{
    collide, collide_brute, CollideStats, FaceTriangles, ObjectTree, Placed, TopDown,
};

use kepler_hsr::{Box3, Face, HierarchyKind, Mesh, Scene, M4, V3};

use crate::generate::Rng;

/// The models of the interference benchmark.
pub const COLLIDE_MODELS: [&str; 5] = ["cow", "fandisk", "rocker-arm", "spot", "suzanne"];
/// Instances in each box.
pub const INSTANCES: usize = 24;
/// Densities: the share of the box the instances' root bounding volumes fill (the paper's
/// sparse 25%, normal 50%, dense 100%).
pub const DENSITIES: [(&str, f64); 3] = [("dense", 1.0), ("normal", 0.5), ("sparse", 0.25)];

/// All leaves of a loaded scene as one mesh in world coordinates.
pub fn one_mesh(scene: &Scene) -> Mesh {
    let mut m = Mesh::default();
    scene
        .root
        .for_each_mesh(&M4::identity(), &mut |_, mesh, xf| {
            let base = m.vertices.len() as u32;
            m.vertices
                .extend(mesh.vertices.iter().map(|v| xf.transform_point(v)));
            m.faces.extend(mesh.faces.iter().map(|f| {
                Face::new(
                    f.vertices
                        .iter()
                        .map(|v| v + base)
                        .collect::<kepler_hsr::FaceIndices>(),
                )
            }));
        });
    m
}

/// Loads a model as one mesh.
pub fn load_mesh(path: &Path) -> Result<Mesh> {
    let scene = kepler_hsr::load_scene(
        path,
        &kepler_hsr::LoadOptions::default(),
        &mut Vec::new(),
        &kepler_hsr::Progress::default(),
    )
    .with_context(|| format!("loading {}", path.display()))?;
    Ok(one_mesh(&scene))
}

/// One row of Table 1.
#[derive(Debug, Clone)]
pub struct Table1Row {
    /// Model or scene name.
    pub name: String,
    /// Faces.
    pub faces: usize,
    /// The simplify tree.
    pub simplify: ObjectTree,
    /// The median tree.
    pub median: ObjectTree,
    /// Median wall time of building each (ms), best of `runs`.
    pub median_ms: f64,
}

/// Table 1 for the meshes of `names` (found in `models`).
pub fn table1(models: &Path, names: &[&str]) -> Result<Vec<Table1Row>> {
    let mut rows = Vec::new();
    for name in names {
        let name = name.trim_end_matches(".obj");
        let path = models.join(format!("{name}.obj"));
        if !path.is_file() {
            eprintln!("bench: {name} not found, skipped");
            continue;
        }
        let mesh = load_mesh(&path)?;
        let simplify = ObjectTree::build(&mesh, HierarchyKind::Simplify);
        let t = Instant::now();
        let median = ObjectTree::build(&mesh, HierarchyKind::Median);
        let median_ms = t.elapsed().as_secs_f64() * 1e3;
        rows.push(Table1Row {
            name: name.to_string(),
            faces: mesh.faces.len(),
            simplify,
            median,
            median_ms,
        });
    }
    Ok(rows)
}

/// Table 1 as markdown.
pub fn table1_markdown(rows: &[Table1Row]) -> String {
    let ms = |d: Duration| format!("{:.1}", d.as_secs_f64() * 1e3);
    let mut s = String::from(
        "| model | faces | levels | cell widths | components per level | simplification + components (ms) | bottom-up (ms) | top-down (ms) | BV per instance (sum of node CBOX volumes) | median split (ms) | median BV per instance |\n|---|---|---|---|---|---|---|---|---|---|---|\n",
    );
    for r in rows {
        let c = &r.simplify.components;
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {} | {} | {} | {} | {:.4e} | {:.1} | {:.4e} |",
            r.name,
            r.faces,
            c.widths.len(),
            c.widths
                .iter()
                .map(|w| format!("{w:.3}"))
                .collect::<Vec<_>>()
                .join(", "),
            c.per_level
                .iter()
                .map(usize::to_string)
                .collect::<Vec<_>>()
                .join(", "),
            ms(r.simplify.times.components),
            ms(r.simplify.times.bottom_up),
            ms(r.simplify.times.top_down),
            r.simplify.total_volume(),
            r.median_ms,
            r.median.total_volume(),
        );
    }
    s
}

/// One model in a box at one density, both trees.
#[derive(Debug, Clone, Default)]
pub struct CollideRow {
    /// Model.
    pub model: String,
    /// Density name.
    pub density: &'static str,
    /// Colliding pairs summed over the steps, per method: simplify, median, brute force, and
    /// the two ablations.
    pub collisions: [u64; 5],
    /// Walk time per step (s): simplify, median, and the two parts of simplify alone
    /// (components with the median split below; the area split alone, no components).
    pub step_s: [f64; 4],
    /// BV nodes traversed, same order.
    pub nodes: [u64; 4],
    /// Triangles per instance and instances.
    pub triangles: usize,
}

/// A moving instance: position, rotation, velocity and spin.
struct Body {
    at: V3,
    rot: nalgebra::Rotation3<f64>,
    vel: V3,
    spin: nalgebra::Rotation3<f64>,
}

impl Body {
    fn transform(&self, centre: &V3) -> M4 {
        nalgebra::Translation3::from(self.at).to_homogeneous()
            * self.rot.to_homogeneous()
            * nalgebra::Translation3::from(-centre).to_homogeneous()
    }
}

/// A random rotation.
fn rotation(rng: &mut Rng, max_angle: f64) -> nalgebra::Rotation3<f64> {
    let axis = V3::new(rng.range(-1., 1.), rng.range(-1., 1.), rng.range(-1., 1.));
    let axis = nalgebra::Unit::try_new(axis, 1e-9).unwrap_or(V3::z_axis());
    nalgebra::Rotation3::from_axis_angle(&axis, rng.range(-max_angle, max_angle))
}

/// Tables 2 and 3 for one model at one density: `steps` steps of [`INSTANCES`] instances
/// moving in a box whose volume their root CBOXes fill to `density`.
pub fn collide_box(
    model: &str,
    mesh: &Mesh,
    density: (&'static str, f64),
    steps: usize,
) -> CollideRow {
    let tris = FaceTriangles::of(mesh);
    let simplify = ObjectTree::build(mesh, HierarchyKind::Simplify);
    let median = ObjectTree::build(mesh, HierarchyKind::Median);
    let components_only = ObjectTree::build_with(mesh, HierarchyKind::Simplify, TopDown::Median);
    let area_only = ObjectTree::build_with(mesh, HierarchyKind::Median, TopDown::Area);
    let root = simplify.nodes[0].cbox;
    let centre = (root.lo.coords + root.hi.coords) * 0.5;
    let side = (INSTANCES as f64 * root.volume() / density.1).cbrt();
    let size = {
        let s = root.size();
        (s[0] * s[0] + s[1] * s[1] + s[2] * s[2]).sqrt()
    };
    let mut rng = Rng::new(0x5eed ^ model.len() as u64 ^ (density.1 * 1000.0) as u64);
    let mut bodies: Vec<Body> = (0..INSTANCES)
        .map(|_| Body {
            at: V3::new(
                rng.range(0., side),
                rng.range(0., side),
                rng.range(0., side),
            ),
            rot: rotation(&mut rng, std::f64::consts::PI),
            vel: V3::new(rng.range(-1., 1.), rng.range(-1., 1.), rng.range(-1., 1.))
                * (0.02 * size),
            spin: rotation(&mut rng, 0.05),
        })
        .collect();
    let mut row = CollideRow {
        model: model.into(),
        density: density.0,
        triangles: tris.tris.len(),
        ..CollideRow::default()
    };
    let mut time = [Duration::ZERO; 4];
    for _ in 0..steps {
        let xf: Vec<M4> = bodies.iter().map(|b| b.transform(&centre)).collect();
        let world: Vec<Box3> = xf.iter().map(|m| root.transformed(m)).collect();
        let pairs: Vec<(usize, usize)> = (0..INSTANCES)
            .flat_map(|i| (i + 1..INSTANCES).map(move |j| (i, j)))
            .filter(|&(i, j)| {
                (0..3).all(|k| world[i].lo[k] <= world[j].hi[k] && world[j].lo[k] <= world[i].hi[k])
            })
            .collect();
        for (m, tree) in [&simplify, &median, &components_only, &area_only]
            .into_iter()
            .enumerate()
        {
            let slot = if m < 2 { m } else { m + 1 };
            let place = |k: usize| Placed {
                mesh,
                tree,
                tris: &tris,
                transform: xf[k],
            };
            let t = Instant::now();
            let mut stats = CollideStats::default();
            for &(i, j) in &pairs {
                row.collisions[slot] += collide(&place(i), &place(j), &mut stats) as u64;
            }
            time[m] += t.elapsed();
            row.nodes[m] += stats.bv_tests;
        }
        let place = |k: usize| Placed {
            mesh,
            tree: &median,
            tris: &tris,
            transform: xf[k],
        };
        let mut stats = CollideStats::default();
        for &(i, j) in &pairs {
            row.collisions[2] += collide_brute(&place(i), &place(j), &mut stats) as u64;
        }
        for b in &mut bodies {
            b.rot = b.spin * b.rot;
            b.at += b.vel;
            for k in 0..3 {
                if !(0.0..=side).contains(&b.at[k]) {
                    b.vel[k] = -b.vel[k];
                    b.at[k] = b.at[k].clamp(0.0, side);
                }
            }
        }
    }
    row.step_s = time.map(|t| t.as_secs_f64() / steps.max(1) as f64);
    row
}

/// Tables 2 and 3 as markdown.
pub fn collide_markdown(rows: &[CollideRow], steps: usize) -> String {
    let pct = |a: f64, b: f64| {
        if b > 0.0 {
            format!("{:.0}%", 100.0 * (b - a) / b)
        } else {
            "-".into()
        }
    };
    let mut s = format!(
        "{INSTANCES} instances per box, {steps} steps. Percentages: how much less than median. Ablations: components with the median split below them; the area split alone (no components).\n\n| model | density | triangles per instance | collisions simplify | median | brute force | time per step median (ms) | simplify (ms) | BV nodes traversed median | simplify | components only | area split only |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n"
    );
    for r in rows {
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {} | {} | {:.3} | {:.3} ({}) | {} | {} ({}) | {} ({}) | {} ({}) |",
            r.model,
            r.density,
            r.triangles,
            r.collisions[0],
            r.collisions[1],
            r.collisions[2],
            r.step_s[1] * 1e3,
            r.step_s[0] * 1e3,
            pct(r.step_s[0], r.step_s[1]),
            r.nodes[1],
            r.nodes[0],
            pct(r.nodes[0] as f64, r.nodes[1] as f64),
            r.nodes[2],
            pct(r.nodes[2] as f64, r.nodes[1] as f64),
            r.nodes[3],
            pct(r.nodes[3] as f64, r.nodes[1] as f64),
        );
    }
    s
}

/// Runs the tables: Table 1 for `table1_names`, Tables 2 and 3 for [`COLLIDE_MODELS`].
pub fn run_tables(
    models: &Path,
    out: &Path,
    steps: usize,
    table1_names: &[&str],
) -> Result<String> {
    let t1 = table1(models, table1_names)?;
    let mut doc =
        String::from("# Object trees (paper 002) on this machine\n\n## Table 1: preprocessing\n\n");
    doc.push_str(&table1_markdown(&t1));
    let mut rows = Vec::new();
    for m in COLLIDE_MODELS {
        let path = models.join(format!("{m}.obj"));
        if !path.is_file() {
            eprintln!("bench: {m} not found, skipped");
            continue;
        }
        let mesh = load_mesh(&path)?;
        for d in DENSITIES {
            eprintln!("bench: {m} {}", d.0);
            let row = collide_box(m, &mesh, d, steps);
            anyhow::ensure!(
                row.collisions.iter().all(|&c| c == row.collisions[2]),
                "{m} {}: the trees and brute force found different collisions: {:?}",
                d.0,
                row.collisions
            );
            rows.push(row);
        }
    }
    doc.push_str("\n## Tables 2 and 3: interference in a box of moving instances\n\n");
    doc.push_str(&collide_markdown(&rows, steps));
    std::fs::write(out.join("trees.md"), &doc).with_context(|| format!("{}", out.display()))?;
    Ok(doc)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The closed octahedron of the primitives, cleaned.
    fn octahedron() -> Mesh {
        Mesh::solid("octahedron").unwrap()
    }

    #[test]
    fn every_tree_and_brute_force_find_the_same_collisions() {
        let m = octahedron();
        let r = collide_box("octahedron", &m, ("dense", 1.0), 30);
        assert!(r.collisions[2] > 0, "{r:?}");
        assert!(r.collisions.iter().all(|&c| c == r.collisions[2]), "{r:?}");
        assert!(r.nodes.iter().all(|&n| n > 0));
        assert!(collide_markdown(&[r], 30).contains("| octahedron | dense | 8 |"));
    }
}
