//! Every malformed mesh file under `tests/fixtures/bad/` is refused with a located error, never a panic;
//! random bytes and truncated good files never panic either.

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::{Path, PathBuf};

use crate::load::mesh_file::{load_mesh, parse_mesh};
use crate::Error;
use kepler_testkit::Rng;

/// The fixture directory `sub` of this crate.
fn fixtures(sub: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures")
        .join(sub)
}

/// The mesh fixtures (names starting `obj_`, `stl_` or `ply_`) in `tests/fixtures/bad/`, sorted.
fn bad_files() -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(fixtures("bad"))
        .expect("tests/fixtures/bad exists")
        .map(|e| e.expect("readable directory entry").path())
        .filter(|p| {
            let name = p.file_name().and_then(|n| n.to_str()).unwrap_or("");
            ["obj_", "stl_", "ply_"]
                .iter()
                .any(|prefix| name.starts_with(prefix))
        })
        .collect();
    files.sort();
    files
}

/// The good fixtures in `tests/fixtures/meshes/`, sorted.
fn good_files() -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(fixtures("meshes"))
        .expect("tests/fixtures/meshes exists")
        .map(|e| e.expect("readable directory entry").path())
        .collect();
    files.sort();
    files
}

#[test]
fn every_bad_mesh_file_is_refused_with_a_position() {
    let files = bad_files();
    assert!(files.len() >= 30, "only {} bad fixtures found", files.len());
    for path in files {
        let result = catch_unwind(|| load_mesh(&path, None, &crate::Progress::default()));
        let Ok(result) = result else {
            panic!("{}: the loader panicked", path.display())
        };
        let Err(e) = result else {
            panic!("{}: loaded without error", path.display())
        };
        let msg = e.to_string();
        let prefix = format!("{}:", path.display());
        assert!(
            msg.starts_with(&prefix),
            "{}: message does not start with the path: {msg}",
            path.display()
        );
        let empty = std::fs::metadata(&path)
            .map(|m| m.len() == 0)
            .unwrap_or(false);
        let rest = &msg[prefix.len()..];
        let has_line_col = {
            let mut parts = rest.splitn(3, ':');
            let line = parts.next().unwrap_or("");
            let col = parts.next().unwrap_or("");
            !line.is_empty()
                && line.bytes().all(|b| b.is_ascii_digit())
                && !col.is_empty()
                && col.bytes().all(|b| b.is_ascii_digit())
        };
        let no_faces = rest.contains("contains no faces");
        assert!(
            empty || no_faces || has_line_col || rest.starts_with(" byte "),
            "{}: the message has no position: {msg}",
            path.display()
        );
        assert!(
            matches!(e, Error::Parse(..) | Error::Invalid(..)),
            "{}: {e:?}",
            path.display()
        );
    }
}

