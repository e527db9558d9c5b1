//! glTF and 3MF scenes against their KDL and OBJ equivalents: the same tree, the same faces,
//! the same visible regions byte for byte, the same culling; and bad files refused with the
//! file and the JSON path or XML line.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use kepler_testkit::{
    model_xml, temp_dir, threemf, unit_cube_triangles as cube, Gltf, GltfMesh, GltfNode,
    ThreeMfObject,
};

use super::common::{models, prepare, render_plain, SHARED_MESHES};
use crate::count::Count;
use crate::emit::write::json::to_json;
use crate::geom::V3;
use crate::scene::{CameraSpec, Content, Object, Scene};
use crate::view::Camera;
use crate::{load_scene, LoadOptions, Progress};

/// Loads `path` with the default options.
fn load(path: &Path) -> crate::error::Result<Scene> {
    load_scene(
        path,
        &LoadOptions::default(),
        &mut Vec::new(),
        &Progress::default(),
    )
}

/// The JSON visible-polygon set of `scene`, prepared as the command prepares it.
fn json(mut scene: Scene, camera: &Camera) -> String {
    prepare(&mut scene);
    let r = render_plain(&scene, camera);
    to_json(&r.view, &r.visibility, None, Count::NONE)
}

/// Every object of the tree as `path kind faces`, and every leaf's vertices and faces.
fn describe(o: &Object, path: &str, out: &mut String) {
    let p = if path.is_empty() {
        o.name.clone()
    } else {
        format!("{path}/{}", o.name)
    };
    match &o.content {
        Content::Mesh(m) => {
            let faces: Vec<&[u32]> = m.faces.iter().map(|f| f.vertices.as_slice()).collect();
            let _ = writeln!(out, "{p} mesh {:?} {faces:?}", m.vertices);
        }
        Content::Subobjects(s) => {
            let _ = writeln!(out, "{p} group");
            for c in s {
                describe(c, &p, out);
            }
        }
        Content::Instance(i) => {
            let _ = writeln!(out, "{p} instance {:?}", i.transform.as_slice());
            describe(&i.prototype, &p, out);
        }
    }
}

/// The scene's tree described.
fn tree(scene: &Scene) -> String {
    let mut s = String::new();
    describe(&scene.root, "", &mut s);
    s
}

/// Positions and triangles.
type Tris = (Vec<[f32; 3]>, Vec<[u32; 3]>);

/// A triangular prism (a gable roof) over the unit square, 1 high.
fn roof() -> (Vec<[f32; 3]>, Vec<[u32; 3]>) {
    let p = vec![
        [0., 0., 0.],
        [1., 0., 0.],
        [0.5, 1., 0.],
        [0., 0., 1.],
        [1., 0., 1.],
        [0.5, 1., 1.],
    ];
    let t = vec![
        [0, 2, 1],
        [3, 4, 5],
        [0, 1, 4],
        [0, 4, 3],
        [1, 2, 5],
        [1, 5, 4],
        [2, 0, 3],
        [2, 3, 5],
    ];
    (p, t)
}

/// OBJ text of one group of triangles.
fn obj_text(name: &str, (p, t): &(Vec<[f32; 3]>, Vec<[u32; 3]>)) -> String {
    let mut s = format!("o {name}\n");
    for v in p {
        let v = v.map(f64::from);
        let _ = writeln!(s, "v {} {} {}", v[0], v[1], v[2]);
    }
    for f in t {
        let _ = writeln!(s, "f {} {} {}", f[0] + 1, f[1] + 1, f[2] + 1);
    }
    s
}

fn gmesh(name: &str, (p, t): (Vec<[f32; 3]>, Vec<[u32; 3]>)) -> GltfMesh {
    GltfMesh {
        name: name.into(),
        positions: p,
        triangles: t,
    }
}

fn gnode(name: &str) -> GltfNode {
    GltfNode {
        name: Some(name.into()),
        ..GltfNode::default()
    }
}

