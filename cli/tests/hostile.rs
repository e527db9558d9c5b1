//! Hostile and odd input through the `kepler` binary (issue 16): every case of
//! `tests/fixtures/bad/hostile_*` and every odd flag ends in a clear answer — an error that
//! names the file and line (exit 1), or a result with a warning that says why it is empty —
//! and never in a panic, a crash by signal, a hang or a silent empty success. Times are
//! measured by `kepler-bench --hostile`, not here.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The fixture directory; commands run there so that messages name files as given.
fn bad() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../tests/fixtures/bad")
}

/// A fresh directory for one test.
fn temp_dir(name: &str) -> PathBuf {
    kepler_testkit::temp_dir("hostile", name)
}

/// Runs kepler in the fixture directory.
fn kepler(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_kepler"))
        .current_dir(bad())
        .args(args)
        .output()
        .unwrap()
}

/// Runs kepler and checks its exit code and that standard error holds every one of `says`.
fn expect(args: &[&str], code: i32, says: &[&str]) -> String {
    let o = kepler(args);
    let err = String::from_utf8_lossy(&o.stderr).to_string();
    assert_eq!(o.status.code(), Some(code), "kepler {args:?}:\n{err}");
    for s in says {
        assert!(err.contains(s), "kepler {args:?}: no {s:?} in:\n{err}");
    }
    assert!(!err.contains("panicked"), "kepler {args:?}:\n{err}");
    err
}

/// The one error line of a failed run, which must start with `at` (file:line:col).
fn error_at(args: &[&str], at: &str, says: &str) {
    let err = expect(args, 1, &[says]);
    let first = err.lines().next().unwrap_or("");
    assert!(
        first.starts_with(&format!("error: {at}")),
        "kepler {args:?}: expected error at {at}:\n{err}"
    );
}

#[test]
fn deep_nesting_is_an_error_not_a_stack_overflow() {
    for f in [
        "hostile_deep_slashdash.kdl",
        "hostile_deep_slashdash_args.kdl",
        "hostile_deep_blocks.kdl",
    ] {
        error_at(&["info", f], &format!("{f}:2:"), "nested more than 64 deep");
    }
    // Comments nested 10,000 deep are only a comment.
    expect(&["info", "hostile_deep_comment.kdl"], 0, &[]);
}

#[test]
fn instancing_bombs_are_refused_from_the_counts() {
    error_at(
        &["info", "hostile_instance_bomb.kdl"],
        "hostile_instance_bomb.kdl:82:1",
        "prototype \"p21\" has 12582912 faces once its instances are placed (prototype chain: p20 (6291456 faces) > p19",
    );
    error_at(
        &["info", "hostile_instance_bomb.kdl", "--max-faces", "100"],
        "hostile_instance_bomb.kdl:18:1",
        "more than the limit of 100 (--max-faces)",
    );
    error_at(
        &["render", "hostile_instance_bomb.kdl", "--json", "/dev/null"],
        "hostile_instance_bomb.kdl:82:1",
        "(--max-faces)",
    );
}

#[test]
fn meshes_that_are_not_files_name_the_scene_line() {
    error_at(
        &["info", "hostile_mesh_dot.kdl"],
        "hostile_mesh_dot.kdl:3:5",
        "unknown mesh file extension",
    );
    error_at(
        &["info", "hostile_mesh_dev_zero.kdl"],
        "hostile_mesh_dev_zero.kdl:3:5",
        "/dev/zero",
    );
    error_at(
        &["info", "hostile_include_dir.kdl"],
        "hostile_include_dir.kdl:2:1",
        "it is a directory, not a file",
    );
    // A directory and a device that carry a mesh extension.
    let d = temp_dir("mesh-not-file");
    std::fs::create_dir(d.join("dir.obj")).unwrap();
    std::os::unix::fs::symlink("/dev/zero", d.join("zero.stl")).unwrap();
    for (mesh, says) in [
        ("dir.obj", "is a directory, not a file"),
        ("zero.stl", "it is not a regular file"),
    ] {
        let scene = d.join(format!("{mesh}.kdl"));
        std::fs::write(
            &scene,
            format!("object \"a\" {{\n    mesh \"{mesh}\"\n}}\n"),
        )
        .unwrap();
        let s = scene.to_str().unwrap();
        error_at(&["info", s], &format!("{s}:2:5"), says);
    }
}

