//! Section views and object styles end to end: `--section` and the scene file's `section`
//! node read back from the JSON and the SVG; `style` nodes and `--styles` files deciding what
//! is drawn, on which layer and how wide.

use std::path::{Path, PathBuf};

use serde_json::Value;

use super::common::{kepler, root, s};

fn temp_dir(name: &str) -> PathBuf {
    kepler_testkit::temp_dir("section", name)
}

/// Runs kepler, which must succeed.
fn ok(args: &[&str]) {
    let o = kepler(args);
    assert!(o.status.success(), "kepler {args:?}: {o:?}");
}

fn json(path: &Path) -> Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn faces(v: &Value) -> &Vec<Value> {
    v["faces"].as_array().unwrap()
}

const CUBE: &str = "object \"cube\" { box 0 0 0 1 1 1 }\n";

#[test]
fn the_unit_cube_cut_in_half_seen_along_minus_x_shows_one_section_face_of_area_1() {
    let d = temp_dir("cube");
    let scene = d.join("cube.kdl");
    std::fs::write(&scene, CUBE).unwrap();
    let out = d.join("c.json");
    ok(&[
        "render",
        s(&scene),
        "--section",
        "0.5,0,0,1,0,0",
        "--dir",
        "-1,0,0",
        "--json",
        s(&out),
    ]);
    let v = json(&out);
    let f = faces(&v);
    assert_eq!(f.len(), 1, "{v}");
    assert_eq!(f[0]["section"], Value::Bool(true));
    assert_eq!(f[0]["area"].as_f64(), Some(1.0));
    assert_eq!(f[0]["id"].as_u64(), Some(6));
    // The exact checker agrees on the cut scene.
    let o = kepler(&[
        "check",
        s(&scene),
        "--exact",
        "--section",
        "0.5,0,0,1,0,0",
        "--dir",
        "-1,-0.4,-0.3",
    ]);
    assert!(o.status.success(), "{o:?}");
    // A scene file's section node does the same.
    let with_node = d.join("node.kdl");
    std::fs::write(
        &with_node,
        format!("section {{ point 0.5 0 0; normal 1 0 0 }}\n{CUBE}"),
    )
    .unwrap();
    let out2 = d.join("n.json");
    ok(&[
        "render",
        s(&with_node),
        "--dir",
        "-1,0,0",
        "--json",
        s(&out2),
    ]);
    assert_eq!(faces(&json(&out2)), f);
}

#[test]
fn uncut_faces_keep_their_ids_and_the_drawing_has_a_hatched_section_layer() {
    let d = temp_dir("assembly");
    let scene = root().join("scenes/assembly.kdl");
    let (plain, cut, svg) = (d.join("p.json"), d.join("c.json"), d.join("c.svg"));
    ok(&["render", s(&scene), "--json", s(&plain)]);
    ok(&[
        "render",
        s(&scene),
        "--section",
        "0,0,0.2,0,0,1",
        "--page",
        "a4",
        "--json",
        s(&cut),
        "--svg",
        s(&svg),
    ]);
    let (p, c) = (json(&plain), json(&cut));
    let n: u64 = 70;
    for f in faces(&c) {
        let id = f["id"].as_u64().unwrap();
        let section = f.get("section") == Some(&Value::Bool(true));
        assert_eq!(section, id >= n, "{f}");
    }
    // The floor's top is cut but keeps its id; a face wholly behind the plane is as it was.
    let by_id = |v: &Value, id: u64| {
        faces(v)
            .iter()
            .find(|f| f["id"].as_u64() == Some(id))
            .cloned()
    };
    let kept = faces(&p)
        .iter()
        .filter(|f| by_id(&c, f["id"].as_u64().unwrap()) == Some((*f).clone()))
        .count();
    assert!(kept > 0, "some faces are untouched by the cut");
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(text.contains("inkscape:label=\"7 section\""), "{text}");
    assert!(text.contains("class=\"section-hatching\""));
    assert!(text.contains("class=\"section\""));
}

#[test]
fn bad_sections_are_refused_clearly() {
    let d = temp_dir("bad");
    let scene = d.join("cube.kdl");
    std::fs::write(&scene, CUBE).unwrap();
    let out = d.join("x.json");
    for (flag, why) in [
        ("0,0,0,0,0,0", "the normal 0,0,0 is zero"),
        ("0,0,0,1,0", "expected six numbers"),
        ("0,0,x,1,0,0", "'x' is not a number"),
        ("2e12,0,0,1,0,0", "beyond 1e12"),
    ] {
        let o = kepler(&["render", s(&scene), "--section", flag, "--json", s(&out)]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success() && err.contains(why), "{flag}: {err}");
    }
    for (node, why) in [
        (
            "section { point 0 0 0 }",
            "cube.kdl:1:1: the section needs `point X Y Z` and `normal X Y Z`",
        ),
        (
            "section { point 0 0 0; normal 0 0 0 }",
            "cube.kdl:1:24: the section's normal is zero",
        ),
        (
            "section { point 0 0 0; normal 1 0 0; tilt 3 }",
            "cube.kdl:1:38: unknown section setting `tilt`",
        ),
    ] {
        std::fs::write(&scene, format!("{node}\n{CUBE}")).unwrap();
        let o = kepler(&["render", s(&scene), "--json", s(&out)]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success() && err.contains(why), "{node}: {err}");
    }
}

