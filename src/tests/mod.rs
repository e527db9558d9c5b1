//! Unit tests that reach into the library's internals (geometry, cleanup, the stages' own
//! functions), one module per former integration-test file; what the public API alone can
//! test lives in tests/integration/.

mod common;

mod bad_import_input;
mod bad_mesh_input;
mod caps;
mod exact_cases;
mod exact_check;
mod flatten;
mod import;
mod inbox;
mod invariants;
mod json_dust;
mod lines;
mod load_mesh_files;
mod long_faces;
mod rng;
mod rounding_units;
mod scene_files;
mod section;
mod shared_meshes;
mod tribox;
mod tribox_uses;
mod whole_regions;
