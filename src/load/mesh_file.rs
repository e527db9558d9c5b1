//! The loaders' shared output (named groups of polygon meshes) and dispatch on the file extension.

use std::path::{Path, PathBuf};

use crate::error::{Error, Location, Pos, Result};
use crate::geom::{PolyMesh, MAX_COORD};
use crate::progress::{Phase, Progress, Stage};

/// One named group of faces from a mesh file (an OBJ `o`/`g` group, or the whole file).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct MeshGroup {
    /// The group's name: the OBJ `o`/`g` name, or the file stem.
    pub name: String,
    /// The group's vertices and faces (polygons are kept, never triangulated).
    pub mesh: PolyMesh,
    /// Source position of each face (parallel to `mesh.faces`), for later warnings.
    pub face_pos: Vec<Pos>,
}

impl MeshGroup {
    /// An empty group with the given name.
    pub(crate) fn new(name: impl Into<String>) -> Self {
        MeshGroup {
            name: name.into(),
            mesh: PolyMesh::default(),
            face_pos: Vec::new(),
        }
    }
}

/// The contents of one mesh file: its groups, in file order.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct MeshFile {
    /// The file the meshes came from.
    pub path: PathBuf,
    /// The groups of faces, in file order; never empty, and every group has faces.
    pub groups: Vec<MeshGroup>,
}

impl MeshFile {
    /// Frees the file's groups, their faces' corner lists on all threads (a million
    /// faces' lists take as long to free as to make).
    pub(crate) fn free(self) {
        for g in self.groups {
            crate::chunked::drop_all(g.mesh.faces);
        }
    }
}

/// The mesh formats, told apart by file extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Format {
    Obj,
    Stl,
    Ply,
}

/// `path`'s extension in lower case ("" when it has none).
pub(crate) fn extension(path: &Path) -> String {
    path.extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase()
}

/// The format named by `path`'s extension (case-insensitive), or a usage error naming the file.
fn format_of(path: &Path) -> Result<Format> {
    match extension(path).as_str() {
        "obj" => Ok(Format::Obj),
        "stl" => Ok(Format::Stl),
        "ply" => Ok(Format::Ply),
        _ => Err(Error::Usage(format!(
            "{}: unknown mesh file extension (expected .obj, .stl or .ply)",
            path.display()
        ))),
    }
}

/// Reads and parses the mesh file at `path`, choosing the format by its extension
/// (`.obj`, `.stl`, `.ply`, case-insensitive).
///
/// # Errors
/// [`Error::Usage`] for an unknown extension, [`Error::Io`] if the file cannot be read, and the
/// format parser's [`Error::Parse`] or [`Error::Invalid`] (with the position) for bad contents.
///
/// `at` is the node that asked for it (a scene file's `mesh` node), where an unknown
/// extension, a missing file, a directory or a device is reported (None: the file itself).
/// The load's phases [`Phase::Read`] and [`Phase::Parse`] count bytes in `progress`.
pub(crate) fn load_mesh(
    path: &Path,
    at: Option<&Location>,
    progress: &Progress,
) -> Result<MeshFile> {
    if let (Err(e), Some(at)) = (format_of(path), at) {
        return Err(Error::invalid(at.clone(), e.to_string()));
    }
    format_of(path)?;
    let bytes = super::read::read_mesh_bytes(path, at, progress)?;
    parse_mesh(path, &bytes, progress)
}

/// Parses mesh file contents already in memory; `path` picks the format by its extension
/// and names the file in messages.
///
/// # Errors
/// As [`load_mesh`], without I/O errors; an empty input is [`Error::Invalid`].
///
/// The load's phase [`Phase::Parse`], counting the bytes parsed in `progress`.
pub(crate) fn parse_mesh(path: &Path, bytes: &[u8], progress: &Progress) -> Result<MeshFile> {
    let format = format_of(path)?;
    if bytes.is_empty() {
        return Err(Error::invalid(Location::file(path), "empty file"));
    }
    progress.enter_phase(Stage::Load, Phase::Parse, bytes.len());
    match format {
        Format::Obj => super::obj::parse_obj(path, bytes, progress.count()),
        Format::Stl => super::stl::parse_stl(path, bytes, progress.count()),
        Format::Ply => super::ply::parse_ply(path, bytes, progress.count()),
    }
}

