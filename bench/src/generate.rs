//! Deterministic generated scenes for benchmarks and tests: the town, fields of polyhedra, terrains.
//!
//! Every generator is a pure function of its arguments (a fixed splitmix64 sequence stands in
//! for randomness), so the same call builds the same scene, face for face, on any machine.

use std::sync::Arc;

use kepler_hsr::{Mesh, Object, Scene, M4, P3};

/// Spacing of the town's building grid.
pub const TOWN_PITCH: f64 = 16.0;

/// The direction the town benchmark looks along (down, slightly tilted; +Y up): a steep tilt
/// gives the wide wall a depth range that reaches the roofs, and an INBOX hides only what lies
/// behind its farthest corner.
pub const TOWN_VIEW_DIR: [f64; 3] = [0.02, 0.03, -1.0];

/// An axis-aligned box mesh.
fn cuboid(lo: [f64; 3], hi: [f64; 3]) -> Mesh {
    Mesh::cuboid(P3::new(lo[0], lo[1], lo[2]), P3::new(hi[0], hi[1], hi[2]))
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

/// How the town's buildings are organised under the root.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TownLayout {
    /// All buildings directly under the root, beside the wall.
    Flat,
    /// Buildings in city blocks of [`TOWN_BLOCK`]² grid cells, blocks in districts of
    /// [`TOWN_DISTRICT`]² blocks: the hierarchy a modeller would build, and the paper assumes.
    Districts,
}

/// Grid cells per side of a city block.
pub const TOWN_BLOCK: usize = 8;
/// Blocks per side of a district.
pub const TOWN_DISTRICT: usize = 4;

/// The town of the INBOX benchmark: a wall (at z = 100..102) in front of `n` detailed
/// buildings (instances of three prototypes) on a grid, seen along [`TOWN_VIEW_DIR`].
pub fn town(n: usize, layout: TownLayout) -> Scene {
    let protos = [
        Arc::new(building("tower", 10., 40., 5, 10)),
        Arc::new(building("block", 12., 20., 6, 5)),
        Arc::new(building("house", 8., 10., 4, 3)),
    ];
    let side = (n as f64).sqrt().ceil() as usize;
    let extent = side as f64 * TOWN_PITCH;
    let mut objs = vec![Object::from_mesh(
        "wall",
        cuboid([-20., -20., 100.], [extent + 20., extent + 20., 102.]),
    )];
    let buildings = (0..n).map(|k| {
        let (i, j) = (k % side, k / side);
        let m: M4 = nalgebra::Translation3::new(i as f64 * TOWN_PITCH, j as f64 * TOWN_PITCH, 0.)
            .to_homogeneous();
        let b = Object::instance(format!("b{k}"), protos[k % 3].clone(), m);
        ((i / TOWN_BLOCK, j / TOWN_BLOCK), b)
    });
    match layout {
        TownLayout::Flat => objs.extend(buildings.map(|b| b.1)),
        TownLayout::Districts => {
            let blocks = group_cells(buildings, "block");
            let districts = blocks.map(|((i, j), b)| ((i / TOWN_DISTRICT, j / TOWN_DISTRICT), b));
            objs.extend(group_cells(districts, "district").map(|d| d.1));
        }
    }
    Scene::new(Object::group("", objs), "town".into())
}

/// Objects grouped by cell, one group per cell in cell order, keyed by the cell.
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

/// A deterministic pseudo-random sequence (splitmix64).
#[derive(Debug, Clone)]
pub struct Rng(u64);