/// A small street as glTF: a house (body and roof under one node), a tower and a shed that
/// share the block mesh with the body, one by TRS, one by a matrix (a quarter turn).
fn street() -> Gltf {
    let house = GltfNode {
        translation: Some([1.0, 0.0, -2.0]),
        children: vec![1, 2],
        ..gnode("house")
    };
    let body = GltfNode {
        mesh: Some(0),
        scale: Some([4.0, 3.0, 5.0]),
        ..gnode("body")
    };
    let gable = GltfNode {
        mesh: Some(1),
        translation: Some([0.0, 3.0, 0.0]),
        scale: Some([4.0, 2.0, 5.0]),
        ..gnode("roof")
    };
    let tower = GltfNode {
        mesh: Some(0),
        translation: Some([8.0, 0.0, 0.0]),
        scale: Some([2.0, 8.0, 2.0]),
        ..gnode("tower")
    };
    // A quarter turn about +y (+z to +x), then a move: column-major.
    let shed = GltfNode {
        mesh: Some(0),
        matrix: Some([
            0., 0., -1., 0., 0., 1., 0., 0., 1., 0., 0., 0., -6., 0., 2., 1.,
        ]),
        ..gnode("shed")
    };
    // A camera node off to the side, not drawn.
    let eye = GltfNode {
        camera: Some(0),
        translation: Some([2.0, 4.0, 30.0]),
        ..gnode("eye")
    };
    Gltf {
        meshes: vec![gmesh("block", cube()), gmesh("gable", roof())],
        nodes: vec![house, body, gable, tower, shed, eye],
        roots: vec![0, 3, 4, 5],
        cameras: vec![
            r#"{"type":"perspective","perspective":{"yfov":0.75,"znear":0.1,"aspectRatio":1.5}}"#
                .into(),
        ],
        extra: vec![r#""materials":[{"name":"brick"}]"#.into()],
    }
}

/// The street as a KDL scene of OBJ meshes.
const STREET_KDL: &str = r#"
prototype "block" { mesh "block.obj" }
object "house" {
    translate 1 0 -2
    instance "body" of="block" { scale 4 3 5 }
    object "roof" { mesh "gable.obj"; scale 4 2 5; translate 0 3 0 }
}
instance "tower" of="block" { scale 2 8 2; translate 8 0 0 }
instance "shed" of="block" { rotate 90 axis="y"; translate -6 0 2 }
"#;

#[test]
fn a_gltf_street_renders_as_its_kdl_scene() {
    let d = temp_dir("import", "street");
    std::fs::write(d.join("block.obj"), obj_text("block", &cube())).unwrap();
    std::fs::write(d.join("gable.obj"), obj_text("gable", &roof())).unwrap();
    std::fs::write(d.join("street.kdl"), STREET_KDL).unwrap();
    let g = street();
    std::fs::write(d.join("street.glb"), g.glb()).unwrap();
    std::fs::write(d.join("street.gltf"), g.gltf_embedded()).unwrap();
    let (json_text, bin) = g.json_and_bin(Some("street%20data.bin"));
    std::fs::write(d.join("external.gltf"), json_text).unwrap();
    std::fs::write(d.join("street data.bin"), bin).unwrap();

    let kdl = load(&d.join("street.kdl")).unwrap();
    let mut warnings = Vec::new();
    let glb = load_scene(
        &d.join("street.glb"),
        &LoadOptions::default(),
        &mut warnings,
        &Progress::default(),
    )
    .unwrap();
    // One note for the materials; nothing else.
    assert_eq!(warnings.len(), 1, "{warnings:?}");
    assert!(
        warnings[0].message.contains("ignored 1 materials"),
        "{}",
        warnings[0]
    );
    // The tree: house/body and the others instances of one prototype, the roof a leaf.
    let names: Vec<&str> = glb
        .root
        .subobjects()
        .iter()
        .map(|o| o.name.as_str())
        .collect();
    assert_eq!(names, ["house", "tower", "shed"]);
    let house = &glb.root.subobjects()[0];
    let (Content::Instance(body), Content::Instance(tower)) = (
        &house.subobjects()[0].content,
        &glb.root.subobjects()[1].content,
    ) else {
        panic!("the shared block is not instanced");
    };
    assert!(std::sync::Arc::ptr_eq(&body.prototype, &tower.prototype));
    assert!(matches!(house.subobjects()[1].content, Content::Mesh(_)));
    // The camera: at the node, looking down its -z, +y up, the field of view in degrees.
    let Some(CameraSpec::Perspective {
        eye,
        target,
        up,
        fov_deg,
    }) = glb.camera.clone()
    else {
        panic!("no perspective camera: {:?}", glb.camera);
    };
    assert_eq!((eye.x, eye.y, eye.z), (2., 4., 30.));
    assert_eq!(target - eye, -V3::z());
    assert_eq!(up, V3::y());
    assert!((fov_deg - 0.75f64.to_degrees()).abs() < 1e-12);

    // The same faces, and the same visible regions, byte for byte, from two views.
    for cam in [
        Camera::orthographic(V3::new(-1., -2., -3.), V3::y()).unwrap(),
        Camera::orthographic(V3::new(0.3, -0.5, -1.), V3::y()).unwrap(),
    ] {
        let want = json(kdl.clone(), &cam);
        assert!(want.contains("\"house/roof\""), "{want}");
        for f in ["street.glb", "street.gltf", "external.gltf"] {
            let s = load(&d.join(f)).unwrap();
            assert_eq!(json(s, &cam), want, "{f}");
        }
    }
    let _ = std::fs::remove_dir_all(&d);
}

/// A mesh file's groups with positions rounded to f32 (as glTF stores them) and polygons cut
/// into fans: the same triangles written as OBJ, glTF and 3MF.
struct Groups(Vec<(String, Tris)>);

impl Groups {
    fn of(path: &Path) -> Groups {
        let file = crate::load::mesh_file::load_mesh(path, None, &Progress::default()).unwrap();
        let groups = file.groups.iter().map(|g| {
            let p = g.mesh.vertices.iter();
            let p = p.map(|v| [v.x as f32, v.y as f32, v.z as f32]).collect();
            let t = g
                .mesh
                .faces
                .iter()
                .flat_map(|f| (1..f.len() - 1).map(move |k| [f[0], f[k], f[k + 1]]));
            (g.name.clone(), (p, t.collect()))
        });
        Groups(groups.collect())
    }

    fn obj(&self) -> String {
        let mut s = String::new();
        let mut base = 1;
        for (name, (p, t)) in &self.0 {
            let _ = writeln!(s, "o {name}");
            for v in p {
                let v = v.map(f64::from);
                let _ = writeln!(s, "v {} {} {}", v[0], v[1], v[2]);
            }
            for f in t {
                let _ = writeln!(s, "f {} {} {}", f[0] + base, f[1] + base, f[2] + base);
            }
            base += p.len() as u32;
        }
        s
    }

    fn gltf(&self) -> Gltf {
        let mut g = Gltf::default();
        for (k, (name, (p, t))) in self.0.iter().enumerate() {
            g.meshes.push(gmesh(name, (p.clone(), t.clone())));
            g.nodes.push(GltfNode {
                mesh: Some(k),
                ..gnode(name)
            });
            g.roots.push(k);
        }
        g
    }

    fn threemf(&self) -> Vec<u8> {
        let objects: Vec<ThreeMfObject> = (self.0.iter().enumerate())
            .map(|(k, (name, (p, t)))| ThreeMfObject {
                id: k as u32 + 1,
                name: Some(name.clone()),
                vertices: p.iter().map(|v| v.map(f64::from)).collect(),
                triangles: t.clone(),
                components: Vec::new(),
            })
            .collect();
        let items: Vec<(u32, Option<[f64; 12]>)> =
            (1..=objects.len() as u32).map(|i| (i, None)).collect();
        threemf(&model_xml(&objects, &items))
    }
}

/// Meshes rendered whole in the default run (the rest compare their loaded trees, which
/// fixes their renders; `KEPLER_IMPORT_ALL=1` renders them all).
const RENDER_FACES: usize = 25_000;

#[test]
fn shared_meshes_as_glb_and_3mf_render_byte_identical_json_to_their_obj() {
    let Some(dir) = models() else { return };
    let all = std::env::var("KEPLER_IMPORT_ALL").is_ok_and(|v| v == "1");
    let d = temp_dir("import", "shared");
    let cam = Camera::orthographic(V3::new(-1., -2., -3.), V3::y()).unwrap();
    let mut rendered = 0;
    for name in SHARED_MESHES {
        let path = dir.join(name);
        if !path.exists() {
            eprintln!("skipping {name}: absent");
            continue;
        }
        let stem = name.trim_end_matches(".obj");
        let g = Groups::of(&path);
        let files: Vec<PathBuf> = ["obj", "glb", "3mf"]
            .iter()
            .map(|e| d.join(format!("{stem}.{e}")))
            .collect();
        std::fs::write(&files[0], g.obj()).unwrap();
        std::fs::write(&files[1], g.gltf().glb()).unwrap();
        std::fs::write(&files[2], g.threemf()).unwrap();
        let scenes: Vec<Scene> = files.iter().map(|f| load(f).unwrap()).collect();
        let want = tree(&scenes[0]);
        for (s, f) in scenes.iter().zip(&files).skip(1) {
            let got = tree(s);
            let diff = got.lines().zip(want.lines()).find(|(a, b)| a != b);
            let short = |l: &str| l.chars().take(300).collect::<String>();
            assert!(
                got == want,
                "{}: another tree than its OBJ: {:?}",
                f.display(),
                diff.map(|(a, b)| (short(a), short(b)))
            );
        }
        if all || scenes[0].root.face_count() <= RENDER_FACES {
            let mut it = scenes.into_iter();
            let want = json(it.next().unwrap(), &cam);
            for (s, f) in it.zip(&files[1..]) {
                assert!(
                    json(s, &cam) == want,
                    "{}: another JSON than its OBJ",
                    f.display()
                );
            }
            rendered += 1;
        }
    }
    assert!(rendered > 0 || !dir.join("cube.obj").exists());
    let _ = std::fs::remove_dir_all(&d);
}

/// Spacing of the town's grid, as in the bench's town.
const PITCH: f64 = 16.0;

/// A box's triangles from `lo` to `hi`, appended to `p` and `t`.
fn add_box(p: &mut Vec<[f32; 3]>, t: &mut Vec<[u32; 3]>, lo: [f32; 3], hi: [f32; 3]) {
    let (cp, ct) = cube();
    let base = p.len() as u32;
    for v in cp {
        p.push([0, 1, 2].map(|k| lo[k] + v[k] * (hi[k] - lo[k])));
    }
    t.extend(ct.iter().map(|f| f.map(|i| i + base)));
}

/// A building kind: its body (a box, w × w × h) and its ledges (one per floor on each side).
fn building(w: f32, h: f32, floors: usize) -> [Tris; 2] {
    let mut body = (Vec::new(), Vec::new());
    add_box(&mut body.0, &mut body.1, [0., 0., 0.], [w, w, h]);
    let mut ledges = (Vec::new(), Vec::new());
    let fl = h / floors as f32;
    for f in 0..floors {
        let z = f as f32 * fl + 0.3 * fl;
        let z1 = z + 0.2 * fl;
        for (lo, hi) in [
            ([0.5, -0.4, z], [w - 0.5, 0., z1]),
            ([0.5, w, z], [w - 0.5, w + 0.4, z1]),
            ([-0.4, 0.5, z], [0., w - 0.5, z1]),
            ([w, 0.5, z], [w + 0.4, w - 0.5, z1]),
        ] {
            add_box(&mut ledges.0, &mut ledges.1, lo, hi);
        }
    }
    [body, ledges]
}

/// The town of the INBOX benchmark, `n` buildings behind a wall, as glTF and as KDL (with
/// OBJ meshes) in `d`: `town.glb`, `town.kdl`.
fn write_town(d: &Path, n: usize) {
    let kinds = [
        ("tower", 10., 40., 10),
        ("block", 12., 20., 5),
        ("house", 8., 10., 3),
    ];
    let side = (n as f64).sqrt().ceil() as usize;
    let extent = (side as f64 * PITCH) as f32;
    let mut g = Gltf::default();
    let mut kdl = String::new();
    let mut wall = (Vec::new(), Vec::new());
    add_box(
        &mut wall.0,
        &mut wall.1,
        [-20., -20., 100.],
        [extent + 20., extent + 20., 102.],
    );
    std::fs::write(d.join("wall.obj"), obj_text("wall", &wall)).unwrap();
    g.meshes.push(gmesh("wall", wall));
    g.nodes.push(GltfNode {
        mesh: Some(0),
        ..gnode("wall")
    });
    g.roots.push(0);
    kdl.push_str("object \"wall\" { mesh \"wall.obj\" }\n");
    for (name, w, h, floors) in kinds {
        for (part, m) in ["body", "ledges"].iter().zip(building(w, h, floors)) {
            let file = format!("{name}_{part}");
            std::fs::write(d.join(format!("{file}.obj")), obj_text(&file, &m)).unwrap();
            let _ = writeln!(kdl, "prototype \"{file}\" {{ mesh \"{file}.obj\" }}");
            g.meshes.push(gmesh(&file, m));
        }
    }
    for k in 0..n {
        let (i, j) = ((k % side) as f64 * PITCH, (k / side) as f64 * PITCH);
        let kind = kinds[k % 3].0;
        let first = g.nodes.len();
        for (m, part) in ["body", "ledges"].iter().enumerate() {
            g.nodes.push(GltfNode {
                mesh: Some(1 + 2 * (k % 3) + m),
                ..gnode(part)
            });
        }
        g.nodes.push(GltfNode {
            translation: Some([i, j, 0.]),
            children: vec![first, first + 1],
            ..gnode(&format!("b{k}"))
        });
        g.roots.push(first + 2);
        let _ = writeln!(
            kdl,
            "object \"b{k}\" {{ translate {i} {j} 0; instance \"body\" of=\"{kind}_body\"; instance \"ledges\" of=\"{kind}_ledges\" }}"
        );
    }
    std::fs::write(d.join("town.glb"), g.glb()).unwrap();
    std::fs::write(d.join("town.kdl"), kdl).unwrap();
}

#[test]
fn the_inbox_cull_works_on_a_gltf_town_as_on_its_kdl() {
    let keep = std::env::var("KEPLER_IMPORT_KEEP").ok().map(PathBuf::from);
    let d = keep.clone().unwrap_or_else(|| temp_dir("import", "town"));
    std::fs::create_dir_all(&d).unwrap();
    write_town(&d, 1000);
    let cam = Camera::orthographic(V3::new(0.02, 0.03, -1.0), V3::y()).unwrap();
    let mut counters = Vec::new();
    let mut jsons = Vec::new();
    for f in ["town.kdl", "town.glb"] {
        let mut s = load(&d.join(f)).unwrap();
        assert_eq!(s.root.subobjects().len(), 1001, "{f}");
        prepare(&mut s);
        let r = render_plain(&s, &cam);
        counters.push(r.stats.counters);
        jsons.push(to_json(&r.view, &r.visibility, None, Count::NONE));
    }
    let (k, g) = (&counters[0], &counters[1]);
    // The wall hides whole buildings through their INBOXes, in both.
    assert!(k.subtrees_hidden >= 900, "{k:?}");
    assert_eq!(k.subtrees_hidden, g.subtrees_hidden, "{k:?}\n{g:?}");
    assert_eq!(k.faces_in_hidden_subtrees, g.faces_in_hidden_subtrees);
    assert_eq!(k.faces_walked, g.faces_walked);
    assert_eq!(jsons[0], jsons[1]);
    if keep.is_none() {
        let _ = std::fs::remove_dir_all(&d);
    }
}