#[test]
fn errors_name_the_line_through_include_and_mesh_chains() {
    error_at(
        &["info", "hostile_chain.kdl"],
        "hostile_chain.kdl:2:1 -> hostile_chain_part.kdl:3:5 -> hostile_chain_mesh.obj:4:7",
        "invalid vertex reference 'x'",
    );
}

#[test]
fn an_explicit_inbox_outside_its_object_is_an_error_at_its_line() {
    error_at(
        &["info", "hostile_bad_inbox.kdl"],
        "hostile_bad_inbox.kdl:4:5",
        "is not inside",
    );
}

#[test]
fn empty_results_say_why() {
    let d = temp_dir("empty");
    let json = d.join("o.json");
    let j = json.to_str().unwrap();
    expect(
        &["render", "hostile_only_degenerate.obj", "--json", j],
        0,
        &[
            "hostile_only_degenerate.obj:4:1: face has zero area; dropped",
            "hostile_only_degenerate.obj: the scene has no faces",
        ],
    );
    expect(
        &["render", "hostile_tiny_box.kdl", "--json", j],
        0,
        &[
            "hostile_tiny_box.kdl:2:5: face has zero area",
            "the scene has no faces",
        ],
    );
    expect(
        &["render", "hostile_behind.kdl", "--json", j],
        0,
        &["hostile_behind.kdl: nothing is visible: all 6 faces are behind the camera"],
    );
    expect(
        &[
            "render",
            "hostile_cam.kdl",
            "--json",
            j,
            "--eye",
            "100,0,0",
            "--target",
            "100,0,10",
        ],
        0,
        &["nothing visible lies in the camera's field of view"],
    );
    // A picture that shows something says nothing.
    let err = expect(&["render", "hostile_cam.kdl", "--json", j], 0, &[]);
    assert!(err.is_empty(), "{err}");
}

#[test]
fn no_output_asked_for_is_an_error() {
    expect(
        &["render", "hostile_cam.kdl"],
        1,
        &["nothing to write: give --json F, --svg F or --png F"],
    );
}

#[test]
fn narrow_fields_of_view_are_errors_not_nan() {
    for fov in ["1e-300", "1e-153", "1e-150"] {
        expect(
            &[
                "render",
                "hostile_cam.kdl",
                "--json",
                "/dev/null",
                "--fov",
                fov,
            ],
            1,
            &["field of view of", "is too narrow"],
        );
    }
    // Narrow but representable: finite JSON.
    let d = temp_dir("fov");
    let json = d.join("o.json");
    let j = json.to_str().unwrap();
    expect(
        &["render", "hostile_cam.kdl", "--json", j, "--fov", "1e-20"],
        0,
        &[],
    );
    let text = std::fs::read_to_string(&json).unwrap();
    let v: serde_json::Value = serde_json::from_str(&text).expect("valid JSON");
    assert!(!v["faces"].as_array().unwrap().is_empty());
}

/// The camera matrix a render wrote.
fn matrix(args: &[&str], out: &Path) -> serde_json::Value {
    let mut all = args.to_vec();
    all.extend(["--json", out.to_str().unwrap()]);
    expect(&all, 0, &[]);
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out).unwrap()).unwrap();
    v["camera"].clone()
}

