//! Loading scene input: KDL scene files and mesh files (OBJ, STL, PLY) into a [`Scene`].

mod args;
mod camera;
mod geometry;
mod kdl;
mod limits;
pub mod mesh_file;
pub mod obj;
pub mod ply;
mod read;
pub mod scene_file;
mod source;
pub mod stl;
mod text;
mod transform;

use std::path::Path;

pub use limits::{LoadOptions, DEFAULT_MAX_FACES};
pub use mesh_file::{load_mesh, parse_mesh, MeshFile, MeshGroup};
pub use scene_file::{load_scene_file, load_scene_file_with};

use crate::error::{Error, Result, Warnings};
use crate::scene::{Object, Scene};

/// Loads a scene: a `.kdl` scene file, or a mesh file (`.obj`, `.stl`, `.ply`) whose groups
/// become the top-level objects (one object, named after its group, for a single group).
/// The root object has the name "" (object paths leave it out). Repairs made on the way are
/// appended to `warnings`.
pub fn load_scene(path: &Path, warnings: &mut Warnings) -> Result<Scene> {
    load_scene_with(path, &LoadOptions::default(), warnings)
}

/// [`load_scene`] with limits: a scene with more faces than `opts.max_faces` once its
/// instances are placed is an error, found from counts before anything is expanded.
pub fn load_scene_with(path: &Path, opts: &LoadOptions, warnings: &mut Warnings) -> Result<Scene> {
    match mesh_file::extension(path).as_str() {
        "kdl" => load_scene_file_with(path, opts, warnings),
        "obj" | "stl" | "ply" => mesh_scene(path, opts, warnings),
        _ => Err(Error::Usage(format!(
            "{}: unknown scene file extension (expected .kdl, .obj, .stl or .ply)",
            path.display()
        ))),
    }
}

/// A scene made of one mesh file: its cleaned groups under the root.
fn mesh_scene(path: &Path, opts: &LoadOptions, warnings: &mut Warnings) -> Result<Scene> {
    let file = load_mesh(path)?;
    let objects = geometry::mesh_file_objects(&file, warnings)?;
    let root = Object::group("", objects);
    opts.check(&root, "the mesh", &crate::error::Location::file(path))?;
    Ok(Scene::new(root, path.to_path_buf()))
}
