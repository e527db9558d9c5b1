//! The paper's Table 1 for a scene: every leaf object's tribox hierarchy cut at each level,
//! with the faces, tribox counts, errors and volumes of the substitutes, and the substitutes
//! themselves (as OBJ, and as objects to render).

use std::time::{Duration, Instant};

use crate::geom::{Box3, PolyMesh, M4, P3};
use crate::scene::{Mesh, Object, Scene};

use super::hierarchy::{Hierarchy, HierarchyOptions};
use crate::geom::hull3::hull_volume;

/// What [`table`] builds.
#[derive(Debug, Clone, PartialEq)]
pub struct TableOptions {
    /// How each object's hierarchy is split.
    pub hierarchy: HierarchyOptions,
    /// Levels of detail (level 0: one tribox per object).
    pub levels: usize,
    /// Simplification tolerance of each tribox, a fraction of its object's CBOX diagonal.
    pub tol: f64,
    /// Whether to compute the convex hulls' volumes (NaN when not).
    pub hull: bool,
}

/// One level of the table.
#[derive(Debug, Clone, PartialEq)]
pub struct TableRow {
    /// Faces of the substitutes (the paper's M).
    pub faces: usize,
    /// Triboxes in the cut.
    pub triboxes: usize,
    /// Largest cut error of an object.
    pub error: f64,
    /// Total volume of the substitutes.
    pub volume: f64,
    /// Each substitute tribox: object path and node, and its boundary mesh.
    substitutes: Vec<(String, PolyMesh)>,
}

/// The paper's Table 1 for a scene.
#[derive(Debug, Clone, PartialEq)]
pub struct Table {
    /// Leaf objects (instances placed).
    pub objects: usize,
    /// Faces of the scene (the paper's N).
    pub faces: usize,
    /// Total volume of the objects' CBOXes.
    pub cbox_volume: f64,
    /// Total volume of the objects' convex hulls (NaN when not asked for).
    pub hull_volume: f64,
    /// Longest CBOX diagonal of an object.
    pub diagonal: f64,
    /// Time to build the hierarchies.
    pub build_time: Duration,
    /// Least and most additions a tribox's boundary evaluation took (paper: at most 112).
    pub additions: (u32, u32),
    /// One row per level.
    pub rows: Vec<TableRow>,
}

/// One leaf object placed in the world with its hierarchy.
struct Part {
    path: String,
    faces: usize,
    diagonal: f64,
    cbox_volume: f64,
    hull_volume: f64,
    hierarchy: Hierarchy,
}

/// Builds every leaf object's hierarchy and cuts it at each level.
pub fn table(scene: &Scene, opts: &TableOptions) -> Table {
    let t = Instant::now();
    let parts: Vec<Part> = scene
        .leaves()
        .iter()
        .filter_map(|l| part(&l.path, l.mesh, &l.transform, opts))
        .collect();
    let build_time = t.elapsed();
    let mut additions = (u32::MAX, 0);
    let rows = (0..opts.levels)
        .map(|level| row(&parts, level, opts.tol, &mut additions))
        .collect();
    Table {
        objects: parts.len(),
        faces: parts.iter().map(|p| p.faces).sum(),
        cbox_volume: parts.iter().map(|p| p.cbox_volume).sum(),
        hull_volume: parts.iter().map(|p| p.hull_volume).sum(),
        diagonal: parts.iter().map(|p| p.diagonal).fold(0.0, f64::max),
        build_time,
        additions,
        rows,
    }
}

/// A leaf placed in the world with its hierarchy (None when nothing survives cleanup).
fn part(path: &str, mesh: &Mesh, xf: &M4, opts: &TableOptions) -> Option<Part> {
    let m = world_mesh(mesh, xf)?;
    let cbox = Box3::from_points(m.vertices.iter());
    let s = cbox.size();
    Some(Part {
        path: path.to_string(),
        faces: m.faces.len(),
        diagonal: (s[0] * s[0] + s[1] * s[1] + s[2] * s[2]).sqrt(),
        cbox_volume: cbox.volume(),
        hull_volume: if opts.hull {
            hull_volume(&m.vertices)
        } else {
            f64::NAN
        },
        hierarchy: Hierarchy::build(&m, &opts.hierarchy),
    })
}

/// Every part's hierarchy cut at `level`.
fn row(parts: &[Part], level: usize, tol: f64, additions: &mut (u32, u32)) -> TableRow {
    let mut r = TableRow {
        faces: 0,
        triboxes: 0,
        error: 0.0,
        volume: 0.0,
        substitutes: Vec::new(),
    };
    for p in parts {
        let cut = p.hierarchy.cut(level);
        for &node in &cut {
            let b = p.hierarchy.nodes[node]
                .tribox
                .simplified(tol * p.diagonal)
                .boundary();
            additions.0 = additions.0.min(b.ops.additions);
            additions.1 = additions.1.max(b.ops.additions);
            r.volume += b.volume();
            let mesh = b.mesh();
            r.faces += mesh.faces.len();
            r.substitutes.push((format!("{}#{}", p.path, node), mesh));
        }
        r.triboxes += cut.len();
        r.error = r.error.max(p.hierarchy.cut_error(&cut));
    }
    r
}

impl TableRow {
    /// The substitutes as one OBJ, one `o` group per tribox.
    pub fn to_obj(&self) -> String {
        use std::fmt::Write as _;
        let num = crate::scene::flatten::num;
        let mut s = String::from("# kepler tribox substitutes\n");
        let mut base = 1;
        for (name, m) in &self.substitutes {
            let _ = writeln!(s, "o {name}");
            for v in &m.vertices {
                let _ = writeln!(s, "v {} {} {}", num(v.x), num(v.y), num(v.z));
            }
            for f in &m.faces {
                let idx: Vec<String> = f.iter().map(|&i| (i as usize + base).to_string()).collect();
                let _ = writeln!(s, "f {}", idx.join(" "));
            }
            base += m.vertices.len();
        }
        s
    }

    /// The substitutes as objects (cleaned up as a loader would), to render in a scene.
    pub fn objects(&self) -> Vec<Object> {
        self.substitutes
            .iter()
            .filter_map(|(name, m)| {
                let mesh = clean(m.vertices.clone(), m.faces.clone())?;
                Some(Object::from_mesh(name.clone(), mesh))
            })
            .collect()
    }
}

/// A leaf's mesh in world coordinates (None when nothing survives cleanup).
fn world_mesh(mesh: &Mesh, xf: &M4) -> Option<Mesh> {
    clean(
        mesh.vertices
            .iter()
            .map(|v| xf.transform_point(v))
            .collect(),
        mesh.faces.iter().map(|f| f.vertices.to_vec()).collect(),
    )
}

/// Polygons cleaned up as a loader would (None when no face survives).
fn clean(vertices: Vec<P3>, faces: Vec<Vec<u32>>) -> Option<Mesh> {
    Mesh::from_polygons(vertices, faces, &mut Vec::new())
        .ok()
        .filter(|m| !m.faces.is_empty())
}
