//! `kepler diff` and `kepler check --report json` end to end: one vertex of a mesh moved lists
//! the faces the move changes and nothing far from it, `--tol` judges changed, added and
//! removed faces alike, the JSON report parses with every field, and the exit statuses (0
//! same, 1 changed, 2 usage or unreadable input) hold.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};
use std::process::Output;

use serde_json::Value;

use super::common::{kepler, s};

fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Points and faces (0-based) of OBJ text: `v` lines and the first index of each `f` corner.
fn parse_obj(text: &str) -> (Vec<[f64; 3]>, Vec<Vec<u32>>) {
    let (mut points, mut faces) = (Vec::new(), Vec::new());
    for line in text.lines() {
        let mut w = line.split_whitespace();
        match w.next() {
            Some("v") => {
                let c: Vec<f64> = w.take(3).map(|x| x.parse().unwrap()).collect();
                points.push([c[0], c[1], c[2]]);
            }
            Some("f") => faces.push(
                w.map(|t| t.split('/').next().unwrap().parse::<u32>().unwrap() - 1)
                    .collect(),
            ),
            _ => {}
        }
    }
    (points, faces)
}

/// Every face fanned into triangles: planar, so face ids stay put when a vertex moves.
fn fan(faces: &[Vec<u32>]) -> Vec<[u32; 3]> {
    faces
        .iter()
        .flat_map(|f| (1..f.len() - 1).map(move |k| [f[0], f[k], f[k + 1]]))
        .collect()
}

/// Writes a triangle mesh and renders it to JSON looking along `view` (orthographic: the
/// camera does not follow the mesh).
fn render(dir: &Path, name: &str, points: &[[f64; 3]], tris: &[[u32; 3]], view: &str) -> PathBuf {
    let faces: Vec<&[u32]> = tris.iter().map(|t| &t[..]).collect();
    let mesh = dir.join(format!("{name}.obj"));
    std::fs::write(&mesh, kepler_testkit::obj_text(points, &faces)).unwrap();
    let json = dir.join(format!("{name}.json"));
    let o = kepler(&["render", s(&mesh), "--dir", view, "--json", s(&json), "-q"]);
    assert!(o.status.success(), "{o:?}");
    json
}

/// Faces by id: (area, visible region as JSON).
type Faces = BTreeMap<u64, (f64, Value)>;

/// A set's faces, and its camera matrix.
fn faces(json: &Path) -> (Faces, Vec<Vec<f64>>) {
    let v: Value = serde_json::from_str(&std::fs::read_to_string(json).unwrap()).unwrap();
    let faces = v["faces"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| {
            let id = f["id"].as_u64().unwrap();
            (id, (f["area"].as_f64().unwrap(), f["visible"].clone()))
        })
        .collect();
    let m = v["camera"]["matrix"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| {
            r.as_array()
                .unwrap()
                .iter()
                .map(|x| x.as_f64().unwrap())
                .collect()
        })
        .collect();
    (faces, m)
}

/// A world point on screen.
fn project(m: &[Vec<f64>], p: [f64; 3]) -> [f64; 2] {
    let row = |r: usize| m[r][0] * p[0] + m[r][1] * p[1] + m[r][2] * p[2] + m[r][3];
    [row(0) / row(3), row(1) / row(3)]
}

fn tri_area(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    ((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1])).abs() / 2.0
}

/// The box [x0, y0, x1, y1] of every point of a visible region (JSON).
fn region_box(v: &Value, b: &mut [f64; 4]) {
    for p in v.as_array().unwrap().iter().flat_map(|poly| {
        poly.as_array()
            .unwrap()
            .iter()
            .flat_map(|r| r.as_array().unwrap())
    }) {
        let (x, y) = (p[0].as_f64().unwrap(), p[1].as_f64().unwrap());
        *b = [b[0].min(x), b[1].min(y), b[2].max(x), b[3].max(y)];
    }
}

const EMPTY_BOX: [f64; 4] = [f64::INFINITY, f64::INFINITY, -f64::INFINITY, -f64::INFINITY];

