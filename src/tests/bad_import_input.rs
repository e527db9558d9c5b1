//! Bad glTF and 3MF files: each refused with an error naming the file and the JSON path (or
//! the part and XML line), never a panic.

use std::path::Path;

use kepler_testkit::{
    glb, temp_dir, threemf, unit_cube_triangles, zip_stored, Gltf, GltfMesh, GltfNode,
};
use serde_json::{json, Value};

use crate::{load_scene, LoadOptions, Progress};

/// A small valid document: a shared cube placed by two nodes, one under the other.
fn doc() -> (Value, Vec<u8>) {
    let (p, t) = unit_cube_triangles();
    let g = Gltf {
        meshes: vec![GltfMesh {
            name: "cube".into(),
            positions: p,
            triangles: t,
        }],
        nodes: vec![
            GltfNode {
                name: Some("a".into()),
                mesh: Some(0),
                children: vec![1],
                ..GltfNode::default()
            },
            GltfNode {
                name: Some("b".into()),
                mesh: Some(0),
                translation: Some([2., 0., 0.]),
                ..GltfNode::default()
            },
        ],
        roots: vec![0],
        ..Gltf::default()
    };
    let (text, bin) = g.json_and_bin(None);
    (serde_json::from_str(&text).unwrap(), bin)
}

/// The error message of loading `path` (which must fail).
fn error_of(path: &Path, opts: &LoadOptions) -> String {
    let r = load_scene(path, opts, &mut Vec::new(), &Progress::default());
    match r {
        Ok(_) => panic!("{} loaded", path.display()),
        Err(e) => e.to_string(),
    }
}

/// Writes a GLB of `v` and `bin` as `name`, and checks its error contains the file name and
/// every one of `want`.
fn check(d: &Path, name: &str, bytes: &[u8], want: &[&str]) {
    check_with(d, name, bytes, want, &LoadOptions::default());
}

fn check_with(d: &Path, name: &str, bytes: &[u8], want: &[&str], opts: &LoadOptions) {
    let path = d.join(name);
    std::fs::write(&path, bytes).unwrap();
    let e = error_of(&path, opts);
    assert!(
        e.contains(name),
        "{name}: the error does not name the file: {e}"
    );
    for w in want {
        assert!(e.contains(w), "{name}: expected {w:?} in: {e}");
    }
}

/// The GLB of the document changed by `edit`.
fn glb_with(edit: impl FnOnce(&mut Value, &mut Vec<u8>)) -> Vec<u8> {
    let (mut v, mut bin) = doc();
    edit(&mut v, &mut bin);
    glb(&v.to_string(), &bin)
}

