//! glTF and 3MF scenes through the command: `info` shows the node tree (with INBOXes computed
//! as for a KDL scene), `render` takes the file's camera, `flatten` writes every object, and
//! bad files exit non-zero with a located message and no panic.

use std::path::PathBuf;

use kepler_testkit::{
    model_xml, temp_dir, threemf, unit_cube_triangles as cube, Gltf, GltfMesh, GltfNode,
    ThreeMfObject,
};

use super::common::{kepler, s};

fn node(name: &str) -> GltfNode {
    GltfNode {
        name: Some(name.into()),
        ..GltfNode::default()
    }
}

/// A three-deep node tree: site > block > (tower, annex), and a shed; the cube mesh is
/// shared by all three leaves. An orthographic camera sits on a node of its own.
fn site() -> Gltf {
    let (p, t) = cube();
    Gltf {
        meshes: vec![GltfMesh {
            name: "cube".into(),
            positions: p,
            triangles: t,
        }],
        nodes: vec![
            GltfNode {
                children: vec![1],
                ..node("site")
            },
            GltfNode {
                translation: Some([0., 0., -5.]),
                children: vec![2, 3],
                ..node("block")
            },
            GltfNode {
                mesh: Some(0),
                scale: Some([2., 6., 2.]),
                ..node("tower")
            },
            GltfNode {
                mesh: Some(0),
                translation: Some([3., 0., 0.]),
                scale: Some([3., 2., 2.]),
                ..node("annex")
            },
            GltfNode {
                mesh: Some(0),
                translation: Some([-4., 0., 0.]),
                ..GltfNode::default()
            },
            GltfNode {
                camera: Some(0),
                translation: Some([0., 3., 20.]),
                ..node("view")
            },
        ],
        roots: vec![0, 4, 5],
        cameras: vec![r#"{"type":"orthographic","orthographic":{"xmag":10,"ymag":10,"znear":0.1,"zfar":100}}"#.into()],
        ..Gltf::default()
    }
}

/// The site as a GLB in a folder of its own for test `name` (tests run side by side, and
/// each clears its folder first).
fn write_site(name: &str) -> PathBuf {
    let d = temp_dir("e2e-import", name);
    let f = d.join("site.glb");
    std::fs::write(&f, site().glb()).unwrap();
    f
}

#[test]
fn info_shows_the_gltf_node_tree() {
    let f = write_site("site-info");
    let out = kepler(&["info", s(&f)]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(text.contains("site.glb: 36 faces, 24 vertices"), "{text}");
    // Nested as in the file, the shared mesh placed as instances of one prototype; the
    // unnamed node named after its index.
    let lines: Vec<&str> = text.lines().map(str::trim_start).collect();
    let at = |p: &str| {
        lines
            .iter()
            .position(|l| l.starts_with(p))
            .unwrap_or_else(|| panic!("no line {p:?} in {text}"))
    };
    assert!(at("site (1 subobjects)") < at("block (2 subobjects)"));
    assert!(at("block (2 subobjects)") < at("tower (instance of cube)"));
    assert!(at("tower (instance of cube)") < at("annex (instance of cube)"));
    assert!(at("annex (instance of cube)") < at("node4 (instance of cube)"));
    // INBOXes computed, as for a KDL scene.
    let out = kepler(&["info", "--json", s(&f)]);
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let block = &json["subobjects"][0]["subobjects"][0];
    assert_eq!(block["name"], "block");
    let tower = &block["subobjects"][0];
    assert_eq!(tower["name"], "tower");
    assert_eq!(tower["inbox"]["lo"], serde_json::json!([0, 0, -5]));
    assert_eq!(tower["inbox"]["hi"], serde_json::json!([2, 6, -3]));
    // `flatten` writes each object under its path.
    let obj = f.with_extension("obj");
    let out = kepler(&["flatten", s(&f), "-o", s(&obj)]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = std::fs::read_to_string(&obj).unwrap();
    for o in ["o site/block/tower", "o site/block/annex", "o node4"] {
        assert!(text.contains(o), "{o} in {text}");
    }
    let _ = std::fs::remove_dir_all(f.parent().unwrap());
}

#[test]
fn render_takes_the_gltf_camera_and_3mf_renders_like_gltf() {
    let f = write_site("site-render");
    let json = f.with_extension("json");
    let out = kepler(&["render", s(&f), "--json", s(&json)]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&std::fs::read(&json).unwrap()).unwrap();
    // Looking down the camera node's -z: the view matrix is the identity's rotation.
    assert_eq!(v["camera"]["projection"], "orthographic");
    assert_eq!(v["camera"]["matrix"][0], serde_json::json!([1, 0, 0, 0]));
    assert_eq!(v["camera"]["matrix"][2], serde_json::json!([0, 0, 1, 0]));
    // The same site as 3MF (the cube as a prototype, components and build items) renders
    // the same faces from the same view, names aside.
    let (p, t) = cube();
    let cube = ThreeMfObject {
        id: 1,
        name: Some("cube".into()),
        vertices: p.iter().map(|v| v.map(f64::from)).collect(),
        triangles: t,
        components: Vec::new(),
    };
    let block = ThreeMfObject {
        id: 2,
        name: Some("block".into()),
        components: vec![
            (1, Some([2., 0., 0., 0., 6., 0., 0., 0., 2., 0., 0., -5.])),
            (1, Some([3., 0., 0., 0., 2., 0., 0., 0., 2., 3., 0., -5.])),
        ],
        ..ThreeMfObject::default()
    };
    let site3 = f.with_file_name("site.3mf");
    let model = model_xml(
        &[cube, block],
        &[
            (2, None),
            (1, Some([1., 0., 0., 0., 1., 0., 0., 0., 1., -4., 0., 0.])),
        ],
    );
    std::fs::write(&site3, threemf(&model)).unwrap();
    let json3 = f.with_file_name("site3.json");
    let out = kepler(&["render", s(&site3), "--dir", "0,0,-1", "--json", s(&json3)]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let out = kepler(&["render", s(&f), "--dir", "0,0,-1", "--json", s(&json)]);
    assert!(out.status.success());
    let faces = |p: &PathBuf| {
        let v: serde_json::Value = serde_json::from_slice(&std::fs::read(p).unwrap()).unwrap();
        let mut f: Vec<String> = v["faces"]
            .as_array()
            .unwrap()
            .iter()
            .map(|f| format!("{} {}", f["area"], f["visible"]))
            .collect();
        f.sort();
        f
    };
    let a = faces(&json);
    assert_eq!(a.len(), 6, "{a:?}");
    assert_eq!(a, faces(&json3));
    let _ = std::fs::remove_dir_all(f.parent().unwrap());
}

#[test]
fn bad_gltf_and_3mf_exit_non_zero_with_a_located_message() {
    let d = temp_dir("e2e-import", "bad");
    let mut g = site();
    g.nodes[1].mesh = Some(7);
    let bad_glb = d.join("bad.glb");
    std::fs::write(&bad_glb, g.glb()).unwrap();
    let bad_3mf = d.join("bad.3mf");
    std::fs::write(&bad_3mf, threemf("<model>\n<resources>\n</model>")).unwrap();
    let trunc = d.join("trunc.glb");
    std::fs::write(&trunc, &site().glb()[..100]).unwrap();
    for (f, says) in [
        (&bad_glb, "bad.glb: nodes[1].mesh: mesh 7 does not exist"),
        (&bad_3mf, "bad.3mf: /3D/3dmodel.model:3:1:"),
        (
            &trunc,
            "trunc.glb: byte 8: GLB header: the length field says",
        ),
    ] {
        let json = d.join("out.json");
        for cmd in [vec!["render", s(f), "--json", s(&json)], vec!["info", s(f)]] {
            let out = kepler(&cmd);
            let err = String::from_utf8_lossy(&out.stderr);
            assert!(!out.status.success(), "{cmd:?}");
            assert!(!err.contains("panicked"), "{err}");
            assert!(err.contains(says), "{cmd:?}: {says:?} not in {err}");
        }
    }
    let _ = std::fs::remove_dir_all(&d);
}
