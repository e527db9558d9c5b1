//! The `kepler` binary end to end: `check` against a golden, SVG and PNG output, JSON lines.

use std::path::PathBuf;

use super::common::{kepler, s};

const CUBES: &str = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n\
v 2 0.2 0.3\nv 2.5 0.2 0.3\nv 2.5 0.7 0.3\nv 2 0.7 0.3\n\
f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\nf 9 10 11 12\n";

/// A fresh directory for one test.
fn temp_dir(name: &str) -> PathBuf {
    kepler_testkit::temp_dir("test", name)
}

#[test]
fn check_passes_unchanged_and_names_the_moved_face() {
    let d = temp_dir("check");
    let mesh = d.join("m.obj");
    let golden = d.join("g.json");
    std::fs::write(&mesh, CUBES).unwrap();
    let o = kepler(&["check", s(&mesh), "--golden", s(&golden), "--update"]);
    assert!(o.status.success(), "{o:?}");
    let o = kepler(&["check", s(&mesh), "--golden", s(&golden)]);
    assert_eq!(o.status.code(), Some(0), "{o:?}");
    // Move one corner of the square (face 6).
    std::fs::write(&mesh, CUBES.replace("v 2.5 0.7 0.3", "v 2.5 0.75 0.3")).unwrap();
    let o = kepler(&["check", s(&mesh), "--golden", s(&golden)]);
    assert_eq!(o.status.code(), Some(1), "{o:?}");
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(text.contains("face 6 (m)"), "{text}");
    // A malformed golden is an error naming the file.
    std::fs::write(&golden, "{\"faces\": 3}").unwrap();
    let o = kepler(&["check", s(&mesh), "--golden", s(&golden)]);
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("g.json"));
}

#[test]
fn svg_is_well_formed_and_deterministic_png_has_the_size() {
    let d = temp_dir("pictures");
    let mesh = d.join("m.obj");
    std::fs::write(&mesh, CUBES).unwrap();
    let (a, b, png) = (d.join("a.svg"), d.join("b.svg"), d.join("p.png"));
    for out in [&a, &b] {
        let o = kepler(&["render", s(&mesh), "--svg", s(out), "--fill", "--hidden"]);
        assert!(o.status.success(), "{o:?}");
    }
    let text = std::fs::read_to_string(&a).unwrap();
    assert_eq!(text, std::fs::read_to_string(&b).unwrap(), "deterministic");
    assert!(text.starts_with("<svg"));
    assert!(text.trim_end().ends_with("</svg>"));
    assert!(text.contains("viewBox=\""));
    assert_eq!(text.matches("<g ").count(), text.matches("</g>").count());
    // 7 filled faces at most, plus line paths (hidden and visible pens of two objects).
    assert!(text.matches("<path").count() >= 4, "{text}");
    let o = kepler(&["render", s(&mesh), "--png", s(&png), "--size", "300"]);
    assert!(o.status.success(), "{o:?}");
    let img = image::open(&png).unwrap();
    assert_eq!(img.width().max(img.height()), 300);
}

#[test]
fn json_carries_lines_when_edges_are_asked_for() {
    let d = temp_dir("json");
    let mesh = d.join("m.obj");
    std::fs::write(&mesh, CUBES).unwrap();
    let (plain, lined) = (d.join("a.json"), d.join("b.json"));
    assert!(kepler(&["render", s(&mesh), "--json", s(&plain)])
        .status
        .success());
    assert!(kepler(&[
        "render",
        s(&mesh),
        "--json",
        s(&lined),
        "--edges",
        "all",
        "--hidden"
    ])
    .status
    .success());
    let a: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&plain).unwrap()).unwrap();
    let b: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&lined).unwrap()).unwrap();
    assert!(a.get("lines").is_none());
    assert_eq!(a["faces"], b["faces"]);
    assert!(!b["lines"]["visible"].as_array().unwrap().is_empty());
    assert!(!b["lines"]["hidden"].as_array().unwrap().is_empty());
}

#[test]
fn info_json_gives_every_mesh_a_hierarchy_and_both_trees_render_the_same_bytes() {
    let d = temp_dir("hierarchy");
    let obj = d.join("cubes.obj");
    std::fs::write(&obj, CUBES).unwrap();
    let o = kepler(&["info", s(&obj), "--json", "-q"]);
    assert!(o.status.success());
    let text = String::from_utf8_lossy(&o.stdout);
    for key in ["\"hierarchy\":{", "\"nodes\":", "\"depth\":", "\"leaves\":"] {
        assert!(text.contains(key), "{key} missing: {text}");
    }
    let Some(cow) = kepler_testkit::model("cow.obj") else {
        return;
    };
    let o = kepler(&["info", s(&cow), "-q"]);
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(text.contains("hierarchy simplify") && text.contains("component 0 (level 0)"));
    let json = |h: &str| {
        let f = d.join(format!("cow-{h}.json"));
        let o = kepler(&["render", s(&cow), "--json", s(&f), "--hierarchy", h, "-q"]);
        assert!(o.status.success());
        std::fs::read(&f).unwrap()
    };
    assert_eq!(json("simplify"), json("median"));
}