impl Rng {
    /// The sequence starting from `seed`.
    pub fn new(seed: u64) -> Rng {
        Rng(seed)
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// A uniform number in [lo, hi).
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        let u = (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
        lo + u * (hi - lo)
    }
}

/// The solids a field is made of (cuboids are added with random proportions).
const FIELD_SOLIDS: [&str; 5] = [
    "octahedron",
    "icosahedron",
    "cuboctahedron",
    "truncated_octahedron",
    "rhombicuboctahedron",
];

/// A random rotation-and-scale-and-translation placing a unit solid in the field.
fn field_transform(rng: &mut Rng, at: [f64; 3], size: f64) -> M4 {
    let axis = nalgebra::Vector3::new(rng.range(-1., 1.), rng.range(-1., 1.), rng.range(0.1, 1.));
    let angle = rng.range(0., std::f64::consts::PI);
    let rot = nalgebra::Rotation3::from_axis_angle(&nalgebra::Unit::new_normalize(axis), angle);
    let t = nalgebra::Translation3::new(at[0], at[1], at[2]);
    t.to_homogeneous() * rot.to_homogeneous() * M4::new_scaling(size)
}

/// A field of at least `target_faces` faces: randomly rotated and sized polyhedra and boxes
/// (separate named objects; the polyhedra are instances of shared prototypes) scattered
/// through a cube whose side grows with the cube root of their number, so the depth
/// complexity of a view grows slowly with the size.
pub fn field(target_faces: usize, seed: u64) -> Scene {
    let protos: Vec<Arc<Object>> = FIELD_SOLIDS
        .iter()
        .map(|n| Arc::new(Object::from_mesh(*n, Mesh::solid(n).expect("known solid"))))
        .collect();
    let mut rng = Rng::new(seed);
    let mut objs = Vec::new();
    let mut faces = 0;
    // Objects average about 16 faces; the cube holds them at a fixed density.
    let count_guess = (target_faces / 16).max(1) as f64;
    let side = 3.0 * count_guess.cbrt();
    while faces < target_faces {
        let k = objs.len();
        let at = [
            rng.range(0., side),
            rng.range(0., side),
            rng.range(0., side),
        ];
        let kind = rng.next_u64() % (protos.len() as u64 + 1);
        let obj = if kind == protos.len() as u64 {
            let half = [
                rng.range(0.2, 0.8),
                rng.range(0.2, 0.8),
                rng.range(0.2, 0.8),
            ];
            let lo = [at[0] - half[0], at[1] - half[1], at[2] - half[2]];
            let hi = [at[0] + half[0], at[1] + half[1], at[2] + half[2]];
            Object::from_mesh(format!("box{k}"), cuboid(lo, hi))
        } else {
            let size = rng.range(0.4, 0.9);
            let m = field_transform(&mut rng, at, size);
            Object::instance(format!("s{k}"), protos[kind as usize].clone(), m)
        };
        faces += obj.face_count();
        objs.push(obj);
    }
    Scene::new(Object::group("", objs), "field".into())
}

/// Height of the terrain at (x, z) in a unit square: a few sine hills and ridges.
fn terrain_height(x: f64, z: f64) -> f64 {
    use std::f64::consts::TAU;
    0.08 * (TAU * 2.0 * x).sin() * (TAU * 1.5 * z).cos()
        + 0.05 * (TAU * (3.0 * x + 2.0 * z)).sin()
        + 0.03 * (TAU * 7.0 * z + 1.0).cos() * (TAU * 5.0 * x).sin()
}

/// Cells along each side of the terrain of at least `target_faces` triangles.
fn terrain_cells(target_faces: usize) -> usize {
    ((target_faces as f64 / 2.0).sqrt().ceil() as usize).max(1)
}

/// The terrain's vertices, row after row of `n + 1`.
fn terrain_vertices(n: usize) -> impl Iterator<Item = P3> {
    (0..=n).flat_map(move |j| {
        (0..=n).map(move |i| {
            let (x, z) = (i as f64 / n as f64, j as f64 / n as f64);
            P3::new(x, terrain_height(x, z), z)
        })
    })
}

/// The terrain's triangles (0-based vertex indices), two per cell, counter-clockwise seen
/// from above (+y).
fn terrain_triangles(n: usize) -> impl Iterator<Item = [u32; 3]> {
    let at = move |i: usize, j: usize| (j * (n + 1) + i) as u32;
    (0..n).flat_map(move |j| {
        (0..n).flat_map(move |i| {
            [
                [at(i, j), at(i, j + 1), at(i + 1, j + 1)],
                [at(i, j), at(i + 1, j + 1), at(i + 1, j)],
            ]
        })
    })
}

/// Writes [`terrain`]`(target_faces)` as a Wavefront OBJ (the issues' "10M-face terrain" is
/// `kepler-bench --terrain-obj 10000000 T.obj`); returns its face count.
pub fn write_terrain_obj(
    target_faces: usize,
    w: &mut impl std::io::Write,
) -> std::io::Result<usize> {
    let n = terrain_cells(target_faces);
    writeln!(w, "# kepler-bench terrain, {n} x {n} cells")?;
    for p in terrain_vertices(n) {
        writeln!(w, "v {} {} {}", p.x, p.y, p.z)?;
    }
    for [a, b, c] in terrain_triangles(n) {
        writeln!(w, "f {} {} {}", a + 1, b + 1, c + 1)?;
    }
    Ok(2 * n * n)
}

/// A terrain of at least `target_faces` triangles: one open mesh object, a height field over
/// the unit square (x, z) with y up, two triangles per grid cell (hills hide valleys from a
/// low view).
pub fn terrain(target_faces: usize) -> Scene {
    let n = terrain_cells(target_faces);
    let vertices = terrain_vertices(n).collect();
    let faces = terrain_triangles(n).map(|t| t.to_vec()).collect();
    let mesh = Mesh::from_polygons(vertices, faces, &mut Vec::new()).expect("terrains are clean");
    Scene::new(
        Object::group("", vec![Object::from_mesh("terrain", mesh)]),
        "terrain".into(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn generators_are_deterministic_and_reach_their_size() {
        for target in [100, 1000] {
            let a = field(target, 7);
            let b = field(target, 7);
            assert!(a.face_count() >= target && a.face_count() < target + 30);
            assert_eq!(a.face_count(), b.face_count());
            let (fa, fb) = (a.flatten(), b.flatten());
            assert_eq!(fa.vertices, fb.vertices);
            assert_eq!(fa.faces, fb.faces);
            let t = terrain(target);
            assert!(t.face_count() >= target && t.face_count() < target * 2);
        }
        assert_eq!(terrain(100).face_count(), 2 * 8 * 8);
    }

    #[test]
    fn the_terrain_obj_loads_as_the_terrain() {
        let dir = kepler_testkit::temp_dir("bench", "terrain-obj");
        let path = dir.join("t.obj");
        let mut file = std::fs::File::create(&path).unwrap();
        assert_eq!(write_terrain_obj(100, &mut file).unwrap(), 128);
        drop(file);
        let loaded = kepler_hsr::load_scene(
            &path,
            &Default::default(),
            &mut Vec::new(),
            &Default::default(),
        )
        .unwrap()
        .flatten();
        let made = terrain(100).flatten();
        assert_eq!((loaded.vertices, loaded.faces), (made.vertices, made.faces));
        std::fs::remove_dir_all(dir).unwrap();
    }

    #[test]
    fn town_has_a_wall_and_n_buildings() {
        let s = town(3, TownLayout::Flat);
        assert_eq!(s.root.subobjects().len(), 4);
        assert!(town(10, TownLayout::Flat).face_count() > 10 * 100);
        // 100 buildings: a 10 x 10 grid, blocks of 8 x 8 cells, all in one district.
        let d = town(100, TownLayout::Districts);
        assert_eq!(d.face_count(), town(100, TownLayout::Flat).face_count());
        assert_eq!(d.root.subobjects().len(), 2);
        assert_eq!(d.root.subobjects()[1].subobjects().len(), 4);
    }
}
