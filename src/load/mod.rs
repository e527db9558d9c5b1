//! Loading scene input: KDL scene files, mesh files (OBJ, STL, PLY) and modellers' scenes
//! (glTF 2.0, 3MF) into a [`Scene`].

mod args;
mod camera_node;
mod confine;
mod geometry;
mod gltf;
mod gltf_accessor;
mod gltf_buffers;
mod gltf_json;
mod gltf_mesh;
mod gltf_nodes;
mod kdl;
pub(crate) mod limits;
pub(crate) mod mesh_file;
pub(crate) mod obj;
pub(crate) mod ply;
mod read;
pub(crate) mod scene_file;
mod section_node;
mod source;
pub(crate) mod stl;
mod style_node;
mod text;
mod threemf;
mod threemf_model;
mod transform;
mod zip;

use std::path::Path;

pub(crate) use limits::LoadOptions;

use crate::error::{Error, Result, Warnings};
use crate::progress::Progress;
use crate::scene::{Object, Scene};

/// Loads a scene: a `.kdl` scene file, or a mesh file (`.obj`, `.stl`, `.ply`) whose groups
/// become the top-level objects (one object, named after its group, for a single group).
/// The root object has the name "" (object paths leave it out). Repairs made on the way are
/// appended to `warnings`. A scene with more faces than `opts.max_faces` once its instances
/// are placed is an error, found from counts before anything is expanded.
///
/// Where it is goes to `progress` (stage `Load`): a mesh file's bytes read and parsed and its
/// faces cleaned up, each as a phase of its own (`Read`, `Parse`, `Cleanup`,
/// [`crate::stats::Phase`]), for the scene file's meshes as for a
/// mesh file given alone. The scene is the same whatever watches it.
pub fn load_scene(
    path: &Path,
    opts: &LoadOptions,
    warnings: &mut Warnings,
    progress: &Progress,
) -> Result<Scene> {
    match mesh_file::extension(path).as_str() {
        "kdl" => scene_file::load_scene_file(path, opts, warnings, progress),
        "obj" | "stl" | "ply" => mesh_scene(path, opts, warnings, progress),
        "gltf" | "glb" => gltf::load_gltf(path, opts, warnings, progress),
        "3mf" => threemf::load_3mf(path, opts, warnings, progress),
        _ => Err(Error::Usage(format!(
            "{}: unknown scene file extension (expected .kdl, .obj, .stl, .ply, .gltf, .glb or .3mf)",
            path.display()
        ))),
    }
}

/// A scene made of one mesh file: its cleaned groups under the root.
fn mesh_scene(
    path: &Path,
    opts: &LoadOptions,
    warnings: &mut Warnings,
    progress: &Progress,
) -> Result<Scene> {
    let file = mesh_file::load_mesh(path, None, progress)?;
    let objects = geometry::mesh_file_objects(&file, warnings, progress)?;
    file.free();
    let root = Object::group("", objects);
    opts.check(&root, "the mesh", &crate::error::Location::file(path))?;
    Ok(Scene::new(root, path.to_path_buf()))
}