#[test]
fn camera_flags_are_applied_or_refused_never_ignored() {
    let d = temp_dir("camera");
    let out = d.join("o.json");
    let own = matrix(&["render", "hostile_cam.kdl"], &out);
    assert_eq!(own["projection"], "perspective");
    let narrow = matrix(&["render", "hostile_cam.kdl", "--fov", "10"], &out);
    let f = |c: &serde_json::Value| c["matrix"][0][0].as_f64().unwrap().abs();
    assert!(
        f(&narrow) > 2.0 * f(&own),
        "--fov alone narrows the scene's camera"
    );
    let ortho = matrix(&["render", "hostile_cam.kdl", "--ortho"], &out);
    assert_eq!(ortho["projection"], "orthographic");
    expect(
        &[
            "render",
            "hostile_cam.kdl",
            "--json",
            "/dev/null",
            "--dir",
            "1,0,0",
            "--eye",
            "0,0,5",
        ],
        1,
        &["--dir is an orthographic view of its own"],
    );
    // Negative numbers are values, refused by range.
    for (flag, says) in [
        ("--fov", "--fov -5: expected degrees between 0 and 180"),
        ("--lod", "--lod -5: expected a number of pixels, 0 or more"),
        (
            "--crease",
            "--crease -5: expected degrees between 0 and 180",
        ),
    ] {
        expect(
            &[
                "render",
                "hostile_cam.kdl",
                "--json",
                "/dev/null",
                flag,
                "-5",
            ],
            1,
            &[says],
        );
    }
    // Flags are checked before the scene is loaded (this scene would fail to load).
    expect(
        &[
            "render",
            "hostile_instance_bomb.kdl",
            "--json",
            "/dev/null",
            "--fov",
            "-5",
        ],
        1,
        &["--fov -5: expected degrees between 0 and 180"],
    );
    // A direction whose length overflows still has a direction.
    let huge = matrix(
        &["render", "hostile_cam.kdl", "--dir", "1e308,1e308,1e308"],
        &out,
    );
    let unit = matrix(&["render", "hostile_cam.kdl", "--dir", "1,1,1"], &out);
    assert_eq!(huge, unit);
    // One default field of view (45 degrees) for an eye on the command line and in files.
    let eye = matrix(
        &[
            "render",
            "hostile_behind.kdl",
            "--eye",
            "0,0,5",
            "--target",
            "0,0,0",
        ],
        &out,
    );
    let f45 = 1.0 / (22.5f64).to_radians().tan();
    assert!((f(&eye) - f45).abs() < 1e-12, "{eye}");
}

#[test]
fn numbers_and_encodings_are_named() {
    error_at(
        &["info", "hostile_number_overflow.kdl"],
        "hostile_number_overflow.kdl:2:19",
        "number 1e400 is out of range",
    );
    error_at(
        &["info", "hostile_kdl_v1.kdl"],
        "hostile_kdl_v1.kdl:4:11",
        "bare `true` is KDL v1; scene files are KDL v2, where it is written #true",
    );
    error_at(
        &["info", "hostile_utf16_no_bom.kdl"],
        "hostile_utf16_no_bom.kdl:1:",
        "not UTF-8",
    );
    error_at(
        &["info", "hostile_stl_five_vertices.stl"],
        "hostile_stl_five_vertices.stl:7:1",
        "an ASCII STL facet is a triangle",
    );
}

#[test]
fn cr_only_line_ends_read_as_lines() {
    let out = kepler(&["info", "hostile_cr_only.obj", "--json"]);
    assert!(out.status.success(), "{out:?}");
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["faces"], 1, "{v}");
}

#[test]
fn a_failed_render_leaves_the_old_output_in_place() {
    let d = temp_dir("atomic");
    let json = d.join("o.json");
    std::fs::write(&json, "good").unwrap();
    let j = json.to_str().unwrap();
    expect(&["render", "hostile_bad_inbox.kdl", "--json", j], 1, &[]);
    assert_eq!(std::fs::read_to_string(&json).unwrap(), "good");
    expect(&["render", "hostile_cam.kdl", "--json", j], 0, &[]);
    assert!(std::fs::read_to_string(&json).unwrap().starts_with('{'));
    assert_eq!(
        std::fs::read_dir(&d).unwrap().count(),
        1,
        "no temporary left"
    );
}
