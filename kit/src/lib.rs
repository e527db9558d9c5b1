//! One copy of what kepler's tests share, so a fix reaches every test: the shared-models lookup
//! and its skips that cannot pass silently, the random generator, mesh text builders, glTF and 3MF writers.
//!
//! It depends on nothing (not even the library), so the library's unit tests, the integration
//! tests, the CLI's tests and the bench can all use it.

mod gltf;
mod models;
mod obj;
mod rng;
mod temp;
mod threemf;

pub use gltf::{base64, glb, json_string, unit_cube_triangles, Gltf, GltfMesh, GltfNode};
pub use models::{model, models_dir, require, skip, MODELS_ENV, REQUIRE_MODELS_ENV};
pub use obj::{cuboid_obj, obj_text};
pub use rng::Rng;
pub use temp::temp_dir;
pub use threemf::{model_xml, threemf, zip_stored, ThreeMfObject};