/// The file's groups as a [`MeshFile`], dropping groups without faces; an error if no face is left.
pub(crate) fn finish(path: &Path, mut groups: Vec<MeshGroup>) -> Result<MeshFile> {
    groups.retain(|g| !g.mesh.faces.is_empty());
    if groups.is_empty() {
        return Err(Error::invalid(
            Location::file(path),
            "the file contains no faces",
        ));
    }
    Ok(MeshFile {
        path: path.to_path_buf(),
        groups,
    })
}

/// The default group name for a file: its stem.
pub(crate) fn stem_name(path: &Path) -> String {
    match path.file_stem() {
        Some(s) => s.to_string_lossy().into_owned(),
        None => "mesh".to_string(),
    }
}

/// What is wrong with coordinate `v`, if anything: NaN, infinite, or beyond [`MAX_COORD`].
pub(crate) fn coord_problem(v: f64) -> Option<String> {
    if v.is_nan() {
        Some("coordinate is NaN".to_string())
    } else if v.is_infinite() {
        Some(format!("coordinate is infinite ({v})"))
    } else if v.abs() > MAX_COORD {
        Some(format!(
            "huge coordinate {v:e} (the limit is {MAX_COORD:e})"
        ))
    } else {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn load_unknown_extension_is_usage_error_naming_file() {
        let e =
            parse_mesh(Path::new("dir/x.dxf"), b"abc", &crate::Progress::default()).unwrap_err();
        assert!(matches!(e, Error::Usage(_)));
        assert!(
            e.to_string()
                .starts_with("dir/x.dxf: unknown mesh file extension"),
            "{e}"
        );
        let e = load_mesh(
            Path::new("no/such/file.3ds"),
            None,
            &crate::Progress::default(),
        )
        .unwrap_err();
        assert!(matches!(e, Error::Usage(_)));
    }

    #[test]
    fn load_extension_is_case_insensitive() {
        assert_eq!(format_of(Path::new("A.OBJ")).unwrap(), Format::Obj);
        assert_eq!(format_of(Path::new("a.Stl")).unwrap(), Format::Stl);
        assert_eq!(format_of(Path::new("a.pLy")).unwrap(), Format::Ply);
        assert!(format_of(Path::new("obj")).is_err());
    }

    #[test]
    fn load_missing_file_is_io_error() {
        let e = load_mesh(
            Path::new("/no/such/dir/m.obj"),
            None,
            &crate::Progress::default(),
        )
        .unwrap_err();
        assert!(matches!(e, Error::Io(..)));
        assert!(e.to_string().starts_with("/no/such/dir/m.obj: "), "{e}");
        let at = Location::line(Path::new("s.kdl"), 2, 7);
        let e = load_mesh(Path::new("."), Some(&at), &Progress::default())
            .unwrap_err()
            .to_string();
        assert_eq!(
            e,
            "s.kdl:2:7: .: unknown mesh file extension (expected .obj, .stl or .ply)"
        );
    }

    #[test]
    fn load_empty_file_is_error() {
        for name in ["e.obj", "e.stl", "e.ply"] {
            let e = parse_mesh(Path::new(name), b"", &crate::Progress::default()).unwrap_err();
            assert_eq!(e.to_string(), format!("{name}: empty file"));
        }
    }

    #[test]
    fn load_coord_problems() {
        assert!(coord_problem(1.5).is_none());
        assert!(coord_problem(-MAX_COORD).is_none());
        assert!(coord_problem(f64::NAN).unwrap().contains("NaN"));
        assert!(coord_problem(f64::NEG_INFINITY)
            .unwrap()
            .contains("infinite"));
        assert!(coord_problem(2e12).unwrap().contains("huge coordinate"));
    }

    #[test]
    fn load_stem_name() {
        assert_eq!(stem_name(Path::new("a/b/cube.obj")), "cube");
        assert_eq!(stem_name(Path::new("")), "mesh");
    }
}
