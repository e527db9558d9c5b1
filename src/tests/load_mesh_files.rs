//! The good mesh fixtures load to the exact meshes they describe, and the shared models load.

use std::path::{Path, PathBuf};
use std::time::Instant;

use crate::geom::P3;
use crate::load::mesh_file::{load_mesh, MeshFile};
use crate::Pos;
use kepler_testkit::{model, models_dir};

/// A good fixture of `tests/fixtures/meshes/`.
fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures/meshes")
        .join(name)
}

fn load(name: &str) -> MeshFile {
    let path = fixture(name);
    load_mesh(&path, None, &crate::Progress::default()).unwrap_or_else(|e| panic!("{e}"))
}

/// The unit cube's corners, as in `make_mesh_fixtures.py`.
fn cube_vertices() -> Vec<P3> {
    [
        (0, 0, 0),
        (1, 0, 0),
        (1, 1, 0),
        (0, 1, 0),
        (0, 0, 1),
        (1, 0, 1),
        (1, 1, 1),
        (0, 1, 1),
    ]
    .iter()
    .map(|&(x, y, z)| P3::new(f64::from(x), f64::from(y), f64::from(z)))
    .collect()
}

/// The unit cube's quads, as in `make_mesh_fixtures.py`.
fn cube_quads() -> Vec<Vec<u32>> {
    vec![
        vec![0, 3, 2, 1],
        vec![4, 5, 6, 7],
        vec![0, 1, 5, 4],
        vec![1, 2, 6, 5],
        vec![2, 3, 7, 6],
        vec![3, 0, 4, 7],
    ]
}

#[test]
fn obj_cube_in_two_groups_keeps_quads() {
    let m = load("cube_groups.obj");
    let names: Vec<&str> = m.groups.iter().map(|g| g.name.as_str()).collect();
    assert_eq!(names, ["bottom_sides", "top_sides"]);
    let (a, b) = (&m.groups[0], &m.groups[1]);
    let v = cube_vertices();
    assert_eq!(a.mesh.vertices, [0, 3, 2, 1, 4, 5, 6, 7].map(|i| v[i]));
    assert_eq!(
        a.mesh.faces,
        vec![vec![0, 1, 2, 3], vec![4, 5, 6, 7], vec![0, 3, 5, 4]]
    );
    assert_eq!(
        a.face_pos,
        [16, 17, 18].map(|line| Pos::Line { line, col: 1 })
    );
    assert_eq!(b.mesh.vertices, [1, 2, 6, 5, 3, 7, 0, 4].map(|i| v[i]));
    assert_eq!(
        b.mesh.faces,
        vec![vec![0, 1, 2, 3], vec![1, 4, 5, 2], vec![4, 6, 7, 5]]
    );
    assert_eq!(
        b.face_pos,
        [20, 21, 22].map(|line| Pos::Line { line, col: 1 })
    );
}

#[test]
fn obj_negative_indices() {
    let m = load("negative_indices.obj");
    assert_eq!(m.groups.len(), 2);
    let (a, b) = (&m.groups[0], &m.groups[1]);
    assert_eq!(a.name, "negative_indices");
    assert_eq!(a.mesh.faces, vec![vec![0, 1, 2], vec![0, 2, 3]]);
    assert_eq!(a.mesh.vertices, cube_vertices()[..4].to_vec());
    assert_eq!(b.name, "quad");
    assert_eq!(b.mesh.faces, vec![vec![0, 1, 2, 3]]);
    assert_eq!(b.mesh.vertices, cube_vertices()[4..].to_vec());
}

#[test]
fn stl_ascii_and_binary_cubes_are_the_same_indexed_mesh() {
    let ascii = load("cube_ascii.stl");
    let binary = load("cube_binary.stl");
    for m in [&ascii, &binary] {
        assert_eq!(m.groups.len(), 1);
        let g = &m.groups[0];
        assert_eq!(g.mesh.vertices.len(), 8);
        assert_eq!(g.mesh.faces.len(), 12);
        assert!(g.mesh.faces.iter().all(|f| f.len() == 3));
        let v = cube_vertices();
        let first: Vec<P3> = g.mesh.face_points(0).copied().collect();
        assert_eq!(first, vec![v[0], v[3], v[2]]);
    }
    assert_eq!(ascii.groups[0].name, "cube_ascii");
    assert_eq!(ascii.groups[0].mesh, binary.groups[0].mesh);
    assert_eq!(ascii.groups[0].face_pos[1], Pos::Line { line: 9, col: 3 });
    assert_eq!(binary.groups[0].face_pos[1], Pos::Byte(134));
}

#[test]
fn ply_ascii_little_and_big_endian_cubes_agree() {
    for name in ["cube_ascii.ply", "cube_le.ply", "cube_be.ply"] {
        let m = load(name);
        assert_eq!(m.groups.len(), 1, "{name}");
        let g = &m.groups[0];
        assert_eq!(g.mesh.vertices, cube_vertices(), "{name}");
        assert_eq!(g.mesh.faces, cube_quads(), "{name}");
    }
    assert_eq!(
        load("cube_ascii.ply").groups[0].face_pos[0],
        Pos::Line { line: 19, col: 1 }
    );
}

#[test]
fn suzanne_has_500_faces_468_of_them_quads() {
    let Some(path) = model("suzanne.obj") else {
        return;
    };
    let m = load_mesh(&path, None, &crate::Progress::default()).unwrap_or_else(|e| panic!("{e}"));
    let faces: Vec<&Vec<u32>> = m.groups.iter().flat_map(|g| &g.mesh.faces).collect();
    assert_eq!(faces.len(), 500);
    assert_eq!(faces.iter().filter(|f| f.len() == 4).count(), 468);
}

#[test]
fn every_shared_model_loads() {
    let Some(dir) = models_dir() else {
        return;
    };
    let mut paths: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .filter_map(|e| e.ok().map(|e| e.path()))
        .collect();
    paths.retain(|p| {
        p.extension()
            .and_then(|e| e.to_str())
            .is_some_and(|e| ["obj", "stl", "ply"].contains(&e))
    });
    paths.sort();
    assert!(
        !paths.is_empty(),
        "{} holds no .obj, .stl or .ply file: an empty or mistyped models directory",
        dir.display()
    );
    for path in paths {
        let t = Instant::now();
        let m =
            load_mesh(&path, None, &crate::Progress::default()).unwrap_or_else(|e| panic!("{e}"));
        let faces: usize = m.groups.iter().map(|g| g.mesh.faces.len()).sum();
        let verts: usize = m.groups.iter().map(|g| g.mesh.vertices.len()).sum();
        println!(
            "{}: {} groups, {verts} vertices, {faces} faces in {:.1} ms",
            path.display(),
            m.groups.len(),
            t.elapsed().as_secs_f64() * 1e3
        );
        assert!(faces > 0);
    }
}