#[test]
fn bad_mesh_files_give_exact_messages() {
    let cases = [
        ("obj_empty.obj", ": empty file"),
        ("obj_nan.obj", ":2:5: coordinate is NaN"),
        ("obj_huge.obj", ":3:7: huge coordinate 1e300"),
        ("obj_index_out_of_range.obj", ":5:7: vertex index 4 is out of range: 3 vertices are defined before this face"),
        ("obj_index_zero.obj", ":4:3: vertex index 0 (OBJ indices start at 1)"),
        ("obj_two_vertex_face.obj", ":4:1: face has 2 vertices; a face needs at least 3"),
        ("obj_garbage.obj", ":3:1: invalid UTF-8 (byte 0xFF)"),
        ("obj_unknown_statement.obj", ":4:1: unknown OBJ statement 'bogus'"),
        ("obj_missing_coord.obj", ":2:6: missing z coordinate"),
        ("obj_bad_number.obj", ":3:5: invalid number '1.0.0'"),
        ("obj_no_faces.obj", ": the file contains no faces"),
        ("obj_binary_data.obj", ":1:82: a NUL byte: not a text file?"),
        ("stl_empty.stl", ": empty file"),
        ("stl_truncated.stl", ": byte 334: file is 351 bytes, header says 12 triangles needing 684: truncated binary STL"),
        ("stl_trailing_bytes.stl", ": byte 684: file is 686 bytes, header says 12 triangles needing 684: trailing bytes"),
        ("stl_header_only.stl", ": byte 0: not an STL file"),
        ("stl_ascii_bad_number.stl", ":6:16: invalid number '1,0'"),
        ("stl_ascii_truncated.stl", ":12:19: unexpected end of file: expected 'vertex' or 'endloop'"),
        ("stl_ascii_missing_endloop.stl", ":7:1: expected 'vertex' or 'endloop', found 'endfacet'"),
        ("stl_nan.stl", ": byte 234: triangle 3, vertex 1, x: coordinate is NaN"),
        ("stl_inf.stl", ": byte 84: triangle 0, vertex 2, y: coordinate is infinite (inf)"),
        ("ply_empty.ply", ": empty file"),
        ("ply_truncated_binary.ply", ": byte 377: unexpected end of file in property 'vertex_indices' of face 5 (of 6) (the file is 378 bytes)"),
        ("ply_truncated_ascii.ply", ":23:9: unexpected end of file: expected property 'vertex_indices' of face 4 (of 6)"),
        ("ply_bad_header.ply", ":5:1: unknown PLY header keyword 'prop'"),
        ("ply_no_end_header.ply", ":10:1: unexpected end of file: the PLY header has no 'end_header'"),
        ("ply_not_ply.ply", ":1:1: not a PLY file: the first line must be 'ply'"),
        ("ply_index_out_of_range.ply", ":23:7: vertex index 8 is out of range: the file has 8 vertices"),
        ("ply_index_out_of_range_be.ply", ": byte 378: vertex index 9 is out of range: the file has 8 vertices"),
        ("ply_unknown_type.ply", ":6:10: unknown PLY type 'float3'"),
        ("ply_missing_z.ply", ":4:1: element 'vertex' has no property 'z'"),
        ("ply_two_vertex_face.ply", ":23:1: face has 2 vertices; a face needs at least 3"),
        ("ply_nan_binary.ply", ": byte 251: coordinate is NaN"),
        ("ply_huge_ascii.ply", ":17:3: huge coordinate 1e13"),
        ("ply_bad_number.ply", ":18:3: invalid number 'one'"),
        ("ply_no_faces_element.ply", ":7:1: the PLY header declares no 'face' element"),
    ];
    let mut failures = Vec::new();
    for (name, want) in cases {
        let path = fixtures("bad").join(name);
        let got = match load_mesh(&path, None, &crate::Progress::default()) {
            Ok(_) => "loaded without error".to_string(),
            Err(e) => e.to_string(),
        };
        let want = format!("{}{want}", path.display());
        if !got.starts_with(&want) {
            failures.push(format!("{name}\n  got:  {got}\n  want: {want}"));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    let listed: Vec<&str> = cases.iter().map(|c| c.0).collect();
    for path in bad_files() {
        let name = path.file_name().and_then(|n| n.to_str()).unwrap_or("");
        assert!(
            listed.contains(&name),
            "{name} has no expected message in this table"
        );
    }
}

/// `n` random bytes.
fn noise_bytes(rng: &mut Rng, n: usize) -> Vec<u8> {
    (0..n).map(|_| (rng.next_u64() >> 56) as u8).collect()
}

/// Parses `bytes` as `name`, failing the test on a panic.
fn no_panic(name: &str, bytes: &[u8], what: &str) {
    let path = Path::new(name);
    if catch_unwind(AssertUnwindSafe(|| {
        parse_mesh(path, bytes, &crate::Progress::default())
    }))
    .is_err()
    {
        panic!(
            "{name}: the loader panicked on {what} ({} bytes: {:?})",
            bytes.len(),
            String::from_utf8_lossy(bytes)
        );
    }
}

#[test]
fn garbage_truncation_and_mutation_never_panic() {
    let mut noise = Rng::new(0x9e37_79b9_7f4a_7c15);
    for ext in ["obj", "stl", "ply"] {
        let name = format!("noise.{ext}");
        for n in [0, 1, 5, 83, 84, 85, 134, 200, 1000] {
            let b = noise_bytes(&mut noise, n);
            no_panic(&name, &b, "random bytes");
        }
    }
    for path in good_files() {
        let bytes = std::fs::read(&path).expect("readable fixture");
        let name = path.to_string_lossy().into_owned();
        assert!(
            parse_mesh(&path, &bytes, &crate::Progress::default()).is_ok(),
            "{name} should load"
        );
        for cut in 0..bytes.len() {
            no_panic(&name, &bytes[..cut], "a truncated prefix");
        }
        for _ in 0..2000 {
            let mut b = bytes.clone();
            for _ in 0..1 + noise.next_u64() % 4 {
                let i = (noise.next_u64() % b.len() as u64) as usize;
                b[i] = match noise.next_u64() % 4 {
                    0 => (noise.next_u64() >> 56) as u8,
                    1 => b'\n',
                    2 => b' ',
                    _ => b"0123456789-.e/"[(noise.next_u64() % 14) as usize],
                };
            }
            no_panic(&name, &b, "a mutated copy");
        }
    }
}