#[test]
fn interfere_answers_alike_with_both_trees_and_brute_force() {
    let d = temp_dir("interfere");
    let obj = d.join("cubes.obj");
    // Two cubes sharing a face and a square apart.
    std::fs::write(&obj, format!("{CUBES}o b\nv 1 0 0\nv 2 0 0\nv 2 1 0\nv 1 1 0\nv 1 0 1\nv 2 0 1\nv 2 1 1\nv 1 1 1\nf 13 16 15 14\nf 17 18 19 20\nf 13 14 18 17\nf 14 15 19 18\nf 15 16 20 19\nf 16 13 17 20\n")).unwrap();
    let run = |extra: &[&str]| {
        let mut args = vec!["query", s(&obj), "--interfere", "-q"];
        args.extend_from_slice(extra);
        let o = kepler(&args);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        String::from_utf8_lossy(&o.stdout).into_owned()
    };
    let brute = run(&["--brute"]);
    assert!(brute.contains("INTERSECT"), "{brute}");
    assert_eq!(run(&["--hierarchy", "simplify"]), brute);
    assert_eq!(run(&["--hierarchy", "median"]), brute);
    assert!(run(&["--stats"]).contains("BV nodes traversed"));
}

#[test]
fn info_merges_signed_zeros_and_says_why_a_mesh_is_not_culled() {
    let d = temp_dir("info");
    // A tetrahedron whose vertex 5 is vertex 3 written with -0: 4 vertices, closed, solid.
    let tet = d.join("tet.obj");
    std::fs::write(
        &tet,
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv -0 1 0\nf 1 3 2\nf 1 2 4\nf 1 4 5\nf 2 3 4\n",
    )
    .unwrap();
    let o = kepler(&["info", "-q", s(&tet)]);
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{o:?}");
    assert!(text.contains("4 faces, 4 vertices, closed solid"), "{text}");
    assert!(text.contains("solid: back faces culled"), "{text}");
    // One object: the render skips its INBOX, info computes it.
    assert!(text.contains("inbox ["), "{text}");
    // Wound inwards: not culled, and info says why; its INBOX is still proven inside.
    let inward = d.join("inward.obj");
    std::fs::write(
        &inward,
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 4 2\nf 1 3 4\nf 2 4 3\n",
    )
    .unwrap();
    let o = kepler(&["info", "-q", "--json", s(&inward)]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let leaf = &v["subobjects"][0];
    assert_eq!(leaf["solidity"], "inside-out", "{v}");
    assert_eq!(leaf["culled_back_faces"], false);
    assert!(leaf["inbox"].is_object(), "{v}");
    // An open mesh has no INBOX, with the reason.
    let open = d.join("open.obj");
    std::fs::write(&open, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
    let o = kepler(&["info", "-q", "--json", s(&open)]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert!(v["subobjects"][0]["inbox"].is_null());
    assert!(v["subobjects"][0]["inbox_reason"]
        .as_str()
        .unwrap()
        .contains("open"));
    assert_eq!(v["subobjects"][0]["solidity"], "open");
}

#[test]
fn info_says_an_open_mesh_is_capped_or_why_not() {
    let d = temp_dir("info-caps");
    // A tetrahedron missing one face: its hole caps into a solid.
    let open = d.join("open-tet.obj");
    std::fs::write(
        &open,
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\n",
    )
    .unwrap();
    let o = kepler(&["info", "-q", s(&open)]);
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{o:?}");
    assert!(
        text.contains("open, capped: back faces culled except near 1 caps"),
        "{text}"
    );
    let o = kepler(&["info", "-q", "--json", s(&open)]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let leaf = &v["subobjects"][0];
    assert_eq!(leaf["solidity"], "capped", "{v}");
    assert_eq!(leaf["culled_back_faces"], true);
    assert_eq!(leaf["caps"], 1);
    // The same faces wound inwards: refused, with the reason.
    let inward = d.join("inward-tet.obj");
    std::fs::write(
        &inward,
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 4 2\nf 1 3 4\n",
    )
    .unwrap();
    let o = kepler(&["info", "-q", s(&inward)]);
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(
        text.contains("back faces not culled: open (an edge has one face); capping failed"),
        "{text}"
    );
}
