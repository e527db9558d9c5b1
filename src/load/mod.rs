//! Loading scene input: mesh files (OBJ, STL, PLY) into named polygon meshes.

pub mod mesh_file;
pub mod obj;
pub mod ply;
pub mod stl;
mod text;

pub use mesh_file::{load_mesh, parse_mesh, MeshFile, MeshGroup, MAX_COORD};
