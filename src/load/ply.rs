//! PLY.
use super::mesh_file::MeshFile;
use crate::error::Result;
use std::path::Path;
/// x
pub fn parse_ply(_path: &Path, _bytes: &[u8]) -> Result<MeshFile> {
    todo!()
}
