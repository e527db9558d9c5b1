//! Views end to end: `--up auto` on real and rotated meshes, `--view` presets, perspective
//! drawings inside the margin, `--sheet`, `--shard`, small pages and flag spellings.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Output;

use kepler_testkit::cuboid_obj;

use super::common::{kepler, s};

fn temp_dir(name: &str) -> PathBuf {
    kepler_testkit::temp_dir("views", name)
}

fn ok(args: &[&str]) -> Output {
    let o = kepler(args);
    assert!(o.status.success(), "{args:?}: {o:?}");
    o
}

fn json(p: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(p).unwrap()).unwrap()
}

/// `kepler info --json`'s up vector.
fn info_up(mesh: &Path) -> [f64; 3] {
    let o = ok(&["info", "-q", "--json", s(mesh)]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let u = &v["up"]["vector"];
    [0, 1, 2].map(|k| u[k].as_f64().unwrap())
}

/// Row `r` of a JSON camera matrix, first three columns.
fn row(j: &serde_json::Value, r: usize) -> [f64; 3] {
    [0, 1, 2].map(|k| j["camera"]["matrix"][r][k].as_f64().unwrap())
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Sum of the visible areas of a kepler-visible/1 file.
fn total_area(j: &serde_json::Value) -> f64 {
    j["faces"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| f["area"].as_f64().unwrap())
        .sum()
}

/// The mesh `src` (OBJ) with every vertex mapped by `f`.
fn mapped_obj(src: &Path, dst: &Path, f: impl Fn([f64; 3]) -> [f64; 3]) {
    let text = std::fs::read_to_string(src).unwrap();
    let out: Vec<String> = text
        .lines()
        .map(|l| match l.strip_prefix("v ") {
            Some(rest) => {
                let c: Vec<f64> = rest
                    .split_whitespace()
                    .take(3)
                    .map(|t| t.parse().unwrap())
                    .collect();
                let p = f([c[0], c[1], c[2]]);
                format!("v {:?} {:?} {:?}", p[0], p[1], p[2])
            }
            None => l.to_string(),
        })
        .collect();
    std::fs::write(dst, out.join("\n")).unwrap();
}

#[test]
fn real_meshes_stand_upright_with_no_flags() {
    let d = temp_dir("upright");
    if let Some(nef) = kepler_testkit::model("nefertiti.obj") {
        assert_eq!(info_up(&nef), [0., 0., 1.], "nefertiti is Z-up");
    }
    let Some(bunny) = kepler_testkit::model("stanford-bunny.obj") else {
        return;
    };
    assert_eq!(info_up(&bunny), [0., 1., 0.], "the bunny is Y-up");
    // The same bunny exported Z-up: (x, y, z) -> (x, -z, y), exact in binary.
    let zup = d.join("bunny-z.obj");
    mapped_obj(&bunny, &zup, |[x, y, z]| [x, -z, y]);
    assert_eq!(info_up(&zup), [0., 0., 1.]);
    let (a, b) = (d.join("y.json"), d.join("z.json"));
    ok(&["render", "-q", s(&bunny), "--json", s(&a)]);
    ok(&["render", "-q", s(&zup), "--json", s(&b)]);
    let (ja, jb) = (json(&a), json(&b));
    // Screen up is the model's up, screen x level with the ground, in both.
    for (j, up) in [(&ja, [0., 1., 0.]), (&jb, [0., 0., 1.])] {
        assert!(dot(row(j, 1), up) > 0.8, "{:?}", row(j, 1));
        assert_eq!(dot(row(j, 0), up), 0.0);
    }
    // ... and it is the same picture: the rotated bunny's camera is the first one turned.
    let (ta, tb) = (total_area(&ja), total_area(&jb));
    assert!((ta - tb).abs() <= 1e-9 * ta, "{ta} vs {tb}");
    // (A face or two of rounding-sized area may come or go.)
    let (na, nb) = (
        ja["faces"].as_array().unwrap().len(),
        jb["faces"].as_array().unwrap().len(),
    );
    assert!(na.abs_diff(nb) <= na / 1000, "{na} vs {nb} faces");
}

#[test]
fn auto_up_is_the_default_only_without_a_camera_or_flags() {
    let d = temp_dir("auto-default");
    // A tower, Z-up: auto stands it on its end; --dir keeps +Y; --up auto applies anyway.
    let tower = d.join("tower.obj");
    std::fs::write(&tower, cuboid_obj([0., 0., 0.], [1., 1., 5.])).unwrap();
    assert_eq!(info_up(&tower), [0., 0., 1.]);
    let j = d.join("t.json");
    ok(&["render", "-q", s(&tower), "--json", s(&j)]);
    assert_eq!(row(&json(&j), 0)[2], 0.0, "screen x level");
    assert!(row(&json(&j), 1)[2] > 0.8, "screen up along +Z");
    ok(&[
        "render",
        "-q",
        s(&tower),
        "--json",
        s(&j),
        "--dir",
        "-1,-1,-1",
    ]);
    assert_eq!(row(&json(&j), 0)[1], 0.0, "--dir alone: +Y up");
    ok(&[
        "render",
        "-q",
        s(&tower),
        "--json",
        s(&j),
        "--dir",
        "-1,-1,-1",
        "--up",
        "auto",
    ]);
    assert_eq!(row(&json(&j), 0)[2], 0.0, "--up auto: +Z up");
    // A scene with a camera keeps its own up.
    let scene = d.join("s.kdl");
    std::fs::write(
        &scene,
        format!(
            "camera {{ dir -1 -1 -1; up 1 0 0 }}\nobject \"t\" {{ mesh \"{}\" }}\n",
            s(&tower)
        ),
    )
    .unwrap();
    let o = ok(&["info", "-q", s(&scene)]);
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(text.contains("up: +X (the scene camera's)"), "{text}");
}

#[test]
fn named_views_relative_to_the_up() {
    let d = temp_dir("named");
    let m = d.join("box.obj");
    std::fs::write(&m, cuboid_obj([0., 0., 0.], [3., 1., 2.])).unwrap();
    let j = d.join("v.json");
    let view = |name: &str, up: &str| {
        ok(&[
            "render",
            "-q",
            s(&m),
            "--json",
            s(&j),
            "--view",
            name,
            "--up",
            up,
        ]);
        let v = json(&j);
        (row(&v, 0), row(&v, 1), row(&v, 2))
    };
    // Z-up: front looks along +Y (from -Y), x right, z up.
    assert_eq!(
        view("front", "0,0,1"),
        ([1., 0., 0.], [0., 0., 1.], [0., -1., 0.])
    );
    assert_eq!(
        view("top", "0,0,1"),
        ([1., 0., 0.], [0., 1., 0.], [0., 0., 1.])
    );
    assert_eq!(
        view("right", "0,0,1"),
        ([0., 1., 0.], [0., 0., 1.], [1., 0., 0.])
    );
    // Y-up: front looks along -Z.
    assert_eq!(
        view("front", "0,1,0"),
        ([1., 0., 0.], [0., 1., 0.], [0., 0., 1.])
    );
    assert_eq!(view("left", "0,1,0").2, [-1., 0., 0.]);
    assert_eq!(view("bottom", "0,1,0").2, [0., -1., 0.]);
    let iso = view("iso", "0,1,0").2;
    assert!(iso.iter().all(|c| (c - 3f64.sqrt().recip()).abs() < 1e-15));
    // A camera of its own: no --dir with it.
    let o = kepler(&[
        "render",
        s(&m),
        "--json",
        s(&j),
        "--view",
        "top",
        "--dir",
        "1,0,0",
    ]);
    assert_eq!(o.status.code(), Some(2), "{o:?}");
    assert!(String::from_utf8_lossy(&o.stderr).contains("cannot be used with"));
}

/// Every coordinate of the SVG's paths, moved by the translate of its group.
fn svg_points(svg: &str) -> Vec<[f64; 2]> {
    let mut out = Vec::new();
    let mut shift = vec![[0.0, 0.0]];
    for line in svg.lines() {
        let t = line.trim();
        if let Some(rest) = t.strip_prefix("<g transform=\"translate(") {
            let nums: Vec<f64> = rest
                .split(')')
                .next()
                .unwrap()
                .split(' ')
                .map(|v| v.parse().unwrap())
                .collect();
            shift.push([nums[0], nums[1]]);
            continue;
        }
        if t.starts_with("<g") {
            shift.push([0.0, 0.0]);
        }
        if t == "</g>" {
            shift.pop();
        }
        if let Some(i) = t.find(" d=\"") {
            let dx: f64 = shift.iter().map(|s| s[0]).sum();
            let dy: f64 = shift.iter().map(|s| s[1]).sum();
            let d = &t[i + 4..];
            let d = &d[..d.find('"').unwrap()];
            for pair in d.split(['M', 'L']).filter(|p| !p.is_empty()) {
                let (x, y) = pair.split_once(',').unwrap();
                out.push([
                    x.parse::<f64>().unwrap() + dx,
                    y.parse::<f64>().unwrap() + dy,
                ]);
            }
        }
    }
    out
}

fn clipped_mm(o: &Output) -> f64 {
    let err = String::from_utf8_lossy(&o.stderr);
    let tail = err
        .split("clipped away ")
        .nth(1)
        .expect("--stats plot line");
    tail.split_whitespace().next().unwrap().parse().unwrap()
}

#[test]
fn perspective_drawings_fit_inside_the_margin() {
    let d = temp_dir("persp-fit");
    // A wide bar close to the eye: it spans far beyond the field of view's 1.6:1 screen.
    let m = d.join("bar.obj");
    std::fs::write(&m, cuboid_obj([-3., -0.5, -0.5], [3., 0.5, 0.5])).unwrap();
    let svg = d.join("p.svg");
    let o = ok(&[
        "render",
        "-q",
        s(&m),
        "--svg",
        s(&svg),
        "--eye",
        "0.5,1,3",
        "--target",
        "0,0,0",
        "--page",
        "a4",
        "--stats",
    ]);
    assert_eq!(clipped_mm(&o), 0.0, "nothing cut away");
    if std::path::Path::new("/proc/self/task").exists() {
        // Each stage's CPU time and serial share, and the run's.
        let err = String::from_utf8_lossy(&o.stderr);
        let visibility = err.lines().find(|l| l.starts_with("time visibility"));
        assert!(
            visibility.is_some_and(|l| l.contains(" cpu ") && l.ends_with('%')),
            "{err}"
        );
        assert!(
            err.contains("serial share of the stages' wall time: "),
            "{err}"
        );
    }
    let pts = svg_points(&std::fs::read_to_string(&svg).unwrap());
    assert!(pts.len() > 5);
    let eps = 1e-9;
    for p in &pts {
        assert!(
            p[0] >= 10.0 - eps && p[0] <= 200.0 + eps && p[1] >= 10.0 - eps && p[1] <= 287.0 + eps,
            "{p:?} outside the margin"
        );
    }
    // It fills the margin box across (width-limited on portrait A4).
    let (x0, x1) = pts
        .iter()
        .fold((f64::MAX, f64::MIN), |(a, b), p| (a.min(p[0]), b.max(p[0])));
    assert!(
        (x0 - 10.0).abs() < 1e-6 && (x1 - 200.0).abs() < 1e-6,
        "{x0} {x1}"
    );
    if let Some(teapot) = kepler_testkit::model("teapot.obj") {
        let o = ok(&[
            "render",
            "-q",
            s(&teapot),
            "--svg",
            s(&svg),
            "--eye",
            "3,2,4",
            "--page",
            "a4",
            "--stats",
        ]);
        assert_eq!(clipped_mm(&o), 0.0, "the spout is whole");
    }
}

#[test]
fn a_sheet_lays_out_views_in_cells() {
    let d = temp_dir("sheet");
    let m = d.join("box.obj");
    std::fs::write(&m, cuboid_obj([0., 0., 0.], [3., 1., 2.])).unwrap();
    let views = d.join("views.txt");
    std::fs::write(
        &views,
        "--view front\n--view right\n--view top\n--eye 6,5,8 --target 1.5,0.5,1\n",
    )
    .unwrap();
    let (svg, png, j) = (d.join("s.svg"), d.join("s.png"), d.join("s.json"));
    ok(&[
        "render",
        "-q",
        s(&m),
        "--views",
        s(&views),
        "--sheet",
        "2x2",
        "--page",
        "a4",
        "--landscape",
        "--svg",
        s(&svg),
        "--png",
        s(&png),
        "--json",
        s(&j),
        "--dpi",
        "50",
    ]);
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(text.starts_with("<svg height=\"210mm\" viewBox=\"0 0 297 210\" width=\"297mm\""));
    assert_eq!(
        text.matches("id=\"layer1\"").count(),
        1,
        "one layer per pen"
    );
    assert!(text.matches("<g transform").count() >= 4);
    // Every line lies inside its own cell's margin box, and every cell has lines.
    let (cw, ch) = (297.0 / 2.0, 210.0 / 2.0);
    let mut per_cell: BTreeMap<(i32, i32), (f64, f64)> = BTreeMap::new();
    for p in svg_points(&text) {
        let (c, r) = ((p[0] / cw).floor(), (p[1] / ch).floor());
        let (x, y) = (p[0] - c * cw, p[1] - r * ch);
        assert!(x >= 10.0 - 1e-9 && x <= cw - 10.0 + 1e-9, "{p:?}");
        assert!(y >= 10.0 - 1e-9 && y <= ch - 10.0 + 1e-9, "{p:?}");
        let e = per_cell
            .entry((r as i32, c as i32))
            .or_insert((f64::MAX, f64::MIN));
        *e = (e.0.min(x), e.1.max(x));
    }
    assert_eq!(per_cell.len(), 4, "{per_cell:?}");
    // One scale: the front (cell 1) and the top (cell 3) both show the box's 3 along X.
    let width = |k: (i32, i32)| per_cell[&k].1 - per_cell[&k].0;
    assert!(width((0, 0)) > 20.0);
    assert!((width((0, 0)) - width((1, 0))).abs() < 1e-6, "{per_cell:?}");
    // No numbered pictures, numbered JSON per view; the PNG is the page at 50 dpi.
    assert!(!d.join("s-001.svg").exists() && d.join("s-004.json").exists());
    let img = image::open(&png).unwrap();
    assert_eq!((img.width(), img.height()), (585, 413));
    // More views than cells, and a sheet of one view, are refused.
    let o = kepler(&[
        "render",
        s(&m),
        "--turntable",
        "5",
        "--sheet",
        "2x2",
        "--svg",
        s(&svg),
    ]);
    assert!(
        String::from_utf8_lossy(&o.stderr).contains("4 cells for 5 views"),
        "{o:?}"
    );
    let o = kepler(&["render", s(&m), "--sheet", "2x2", "--svg", s(&svg)]);
    assert!(!o.status.success());
}

/// The files of a folder and their bytes.
fn files(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| {
            let p = e.unwrap().path();
            (
                p.file_name().unwrap().to_string_lossy().into_owned(),
                std::fs::read(&p).unwrap(),
            )
        })
        .collect()
}

#[test]
fn shards_together_make_the_whole_run() {
    let d = temp_dir("shard");
    let m = d.join("box.obj");
    std::fs::write(&m, cuboid_obj([0., 0., 0.], [3., 1., 2.])).unwrap();
    let views = d.join("views.txt");
    std::fs::write(&views, "--view front\n--view top\n--dir -1,-2,-3\n").unwrap();
    for (what, flag, n) in [
        ("turntable", "--turntable", "7"),
        ("views", "--views", s(&views)),
    ] {
        let (whole, parts) = (
            d.join(format!("{what}-whole")),
            d.join(format!("{what}-parts")),
        );
        std::fs::create_dir_all(&whole).unwrap();
        std::fs::create_dir_all(&parts).unwrap();
        let outs = |dir: &Path| {
            [
                "--json".to_string(),
                s(&dir.join("a.json")).to_string(),
                "--svg".into(),
                s(&dir.join("a.svg")).into(),
            ]
        };
        let mut args = vec!["render", "-q", s(&m), flag, n];
        let o = outs(&whole);
        args.extend(o.iter().map(String::as_str));
        ok(&args);
        for i in 1..=3 {
            let shard = format!("{i}/3");
            let mut args = vec!["render", "-q", s(&m), flag, n, "--shard", &shard];
            let o = outs(&parts);
            args.extend(o.iter().map(String::as_str));
            ok(&args);
        }
        let (a, b) = (files(&whole), files(&parts));
        assert!(a.len() >= 6, "{what}: {:?}", a.keys());
        assert_eq!(a, b, "{what}: the union of the shards is the whole run");
    }
    // Shard 2 of 3 of a 7-view turntable: views 2 and 5 (strided).
    let one = d.join("one");
    std::fs::create_dir_all(&one).unwrap();
    ok(&[
        "render",
        "-q",
        s(&m),
        "--turntable",
        "7",
        "--shard",
        "2/3",
        "--svg",
        s(&one.join("a.svg")),
    ]);
    let names: Vec<String> = files(&one).into_keys().collect();
    assert_eq!(names, ["a-002.svg", "a-005.svg"]);
    for bad in ["0/3", "4/3", "1", "a/b"] {
        let o = kepler(&[
            "render",
            s(&m),
            "--turntable",
            "3",
            "--shard",
            bad,
            "--svg",
            "x.svg",
        ]);
        assert!(!o.status.success(), "{bad}");
    }
    let o = kepler(&["render", s(&m), "--shard", "1/2", "--svg", "x.svg"]);
    assert!(String::from_utf8_lossy(&o.stderr).contains("--turntable N or --views FILE"));
}

#[test]
fn small_pages_and_flag_spellings() {
    let d = temp_dir("gaps");
    let m = d.join("box.obj");
    std::fs::write(&m, cuboid_obj([0., 0., 0.], [3., 1., 2.])).unwrap();
    let svg = d.join("a.svg");
    for (page, land, head) in [
        (
            "a5",
            false,
            "height=\"210mm\" viewBox=\"0 0 148 210\" width=\"148mm\"",
        ),
        (
            "a6",
            false,
            "height=\"148mm\" viewBox=\"0 0 105 148\" width=\"105mm\"",
        ),
        (
            "A6",
            true,
            "height=\"105mm\" viewBox=\"0 0 148 105\" width=\"148mm\"",
        ),
    ] {
        let mut args = vec!["render", "-q", s(&m), "--svg", s(&svg), "--page", page];
        if land {
            args.push("--landscape");
        }
        ok(&args);
        let text = std::fs::read_to_string(&svg).unwrap();
        assert!(
            text.starts_with(&format!("<svg {head}")),
            "{page}: {}",
            &text[..120]
        );
    }
    // A swapped pair of letters gets clap's tip.
    let o = kepler(&["render", s(&m), "--sgv", s(&svg)]);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("a similar argument exists: '--svg'"), "{err}");
    let help = String::from_utf8_lossy(&ok(&["render", "--help"]).stdout).into_owned();
    assert!(
        help.contains("[default: feature]"),
        "--edges shows its default"
    );
    // flatten and tribox take -o, --output and --out alike.
    for flag in ["-o", "--output", "--out"] {
        ok(&["flatten", "-q", s(&m), flag, s(&d.join("f.obj"))]);
        ok(&[
            "tribox",
            "-q",
            s(&m),
            "--levels",
            "1",
            flag,
            s(&d.join("t")),
        ]);
    }
}
