//! FLATTEN round trips: flatten a scene, load the OBJ, flatten again: the same faces (same
//! world corners) in the same order, and from then on the same bytes. (Object paths come back
//! with '/' as '_': an OBJ group name is one object name.)

use std::path::{Path, PathBuf};

use crate::scene::flatten::flatten;
use crate::FlatMesh;

fn corners(f: &FlatMesh) -> Vec<Vec<[f64; 3]>> {
    f.faces
        .iter()
        .map(|face| {
            face.iter()
                .map(|&k| f.vertices[k as usize].coords.into())
                .collect()
        })
        .collect()
}

fn round_trip(scene_path: &Path, tmp: &Path) {
    let scene = super::common::load(scene_path);
    let first = flatten(&scene);
    let obj1 = tmp.join("first.obj");
    std::fs::write(&obj1, first.to_obj()).unwrap();
    let second = flatten(&super::common::load(&obj1));
    assert_eq!(
        corners(&first),
        corners(&second),
        "{}: faces changed in the round trip",
        scene_path.display()
    );
    // OBJ group names become object names, where '/' is not allowed: a path a/b comes back as a_b.
    let paths = |f: &FlatMesh| {
        f.groups
            .iter()
            .map(|(p, r)| (p.replace('/', "_"), r.clone()))
            .collect::<Vec<_>>()
    };
    assert_eq!(
        paths(&first),
        paths(&second),
        "{}: object paths changed",
        scene_path.display()
    );
    let obj2 = tmp.join("second.obj");
    std::fs::write(&obj2, second.to_obj()).unwrap();
    let third = flatten(&super::common::load(&obj2));
    assert_eq!(
        second.to_obj(),
        third.to_obj(),
        "{}: not a fixed point",
        scene_path.display()
    );
}

fn temp_dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("kepler-flatten-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

#[test]
fn scenes_and_fixtures_round_trip() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files: Vec<PathBuf> = std::fs::read_dir(root.join("scenes"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    files.extend(
        std::fs::read_dir(root.join("tests/fixtures/meshes"))
            .unwrap()
            .map(|e| e.unwrap().path()),
    );
    files.sort();
    let tmp = temp_dir("scenes");
    for f in &files {
        if matches!(
            f.extension().and_then(|e| e.to_str()),
            Some("kdl" | "obj" | "stl" | "ply")
        ) {
            round_trip(f, &tmp);
        }
    }
    std::fs::remove_dir_all(&tmp).ok();
}

#[test]
fn shared_meshes_round_trip() {
    let tmp = temp_dir("models");
    for name in ["suzanne.obj", "beetle.obj", "teapot.obj", "twocubes.obj"] {
        if let Some(p) = kepler_testkit::model(name) {
            round_trip(&p, &tmp);
        }
    }
    std::fs::remove_dir_all(&tmp).ok();
}