/// Each layer's label and stroke widths in an SVG.
fn layers(svg: &str) -> Vec<(String, String)> {
    svg.split("<g ")
        .skip(1)
        .filter_map(|g| {
            let head = &g[..g.find('>')?];
            let label = head.split("inkscape:label=\"").nth(1)?.split('"').next()?;
            let width = head
                .split("stroke-width=\"")
                .nth(1)
                .and_then(|w| w.split('"').next())
                .unwrap_or("");
            Some((label.to_string(), width.to_string()))
        })
        .collect()
}

#[test]
fn styles_in_a_scene_file_hide_move_and_weigh_lines() {
    let d = temp_dir("styles");
    let scene = d.join("st.kdl");
    let unstyled =
        "object \"front\" { box -2 -2 2 2 2 3 }\nobject \"back\" { box -3 -1 0 3 1 1 }\n";
    let styled = "object \"front\" {\n    box -2 -2 2 2 2 3\n    style occlude-only=#true\n}\n\
                  object \"back\" {\n    box -3 -1 0 3 1 1\n    style pen=3 weight=1.2\n}\n";
    let (j, svg) = (d.join("s.json"), d.join("s.svg"));
    let run = |text: &str| {
        std::fs::write(&scene, text).unwrap();
        ok(&[
            "render",
            s(&scene),
            "--dir",
            "0,0,-1",
            "--json",
            s(&j),
            "--svg",
            s(&svg),
        ]);
        (json(&j), std::fs::read_to_string(&svg).unwrap())
    };
    let (pj, psvg) = run(unstyled);
    let (sj, ssvg) = run(styled);
    // Unstyled: the front box hides the back box's middle, and both are listed and drawn.
    assert!(faces(&pj).iter().any(|f| f["object"] == "front"));
    assert_eq!(layers(&psvg), vec![("1 outline".into(), "0.5".into())]);
    // Occlude-only: still hides (the back box shows only its two ends, area 2 + 2), but
    // is neither listed nor drawn.
    assert!(faces(&sj).iter().all(|f| f["object"] == "back"), "{sj}");
    let area: f64 = faces(&sj).iter().map(|f| f["area"].as_f64().unwrap()).sum();
    assert_eq!(area, 4.0);
    // Pen 3: the back box's lines are on layer 3, 1.2 mm wide; nothing else is drawn.
    assert_eq!(
        layers(&ssvg),
        vec![("3 intersections".into(), "1.2".into())]
    );
    // Errors name the line.
    std::fs::write(
        &scene,
        "object \"a\" {\n    box 0 0 0 1 1 1\n    style pen=0\n}\n",
    )
    .unwrap();
    let o = kepler(&["render", s(&scene), "--json", s(&j)]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("st.kdl:3:5: pen=0: expected a whole number from 1 to 99"),
        "{err}"
    );
}

#[test]
fn a_style_file_applies_by_object_name_to_obj_groups() {
    let d = temp_dir("obj");
    let obj = d.join("two.obj");
    std::fs::write(
        &obj,
        "o wall\nv -2 -2 2\nv 2 -2 2\nv 2 2 2\nv -2 2 2\nf 1 2 3 4\n\
         o floor\nv -3 -1 0\nv 3 -1 0\nv 3 1 0\nv -3 1 0\nf 5 6 7 8\n",
    )
    .unwrap();
    let styles = d.join("two.styles.kdl");
    std::fs::write(
        &styles,
        "style \"wall\" occlude-only=#true\nstyle \"fl*\" pen=5 weight=0.8\n",
    )
    .unwrap();
    let (j, svg) = (d.join("t.json"), d.join("t.svg"));
    ok(&[
        "render",
        s(&obj),
        "--styles",
        s(&styles),
        "--dir",
        "0,0,-1",
        "--json",
        s(&j),
        "--svg",
        s(&svg),
    ]);
    let v = json(&j);
    assert_eq!(faces(&v).len(), 1);
    assert_eq!(faces(&v)[0]["object"], "floor");
    assert_eq!(faces(&v)[0]["area"].as_f64(), Some(4.0));
    let text = std::fs::read_to_string(&svg).unwrap();
    assert_eq!(layers(&text), vec![("5 hatching".into(), "0.8".into())]);
    // A bad style file: located.
    std::fs::write(&styles, "style \"wall\" colour=3\n").unwrap();
    let o = kepler(&["render", s(&obj), "--styles", s(&styles), "--json", s(&j)]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        !o.status.success() && err.contains("two.styles.kdl:1:"),
        "{err}"
    );
}