#[test]
fn bad_gltf_files_get_located_errors() {
    let d = temp_dir("bad-import", "gltf");
    // The valid document loads (so each case below fails for its own reason).
    std::fs::write(d.join("ok.glb"), glb_with(|_, _| {})).unwrap();
    let s = load_scene(
        &d.join("ok.glb"),
        &LoadOptions::default(),
        &mut Vec::new(),
        &Progress::default(),
    )
    .unwrap();
    assert_eq!(s.root.face_count(), 24);

    let cases: Vec<(&str, Vec<u8>, Vec<&str>)> = vec![
        (
            "mesh7.glb",
            glb_with(|v, _| v["nodes"][1]["mesh"] = json!(7)),
            vec!["nodes[1].mesh: mesh 7 does not exist"],
        ),
        (
            "cycle.glb",
            glb_with(|v, _| v["nodes"][1]["children"] = json!([0])),
            vec!["nodes[", "is its own ancestor"],
        ),
        (
            "two-parents.glb",
            glb_with(|v, _| {
                v["nodes"]
                    .as_array_mut()
                    .unwrap()
                    .push(json!({"children":[1]}));
                v["scenes"][0]["nodes"] = json!([0, 2]);
            }),
            vec!["nodes[2].children[0]: node 1 is already a child of node 0"],
        ),
        (
            "count.glb",
            glb_with(|v, _| v["accessors"][0]["count"] = json!(1000)),
            vec!["accessors[0]: 1000 elements of 12 bytes"],
        ),
        (
            "view.glb",
            glb_with(|v, _| v["bufferViews"][1]["byteOffset"] = json!(100000)),
            vec!["bufferViews[1]: bytes 100000..", "of buffer 0"],
        ),
        (
            "sparse.glb",
            glb_with(|v, _| v["accessors"][0]["sparse"] = json!({"count": 1})),
            vec!["accessors[0].sparse: sparse accessors are not supported"],
        ),
        (
            "draco.glb",
            glb_with(|v, _| v["extensionsRequired"] = json!(["KHR_draco_mesh_compression"])),
            vec!["extensionsRequired[0]: the file requires extension KHR_draco_mesh_compression"],
        ),
        (
            "meshopt.glb",
            glb_with(|v, _| {
                v["extensionsRequired"] = json!(["KHR_materials_unlit", "EXT_meshopt_compression"])
            }),
            vec!["extensionsRequired[1]: the file requires extension EXT_meshopt_compression"],
        ),
        (
            "nan.glb",
            glb_with(|_, b| b[12..16].copy_from_slice(&f32::NAN.to_le_bytes())),
            vec!["accessors[0]: position 1: coordinate is NaN"],
        ),
        (
            "index.glb",
            glb_with(|_, b| b[96..100].copy_from_slice(&99u32.to_le_bytes())),
            vec!["accessors[1]: index 0 is 99, but the positions have only 8 vertices"],
        ),
        (
            "quantized.glb",
            glb_with(|v, _| v["accessors"][0]["componentType"] = json!(5123)),
            vec!["accessors[0].componentType: positions must be FLOAT (5126)"],
        ),
        (
            "singular.glb",
            glb_with(|v, _| v["nodes"][1]["scale"] = json!([1, 0, 1])),
            vec!["nodes[1]: the transform is singular"],
        ),
        (
            "version.glb",
            glb_with(|v, _| v["asset"]["version"] = json!("1.0")),
            vec!["asset.version: glTF version 1.0: only glTF 2.x is read"],
        ),
        (
            "scene9.glb",
            glb_with(|v, _| v["scene"] = json!(9)),
            vec!["scene: scene 9 does not exist (the file has 1 scenes)"],
        ),
        (
            "strip.glb",
            glb_with(|v, _| v["meshes"][0]["primitives"][0]["mode"] = json!(9)),
            vec!["meshes[0].primitives[0].mode: unknown primitive mode 9"],
        ),
    ];
    for (name, bytes, want) in &cases {
        check(&d, name, bytes, want);
    }
    // The GLB container itself, located by byte.
    let good = glb_with(|_, _| {});
    let mut len = good.clone();
    len[8] ^= 4;
    check(
        &d,
        "header.glb",
        &len,
        &["byte 8: GLB header: the length field says"],
    );
    let mut chunk = good.clone();
    chunk[13] = 0x7f;
    check(
        &d,
        "chunk.glb",
        &chunk,
        &["byte 12: GLB chunk 0: its length is"],
    );
    check(
        &d,
        "short.glb",
        &good[..10],
        &["byte 0: GLB header: the file has 10 bytes"],
    );
    // JSON text: syntax errors by line and column, buffers by URI.
    check(
        &d,
        "syntax.gltf",
        b"{\"asset\": {\"version\": \"2.0\"},\n  nodes: []}",
        &["syntax.gltf:2:3: invalid glTF JSON"],
    );
    let with_uri = |uri: &str| {
        let (mut v, _) = doc();
        v["buffers"][0]["uri"] = json!(uri);
        v.to_string().into_bytes()
    };
    check(
        &d,
        "missing.gltf",
        &with_uri("missing.bin"),
        &["buffers[0].uri: cannot read buffer file", "missing.bin"],
    );
    check(
        &d,
        "base64.gltf",
        &with_uri("data:application/octet-stream;base64,AAAA*AAA"),
        &["buffers[0].uri: invalid base64 at character 4"],
    );
    check(
        &d,
        "short64.gltf",
        &with_uri("data:application/octet-stream;base64,AAAA"),
        &[
            "buffers[0].byteLength: the buffer should have",
            "its data URI has only 3",
        ],
    );
    check(
        &d,
        "http.gltf",
        &with_uri("http://example.invalid/a.bin"),
        &["buffers[0].uri: http://example.invalid/a.bin: only relative file paths and data: URIs"],
    );
    let (mut v, _) = doc();
    v["buffers"][0].as_object_mut().unwrap().remove("uri");
    check(
        &d,
        "nouri.gltf",
        v.to_string().as_bytes(),
        &["buffers[0]: the buffer has no uri"],
    );
    // A buffer outside the include root.
    let inner = d.join("inner");
    std::fs::create_dir_all(&inner).unwrap();
    let (_, bin) = doc();
    std::fs::write(d.join("outside.bin"), bin).unwrap();
    let opts = LoadOptions {
        include_root: Some(inner.clone()),
        ..LoadOptions::default()
    };
    check_with(
        &inner,
        "escape.gltf",
        &with_uri("../outside.bin"),
        &["buffers[0].uri: ", "is outside the include root"],
        &opts,
    );
    let _ = std::fs::remove_dir_all(&d);
}

/// A 3MF model part around `body` (which starts on line 3).
fn model(body: &str) -> String {
    format!(
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<model unit=\"millimeter\" \
         xmlns=\"http://schemas.microsoft.com/3dmanufacturing/core/2015/02\">\n{body}\n</model>\n"
    )
}