/// `kepler diff A B --tol T --report json`, parsed, with its exit status.
fn diff_json(a: &Path, b: &Path, tol: &str) -> (Value, Option<i32>) {
    let o = kepler(&["diff", s(a), s(b), "--tol", tol, "--report", "json"]);
    let v = serde_json::from_str(&stdout(&o)).unwrap_or_else(|e| panic!("{e}: {o:?}"));
    (v, o.status.code())
}

/// Renders a triangle mesh, moves one vertex whose faces are all fully visible by `by`,
/// renders again, and checks what `kepler diff` lists against what can be known without it:
/// - a face is listed (tol 0) only if its region's JSON differs, and every face whose JSON
///   differs but is not listed has the same area (a re-spelling of one region);
/// - every face of the moved vertex is listed (each was fully visible and its outline moved);
/// - a face whose visibility changed did so where the vertex's faces were or are now on
///   screen: every listed face's regions (before or after) meet the box of those faces'
///   projections, old and new, and its symmetric difference is at most that box's area;
/// - `--tol T` lists exactly the faces whose relative change exceeds T, of every kind.
fn moved_vertex_case(name: &str, points: Vec<[f64; 3]>, tris: Vec<[u32; 3]>, by: [f64; 3]) {
    let dir = kepler_testkit::temp_dir("diff", name);
    let a = render(&dir, "a", &points, &tris, "-1,-2,-3");
    let (fa, m) = faces(&a);
    let on_screen = |p: &[[f64; 3]], t: &[u32; 3]| t.map(|k| project(&m, p[k as usize]));
    let fully_visible = |id: usize| {
        let [p, q, r] = on_screen(&points, &tris[id]);
        let proj = tri_area(p, q, r);
        fa.get(&(id as u64))
            .is_some_and(|f| proj > 0.0 && (f.0 - proj).abs() <= 1e-9 * proj)
    };
    let star =
        |v: u32| -> Vec<usize> { (0..tris.len()).filter(|&i| tris[i].contains(&v)).collect() };
    let v = (0..points.len() as u32)
        .find(|&v| {
            let st = star(v);
            st.len() >= 4 && st.iter().all(|&i| fully_visible(i))
        })
        .expect("a vertex whose faces are all fully visible");
    let mut moved = points.clone();
    for k in 0..3 {
        moved[v as usize][k] += by[k];
    }
    let b = render(&dir, "b", &moved, &tris, "-1,-2,-3");
    let (fb, mb) = faces(&b);
    assert_eq!(m, mb, "the camera does not follow the mesh");

    let (report, code) = diff_json(&a, &b, "0");
    assert_eq!(code, Some(1));
    assert_eq!(report["camera_differs"], false);
    let listed: BTreeMap<u64, &Value> = report["changes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| (c["id"].as_u64().unwrap(), c))
        .collect();
    assert_eq!(report["changed"].as_u64(), Some(listed.len() as u64));
    // Listed only where the JSON differs; the rest of the differing faces are re-spellings.
    let ids: BTreeSet<u64> = fa.keys().chain(fb.keys()).copied().collect();
    for &id in &ids {
        let (x, y) = (fa.get(&id), fb.get(&id));
        let differs = x.map(|f| &f.1) != y.map(|f| &f.1);
        if listed.contains_key(&id) {
            assert!(differs, "{name}: face {id} listed with the same region");
        } else if differs {
            let (p, q) = (x.map_or(0.0, |f| f.0), y.map_or(0.0, |f| f.0));
            assert!(
                (p - q).abs() <= 1e-12 * p.max(q),
                "{name}: face {id} not listed"
            );
        }
    }
    // The moved vertex's faces, and nothing far from them.
    let st = star(v);
    for &i in &st {
        assert!(
            listed.contains_key(&(i as u64)),
            "{name}: face {i} of vertex {v} not listed"
        );
    }
    let mut near = EMPTY_BOX;
    for &i in &st {
        for p in on_screen(&points, &tris[i])
            .into_iter()
            .chain(on_screen(&moved, &tris[i]))
        {
            near = [
                near[0].min(p[0]),
                near[1].min(p[1]),
                near[2].max(p[0]),
                near[3].max(p[1]),
            ];
        }
    }
    let pad = 1e-9 * near.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let near_area = (near[2] - near[0]) * (near[3] - near[1]);
    for (&id, c) in &listed {
        let mut b = EMPTY_BOX;
        for f in [fa.get(&id), fb.get(&id)].into_iter().flatten() {
            region_box(&f.1, &mut b);
        }
        let meets = b[0] <= near[2] + pad
            && near[0] <= b[2] + pad
            && b[1] <= near[3] + pad
            && near[1] <= b[3] + pad;
        assert!(
            meets,
            "{name}: face {id} listed, far from vertex {v}: {b:?} {near:?}"
        );
        assert!(c["xor_area"].as_f64().unwrap() <= near_area * (1.0 + 1e-9));
        // Every field, consistent.
        let num = |k: &str| c[k].as_f64().unwrap_or_else(|| panic!("{k} in {c}"));
        let (g, cur) = (num("golden_area"), num("current_area"));
        assert_eq!(g, fa.get(&id).map_or(0.0, |f| f.0.abs()), "{c}");
        assert_eq!(cur, fb.get(&id).map_or(0.0, |f| f.0.abs()), "{c}");
        assert!((num("area_delta") - (cur - g)).abs() <= 1e-15 * g.max(cur));
        let kind = match (fa.contains_key(&id), fb.contains_key(&id)) {
            (true, true) => "changed",
            (true, false) => "removed",
            _ => "added",
        };
        assert_eq!(c["kind"], kind);
        assert!(num("relative") > 0.0 && num("relative") <= 2.0);
        assert!(c["object"].is_string());
    }
    // --tol judges every kind alike: exactly the faces above it, for several thresholds.
    let mut rel: Vec<f64> = listed
        .values()
        .map(|c| c["relative"].as_f64().unwrap())
        .collect();
    rel.sort_by(f64::total_cmp);
    for t in [rel[0] / 2.0, rel[rel.len() / 2], 0.999, 1.0] {
        let (r, code) = diff_json(&a, &b, &t.to_string());
        let got: BTreeSet<u64> = r["changes"]
            .as_array()
            .unwrap()
            .iter()
            .map(|c| c["id"].as_u64().unwrap())
            .collect();
        let want: BTreeSet<u64> = listed
            .iter()
            .filter(|(_, c)| c["relative"].as_f64().unwrap() > t)
            .map(|(&id, _)| id)
            .collect();
        assert_eq!(got, want, "{name}: --tol {t}");
        assert_eq!(
            code,
            Some(if want.is_empty() { 0 } else { 1 }),
            "{name}: --tol {t}"
        );
    }
    eprintln!(
        "{name}: vertex {v} moved: {} faces listed, kinds {:?}",
        listed.len(),
        listed
            .values()
            .map(|c| c["kind"].as_str().unwrap())
            .collect::<BTreeSet<_>>()
    );
}

/// A hill on a 12 x 12 grid of triangles: faces behind it are partly and wholly hidden.
fn hill() -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    let n = 12u32;
    let mut points = Vec::new();
    for i in 0..=n {
        for j in 0..=n {
            let (x, z) = (i as f64, j as f64);
            let h = 3.0 * (-((x - 6.0).powi(2) + (z - 6.0).powi(2)) / 6.0).exp()
                + 0.2 * (1.3 * x).sin() * (0.7 * z).cos();
            points.push([x, h, z]);
        }
    }
    let at = |i: u32, j: u32| i * (n + 1) + j;
    let mut tris = Vec::new();
    for i in 0..n {
        for j in 0..n {
            tris.push([at(i, j), at(i, j + 1), at(i + 1, j + 1)]);
            tris.push([at(i, j), at(i + 1, j + 1), at(i + 1, j)]);
        }
    }
    (points, tris)
}

