//! 3MF input: the archive opened, its model part found (through `_rels/.rels`, else
//! `/3D/3dmodel.model`) and read into a scene by [`super::threemf_model`].

use std::path::Path;

use super::zip::Archive;
use super::LoadOptions;
use crate::error::{Error, Location, Result, Warnings};
use crate::progress::{Phase, Progress, Stage};
use crate::scene::Scene;

/// The relationship type of a 3MF package's model part.
const MODEL_REL: &str = "http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel";

/// The default name of the model part.
const DEFAULT_PART: &str = "/3D/3dmodel.model";

/// The largest part inflated: as large as a mesh file may be.
const MAX_PART_BYTES: u64 = super::read::MAX_MESH_BYTES;

/// Loads the 3MF file at `path`.
pub(super) fn load_3mf(
    path: &Path,
    opts: &LoadOptions,
    warnings: &mut Warnings,
    progress: &Progress,
) -> Result<Scene> {
    let bytes = super::read::read_mesh_bytes(path, None, progress)?;
    progress.enter_phase(Stage::Load, Phase::Parse, bytes.len());
    let archive = Archive::open(path, &bytes)?;
    let part = model_part(path, &archive)?;
    let Some(entry) = archive.find(&part) else {
        return Err(Error::invalid(
            Location::file(path),
            format!(
                "the archive has no model part {}",
                crate::scene::names::printable(&part)
            ),
        ));
    };
    let xml = archive.read(entry, MAX_PART_BYTES)?;
    let part = format!("/{}", entry.name);
    let root = super::threemf_model::read_model(path, &part, &xml, warnings, progress)?;
    opts.check(&root, "the scene", &Location::file(path))?;
    Ok(Scene::new(root, path.to_path_buf()))
}

/// The model part's name: the target of the package's 3D model relationship, else the
/// default one.
fn model_part(path: &Path, archive: &Archive) -> Result<String> {
    let Some(rels) = archive.find("_rels/.rels") else {
        return Ok(DEFAULT_PART.into());
    };
    let bytes = archive.read(rels, 1 << 20)?;
    let err = |msg: String| Error::invalid(Location::file(path), format!("/_rels/.rels: {msg}"));
    let text = std::str::from_utf8(&bytes).map_err(|_| err("not UTF-8".into()))?;
    let doc = roxmltree::Document::parse(text).map_err(|e| {
        let p = e.pos();
        err(format!("{}:{}: {e}", p.row, p.col))
    })?;
    let target = doc
        .descendants()
        .filter(|n| n.has_tag_name("Relationship"))
        .find(|n| n.attribute("Type") == Some(MODEL_REL))
        .and_then(|n| n.attribute("Target"));
    Ok(match target {
        Some(t) if t.starts_with('/') => t.to_string(),
        Some(t) => format!("/{t}"),
        None => DEFAULT_PART.into(),
    })
}