const TRI: &str = "<object id=\"1\" name=\"t\"><mesh><vertices><vertex x=\"0\" y=\"0\" z=\"0\"/>\
<vertex x=\"1\" y=\"0\" z=\"0\"/><vertex x=\"0\" y=\"1\" z=\"0\"/></vertices>\
<triangles><triangle v1=\"0\" v2=\"1\" v3=\"2\"/></triangles></mesh></object>";

#[test]
fn bad_3mf_files_get_located_errors() {
    let d = temp_dir("bad-import", "3mf");
    let ok = threemf(&model(&format!(
        "<resources>{TRI}</resources><build><item objectid=\"1\"/></build>"
    )));
    std::fs::write(d.join("ok.3mf"), &ok).unwrap();
    assert!(load_scene(
        &d.join("ok.3mf"),
        &LoadOptions::default(),
        &mut Vec::new(),
        &Progress::default()
    )
    .is_ok());
    let m = |body: &str| threemf(&model(body));
    let cases: Vec<(&str, Vec<u8>, Vec<&str>)> = vec![
        (
            "notzip.3mf",
            b"<model/> is not a zip archive, whatever its name says".to_vec(),
            vec!["byte 0: not a ZIP archive"],
        ),
        (
            "nopart.3mf",
            zip_stored(&[("3D/other.model", b"<model/>")]),
            vec!["the archive has no model part /3D/3dmodel.model"],
        ),
        (
            "syntax.3mf",
            m("<resources>\n<object id=\"1\"></resources>"),
            vec![concat!("/3D/3dmodel.model", ":4:")],
        ),
        (
            "index.3mf",
            m(&format!(
                "<resources>{}</resources>\n<build><item objectid=\"1\"/></build>",
                TRI.replace("v3=\"2\"", "v3=\"5\"")
            )),
            vec![concat!("/3D/3dmodel.model", ":3:"), "v3=5: the mesh has only 3 vertices"],
        ),
        (
            "objectid.3mf",
            m(&format!("<resources>{TRI}</resources>\n<build>\n<item objectid=\"9\"/></build>")),
            vec![concat!("/3D/3dmodel.model", ":5:1: object 9 does not exist in <resources>")],
        ),
        (
            "cycle.3mf",
            m("<resources>\n<object id=\"2\"><components><component objectid=\"2\"/></components></object>\n\
               </resources><build><item objectid=\"2\"/></build>"),
            vec![concat!("/3D/3dmodel.model", ":4:1: object 2 contains itself")],
        ),
        (
            "transform.3mf",
            m(&format!(
                "<resources>{TRI}</resources>\n<build><item objectid=\"1\" transform=\"1 0 0 0 1 0 0 0 1 0 0\"/></build>"
            )),
            vec![concat!("/3D/3dmodel.model", ":4:8: transform= needs 12 finite numbers")],
        ),
        (
            "nan.3mf",
            m(&format!(
                "<resources>{}</resources><build><item objectid=\"1\"/></build>",
                TRI.replacen("x=\"1\"", "x=\"NaN\"", 1)
            )),
            vec![concat!("/3D/3dmodel.model", ":3:"), "x: coordinate is NaN"],
        ),
        (
            "required.3mf",
            threemf(
                "<?xml version=\"1.0\"?>\n<model xmlns=\"http://schemas.microsoft.com/3dmanufacturing/core/2015/02\" \
                 xmlns:b=\"http://schemas.microsoft.com/3dmanufacturing/beamlattice/2017/02\" \
                 requiredextensions=\"b\"><resources/><build/></model>",
            ),
            vec![concat!("/3D/3dmodel.model", ":2:1: the model requires extension b")],
        ),
        (
            "dtd.3mf",
            threemf(
                "<?xml version=\"1.0\"?>\n<!DOCTYPE model [<!ENTITY a \"aaaaaaaaaa\"><!ENTITY b \"&a;&a;&a;&a;\">]>\n<model/>",
            ),
            vec![concat!("/3D/3dmodel.model", ":1:1: XML with DTD detected")],
        ),
        (
            "nobuild.3mf",
            m(&format!("<resources>{TRI}</resources>")),
            vec![concat!("/3D/3dmodel.model", ":2:1: the model has no <build>")],
        ),
    ];
    for (name, bytes, want) in &cases {
        check(&d, name, bytes, want);
    }
    // A damaged archive: a flipped byte in a stored part fails its CRC; a cut one has no end.
    let at = ok.windows(5).position(|w| w == b"<mesh").unwrap();
    let mut crc = ok.clone();
    crc[at + 1] = b'M';
    check(
        &d,
        "crc.3mf",
        &crc,
        &["/3D/3dmodel.model: its CRC-32 does not match"],
    );
    check(&d, "cut.3mf", &ok[..ok.len() - 30], &["not a ZIP archive"]);
    let _ = std::fs::remove_dir_all(&d);
}