#[test]
fn diff_lists_the_faces_a_moved_vertex_changes() {
    let (points, tris) = hill();
    moved_vertex_case("hill", points, tris, [0.3, 2.5, -0.2]);
}

#[test]
fn diff_on_suzanne_with_one_vertex_moved() {
    let Some(path) = kepler_testkit::model("suzanne.obj") else {
        return;
    };
    let (points, faces) = parse_obj(&std::fs::read_to_string(path).unwrap());
    moved_vertex_case("suzanne", points, fan(&faces), [0.03, -0.02, 0.05]);
}

/// A 2-unit square in front of a small one, seen along -z: moving the front one's corner from
/// (2, 2) to (4, 4) hides the small one wholly (its faces removed; added the other way).
fn squares(corner: [f64; 3]) -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    let points = vec![
        [0.0, 0.0, 1.0],
        [2.0, 0.0, 1.0],
        corner,
        [0.0, 2.0, 1.0],
        [2.2, 2.2, 0.0],
        [2.6, 2.2, 0.0],
        [2.6, 2.6, 0.0],
        [2.2, 2.6, 0.0],
    ];
    (points, vec![[0, 1, 2], [0, 2, 3], [4, 5, 6], [4, 6, 7]])
}

#[test]
fn diff_exit_statuses_and_added_and_removed_faces() {
    let dir = kepler_testkit::temp_dir("diff", "exits");
    let (p, t) = squares([2.0, 2.0, 1.0]);
    let a = render(&dir, "a", &p, &t, "0,0,-1");
    let (p, t) = squares([4.0, 4.0, 1.0]);
    let b = render(&dir, "b", &p, &t, "0,0,-1");
    // Same: 0.
    let o = kepler(&["diff", s(&a), s(&a)]);
    assert_eq!(o.status.code(), Some(0), "{o:?}");
    assert!(stdout(&o).starts_with("ok: "), "{o:?}");
    // Changed: 1, every kind named; the back square's faces are removed one way, added the other.
    let o = kepler(&["diff", s(&a), s(&b)]);
    assert_eq!(o.status.code(), Some(1), "{o:?}");
    let text = stdout(&o);
    assert!(text.contains("no longer visible"), "{text}");
    assert!(text.trim_end().ends_with("tolerance 1e-9)"), "{text}");
    let (r, code) = diff_json(&b, &a, "0");
    assert_eq!(code, Some(1));
    let kinds: BTreeSet<&str> = r["changes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c["kind"].as_str().unwrap())
        .collect();
    assert!(kinds.contains("added") && kinds.contains("changed"), "{r}");
    // A face on one side only changed by its whole region: relative 1, on both sides of it.
    for (x, y) in [(&a, &b), (&b, &a)] {
        let (r, _) = diff_json(x, y, "0.999");
        let kinds: BTreeSet<&str> = r["changes"]
            .as_array()
            .unwrap()
            .iter()
            .map(|c| c["kind"].as_str().unwrap())
            .collect();
        assert!(kinds.contains("added") || kinds.contains("removed"), "{r}");
        let (r, _) = diff_json(x, y, "1");
        assert!(r["changes"]
            .as_array()
            .unwrap()
            .iter()
            .all(|c| c["kind"] == "changed"));
    }
    // Usage and unreadable input: 2, naming the file and the line.
    let bad = dir.join("bad.json");
    std::fs::write(
        &bad,
        "{\"format\":\"kepler-visible/1\",\n\"faces\":[\n{\"id\":0,]}",
    )
    .unwrap();
    let o = kepler(&["diff", s(&a), s(&bad)]);
    assert_eq!(o.status.code(), Some(2), "{o:?}");
    assert!(stderr(&o).contains("bad.json:3:"), "{o:?}");
    std::fs::write(
        &bad,
        "{\"format\":\"kepler-visible/1\",\n\"faces\":[\n{\"id\":0,\"visible\":[[[1]]]}]}",
    )
    .unwrap();
    let o = kepler(&["diff", s(&bad), s(&a)]);
    assert_eq!(o.status.code(), Some(2), "{o:?}");
    assert!(
        stderr(&o).contains("bad.json:3:1: faces[0] (id 0)"),
        "{o:?}"
    );
    let missing = dir.join("missing.json");
    let o = kepler(&["diff", s(&a), s(&missing)]);
    assert_eq!(o.status.code(), Some(2), "{o:?}");
    assert!(stderr(&o).contains("missing.json"), "{o:?}");
    for args in [
        vec!["diff", s(&a), s(&b), "--tol", "-1"],
        vec!["diff", s(&a), s(&b), "--tol", "nan"],
        vec!["diff", s(&a), s(&b), "--report", "xml"],
        vec!["diff", s(&a)],
        vec!["diff", s(&a), s(&b), "--bogus"],
    ] {
        let o = kepler(&args);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {o:?}");
        assert!(stdout(&o).is_empty(), "{args:?}: {o:?}");
    }
    // The exit statuses are in the help.
    for cmd in ["diff", "check"] {
        let o = kepler(&[cmd, "--help"]);
        assert!(o.status.success());
        assert!(stdout(&o).contains("Exit status: 0 when"), "{cmd}: {o:?}");
    }
}

#[test]
fn check_reports_json_and_counts_faces_in_the_singular() {
    let dir = kepler_testkit::temp_dir("diff", "check");
    let mesh = dir.join("m.obj");
    let golden = dir.join("g.json");
    std::fs::write(&mesh, kepler_testkit::cuboid_obj([0.0; 3], [1.0; 3])).unwrap();
    let check = |more: &[&str]| {
        let mut args = vec![
            "check",
            s(&mesh),
            "--golden",
            s(&golden),
            "--dir",
            "-1,-2,-3",
        ];
        args.extend_from_slice(more);
        kepler(&args)
    };
    let o = check(&["--update"]);
    assert!(o.status.success(), "{o:?}");
    let o = check(&["--report", "json"]);
    assert_eq!(o.status.code(), Some(0), "{o:?}");
    let r: Value = serde_json::from_str(&stdout(&o)).unwrap();
    assert_eq!(
        (r["format"].as_str(), r["changed"].as_u64()),
        (Some("kepler-diff/1"), Some(0))
    );
    assert_eq!(r["compared"].as_u64(), Some(3), "{r}");
    // Stretch the box in x: the faces seen change; the report lists each with every field.
    std::fs::write(&mesh, kepler_testkit::cuboid_obj([0.0; 3], [1.2, 1.0, 1.0])).unwrap();
    let o = check(&["--report", "json"]);
    assert_eq!(o.status.code(), Some(1), "{o:?}");
    let r: Value = serde_json::from_str(&stdout(&o)).unwrap();
    let changes = r["changes"].as_array().unwrap();
    assert!(!changes.is_empty());
    for c in changes {
        for k in [
            "golden_area",
            "current_area",
            "area_delta",
            "xor_area",
            "relative",
        ] {
            assert!(c[k].is_f64(), "{k}: {c}");
        }
        assert_eq!(c["kind"], "changed");
    }
    // A tolerance between the changes: the text lists the one face above it, "1 face changed".
    let mut rel: Vec<f64> = changes
        .iter()
        .map(|c| c["relative"].as_f64().unwrap())
        .collect();
    rel.sort_by(f64::total_cmp);
    assert!(
        rel.len() >= 2 && rel[rel.len() - 2] < rel[rel.len() - 1],
        "{rel:?}"
    );
    let t = (rel[rel.len() - 2] + rel[rel.len() - 1]) / 2.0;
    let o = check(&["--tol", &t.to_string()]);
    assert_eq!(o.status.code(), Some(1), "{o:?}");
    let text = stdout(&o);
    assert_eq!(
        text.lines().filter(|l| l.starts_with("face ")).count(),
        1,
        "{text}"
    );
    let summary = format!("\n1 face changed (of 3 faces compared, tolerance {t:e})\n");
    assert!(text.ends_with(&summary), "{text}");
    // An unreadable golden is a usage error, not a change.
    std::fs::remove_file(&golden).unwrap();
    let o = check(&[]);
    assert_eq!(o.status.code(), Some(2), "{o:?}");
    assert!(stderr(&o).contains("g.json"), "{o:?}");
}
